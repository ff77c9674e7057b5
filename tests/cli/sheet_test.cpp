// `streyes sheet`: the sheet's size, where each frame lands, labels, and bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "cli_run.h"
#include "io/contact_sheet.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::CliRun;
using test::runStreyes;

// A w x h frame of one linear colour, opaque.
void writeFlat(const std::string& path, int w, int h, float r, float g, float b) {
    FrameImage f;
    f.resize(w, h);
    for (size_t i = 0; i < size_t(w) * size_t(h); ++i) {
        f.rgba[i * 4 + 0] = r, f.rgba[i * 4 + 1] = g, f.rgba[i * 4 + 2] = b, f.rgba[i * 4 + 3] = 1;
    }
    writeFrame(path, f, "rgbaz");
}

// Frame k of the test animations has the colour (0.1 k, 0.05 k, 1 - 0.1 k).
float colour(int k, int c) { return c == 0 ? 0.1f * k : c == 1 ? 0.05f * k : 1 - 0.1f * k; }

// The 8-bit sRGB value the sheet must hold for a linear value, as read back (0..1).
float srgb8(float c) {
    float e = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1 / 2.4f) - 0.055f;
    return std::round(e * 255) / 255;
}

// A folder of `frames` flat frames f.01.exr, ... of w x h pixels, removed with the returned TempDir.
test::TempDir animation(const std::string& tag, int frames, int w, int h) {
    test::TempDir tempDir(tag);
    const std::string& dir = tempDir.path();
    for (int k = 1; k <= frames; ++k)
        writeFlat(dir + "/f." + std::to_string(100 + k).substr(1) + ".exr", w, h, colour(k, 0), colour(k, 1), colour(k, 2));
    return tempDir;
}

TEST(Sheet, LaysFramesOutLikeABook) {
    const test::TempDir tempDir = animation("sheet-book", 5, 8, 4);
    const std::string& dir = tempDir.path();
    CliRun r = runStreyes("sheet " + dir + "/f.##.exr --columns 2 --gap 2 --no-labels -o " + dir + "/sheet.png");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ImageData s = readImage(dir + "/sheet.png");
    // 2 columns, 3 rows of 8x4 cells with 2 pixels around each.
    EXPECT_EQ(s.width, 2 + 2 * (8 + 2));
    EXPECT_EQ(s.height, 2 + 3 * (4 + 2));
    ASSERT_EQ(s.channels.size(), 3u);
    // Frame k goes to cell k - 1, left to right, top to bottom: frame 4 is row 1, column 1.
    for (int k = 1; k <= 5; ++k) {
        const int col = (k - 1) % 2, row = (k - 1) / 2;
        const int x = 2 + col * 10, y = 2 + row * 6;
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(s.at(x, y, c), srgb8(colour(k, c)), 1e-6) << "frame " << k << " channel " << c;
            EXPECT_NEAR(s.at(x + 7, y + 3, c), srgb8(colour(k, c)), 1e-6) << "frame " << k << " channel " << c;
        }
        EXPECT_EQ(s.at(x - 1, y, 0), 1.0f);  // the white page between cells
    }
    EXPECT_EQ(s.at(2 + 10 + 4, 2 + 12 + 2, 0), 1.0f);  // the sixth cell is empty
}

TEST(Sheet, EveryNthFrameAndScaledCells) {
    const test::TempDir tempDir = animation("sheet-every", 5, 8, 4);
    const std::string& dir = tempDir.path();
    CliRun r = runStreyes("sheet " + dir + "/f.##.exr --every 2 --cell-width 4 --gap 0 --no-labels -o " + dir + "/s.png");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ImageData s = readImage(dir + "/s.png");
    // Frames 1, 3, 5: two columns (the square root of 3, rounded up), cells 4x2.
    EXPECT_EQ(s.width, 8);
    EXPECT_EQ(s.height, 4);
    // Scaling a flat frame keeps its colour, up to one 8-bit step of rounding.
    EXPECT_NEAR(s.at(5, 1, 0), srgb8(colour(3, 0)), 1.01 / 255);  // frame 3 in the second cell
    EXPECT_NEAR(s.at(1, 3, 2), srgb8(colour(5, 2)), 1.01 / 255);  // frame 5 starts the second row
}

TEST(Sheet, LabelsShowTheFrameNumber) {
    const test::TempDir tempDir("sheet-label");
    const std::string& dir = tempDir.path();
    writeFlat(dir + "/f.12.exr", 64, 48, 0.5f, 0.5f, 0.5f);
    ASSERT_EQ(runStreyes("sheet " + dir + "/f.##.exr --gap 0 -o " + dir + "/s.png").exitCode, 0);
    ImageData s = readImage(dir + "/s.png");
    // 48 pixels high: font pixels of 1; a black box from (1, 40) holding "12" in white from (2, 41).
    EXPECT_EQ(s.at(1, 40, 0), 0.0f);
    EXPECT_EQ(s.at(2, 41, 0), 0.0f);  // '1' is .#. in its top row
    EXPECT_EQ(s.at(3, 41, 0), 1.0f);
    EXPECT_EQ(s.at(6, 41, 0), 1.0f);  // '2' is ### in its top row
    EXPECT_NEAR(s.at(32, 20, 0), srgb8(0.5f), 1e-6);
}

TEST(Sheet, BadInputIsAnError) {
    const test::TempDir tempDir = animation("sheet-bad", 2, 8, 4);
    const std::string& dir = tempDir.path();
    CliRun noOut = runStreyes("sheet " + dir + "/f.##.exr");
    EXPECT_EQ(noOut.exitCode, 2);
    EXPECT_NE(noOut.output.find("-o sheet.png"), std::string::npos) << noOut.output;
    CliRun exr = runStreyes("sheet " + dir + "/f.##.exr -o " + dir + "/s.exr");
    EXPECT_EQ(exr.exitCode, 2);
    EXPECT_NE(exr.output.find("write a .png or .jpg"), std::string::npos) << exr.output;
    EXPECT_EQ(runStreyes("sheet " + dir + "/g.##.exr -o " + dir + "/s.png").exitCode, 2);  // no frames
    EXPECT_EQ(runStreyes("sheet " + dir + "/f.##.exr --frames 1-3 -o " + dir + "/s.png").exitCode, 2);
    writeFlat(dir + "/f.03.exr", 4, 4, 0, 0, 0);
    CliRun sizes = runStreyes("sheet " + dir + "/f.##.exr -o " + dir + "/s.png");
    EXPECT_EQ(sizes.exitCode, 2);
    EXPECT_NE(sizes.output.find("frames of one size"), std::string::npos) << sizes.output;
    EXPECT_FALSE(std::ifstream(dir + "/s.png").good());  // nothing half-written
}

TEST(Sheet, LayoutArithmetic) {
    SheetOptions o;
    SheetLayout l = layoutSheet(12, 160, 90, o);  // the README's demo sheet: 4 x 3 cells
    EXPECT_EQ(l.columns, 4);
    EXPECT_EQ(l.rows, 3);
    EXPECT_EQ(l.width, 4 + 4 * 164);
    EXPECT_EQ(l.height, 4 + 3 * 94);
    EXPECT_EQ(l.cellX(5), 4 + 164);
    EXPECT_EQ(l.cellY(5), 4 + 94);
    o.cellWidth = 80;
    o.columns = 20;  // never more columns than frames
    l = layoutSheet(12, 160, 90, o);
    EXPECT_EQ(l.columns, 12);
    EXPECT_EQ(l.cellHeight, 45);
}

}  // namespace
}  // namespace streyes
