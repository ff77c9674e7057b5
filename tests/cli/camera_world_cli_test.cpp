// A zooming, panning camera over a still world, as a file of FrameBegin blocks (issue 48 point 4):
// each frame's projection differs, so its frames render as passes of their own (docs/
// ARCHITECTURE.md, "Passes"); a frame rendered alone is the frame rendered with the others.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace streyes
