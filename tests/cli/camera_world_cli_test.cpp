// A zooming, panning camera over a still world, as a file of FrameBegin blocks (issue 48 point 4):
// the frames are one pass, each frame under its own projection (docs/ARCHITECTURE.md, "Zooms");
// a frame rendered alone is the frame rendered with the others.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

std::string zoomShot() {
    std::string rib;
    for (int f = 1; f <= 5; ++f) {
        char head[512];
        std::snprintf(head, sizeof head,
                      "FrameBegin %d\nFormat 64 48 1\nPixelSamples 2 2\nShutter 0 0.5\n"
                      "Display \"zoom.%04d.exr\" \"openexr\" \"rgba\"\n"
                      "Projection \"perspective\" \"fov\" [%g]\nTranslate %g 0 %g\n",
                      f, f, 50.0 - 6.0 * f, 0.3 - 0.1 * f, 0.05 * f);
        rib += head;
        rib += R"(WorldBegin
LightSource "distantlight" 1 "from" [-1 2 -1] "to" [0 0 0]
AttributeBegin
  Surface "matte"
  Patch "bilinear" "P" [-4 -1 2  4 -1 2  -4 -1 10  4 -1 10]
AttributeEnd
AttributeBegin
  Surface "plastic" "roughness" [0.05]
  Color [0.2 0.3 0.8]
  Translate 0 0 5
  Sphere 1 -1 1 360
AttributeEnd
WorldEnd
FrameEnd
)";
    }
    return rib;
}

TEST(CameraWorldCli, AZoomingCamerasFrameAloneIsTheFrameInItsShot) {
    test::TempDir tmp("zoomcli");
    test::writeFile(tmp.path(), "zoom.rib", zoomShot());
    const std::string cd = "cd " + tmp.path() + " && ";
    test::CliRun r = test::runStreyesWith(cd, "render zoom.rib -q -o 'all.####.exr'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (int f : {2, 4}) {
        r = test::runStreyesWith(cd, "render zoom.rib -q --frames " + std::to_string(f) + " -o 'one.####.exr'");
        ASSERT_EQ(r.exitCode, 0) << r.output;
        char n[16];
        std::snprintf(n, sizeof n, ".%04d.exr", f);
        const ImageData all = readImage(tmp.path() + "/all" + n), one = readImage(tmp.path() + "/one" + n);
        ASSERT_FALSE(all.pixels.empty());
        EXPECT_EQ(all.pixels, one.pixels) << "frame " << f;
    }
    // The zoom shows: frame 5 (fov 20) sees the sphere larger than frame 1 (fov 44).
    auto covered = [&](int f) {
        char n[16];
        std::snprintf(n, sizeof n, ".%04d.exr", f);
        const ImageData im = readImage(tmp.path() + "/all" + n);
        const int r = im.channelIndex("R"), b = im.channelIndex("B");
        size_t blue = 0;
        for (int y = 0; y < im.height; ++y)
            for (int x = 0; x < im.width; ++x)
                if (im.at(x, y, b) > im.at(x, y, r) + 0.05f) ++blue;
        return blue;
    };
    EXPECT_GT(covered(5), 2 * covered(1));
}

// A unit square facing the camera at depth 5, seen through a zoom whose every frame puts its edges
// on pixel edges: frame f covers exactly its analytic pixels (a box filter one pixel wide, so a
// pixel's alpha is the share of its samples the square covers: 1 inside, 0 outside). The field of
// view narrows (frames 1-3), the screen window halves (frame 4) and moves (frame 5).
TEST(CameraWorldCli, AZoomCoversEachFramesAnalyticPixels) {
    struct Zoom {
        double tanHalf;      // tan(fov / 2): the square's half-width on screen is 0.1 / tanHalf
        const char* window;  // ScreenWindow, or none
        int x0, x1, y0, y1;  // the pixels it covers: [x0, x1) x [y0, y1) of 64 x 64
    };
    const Zoom zooms[] = {{0.4, "", 24, 40, 24, 40},
                          {0.32, "", 22, 42, 22, 42},
                          {0.2, "", 16, 48, 16, 48},
                          {0.4, "ScreenWindow -0.5 0.5 -0.5 0.5\n", 16, 48, 16, 48},
                          {0.4, "ScreenWindow 0 1 -0.5 0.5\n", 0, 16, 16, 48}};
    std::string rib;
    for (int f = 1; f <= 5; ++f) {
        const Zoom& z = zooms[f - 1];
        char head[512];
        std::snprintf(head, sizeof head,
                      "FrameBegin %d\nFormat 64 64 1\nPixelSamples 4 4\nPixelFilter \"box\" 1 1\n"
                      "Display \"sq.%04d.exr\" \"openexr\" \"rgba\"\nProjection \"perspective\" \"fov\" [%.17g]\n%s",
                      f, f, 2 * std::atan(z.tanHalf) * 180 / M_PI, z.window);
        rib += head;
        rib += "WorldBegin\nSurface \"constant\"\nPatch \"bilinear\" \"P\" [-0.5 -0.5 5  0.5 -0.5 5  -0.5 0.5 5  0.5 0.5 5]\n"
               "WorldEnd\nFrameEnd\n";
    }
    test::TempDir tmp("zoomsquare");
    test::writeFile(tmp.path(), "sq.rib", rib);
    const std::string cd = "cd " + tmp.path() + " && ";
    const test::CliRun r = test::runStreyesWith(cd, "render sq.rib -q --stats sq.json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string json = test::readFile(tmp.path() + "/sq.json");
    EXPECT_NE(json.find("\"renders\": 1,"), std::string::npos) << json;  // one pass, one block
    for (int f = 1; f <= 5; ++f) {
        const Zoom& z = zooms[f - 1];
        char n[16];
        std::snprintf(n, sizeof n, "/sq.%04d.exr", f);
        const ImageData im = readImage(tmp.path() + n);
        ASSERT_EQ(im.width, 64);
        const int a = im.channelIndex("A");
        double wrong = 0, sum = 0;
        for (int y = 0; y < im.height; ++y)
            for (int x = 0; x < im.width; ++x) {
                const bool inside = x >= z.x0 && x < z.x1 && y >= z.y0 && y < z.y1;
                const float alpha = im.at(x, y, a);
                const double off = std::fabs(double(alpha) - (inside ? 1.0 : 0.0));
                if (!(off <= wrong)) wrong = off;  // a NaN stays
                sum += alpha;
            }
        EXPECT_LT(wrong, 1e-6) << "frame " << f;
        EXPECT_NEAR(sum, double((z.x1 - z.x0) * (z.y1 - z.y0)), 1e-3) << "frame " << f;
    }
}

}  // namespace
}  // namespace streyes
