// Passes through the streyes command (streyes/passes.h): depth frames and pictures in one file,
// each picture reading its own frame's maps; --frames and -o; zooms; autoshadows; bad maps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <tuple>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;
using test::listDir;
using test::readFile;
using test::runStreyesWith;
using test::writeFile;

test::CliRun renderIn(const std::string& dir, const std::string& args) {
    return runStreyesWith("cd " + dir + " && ", "render " + args);
}

std::string copyScene(const std::string& dir, const std::string& name) {
    fs::copy_file(test::sourcePath("scenes/shadows/" + name), dir + "/" + name);
    return name;
}

bool samePixels(const std::string& a, const std::string& b) {
    const ImageData x = readImage(a), y = readImage(b);
    return x.width == y.width && x.height == y.height && x.channels == y.channels && x.pixels == y.pixels;
}

// RMSE of R G B (infinite when the images differ in size).
double rmse(const std::string& a, const std::string& b) {
    const ImageData x = readImage(a), y = readImage(b);
    if (x.width != y.width || x.height != y.height) return INFINITY;
    double sum = 0;
    for (int py = 0; py < x.height; ++py)
        for (int px = 0; px < x.width; ++px)
            for (int c = 0; c < 3; ++c) sum += std::pow(double(x.at(px, py, c)) - y.at(px, py, c), 2);
    return std::sqrt(sum / (3.0 * x.width * x.height));
}

// The fraction of a picture's light a shadow takes: 1 - (sum of RGB) / (sum of RGB unshadowed).
double darkened(const std::string& shadowed, const std::string& lit) {
    const ImageData s = readImage(shadowed), l = readImage(lit);
    double a = 0, b = 0;
    for (int y = 0; y < l.height; ++y)
        for (int x = 0; x < l.width; ++x)
            for (int c = 0; c < 3; ++c) a += s.at(x, y, c), b += l.at(x, y, c);
    return 1 - a / b;
}

// The same scene file with every shadow map name blanked: its pictures unshadowed.
std::string withoutShadows(const std::string& dir, const std::string& name) {
    std::string text = readFile(dir + "/" + name);
    for (const char* map : {"key.shd", "rim.shd", "autoshadow.shad"})
        for (size_t at; (at = text.find("[\"" + std::string(map) + "\"]")) != std::string::npos;)
            text.replace(at, std::string(map).size() + 4, "[\"\"]");
    for (size_t at; (at = text.find("Attribute \"autoshadows\"")) != std::string::npos;)
        text.replace(at, 10, "#ttribute ");  // a comment line from there
    return writeFile(dir, "lit-" + name, text);
}

// As exporters write a shot (scenes/shadows/shot.rib): per frame a depth frame writing key.z,
// MakeShadow key.z key.shd, the picture reading key.shd. The whole file renders the depth frames as
// one job and the pictures as another; each picture is the one its own frame's passes give alone
// (--frames f renders that frame's depth frame, MakeShadow and picture), bit for bit with
// --algorithm frames. Were a picture handed another frame's map (the last written, say), its
// bouncing ball's shadow would be elsewhere.
TEST(PassesCli, EachPictureReadsTheMapItsOwnFrameMade) {
    test::TempDir tmp("passes-shot");
    copyScene(tmp.path(), "shot.rib");
    test::CliRun r = renderIn(tmp.path(), "shot.rib --algorithm frames --stats s.json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("8 frames"), std::string::npos) << r.output;
    fs::create_directory(tmp.path() + "/whole");
    for (int f = 1; f <= 8; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "shot.%04d.exr", f);
        fs::rename(tmp.path() + "/" + name, tmp.path() + "/whole/" + name);
    }
    EXPECT_TRUE(fs::exists(tmp.path() + "/key.z"));
    EXPECT_TRUE(fs::exists(tmp.path() + "/key.shd"));
    for (int f : {2, 5, 8}) {
        r = renderIn(tmp.path(), "shot.rib --algorithm frames -q --frames " + std::to_string(f));
        ASSERT_EQ(r.exitCode, 0) << r.output;
        char name[32];
        std::snprintf(name, sizeof name, "shot.%04d.exr", f);
        EXPECT_TRUE(samePixels(tmp.path() + "/" + name, tmp.path() + "/whole/" + name)) << "frame " << f;
    }
    EXPECT_FALSE(samePixels(tmp.path() + "/whole/shot.0002.exr", tmp.path() + "/whole/shot.0005.exr"));
    // The shadows are there: the unshadowed pictures are brighter.
    withoutShadows(tmp.path(), "shot.rib");
    ASSERT_EQ(renderIn(tmp.path(), "lit-shot.rib --algorithm frames -q --frames 5 -o lit.####.exr").exitCode, 0);
    EXPECT_GT(darkened(tmp.path() + "/whole/shot.0005.exr", tmp.path() + "/lit.0005.exr"), 0.02);
    // The default algorithm: the pictures against the frames' own, within the sampling noise.
    ASSERT_EQ(renderIn(tmp.path(), "shot.rib -q -o st.####.exr").exitCode, 0);
    ASSERT_EQ(renderIn(tmp.path(), "shot.rib -q --frames 5 -o one.####.exr").exitCode, 0);
    EXPECT_LT(rmse(tmp.path() + "/st.0005.exr", tmp.path() + "/one.0005.exr"), 0.005);
}

// The same shot as a frame pattern, a file a frame each holding its depth frame, MakeShadow and
// picture (the blocks of a frame's file are its passes): the same pictures as the one file.
TEST(PassesCli, AFramePatternsFilesHoldEachFramesPasses) {
    test::TempDir tmp("passes-pattern");
    const std::string text = readFile(test::sourcePath("scenes/shadows/shot.rib"));
    for (int f = 1; f <= 3; ++f) {
        // Frame f: its depth FrameBegin, the MakeShadow after it, its picture FrameBegin.
        const size_t a = text.find("FrameBegin " + std::to_string(f) + "\n");
        const size_t b = text.find("FrameBegin " + std::to_string(f + 1) + "\n");
        char name[32];
        std::snprintf(name, sizeof name, "shot.%04d.rib", f);
        writeFile(tmp.path(), name, text.substr(a, b == std::string::npos ? std::string::npos : b - a));
    }
    test::CliRun r = renderIn(tmp.path(), "'shot.####.rib' --algorithm frames -o p.####.exr");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    fs::copy_file(test::sourcePath("scenes/shadows/shot.rib"), tmp.path() + "/whole.rib");
    r = renderIn(tmp.path(), "whole.rib --algorithm frames -q --frames 1-3 -o w.####.exr");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (int f = 1; f <= 3; ++f) {
        char a[32], b[32];
        std::snprintf(a, sizeof a, "/p.%04d.exr", f);
        std::snprintf(b, sizeof b, "/w.%04d.exr", f);
        EXPECT_TRUE(samePixels(tmp.path() + a, tmp.path() + b)) << "frame " << f;
    }
}

// --frames picks pictures and renders the depth frames they read; -o names the pictures' files
// only (the maps go to their Display names).
TEST(PassesCli, FramesPicksPicturesAndOutputNamesOnlyThem) {
    test::TempDir tmp("passes-frames");
    copyScene(tmp.path(), "lamps.rib");  // depth frames 1 and 2, MakeShadow x 2, picture 3
    const test::CliRun r = renderIn(tmp.path(), "lamps.rib --frames 3 -o pic.####.exr");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    const std::vector<std::string> files = listDir(tmp.path());
    EXPECT_EQ(files, (std::vector<std::string>{"key.shd", "key.z", "lamps.rib", "pic.0003.exr", "rim.shd", "rim.z"}));
    withoutShadows(tmp.path(), "lamps.rib");
    ASSERT_EQ(renderIn(tmp.path(), "lit-lamps.rib --frames 3 -q -o lit.####.exr").exitCode, 0);
    const double dark = darkened(tmp.path() + "/pic.0003.exr", tmp.path() + "/lit.0003.exr");
    EXPECT_GT(dark, 0.05);
    EXPECT_LT(dark, 0.6);
}

// A still light over a still set makes the same map every frame: one map serves them all, and
// what reads it stays still: six frames' depth frames and pictures are diced and shaded as one's.
TEST(PassesCli, AStillLightOverAStillSetIsRenderedOnceForTheShot) {
    test::TempDir tmp("passes-still");
    const std::string text = readFile(test::sourcePath("scenes/shadows/lamps.rib"));
    // Frames 1 (key light's map), 2 (rim light's) and 3 (the picture), made a shot of six: frames
    // 1-6 of each, every frame reusing the names.
    const size_t two = text.find("FrameBegin 2"), makes = text.find("MakeShadow \""), three = text.find("FrameBegin 3");
    const std::string key = text.substr(text.find("FrameBegin 1"), two - text.find("FrameBegin 1"));
    const std::string rim = text.substr(two, makes - two), make = text.substr(makes, three - makes);
    const std::string picture = text.substr(three);
    auto numbered = [](std::string frame, int f) {
        frame.replace(frame.find("FrameBegin ") + 11, 1, std::to_string(f));
        return frame;
    };
    std::string shot;
    for (int f = 1; f <= 6; ++f) shot += numbered(key, f) + numbered(rim, f) + make + numbered(picture, f);
    // The picture's Display has no frame field: give it one.
    for (size_t at; (at = shot.find("\"lamps.exr\"")) != std::string::npos;) shot.replace(at, 11, "\"lamps.####.exr\"");
    writeFile(tmp.path(), "still.rib", shot);
    // Without occlusion culling, whose depth layers adapt to how many frames a block holds.
    test::CliRun r = renderIn(tmp.path(), "still.rib -q --algorithm spacetime --stats six.json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = renderIn(tmp.path(), "still.rib -q --algorithm spacetime --frames 1 --stats one.json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    auto count = [&](const std::string& file, const std::string& key) {
        const std::string json = readFile(tmp.path() + "/" + file);
        const size_t at = json.find("\"" + key + "\": ");
        return at == std::string::npos ? -1L : std::stol(json.substr(at + key.size() + 4));
    };
    EXPECT_GT(count("one.json", "grids_diced"), 0);
    EXPECT_EQ(count("six.json", "grids_diced"), count("one.json", "grids_diced"));
    EXPECT_EQ(count("six.json", "micropolygons"), count("one.json", "micropolygons"));
    EXPECT_TRUE(samePixels(tmp.path() + "/lamps.0001.exr", tmp.path() + "/lamps.0006.exr"));
}

// A zoom: the field of view narrows every frame. The frames are one pass (docs/ARCHITECTURE.md,
// "Zooms"): one spacetime render a block of frames, each frame under its own projection, and a
// frame renders what it renders alone, whatever the block, algorithm or thread count.
TEST(PassesCli, AZoomIsOnePassAndAFrameAloneEqualsTheFrameInEveryBlock) {
    test::TempDir tmp("passes-zoom");
    copyScene(tmp.path(), "zoom.rib");
    auto renders = [&](const std::string& stats) {
        const std::string json = readFile(tmp.path() + "/" + stats);
        const size_t at = json.find("\"renders\": ");
        return at == std::string::npos ? -1 : std::stoi(json.substr(at + 11));
    };
    auto frameFile = [](const std::string& stem, int f) {
        char n[64];
        std::snprintf(n, sizeof n, "/%s.%04d.exr", stem.c_str(), f);
        return std::string(n);
    };
    for (const std::string algorithm : {"spacetime-occlusion", "spacetime", "frames", "raytrace"}) {
        const std::string a = " --algorithm " + algorithm;
        for (int f = 1; f <= 4; ++f) {
            const test::CliRun r =
                renderIn(tmp.path(), "zoom.rib -q" + a + " -o " + algorithm + "-one.####.exr --frames " + std::to_string(f));
            ASSERT_EQ(r.exitCode, 0) << r.output;
        }
        for (int block : {4, 3, 2}) {
            const std::string stem = algorithm + "-b" + std::to_string(block);
            const test::CliRun r = renderIn(tmp.path(), "zoom.rib" + a + " --frame-block " + std::to_string(block) +
                                                            " -o " + stem + ".####.exr --stats " + stem + ".json");
            ASSERT_EQ(r.exitCode, 0) << r.output;
            EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
            EXPECT_EQ(renders(stem + ".json"), (4 + block - 1) / block) << algorithm << ", blocks of " << block;
            for (int f = 1; f <= 4; ++f)
                EXPECT_TRUE(samePixels(tmp.path() + frameFile(stem, f), tmp.path() + frameFile(algorithm + "-one", f)))
                    << algorithm << ", frame " << f << " in blocks of " << block;
        }
    }
    // Occlusion culling at tolerance 0 changes no bit; one thread gives what two give.
    ASSERT_EQ(renderIn(tmp.path(), "zoom.rib -q --threads 1 -o t1.####.exr").exitCode, 0);
    for (int f = 1; f <= 4; ++f) {
        EXPECT_TRUE(samePixels(tmp.path() + frameFile("spacetime-b4", f), tmp.path() + frameFile("spacetime-occlusion-b4", f)))
            << "frame " << f;
        EXPECT_TRUE(samePixels(tmp.path() + frameFile("t1", f), tmp.path() + frameFile("spacetime-occlusion-b4", f)))
            << "frame " << f;
    }
    EXPECT_FALSE(samePixels(tmp.path() + "/spacetime-b4.0001.exr", tmp.path() + "/spacetime-b4.0004.exr"));  // it zooms
}

// Aqsis's autoshadows: the map is rendered from the light before the picture and written.
TEST(PassesCli, AutoshadowsRenderTheMapOnTheFly) {
    test::TempDir tmp("passes-auto");
    copyScene(tmp.path(), "autoshadow.rib");
    const test::CliRun r = renderIn(tmp.path(), "autoshadow.rib");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    ASSERT_TRUE(fs::exists(tmp.path() + "/autoshadow.shad"));
    ASSERT_TRUE(fs::exists(tmp.path() + "/autoshadow.exr"));
    withoutShadows(tmp.path(), "autoshadow.rib");
    std::string lit = readFile(tmp.path() + "/lit-autoshadow.rib");
    lit.replace(lit.find("autoshadow.exr"), 14, "lit.exr");
    writeFile(tmp.path(), "lit-autoshadow.rib", lit);
    ASSERT_EQ(renderIn(tmp.path(), "lit-autoshadow.rib -q").exitCode, 0);
    EXPECT_GT(darkened(tmp.path() + "/autoshadow.exr", tmp.path() + "/lit.exr"), 0.02);  // 3.6% when written
}

// A good shadow map of a sphere, made in `dir` by a depth frame and MakeShadow (good.shd): its bytes.
std::string goodShadowMap(const std::string& dir) {
    writeFile(
        dir, "make.rib",
        "FrameBegin 1\nDisplay \"good.z\" \"zfile\" \"z\"\nFormat 64 64 1\nProjection \"perspective\" \"fov\" [40]\n"
        "Translate 0 0 5\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\nFrameEnd\nMakeShadow \"good.z\" \"good.shd\"\n");
    const test::CliRun r = renderIn(dir, "make.rib -q");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return readFile(dir + "/good.shd");
}

// A picture reading maps: the light's RIB line gives the name.
std::string pictureReading(const std::string& map) {
    return "Display \"pic.exr\" \"file\" \"rgba\"\nFormat 40 30 1\nProjection \"perspective\" \"fov\" [40]\n"
           "Translate 0 0 5\nWorldBegin\n"
           "LightSource \"shadowspot\" 1 \"from\" [0 4 -2] \"to\" [0 0 0] \"shadowname\" [\"" +
           map + "\"]\nSurface \"matte\"\nSphere 1 -1 1 360\nWorldEnd\n";
}

TEST(PassesCli, AShadowMapNoPassWritesAndNoFileHoldsWarnsOnceAndLeavesSurfacesLit) {
    test::TempDir tmp("passes-missing");
    writeFile(tmp.path(), "a.rib", pictureReading("nothere.shd"));
    writeFile(tmp.path(), "b.rib", pictureReading(""));
    const test::CliRun r = renderIn(tmp.path(), "a.rib");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string warning = "a.rib:6: warning: shadow map \"nothere.shd\" is written by no pass of this render";
    EXPECT_NE(r.output.find(warning), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find(warning), r.output.rfind(warning)) << r.output;  // once
    fs::rename(tmp.path() + "/pic.exr", tmp.path() + "/a.exr");
    ASSERT_EQ(renderIn(tmp.path(), "b.rib -q").exitCode, 0);
    EXPECT_TRUE(samePixels(tmp.path() + "/a.exr", tmp.path() + "/pic.exr"));
}

// A map file that is truncated, or that is no depth map (an ordinary picture): exit 2 naming the
// line that gives its name, nothing written.
TEST(PassesCli, ABadShadowMapFileIsAnErrorNamingTheLineThatNamesIt) {
    test::TempDir tmp("passes-bad");
    const std::string good = goodShadowMap(tmp.path());
    test::CliRun r;
    ASSERT_GT(good.size(), 1000u);
    writeFile(tmp.path(), "cut.shd", good.substr(0, good.size() / 2));
    writeFile(tmp.path(), "cut.rib", pictureReading("cut.shd"));
    r = renderIn(tmp.path(), "cut.rib");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("cut.rib:6: error: shadow map \"cut.shd\""), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(tmp.path() + "/pic.exr"));
    // An ordinary picture under a map's name.
    writeFile(tmp.path(), "picture.rib",
              "Display \"notmap.tif\" \"file\" \"rgba\"\nFormat 16 16 1\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n");
    ASSERT_EQ(renderIn(tmp.path(), "picture.rib -q").exitCode, 0);
    writeFile(tmp.path(), "notmap.rib", pictureReading("notmap.tif"));
    r = renderIn(tmp.path(), "notmap.rib");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("notmap.rib:6: error: shadow map \"notmap.tif\""), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("not a depth map"), std::string::npos) << r.output;
    // The good one reads.
    writeFile(tmp.path(), "good.rib", pictureReading("good.shd"));
    r = renderIn(tmp.path(), "good.rib");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
}

// A TIFF's image size tags (ImageWidth, ImageLength) set to `width` x `height` in its first
// directory: a file whose header claims another size than its pixels hold.
std::string withTiffSize(std::string tiff, uint32_t width, uint32_t height) {
    const bool little = tiff.compare(0, 2, "II") == 0;
    auto get = [&](size_t at, int n) {
        uint32_t v = 0;
        for (int i = 0; i < n; ++i)
            v |= uint32_t(uint8_t(tiff[at + size_t(little ? i : n - 1 - i)])) << (8 * i);
        return v;
    };
    auto put = [&](size_t at, int n, uint32_t v) {
        for (int i = 0; i < n; ++i) tiff[at + size_t(little ? i : n - 1 - i)] = char((v >> (8 * i)) & 0xff);
    };
    const size_t ifd = get(4, 4);
    const uint32_t entries = get(ifd, 2);
    int set = 0;
    for (uint32_t e = 0; e < entries; ++e) {
        const size_t at = ifd + 2 + 12 * size_t(e);
        const uint32_t tag = get(at, 2), type = get(at + 2, 2);
        if (tag != 256 && tag != 257) continue;
        put(at + 8, type == 3 ? 2 : 4, tag == 256 ? width : height);  // SHORT or LONG
        ++set;
    }
    EXPECT_EQ(set, 2) << "a TIFF's first directory has ImageWidth and ImageLength";
    return tiff;
}

// A map whose header claims a larger size than its pixels hold: exit 2 naming the line that
// names it, nothing written. (One that claims a smaller size reads as the smaller map its first
// pixels make: OpenImageIO finds nothing wrong with it.)
TEST(PassesCli, AShadowMapOfTheWrongSizeIsAnErrorNamingTheLineThatNamesIt) {
    test::TempDir tmp("passes-size");
    const std::string good = goodShadowMap(tmp.path());
    ASSERT_EQ(good.compare(0, 2, good[0] == 'I' ? "II" : "MM"), 0) << "a TIFF";
    for (const auto& [name, w, h] : {std::tuple{"wide", 4096u, 4096u}, std::tuple{"tall", 64u, 65u}}) {
        SCOPED_TRACE(name);
        const std::string map = std::string(name) + ".shd";
        writeFile(tmp.path(), map, withTiffSize(good, w, h));
        writeFile(tmp.path(), "pic.rib", pictureReading(map));
        const test::CliRun r = renderIn(tmp.path(), "pic.rib");
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("pic.rib:6: error: shadow map \"" + map + "\""), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(tmp.path() + "/pic.exr"));
    }
}

// MakeShadow of a depth map that nothing makes, or of a file that is no depth map: exit 2 at its line.
TEST(PassesCli, MakeShadowOfNoDepthMapIsAnErrorAtItsLine) {
    test::TempDir tmp("passes-make");
    writeFile(tmp.path(), "a.rib", "MakeShadow \"none.z\" \"none.shd\"\n" + pictureReading("none.shd"));
    test::CliRun r = renderIn(tmp.path(), "a.rib");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("a.rib:1: error: MakeShadow: cannot read the depth map 'none.z'"), std::string::npos)
        << r.output;
    writeFile(tmp.path(), "picture.rib",
              "Display \"p.tif\" \"file\" \"rgba\"\nFormat 16 16 1\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n");
    ASSERT_EQ(renderIn(tmp.path(), "picture.rib -q").exitCode, 0);
    writeFile(tmp.path(), "b.rib", "\nMakeShadow \"p.tif\" \"p.shd\"\n" + pictureReading("p.shd"));
    r = renderIn(tmp.path(), "b.rib");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("b.rib:2: error: MakeShadow 'p.tif' -> 'p.shd'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("not a depth map"), std::string::npos) << r.output;
}

// A render farm takes a multi-pass file as the tasks will: its frames are the pictures'.
TEST(PassesCli, FarmPlansThePicturesOfAMultiPassFile) {
    test::TempDir tmp("passes-farm");
    copyScene(tmp.path(), "shot.rib");
    const test::CliRun r = runStreyesWith("cd " + tmp.path() + " && ",
                                          "farm submit shot.rib -o " + tmp.path() + "/f.####.exr --block 4 --dry-run");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("frames 1-8 (8), 320x180, in 2 blocks of 4"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace streyes
