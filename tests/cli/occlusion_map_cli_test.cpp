// Occlusion maps through the streyes command: depth frames appended into one file (Display
// "shadow" with "append", as Aqsis's occlmap.rib writes them) and occlusion(mapname, P, N) reading
// them, against the cosine-weighted share of the maps that see a wall; the file read back from
// disk; frame-block invariance; bad maps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;
using test::runStreyesWith;
using test::writeFile;

constexpr double kPi = 3.14159265358979323846;

struct D {
    double x, y, z;
};
D polar(double thetaDeg, double phiDeg) {
    const double t = thetaDeg * kPi / 180, p = phiDeg * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// Eight map directions (the sky each map sees), two of them below the ground.
const D kDirs[] = {polar(0, 0),  polar(30, 0),   polar(30, 180), polar(60, 90),
                   polar(60, 0), polar(60, 200), polar(135, 0),  polar(180, 0)};

// RIB's Transform for an orthographic camera at 10 d looking at the origin (world -> camera).
std::string cameraAlong(D d) {
    const D z{-d.x, -d.y, -d.z};
    const D up{0, 1, 0};
    D x{up.y * z.z - up.z * z.y, up.z * z.x - up.x * z.z, up.x * z.y - up.y * z.x};
    const double l = std::sqrt(x.x * x.x + x.y * x.y + x.z * x.z);
    x = {x.x / l, x.y / l, x.z / l};
    const D y{z.y * x.z - z.z * x.y, z.z * x.x - z.x * x.z, z.x * x.y - z.y * x.x};
    const D e{10 * d.x, 10 * d.y, 10 * d.z};
    auto dot = [](D a, D b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "Transform [%.17g %.17g %.17g 0 %.17g %.17g %.17g 0 %.17g %.17g %.17g 0 %.17g %.17g %.17g 1]\n", x.x,
                  y.x, z.x, x.y, y.y, z.y, x.z, y.z, z.z, -dot(e, x), -dot(e, y), -dot(e, z));
    return buf;
}

// The ground z = 0 and a wall 0.5 <= x <= 0.6, |y| <= 20, up to z = 20 (its two big faces).
const char* kGeometry =
    "Patch \"bilinear\" \"P\" [-40 -40 0  40 -40 0  -40 40 0  40 40 0]\n"
    "Patch \"bilinear\" \"P\" [0.5 -20 0  0.5 20 0  0.5 -20 20  0.5 20 20]\n"
    "Patch \"bilinear\" \"P\" [0.6 -20 0  0.6 20 0  0.6 -20 20  0.6 20 20]\n";

const char* kShader =
    "surface occlview(string map = \"occl.sm\"; float blur = 0; float bias = 0.2;) {\n"
    "    normal Nf = faceforward(normalize(N), I);\n"
    "    float o = occlusion(map, P, Nf, 0, \"blur\", blur, \"bias\", bias);\n"
    "    Ci = 1 - o;\n"
    "    Oi = 1;\n"
    "}\n";

std::string depthFrames() {
    std::string s;
    for (int i = 0; i < 8; ++i)
        s += "FrameBegin " + std::to_string(i + 1) + "\nDisplay \"occl.sm\" \"shadow\" \"z\"" +
             (i > 0 ? " \"float append\" [1.0]" : "") +
             "\nFormat 256 256 1\nPixelSamples 1 1\nProjection \"orthographic\"\nScreenWindow -4 4 -4 4\n" +
             cameraAlong(kDirs[i]) + "WorldBegin\n" + kGeometry + "WorldEnd\nFrameEnd\n";
    return s;
}

// Looking down at the ground x in [-1, 0], |y| <= 0.5, left of the wall.
std::string pictureFrame(int n, const std::string& out) {
    return "FrameBegin " + std::to_string(n) + "\nDisplay \"" + out +
           "\" \"file\" \"rgba\"\nFormat 32 32 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
           "ScreenWindow -0.5 0.5 -0.5 0.5\nTransform [1 0 0 0  0 1 0 0  0 0 -1 0  0.5 0 10 1]\n" +
           "WorldBegin\nSurface \"occlview\" \"string map\" [\"occl.sm\"]\n" + kGeometry + "WorldEnd\nFrameEnd\n";
}

// What every pixel should be: 1 less the cosine-weighted share of the facing maps that see the
// wall in front of the ground (those whose sky lies toward +x).
double expectedLight() {
    double blocked = 0, total = 0;
    for (const D& d : kDirs) {
        if (d.z <= 0) continue;
        total += d.z;
        if (d.x > 1e-9) blocked += d.z;
    }
    return 1 - blocked / total;
}

test::CliRun runIn(const std::string& dir, const std::string& args) {
    return runStreyesWith("cd " + dir + " && ", "render " + args);
}

TEST(OcclusionMapCli, AppendedMapsGiveTheCosineWeightedShareOfTheDirectionsTheWallBlocks) {
    test::TempDir tmp("occlmap");
    writeFile(tmp.path(), "occlview.sl", kShader);
    writeFile(tmp.path(), "scene.rib", depthFrames() + pictureFrame(9, "pic.####.exr"));
    const test::CliRun r = runIn(tmp.path(), "scene.rib");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    const double want = expectedLight();
    EXPECT_NEAR(want, 1 - (std::cos(kPi / 6) + 0.5) / (1 + 2 * std::cos(kPi / 6) + 1.5), 1e-12);
    const ImageData pic = readImage(tmp.path() + "/pic.0009.exr");
    double sum = 0;
    for (int y = 0; y < pic.height; ++y)
        for (int x = 0; x < pic.width; ++x) {
            const float v = pic.at(x, y, 0);
            ASSERT_TRUE(std::isfinite(v));
            EXPECT_NEAR(v, want, 2e-3) << x << " " << y;  // half floats
            sum += v;
        }
    EXPECT_NEAR(sum / (pic.width * pic.height), want, 1e-3);

    // The file on disk holds the eight maps with their cameras: a picture reading it from disk
    // (no frame of its input writes it) gives the same pixels.
    writeFile(tmp.path(), "fromdisk.rib", pictureFrame(9, "disk.####.exr"));
    const test::CliRun d = runIn(tmp.path(), "fromdisk.rib");
    ASSERT_EQ(d.exitCode, 0) << d.output;
    const ImageData disk = readImage(tmp.path() + "/disk.0009.exr");
    EXPECT_EQ(disk.pixels, pic.pixels);

    // Without "append" the file holds the last map only (the one from below the ground): open.
    std::string single = depthFrames();
    for (size_t at; (at = single.find(" \"float append\" [1.0]")) != std::string::npos;) single.erase(at, 21);
    writeFile(tmp.path(), "single.rib", single + pictureFrame(9, "single.####.exr"));
    ASSERT_EQ(runIn(tmp.path(), "single.rib -q").exitCode, 0);
    const ImageData one = readImage(tmp.path() + "/single.0009.exr");
    EXPECT_EQ(one.at(5, 5, 0), 1.0f);
}

// A picture frame renders the same alone (--frames) as in a block with another.
TEST(OcclusionMapCli, APictureFrameAloneEqualsItInABlock) {
    test::TempDir tmp("occlmapblock");
    writeFile(tmp.path(), "occlview.sl", kShader);
    writeFile(tmp.path(), "scene.rib", depthFrames() + pictureFrame(9, "pic.####.exr") + pictureFrame(10, "pic.####.exr"));
    ASSERT_EQ(runIn(tmp.path(), "scene.rib -q").exitCode, 0);
    const ImageData block = readImage(tmp.path() + "/pic.0010.exr");
    fs::remove(tmp.path() + "/pic.0010.exr");
    ASSERT_EQ(runIn(tmp.path(), "scene.rib -q --frames 10").exitCode, 0);
    const ImageData alone = readImage(tmp.path() + "/pic.0010.exr");
    EXPECT_EQ(alone.pixels, block.pixels);
    EXPECT_NEAR(alone.at(3, 3, 0), expectedLight(), 2e-3);
}

TEST(OcclusionMapCli, AMissingMapWarnsOnceAndIsOpenSkyABadOneStopsAtItsLine) {
    test::TempDir tmp("occlmapbad");
    writeFile(tmp.path(), "occlview.sl", kShader);
    writeFile(tmp.path(), "missing.rib", pictureFrame(1, "missing.####.exr"));
    const test::CliRun m = runIn(tmp.path(), "missing.rib");
    ASSERT_EQ(m.exitCode, 0) << m.output;
    const size_t w = m.output.find("\"occl.sm\" is written by no pass");
    EXPECT_NE(w, std::string::npos) << m.output;
    EXPECT_EQ(m.output.find("\"occl.sm\" is written by no pass", w + 1), std::string::npos) << "warned once";
    EXPECT_EQ(readImage(tmp.path() + "/missing.0001.exr").at(4, 4, 0), 1.0f);

    // Not a depth map (a picture), then a depth map cut short: exit 2 naming the file and line.
    writeFile(tmp.path(), "scene.rib", depthFrames() + pictureFrame(9, "pic.####.exr"));
    ASSERT_EQ(runIn(tmp.path(), "scene.rib -q").exitCode, 0);
    fs::copy_file(tmp.path() + "/pic.0009.exr", tmp.path() + "/occl.sm", fs::copy_options::overwrite_existing);
    const test::CliRun notMap = runIn(tmp.path(), "missing.rib");
    EXPECT_EQ(notMap.exitCode, 2) << notMap.output;
    EXPECT_NE(notMap.output.find("missing.rib:"), std::string::npos) << notMap.output;
    EXPECT_NE(notMap.output.find("not a depth map"), std::string::npos) << notMap.output;

    ASSERT_EQ(runIn(tmp.path(), "scene.rib -q").exitCode, 0);
    const auto size = fs::file_size(tmp.path() + "/occl.sm");
    fs::resize_file(tmp.path() + "/occl.sm", size * 2 / 3);
    const test::CliRun cut = runIn(tmp.path(), "missing.rib");
    EXPECT_EQ(cut.exitCode, 2) << cut.output;
    EXPECT_NE(cut.output.find("missing.rib:"), std::string::npos) << cut.output;
    EXPECT_NE(cut.output.find("occl.sm"), std::string::npos) << cut.output;
}

}  // namespace
}  // namespace streyes
