// Output variables from the command line: a "+" display of a variable writes its own file beside
// -o's, the -o file is unchanged by it, and a bad mode exits 2 naming the file and line.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::CliRun;
using test::writeFile;

const char* kScene = R"(Format 24 16 1
Projection "perspective" "fov" 40
Shutter 0 1
Display "primary.exr" "openexr" "rgba"
%AOV%
WorldBegin
AttributeBegin
MotionBegin [0 3]
Translate -1 0 6
Translate 1 0 6
MotionEnd
Sphere 1 -1 1 360
AttributeEnd
WorldEnd
)";

std::string scene(const std::string& aov) {
    std::string s = kScene;
    s.replace(s.find("%AOV%"), 5, aov);
    return s;
}

std::string bytesOf(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

TEST(AovCli, APlusDisplayOfAVariableWritesItsOwnFileBesideMinusO) {
    const test::TempDir dir("aov-cli");
    const std::string d = dir.path();
    const std::string with = writeFile(d, "with.rib", scene("Display \"+" + d + "/normals.####.exr\" \"openexr\" \"N,motion\""));
    const std::string without = writeFile(d, "without.rib", scene(""));
    CliRun r = test::runStreyes("render " + with + " -o " + d + "/a.####.exr --frames 0-1 --threads 1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = test::runStreyes("render " + without + " -o " + d + "/b.####.exr --frames 0-1 --threads 1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* f : {"0000", "0001"}) {
        // The colour file is the same bytes with or without the variables asked for.
        EXPECT_EQ(bytesOf(d + "/a." + f + ".exr"), bytesOf(d + "/b." + f + ".exr"));
        const ImageData n = readImage(d + "/normals." + f + ".exr");
        EXPECT_EQ(n.channels, (std::vector<std::string>{"N.X", "N.Y", "N.Z", "motion.X", "motion.Y"}));
        // The image's centre, on the sphere in both frames: normals towards the eye (a mean over
        // the exposure, which sweeps the sphere's edge past it: not unit); moving 2/3 unit a frame
        // at a depth of about 5 (4.4 pixels a unit there: AovRender holds it exactly).
        const int x = n.width / 2, y = n.height / 2;
        const float nx = n.at(x, y, n.channelIndex("N.X")), ny = n.at(x, y, n.channelIndex("N.Y")),
                    nz = n.at(x, y, n.channelIndex("N.Z"));
        EXPECT_GT(nx * nx + ny * ny + nz * nz, 0.5f);
        EXPECT_LE(nx * nx + ny * ny + nz * nz, 1.0f + 1e-5f);
        EXPECT_LT(nz, 0.0f);  // towards the eye
        EXPECT_GT(n.at(x, y, n.channelIndex("motion.X")), 2.0f);
        EXPECT_LT(n.at(x, y, n.channelIndex("motion.X")), 4.0f);
        EXPECT_NEAR(n.at(x, y, n.channelIndex("motion.Y")), 0.0f, 1e-3f);
    }
}

TEST(AovCli, BadModesAndTheRayTracerExitTwoNamingTheLine) {
    const test::TempDir dir("aov-cli-bad");
    const std::string bad = writeFile(dir.path(), "bad.rib", scene("Display \"+n.exr\" \"openexr\" \"rgba,normals\""));
    CliRun r = test::runStreyes("render " + bad + " -o " + dir.path() + "/x.exr");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("bad.rib:5"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\"normals\""), std::string::npos) << r.output;
    const std::string traced = writeFile(dir.path(), "traced.rib", scene("Display \"+n.exr\" \"openexr\" \"N\""));
    r = test::runStreyes("render " + traced + " --algorithm raytrace -o " + dir.path() + "/x.exr");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("traced.rib:5"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace streyes
