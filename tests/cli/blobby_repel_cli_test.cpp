// Blobby repelling planes (opcode 1003) through the streyes command: the depth map read from the
// working folder, a missing one taken as the plane z = 0 of the blobby's space (as Aqsis takes it)
// with one warning, a file that is no depth map an error at the Blobby's line.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

test::CliRun renderIn(const std::string& dir, const std::string& args) {
    return test::runStreyesWith("cd " + dir + " && ", "render " + args);
}

// RMSE of alpha (the blob's silhouette), infinite when the sizes differ.
double alphaRmse(const std::string& a, const std::string& b) {
    const ImageData x = readImage(a), y = readImage(b);
    if (x.width != y.width || x.height != y.height || x.channels.size() < 4 || y.channels.size() < 4) return INFINITY;
    double sum = 0;
    for (int py = 0; py < x.height; ++py)
        for (int px = 0; px < x.width; ++px) sum += std::pow(double(x.at(px, py, 3)) - y.at(px, py, 3), 2);
    return std::sqrt(sum / (double(x.width) * x.height));
}

bool samePixels(const std::string& a, const std::string& b) {
    const ImageData x = readImage(a), y = readImage(b);
    return x.width == y.width && x.height == y.height && x.channels == y.channels && !x.pixels.empty() &&
           x.pixels == y.pixels;
}

// A blob of radius 1.5 at height 0.85 over the plane z = 0 (its bottom 0.1 above it; heights are -z), seen from the side
// (up on screen is -z); `code` and `floats` after the blob's own.
std::string blobScene(const std::string& out, const std::string& code, const std::string& floats,
                      const std::string& strings, int blobbies = 1) {
    std::string s = "Format 160 120 1\nPixelSamples 3 3\nProjection \"perspective\" \"fov\" [18]\n"
                    "Display \"" + out + "\" \"openexr\" \"rgba\"\nTranslate 0 0.3 6\nRotate 90 1 0 0\nWorldBegin\n"
                    "Surface \"constant\"\n";
    for (int i = 0; i < blobbies; ++i)
        s += "Blobby " + std::to_string(code.empty() ? 1 : 2) + " [1001 0 " + code + "] [1.5 0 0 0 0 1.5 0 0 0 0 1.5 0 0 0 -0.85 1 " +
             floats + "] [" + strings + "]\n";
    return s + "WorldEnd\n";
}

const char* kPlane = "1003 0 16 0 2 0 1";
const char* kRepel = ".4 .01 .3 .08";

TEST(BlobbyRepelCli, AMissingMapIsTheGroundZEqualsZeroAndAMapOfThatGroundGivesTheSamePicture) {
    test::TempDir tmp("blobby-repel");
    const std::string d = tmp.path();
    test::writeFile(d, "alone.rib", blobScene("alone.exr", "", "", ""));
    test::writeFile(d, "zeroA.rib", blobScene("zeroA.exr", kPlane, "0 .01 .3 .08", "\"none.zfile\""));
    test::writeFile(d, "missing.rib", blobScene("missing.exr", kPlane, kRepel, "\"none.zfile\"", 2));
    test::writeFile(d, "mapped.rib", blobScene("mapped.exr", kPlane, kRepel, "\"flat.zfile\""));
    // The ground z = 0 seen from 10 above (camera z = world z + 10, looking along +z): depth 10.
    test::writeFile(d, "ground.rib",
                    "Format 32 32 1\nProjection \"orthographic\"\nScreenWindow -4 4 -4 4\nTranslate 0 0 10\n"
                    "Display \"flat.zfile\" \"zfile\" \"z\"\nWorldBegin\n"
                    "Patch \"bilinear\" \"P\" [-6 -6 0  6 -6 0  -6 6 0  6 6 0]\nWorldEnd\n");
    for (const char* f : {"alone.rib", "zeroA.rib", "ground.rib", "mapped.rib"}) {
        const test::CliRun r = renderIn(d, f);
        ASSERT_EQ(r.exitCode, 0) << f << "\n" << r.output;
        EXPECT_EQ(r.output.find("warning"), std::string::npos) << f << "\n" << r.output;
    }
    const test::CliRun r = renderIn(d, "missing.rib");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string warning =
        "missing.rib:9: warning: Blobby: the repelling plane's depth map \"none.zfile\" is not a file: the ground "
        "is taken as the plane z = 0 of the blobby's space, as Aqsis does";
    EXPECT_NE(r.output.find(warning), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("repelling plane"), r.output.rfind("repelling plane")) << r.output;  // once for both
    // A = 0: no repulsion, the blob's own surface bit for bit (with a missing map: no warning,
    // nothing is missing from the picture).
    EXPECT_TRUE(samePixels(d + "/zeroA.exr", d + "/alone.exr"));
    // The push shows: the blob's bottom rises by about 0.04 of 1.5 (a few pixels of silhouette).
    EXPECT_GT(alphaRmse(d + "/missing.exr", d + "/alone.exr"), 0.03);
    // The map of the ground z = 0 is that ground: the same silhouette but for rounding.
    EXPECT_LT(alphaRmse(d + "/mapped.exr", d + "/missing.exr"), 0.003);
}

TEST(BlobbyRepelCli, AFileThatIsNoDepthMapIsAnErrorAtTheBlobbysLine) {
    test::TempDir tmp("blobby-repel-bad");
    test::writeFile(tmp.path(), "bad.zfile", "not a depth map\n");
    test::writeFile(tmp.path(), "bad.rib", blobScene("bad.exr", kPlane, kRepel, "\"bad.zfile\""));
    const test::CliRun r = renderIn(tmp.path(), "bad.rib");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("bad.rib:9"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("depth map \"bad.zfile\""), std::string::npos) << r.output;
    EXPECT_EQ(test::listDir(tmp.path()), (std::vector<std::string>{"bad.rib", "bad.zfile"}));
}

// A depth pass earlier in the same file writes the map: the Blobby is cut when its own pass
// renders, after that map is written, and reads it as it reads a map made beforehand.
TEST(BlobbyRepelCli, AMapAnEarlierFrameOfTheFileWritesIsReadWhenTheBlobbyRenders) {
    // The ground 0.1 above z = 0 (z = -0.1, depth 9.9 from the map's camera): not the z = 0 ground a
    // missing map gives, so a map read too early would show.
    const std::string ground = "Format 32 32 1\nProjection \"orthographic\"\nScreenWindow -4 4 -4 4\nTranslate 0 0 10\n"
                               "Display \"high.zfile\" \"zfile\" \"z\"\nWorldBegin\n"
                               "Patch \"bilinear\" \"P\" [-6 -6 -.1  6 -6 -.1  -6 6 -.1  6 6 -.1]\nWorldEnd\n";
    const std::string picture = "FrameBegin 2\n" + blobScene("out.exr", kPlane, kRepel, "\"high.zfile\"") + "FrameEnd\n";
    // Beforehand: the map from its own file, then the picture.
    test::TempDir before("blobby-repel-before");
    test::writeFile(before.path(), "ground.rib", ground);
    test::writeFile(before.path(), "picture.rib", picture);
    test::writeFile(before.path(), "zero.rib", "FrameBegin 2\n" + blobScene("zero.exr", kPlane, kRepel, "\"none.zfile\"") +
                                                   "FrameEnd\n");
    for (const char* f : {"ground.rib", "picture.rib", "zero.rib"}) {
        const test::CliRun r = renderIn(before.path(), f);
        ASSERT_EQ(r.exitCode, 0) << f << "\n" << r.output;
    }
    // One file: frame 1 renders the map, frame 2 the Blobby repelled by it; no map there before.
    test::TempDir one("blobby-repel-passes");
    test::writeFile(one.path(), "passes.rib", "FrameBegin 1\n" + ground + "FrameEnd\n" + picture);
    const test::CliRun r = renderIn(one.path(), "passes.rib");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    EXPECT_TRUE(samePixels(one.path() + "/out.exr", before.path() + "/out.exr"));
    // And that map did move the blob: not the picture of the z = 0 ground.
    EXPECT_GT(alphaRmse(one.path() + "/out.exr", before.path() + "/zero.exr"), 0.02);
}

}  // namespace
}  // namespace streyes
