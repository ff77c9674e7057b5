// Quantize and a Display's "quantize"/"dither": an 8- or 16-bit file holds round(one * v + dither *
// r) clamped to [min, max] (streyes/quantize.h), checked against that formula on a picture of
// known colours; RenderMan's default is 8-bit with dither 0.5; EXR stays float; a dithered frame
// is the same file alone as in a block of frames; a bad Quantize exits 2 naming file:line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

// 16 x 8 pixels: the left half covered by a constant square of colour (0.5, 0.2, 1.7), the right
// half empty. Box filter of one pixel: every pixel is wholly one or the other.
std::string scene(const std::string& display, const std::string& options) {
    return "Format 16 8 1\nProjection \"orthographic\"\nScreenWindow -2 2 -1 1\nPixelFilter \"box\" 1 1\n" + display +
           "\n" + options +
           "\nWorldBegin\nSurface \"constant\"\nColor [0.5 0.2 1.7]\n"
           "Polygon \"P\" [-2.5 -1.5 5  0 -1.5 5  0 1.5 5  -2.5 1.5 5]\nWorldEnd\n";
}

std::string bytesOf(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

struct Rendered {
    ImageData image;
    std::string output;
};

Rendered render(const test::TempDir& dir, const std::string& name, const std::string& display,
                const std::string& options, const std::string& args = "") {
    const std::string rib = test::writeFile(dir.path(), name + ".rib", scene(display, options));
    const test::CliRun r = test::runStreyes("render " + rib + " " + args);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    Rendered out;
    out.output = r.output;
    return out;
}

// The stored integer of channel c at (x, y): readImage gives integer files as v / max.
double stored(const ImageData& img, int x, int y, int c, double max) {
    const size_t n = img.channels.size();
    return double(img.pixels[(size_t(y) * size_t(img.width) + size_t(x)) * n + size_t(c)]) * max;
}

TEST(Quantize, EightBitValuesFollowTheFormulaWithoutDither) {
    const test::TempDir dir("quantize-8");
    const std::string file = dir.path() + "/q.tif";
    render(dir, "q", "Display \"" + file + "\" \"file\" \"rgba\"", "Quantize \"rgba\" 255 0 255 0");
    const ImageData img = readImage(file);
    ASSERT_EQ(img.channels, (std::vector<std::string>{"R", "G", "B", "A"}));
    ASSERT_EQ(img.formats.front(), "uint8");
    const double colour[4] = {0.5, 0.2, 1.7, 1.0};
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x)
            for (int c = 0; c < 4; ++c) {
                const double v = x < 8 ? colour[c] : 0.0;
                const double want = std::clamp(std::round(255 * v), 0.0, 255.0);  // 128, 51, 255, 255
                EXPECT_NEAR(stored(img, x, y, c, 255), want, 1e-3) << x << " " << y << " " << c;
            }
}

TEST(Quantize, SixteenBitRangeClampsToMinAndMax) {
    const test::TempDir dir("quantize-16");
    const std::string file = dir.path() + "/q.tif";
    render(dir, "q", "Display \"" + file + "\" \"file\" \"rgba\"", "Quantize \"rgba\" 1000 100 600 0");
    const ImageData img = readImage(file);
    ASSERT_EQ(img.formats.front(), "uint16");
    // 0.5 -> 500, 0.2 -> 200, 1.7 -> 1700 clamped to 600, alpha 1000 -> 600; empty 0 -> min 100.
    const double covered[4] = {500, 200, 600, 600};
    for (int c = 0; c < 4; ++c) {
        EXPECT_NEAR(stored(img, 3, 4, c, 65535), covered[c], 1e-2) << c;
        EXPECT_NEAR(stored(img, 12, 4, c, 65535), 100, 1e-2) << c;
    }
}

// A display's own "quantize" [zero one min max] and "dither" override the Quantize request.
TEST(Quantize, DisplayParametersOverrideTheRequest) {
    const test::TempDir dir("quantize-display");
    const std::string file = dir.path() + "/q.tif";
    render(dir, "q", "Display \"" + file + "\" \"file\" \"rgba\" \"quantize\" [0 65535 0 65535] \"dither\" [0]",
           "Quantize \"rgba\" 255 0 255 0.5");
    const ImageData img = readImage(file);
    ASSERT_EQ(img.formats.front(), "uint16");
    EXPECT_NEAR(stored(img, 3, 4, 0, 65535), 32768, 1e-2);  // round(32767.5)
    EXPECT_NEAR(stored(img, 3, 4, 1, 65535), std::round(0.2f * 65535.0), 1e-2);
}

// Dither 0.5 around 127.5 (0.5 * 255) gives 127 or 128, both, about equally often (the dither is
// uniform in [-1, 1) times the amplitude: no bias); 1.7 stays clamped at 255; with no Quantize the
// file is RenderMan's default, the same bytes.
TEST(Quantize, DitherSpreadsAHalfStepWithoutBiasAndIsTheDefault) {
    const test::TempDir dir("quantize-dither");
    const std::string a = dir.path() + "/a.tif", b = dir.path() + "/b.tif";
    render(dir, "a", "Display \"" + a + "\" \"file\" \"rgba\"", "Quantize \"rgba\" 255 0 255 0.5");
    render(dir, "b", "Display \"" + b + "\" \"file\" \"rgba\"", "");
    EXPECT_EQ(bytesOf(a), bytesOf(b));
    const ImageData img = readImage(a);
    ASSERT_EQ(img.formats.front(), "uint8");
    int high = 0, n = 0;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const double r = stored(img, x, y, 0, 255);
            EXPECT_TRUE(std::abs(r - 127) < 1e-3 || std::abs(r - 128) < 1e-3) << r;
            high += r > 127.5;
            ++n;
            EXPECT_NEAR(stored(img, x, y, 2, 255), 255, 1e-3);
        }
    EXPECT_GT(high, n / 4);
    EXPECT_LT(high, 3 * n / 4);
}

// The dither is a function of the pixel and the frame number: frame 1 rendered alone is the same
// file as frame 1 of a block of three; frames differ in their dither.
TEST(Quantize, ADitheredFrameAloneEqualsItInABlock) {
    const test::TempDir dir("quantize-frames");
    const std::string block = dir.path() + "/block.####.tif", alone = dir.path() + "/alone.####.tif";
    render(dir, "block", "Display \"" + block + "\" \"file\" \"rgba\"", "Option \"streyes\" \"frames\" [0 2]");
    render(dir, "alone", "Display \"" + alone + "\" \"file\" \"rgba\"", "Option \"streyes\" \"frames\" [0 2]",
           "--frames 1");
    const std::string one = bytesOf(dir.path() + "/block.0001.tif");
    ASSERT_FALSE(one.empty());
    EXPECT_EQ(one, bytesOf(dir.path() + "/alone.0001.tif"));
    EXPECT_NE(one, bytesOf(dir.path() + "/block.0000.tif"));
}

// EXR files hold floats whatever Quantize says.
TEST(Quantize, ExrStaysFloat) {
    const test::TempDir dir("quantize-exr");
    const std::string file = dir.path() + "/q.exr";
    render(dir, "q", "Display \"" + file + "\" \"openexr\" \"rgba\"", "Quantize \"rgba\" 255 0 255 0.5");
    const ImageData img = readImage(file);
    EXPECT_EQ(img.formats.front(), "half");
    EXPECT_EQ(img.pixels[(4 * 16 + 3) * 4 + 0], 0.5f);
    EXPECT_NEAR(img.pixels[(4 * 16 + 3) * 4 + 2], 1.7f, 1e-3f);
}

TEST(Quantize, BadValuesExitTwoNamingTheLine) {
    const test::TempDir dir("quantize-bad");
    const struct {
        const char* quantize;
        const char* says;
    } cases[] = {
        {"Quantize \"rgba\" 255 10 5 0", "min 10 is above max 5"},
        {"Quantize \"rgba\" -1 0 255 0", "one must be at least 0"},
        {"Quantize \"rgba\" 255 0 255 -0.5", "dither amplitude must be at least 0"},
        {"Quantize \"rgba\" 255 0 255", "ditheramplitude"},
    };
    for (const auto& c : cases) {
        const std::string rib = test::writeFile(dir.path(), "bad.rib", scene("Display \"q.tif\" \"file\" \"rgba\"", c.quantize));
        const test::CliRun r = test::runStreyes("render " + rib + " -o " + dir.path() + "/x.tif");
        EXPECT_EQ(r.exitCode, 2) << c.quantize << ": " << r.output;
        EXPECT_NE(r.output.find("bad.rib:6"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(c.says), std::string::npos) << r.output;
    }
}

}  // namespace
}  // namespace streyes
