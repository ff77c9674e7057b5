// CropWindow written as RenderMan writes it: the EXR's data window is the crop's pixels, its
// display window the whole frame, and those pixels are the whole frame's file's, bit for bit.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstring>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

std::string scene(const std::string& out, const std::string& crop) {
    return "Format 80 60 1\nProjection \"perspective\" \"fov\" 40\nPixelSamples 2 2\n"
           "Display \"" + out + "\" \"openexr\" \"rgbaz\"\n" + crop +
           "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0.3 -0.4 1]\n"
           "Surface \"plastic\"\nTranslate 0 0 5\nSphere 1.5 -1.5 1.5 360\nWorldEnd\n";
}

TEST(CropWindowCli, TheExrHoldsTheCropInItsFrame) {
    const test::TempDir dir("crop-cli");
    const std::string full = dir.path() + "/full.exr", part = dir.path() + "/part.exr";
    ASSERT_EQ(test::runStreyes("render " + test::writeFile(dir.path(), "full.rib", scene(full, ""))).exitCode, 0);
    const test::CliRun r =
        test::runStreyes("render " + test::writeFile(dir.path(), "part.rib", scene(part, "CropWindow 0.1 0.6 0.3 0.9\n")));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    // Columns ceil(8) = 8 to ceil(48 - 1) = 47, rows ceil(18) = 18 to ceil(54 - 1) = 53.
    auto in = OIIO::ImageInput::open(part);
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.x, 8);
    EXPECT_EQ(spec.y, 18);
    EXPECT_EQ(spec.width, 40);
    EXPECT_EQ(spec.height, 36);
    EXPECT_EQ(spec.full_x, 0);
    EXPECT_EQ(spec.full_y, 0);
    EXPECT_EQ(spec.full_width, 80);
    EXPECT_EQ(spec.full_height, 60);
    in->close();
    const ImageData a = readImage(full), b = readImage(part);
    ASSERT_EQ(a.channels, b.channels);
    const size_t n = a.channels.size();
    int differing = 0;
    for (int y = 0; y < 36; ++y)
        for (int x = 0; x < 40; ++x)
            if (std::memcmp(&a.pixels[(size_t(y + 18) * 80 + size_t(x + 8)) * n], &b.pixels[(size_t(y) * 40 + size_t(x)) * n],
                            n * sizeof(float)) != 0)
                ++differing;
    EXPECT_EQ(differing, 0);
    // --resume finds the crop's file complete and leaves it.
    const test::CliRun again = test::runStreyes("render --resume " + dir.path() + "/part.rib");
    EXPECT_EQ(again.exitCode, 0) << again.output;
    EXPECT_NE(again.output.find("1 frame already complete"), std::string::npos) << again.output;
}

}  // namespace
}  // namespace streyes
