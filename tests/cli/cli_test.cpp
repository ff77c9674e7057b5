// The streyes command as a user runs it: exit codes, messages, files written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "raster/sample_kernels.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;

using Json = nlohmann::ordered_json;
using test::CliRun;
using test::writeFile;

CliRun streyes(const std::string& args) { return test::runStreyes(args); }

std::vector<std::string> listDir(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

const char* kTiny = R"(Format 16 8 1
PixelSamples 2 2
WorldBegin
Surface "constant"
Patch "bilinear" "P" [-0.5 -0.5 1  0.5 -0.5 1  -0.5 0.5 1  0.5 0.5 1]
WorldEnd
)";

TEST(Cli, HelpAndUsageErrors) {
    CliRun help = streyes("--help");
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_NE(help.output.find("streyes render"), std::string::npos);
    CliRun bad = streyes("render --bogus x.rib");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.output.find("unknown option '--bogus'"), std::string::npos);
    // The message, the synopsis and where the options are; not the whole help, which would scroll
    // the message away.
    EXPECT_NE(bad.output.find("usage: streyes render"), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find("streyes render --help lists the options."), std::string::npos) << bad.output;
    EXPECT_EQ(bad.output.find("--tolerance EPS"), std::string::npos) << bad.output;
    EXPECT_EQ(bad.output.find("unknown option"), bad.output.find("streyes: ") + 9);  // the first line
    CliRun badFrames = streyes("render x.rib --frames 5-2");
    EXPECT_EQ(badFrames.exitCode, 2);
}

TEST(Cli, MissingSceneIsBadInput) {
    CliRun r = streyes("render /nonexistent/scene.rib -o /tmp/x.exr");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("/nonexistent/scene.rib"), std::string::npos) << r.output;
}

TEST(Cli, MalformedRibExits2WithFileAndLine) {
    const test::TempDir tempDir("cli-bad");
    const std::string& dir = tempDir.path();
    std::string scene = writeFile(dir, "bad.rib", "Format 16 8 1\nWorldBegin\nTranslate 1 2\nWorldEnd\n");
    CliRun r = streyes("render " + scene + " -o " + dir + "/out.####.exr");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("bad.rib:3: error:"), std::string::npos) << r.output;
    EXPECT_EQ(listDir(dir), std::vector<std::string>{"bad.rib"});  // nothing written
}

TEST(Cli, UnknownRequestWarnsOnceAndRenders) {
    const test::TempDir tempDir("cli-warn");
    const std::string& dir = tempDir.path();
    std::string rib = std::string("ShaderGroupBegin \"plastic\" \"a\"\n") + kTiny;  // a later RenderMan's request
    rib.insert(rib.find("WorldEnd"), "ShaderGroupBegin \"plastic\" \"b\"\n");
    std::string scene = writeFile(dir, "warn.rib", rib);
    CliRun r = streyes("render " + scene + " -o " + dir + "/out.####.exr");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("warn.rib:1: warning: unknown request 'ShaderGroupBegin' ignored"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("warn.rib:7: warning:"), std::string::npos) << "warned twice: " << r.output;
    ImageData img = readImage(dir + "/out.0000.exr");
    EXPECT_EQ(img.width, 16);
    EXPECT_GT(img.at(8, 4, img.channelIndex("A")), 0.99f);
}

TEST(Cli, WritesHalfRgbaAndFloatZWithStats) {
    const test::TempDir tempDir("cli-exr");
    const std::string& dir = tempDir.path();
    std::string scene = writeFile(dir, "tiny.rib", kTiny);
    CliRun r = streyes("render " + scene + " --frames 3-4 --res 20x10 -o " + dir + "/f.####.exr --stats " + dir +
                    "/stats.json --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output, "");  // --quiet
    EXPECT_EQ(listDir(dir), (std::vector<std::string>{"f.0003.exr", "f.0004.exr", "stats.json", "tiny.rib"}));
    ImageData img = readImage(dir + "/f.0003.exr");
    EXPECT_EQ(img.width, 20);
    EXPECT_EQ(img.height, 10);
    ASSERT_EQ(img.channels, (std::vector<std::string>{"R", "G", "B", "A", "Z"}));
    EXPECT_EQ(img.formats, (std::vector<std::string>{"half", "half", "half", "half", "float"}));
    EXPECT_FLOAT_EQ(img.at(10, 5, 4), 1.0f);  // Z: camera-space depth of the patch
    std::ifstream f(dir + "/stats.json");
    const Json json = Json::parse(f);
    EXPECT_EQ(json["counters"]["eye_splits"], 0);
    EXPECT_EQ(json["frames"], Json::array({3, 4}));
}

// An animation's EXR chunks (16 scanlines each) that equal the frame before's are stored as it
// stored them, and --stats counts them: a still background under a box moving in the top rows,
// 32x64 pixels, 4 chunks a frame. The count is checked against the frames read back: a chunk is
// reused exactly where its 16 rows equal the frame before's.
TEST(Cli, StatsCountTheExrChunksReusedFromTheFrameBefore) {
    const test::TempDir tempDir("cli-chunks");
    const std::string& dir = tempDir.path();
    const std::string scene = writeFile(dir, "box.rib", R"(Format 32 64 1
PixelSamples 2 2
Projection "orthographic"
ScreenWindow 0 32 0 64
Option "streyes" "int frames" [1 3]
WorldBegin
Surface "constant"
Color [0.2 0.3 0.4]
Patch "bilinear" "P" [0 0 5  32 0 5  0 64 5  32 64 5]
AttributeBegin
Color [1 0.5 0]
MotionBegin [1 3]
Translate 2 0 0
Translate 20 0 0
MotionEnd
Patch "bilinear" "P" [0 54 2  6 54 2  0 61 2  6 61 2]
AttributeEnd
WorldEnd
)");
    const CliRun r = streyes("render " + scene + " -o " + dir + "/f.####.exr --stats " + dir + "/stats.json --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::vector<ImageData> frames;
    for (const char* f : {"/f.0001.exr", "/f.0002.exr", "/f.0003.exr"}) frames.push_back(readImage(dir + f));
    int same = 0;
    for (size_t f = 1; f < frames.size(); ++f) {
        ASSERT_NE(frames[f - 1].pixels, frames[f].pixels);  // the box moved: no frame is the last
        for (int chunk = 0; chunk < 4; ++chunk) {
            bool equal = true;
            for (int y = chunk * 16; y < chunk * 16 + 16; ++y)
                for (int x = 0; x < 32; ++x)
                    for (size_t c = 0; c < frames[f].channels.size(); ++c) {
                        const float a = frames[f - 1].at(x, y, int(c)), b = frames[f].at(x, y, int(c));
                        equal = equal && std::memcmp(&a, &b, sizeof a) == 0;
                    }
            same += equal;
        }
    }
    EXPECT_EQ(same, 6);  // the box stays in the first chunk's rows
    std::ifstream in(dir + "/stats.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(json.find("\"exr_chunks_reused\": " + std::to_string(same) + ","), std::string::npos) << json;
    EXPECT_NE(json.find("\"exr_chunks_compressed\": " + std::to_string(12 - same) + ","), std::string::npos) << json;
}

// Bodies exist over the shot only: frames outside --shot would render empty, so they are refused.
TEST(Cli, FramesOutsideTheShotAreBadInput) {
    const test::TempDir tempDir("cli-shot");
    const std::string& dir = tempDir.path();
    const std::string scene = writeFile(dir, "tiny.rib", kTiny);
    const CliRun r = streyes("render " + scene + " --frames 3 --shot 4-6 -o " + dir + "/f.####.exr");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("frames 3-3 lie outside the shot 4-6 (--shot)"), std::string::npos) << r.output;
    EXPECT_EQ(listDir(dir), (std::vector<std::string>{"tiny.rib"}));  // nothing written
    const CliRun inside = streyes("render " + scene + " --frames 4 --shot 4-6 -q -o " + dir + "/f.####.exr");
    EXPECT_EQ(inside.exitCode, 0) << inside.output;
    EXPECT_GT(readImage(dir + "/f.0004.exr").at(8, 4, 3), 0.99f);  // the patch is there
}

// DepthOfField from the command line: a bad lens exits 2 at its line; --dof-preview writes every
// frame, blurred (the square's edge spreads over pixels the pinhole leaves empty).
TEST(Cli, DepthOfFieldPreviewWritesEveryFrameBlurred) {
    const test::TempDir tempDir("cli-dof");
    const std::string& dir = tempDir.path();
    const std::string head = "Format 32 16 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 2 2\n";
    const std::string world = "WorldBegin\nSurface \"constant\"\n"
                              "Patch \"bilinear\" \"P\" [-3 -3 6  0 -3 6  -3 3 6  0 3 6]\nWorldEnd\n";
    std::string bad = writeFile(dir, "bad.rib", head + "\nDepthOfField 2 0 3\n" + world);
    CliRun r = streyes("render " + bad + " -o " + dir + "/b.####.exr");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("bad.rib:5:"), std::string::npos) << r.output;
    EXPECT_EQ(streyes("render " + bad + " --dof-preview 0").exitCode, 2);
    std::string scene = writeFile(dir, "dof.rib", head + "DepthOfField 1 1 2\n" + world);
    r = streyes("render " + scene + " --frames 0-1 --dof-preview 4 -o " + dir + "/p.####.exr --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(listDir(dir), (std::vector<std::string>{"bad.rib", "dof.rib", "p.0000.exr", "p.0001.exr"}));
    // The square's right edge x = 0 is at the image's centre; its blur (a circle of confusion of
    // 1 / (2 * 1) * (1/2 - 1/6) * 22 = 3.7 pixels) covers part of the pixel right of the centre.
    ImageData img = readImage(dir + "/p.0001.exr");
    const float a = img.at(17, 8, 3);
    EXPECT_GT(a, 0.02f);
    EXPECT_LT(a, 0.98f);
    EXPECT_FLOAT_EQ(img.at(10, 8, 3), 1.0f);  // over 3.7 pixels from every edge
}

// --preview: half the scene's resolution, at most 4 samples per pixel, exact culling; options
// given explicitly win.
TEST(Cli, PreviewHalvesResolutionAndCapsSamples) {
    const test::TempDir tempDir("cli-preview");
    const std::string& dir = tempDir.path();
    auto statsOf = [&](const std::string& pixelSamples, const std::string& options) {
        std::string rib = kTiny;
        rib.replace(rib.find("PixelSamples 2 2"), 16, "PixelSamples " + pixelSamples);
        const std::string scene = writeFile(dir, "tiny.rib", rib);
        CliRun r = streyes("render " + scene + " --preview " + options + " -o " + dir + "/f.####.exr --stats " + dir +
                           "/stats.json --quiet");
        EXPECT_EQ(r.exitCode, 0) << r.output;
        std::ifstream f(dir + "/stats.json");
        return Json::parse(f);
    };
    Json s = statsOf("4 4", "");
    EXPECT_EQ(s["resolution"], Json::array({8, 4})) << s;  // the scene's 16x8, halved
    EXPECT_EQ(s["samples_per_pixel"], 4) << s;
    EXPECT_EQ(s["tolerance"], 0.0) << s;
    s = statsOf("1 1", "");  // never more samples than the scene's own
    EXPECT_EQ(s["samples_per_pixel"], 1) << s;
    s = statsOf("4 4", "--res 12x6 --samples 9 --tolerance 0.1");
    EXPECT_EQ(s["resolution"], Json::array({12, 6})) << s;
    EXPECT_EQ(s["samples_per_pixel"], 9) << s;
    EXPECT_EQ(s["tolerance"], 0.1) << s;
}

// A Blobby is cut while the scene is read, for the size the frames are rendered at: --res and
// --preview give the same pixels as a scene whose Format is that size.
TEST(Cli, BlobbyIsCutForTheSizeRendered) {
    const test::TempDir tempDir("cli-blobby-res");
    const std::string& dir = tempDir.path();
    auto render = [&](int format, const std::string& options) {
        const std::string rib = "Format " + std::to_string(format) + " " + std::to_string(format) +
                                " 1\nPixelSamples 2 2\nProjection \"perspective\" \"fov\" [40]\nTranslate 0 0 5\n"
                                "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [1 -1 2]\n"
                                "Surface \"matte\"\nBlobby 2 [1001 0  1001 16  0 2 0 1]\n"
                                "[1.5 0 0 0  0 1.5 0 0  0 0 1.5 0  -0.4 0 0 1  1 0 0 0  0 1 0 0  0 0 1 0  0.8 0.3 0 1]"
                                " [\"\"]\nWorldEnd\n";
        const std::string scene = writeFile(dir, "blob" + std::to_string(format) + ".rib", rib);
        const std::string out = dir + "/f" + std::to_string(format) + std::to_string(options.size()) + ".exr";
        const CliRun r = streyes("render " + scene + " " + options + " -o " + out + " --quiet");
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return readImage(out);
    };
    const ImageData at64 = render(64, "");
    EXPECT_GT(at64.at(32, 32, 3), 0.99f);  // the blob fills the middle
    EXPECT_EQ(render(32, "--res 64x64").pixels, at64.pixels);
    EXPECT_EQ(render(128, "--preview").pixels, at64.pixels);  // half of 128, the scene's 4 samples
}

// "streyes: P% (D/32 buckets), M:SS elapsed, ETA M:SS", exactly.
bool isProgressLine(const std::string& line) {
    int percent = 0, done = 0, total = 0, em = 0, es = 0, rm = 0, rs = 0, end = 0;
    if (std::sscanf(line.c_str(), "streyes: %d%% (%d/%d buckets), %d:%d elapsed, ETA %d:%d%n", &percent, &done, &total,
                    &em, &es, &rm, &rs, &end) != 7)
        return false;
    char again[128];
    std::snprintf(again, sizeof again, "streyes: %d%% (%d/%d buckets), %d:%02d elapsed, ETA %d:%02d", percent, done,
                  total, em, es, rm, rs);
    return size_t(end) == line.size() && line == again && total == 32 && es < 60 && rs < 60;
}

// Off a terminal, progress is one plain line per tenth of the buckets done, without carriage
// returns: 64x32 pixels in 8-pixel buckets are 32 buckets, each under a tenth of the render. On one
// thread buckets finish in order, so the lines are those of the first bucket past each tenth
// (4/32 = 12%, 7/32 = 21%, ...); on two they may finish out of order, and still the percentages
// only rise, one line per tenth, ending with 100%.
TEST(Cli, ProgressOffATerminalIsOneLinePerTenth) {
    const test::TempDir tempDir("cli-progress");
    const std::string& dir = tempDir.path();
    std::string scene = writeFile(dir, "tiny.rib", kTiny);
    for (const char* threads : {"1", "2"}) {
        const std::string log = dir + "/stderr" + threads + ".txt";
        ASSERT_EQ(test::runStreyesLogged("render " + scene + " --res 64x32 --bucket 8 --threads " + threads + " -o " +
                                             dir + "/f.####.exr",
                                         log),
                  0);
        const std::string text = test::readFile(log);
        EXPECT_EQ(text.find('\r'), std::string::npos) << text;
        std::vector<int> percents, tenths;
        std::istringstream lines(text);
        for (std::string l; std::getline(lines, l);) {
            if (!isProgressLine(l)) continue;
            int percent = 0, done = 0;
            std::sscanf(l.c_str(), "streyes: %d%% (%d/32 buckets)", &percent, &done);
            EXPECT_EQ(percent, done * 100 / 32) << l;
            percents.push_back(percent);
            tenths.push_back(done * 10 / 32);
        }
        EXPECT_EQ(tenths, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10})) << text;
        EXPECT_TRUE(std::is_sorted(percents.begin(), percents.end())) << text;
        if (std::string(threads) == "1") {
            EXPECT_EQ(percents, (std::vector<int>{12, 21, 31, 40, 50, 62, 71, 81, 90, 100})) << text;
        }
        // Then the summary, after the last progress line.
        const size_t summary = text.find("streyes: 1 frame 64x32");
        ASSERT_NE(summary, std::string::npos) << text;
        EXPECT_LT(text.find("streyes: 100% (32/32 buckets)"), summary) << text;
    }
    // --quiet: no progress either.
    const std::string quiet = dir + "/quiet.txt";
    ASSERT_EQ(test::runStreyesLogged("render " + scene + " --res 64x32 --bucket 8 -q -o " + dir + "/f.####.exr", quiet),
              0);
    EXPECT_EQ(test::readFile(quiet), "");
}

// A square off the pixel grid and slanted in depth: edge pixels are partly covered, so frames
// that agree bit for bit agree on where every sample lies and what it sees.
const char* kOffGrid = R"(Format 16 8 1
PixelSamples 2 2
WorldBegin
Surface "constant"
Patch "bilinear" "P" [-0.43 -0.37 1  0.61 -0.37 1  -0.43 0.52 1.2  0.61 0.52 1.2]
WorldEnd
)";

// Where two images read back differ (channel names and every value: bit for bit as written,
// half RGBA and float Z, but Z within a relative zTolerance); empty when they do not.
std::string imageDifference(const ImageData& a, const ImageData& b, float zTolerance = 0) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels) return "different sizes or channels";
    if (a.pixels.size() != b.pixels.size()) return "different pixel counts";
    const size_t nc = a.channels.size();
    for (size_t i = 0; i < a.pixels.size(); ++i)
        if (a.channels[i % nc] == "Z" && zTolerance > 0
                ? !(test::absDifference(a.pixels[i], b.pixels[i]) <= zTolerance * std::fabs(a.pixels[i]))
                : std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) != 0)
            return "pixel " + std::to_string(i / nc % size_t(a.width)) + "," + std::to_string(i / nc / size_t(a.width)) +
                   " " + a.channels[i % nc] + ": " + std::to_string(a.pixels[i]) + " against " +
                   std::to_string(b.pixels[i]);
    return "";
}

// The ray tracer sees the same flat, constant-coloured square through the same samples as the
// rasterizer (which dices it exactly: it is flat): the same colour and coverage, bit for bit, and
// depths equal to float rounding (the rasterizer interpolates them across micropolygons, the ray
// tracer solves for each hit: a few float ulps, beyond 1e-7 relative but within 1e-6). One hierarchy for
// every frame finds the same nearest hits as one per frame: bit for bit, depth included.
TEST(Cli, RaytraceWritesTheSameFramesAndItsCounters) {
    const test::TempDir tempDir("cli-raytrace");
    const std::string& dir = tempDir.path();
    std::string scene = writeFile(dir, "offgrid.rib", kOffGrid);
    auto render = [&](const std::string& alg) {
        CliRun r = streyes("render " + scene + " --algorithm " + alg + " -o " + dir + "/" + alg + ".####.exr --stats " +
                           dir + "/" + alg + ".json --quiet");
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return readImage(dir + "/" + alg + ".0000.exr");
    };
    const ImageData raster = render("spacetime");
    ASSERT_EQ(raster.channels, (std::vector<std::string>{"R", "G", "B", "A", "Z"}));
    int covered = 0, partly = 0;
    for (int y = 0; y < raster.height; ++y)
        for (int x = 0; x < raster.width; ++x) {
            const float a = raster.at(x, y, raster.channelIndex("A"));
            covered += a == 1.0f;
            partly += a > 0.0f && a < 1.0f;
        }
    EXPECT_GE(covered, 4);  // the square is about 4 x 4 pixels, with partly covered rims
    EXPECT_GE(partly, 8);
    const ImageData traced = render("raytrace");
    EXPECT_EQ(imageDifference(raster, traced, 1e-6f), "");
    EXPECT_EQ(imageDifference(traced, render("raytrace-frames")), "");
    for (const char* alg : {"raytrace", "raytrace-frames"}) {
        std::ifstream f(dir + "/" + alg + ".json");
        std::string json((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
        EXPECT_NE(json.find(std::string("\"algorithm\": \"") + alg + "\""), std::string::npos) << json;
        EXPECT_NE(json.find("\"bounding_volumes\": 1,"), std::string::npos) << json;
        EXPECT_NE(json.find("\"eye_rays\": 512,"), std::string::npos) << json;  // 16 x 8 pixels x 4 samples
    }
    CliRun bad = streyes("render " + scene + " --algorithm raytraced");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.output.find("frames, raytrace or raytrace-frames"), std::string::npos) << bad.output;
}

// --simd caps the sample kernels' instruction set: each one this CPU runs gives the default's
// frames bit for bit (a still patch, a moving one and a lens: every kernel), and --stats names it.
TEST(Cli, SimdCapKeepsThePixels) {
    const test::TempDir tempDir("cli-simd");
    const std::string& dir = tempDir.path();
    const std::string scene = writeFile(dir, "simd.rib", R"(Format 24 16 1
Projection "perspective" "fov" [40]
DepthOfField 8 0.2 3
PixelSamples 3 3
Shutter 0 0.5
WorldBegin
Surface "constant"
Patch "bilinear" "P" [-0.43 -0.37 3  0.61 -0.37 3  -0.43 0.52 3.2  0.61 0.52 3.2]
AttributeBegin
Color [1 0 0]
MotionBegin [0 1]
Translate -0.3 0 0
Translate 0.4 0.1 0
MotionEnd
Patch "bilinear" "P" [-0.2 -0.2 2.5  0.2 -0.2 2.5  -0.2 0.2 2.5  0.2 0.2 2.5]
AttributeEnd
WorldEnd
)");
    auto render = [&](const std::string& name, const std::string& simd) {
        CliRun r = streyes("render " + scene + " --frames 0-1" + (simd.empty() ? "" : " --simd " + simd) + " -o " + dir +
                           "/" + name + ".####.exr --stats " + dir + "/" + name + ".json --quiet");
        EXPECT_EQ(r.exitCode, 0) << r.output;
        std::ifstream f(dir + "/" + name + ".json");
        return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    };
    const std::vector<std::string> targets = simdTargets();
    ASSERT_FALSE(targets.empty());
    const std::string best = render("best", "");
    EXPECT_NE(best.find("\"simd\": \"" + targets.front() + "\""), std::string::npos) << best;
    const ImageData frame1 = readImage(dir + "/best.0001.exr");
    float red = 0;
    for (int y = 0; y < frame1.height; ++y)
        for (int x = 0; x < frame1.width; ++x) red = std::max(red, frame1.at(x, y, 0) - frame1.at(x, y, 1));
    EXPECT_GT(red, 0.5f);  // the moving patch is in the frame
    for (const std::string& t : targets) {
        const std::string json = render(t, t == "AVX3" ? "avx512" : t);
        EXPECT_NE(json.find("\"simd\": \"" + t + "\""), std::string::npos) << json;
        for (const char* f : {".0000.exr", ".0001.exr"})
            EXPECT_EQ(imageDifference(readImage(dir + "/best" + f), readImage(dir + "/" + t + f)), "") << t << f;
    }
    CliRun bad = streyes("render " + scene + " --simd avx9000");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.output.find("no instruction set 'avx9000'"), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find(targets.front()), std::string::npos) << bad.output;
}

TEST(Cli, UnwritableOutputFailsCleanly) {
    const test::TempDir tempDir("cli-unwritable");
    const std::string& dir = tempDir.path();
    std::string scene = writeFile(dir, "tiny.rib", kTiny);
    // A folder that does not exist.
    CliRun missing = streyes("render " + scene + " -o " + dir + "/no/such/folder/f.####.exr");
    EXPECT_EQ(missing.exitCode, 1) << missing.output;
    EXPECT_NE(missing.output.find("does not exist"), std::string::npos) << missing.output;
    // A "folder" that is a file.
    writeFile(dir, "afile", "x");
    CliRun notDir = streyes("render " + scene + " -o " + dir + "/afile/f.####.exr");
    EXPECT_EQ(notDir.exitCode, 1);
    // The final name is taken by a folder: the write fails at the rename, the temporary is removed.
    fs::create_directory(dir + "/f.0000.exr");
    CliRun blocked = streyes("render " + scene + " -o " + dir + "/f.####.exr");
    EXPECT_EQ(blocked.exitCode, 1) << blocked.output;
    EXPECT_NE(blocked.output.find("cannot write"), std::string::npos) << blocked.output;
    EXPECT_EQ(listDir(dir), (std::vector<std::string>{"afile", "f.0000.exr", "tiny.rib"}));
    EXPECT_TRUE(fs::is_empty(dir + "/f.0000.exr"));
}

}  // namespace
}  // namespace streyes
