// `streyes compare`: figures against known answers, NaN reporting, mismatches as errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>

#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::CliRun;
using test::runStreyes;

constexpr float kInf = std::numeric_limits<float>::infinity();

// An 8x4 frame: every pixel RGBA (0.5, 0.25, 0.75, 1), Z = 2, except the background pixel (7, 3)
// (RGBA 0, Z = +inf). All values are exact in half floats.
FrameImage baseFrame() {
    FrameImage f;
    f.resize(8, 4);
    for (int i = 0; i < 32; ++i) {
        float* p = &f.rgba[size_t(i) * 4];
        p[0] = 0.5f, p[1] = 0.25f, p[2] = 0.75f, p[3] = 1.0f;
        f.z[size_t(i)] = 2.0f;
    }
    float* bg = &f.rgba[size_t(3 * 8 + 7) * 4];
    bg[0] = bg[1] = bg[2] = bg[3] = 0;
    f.z[size_t(3 * 8 + 7)] = kInf;
    return f;
}

float& px(FrameImage& f, int x, int y, int c) { return f.rgba[(size_t(y) * size_t(f.width) + size_t(x)) * 4 + size_t(c)]; }
float& zAt(FrameImage& f, int x, int y) { return f.z[size_t(y) * size_t(f.width) + size_t(x)]; }

std::string write(const std::string& dir, const std::string& name, const FrameImage& f, const std::string& mode = "rgbaz") {
    std::string path = dir + "/" + name;
    writeFrame(path, f, mode);
    return path;
}

// The number after "key": in `json`, searching from the first occurrence of `section`.
double jsonNumber(const std::string& json, const std::string& section, const std::string& key) {
    size_t at = json.find(section);
    if (at == std::string::npos) return std::nan("");
    at = json.find("\"" + key + "\": ", at);
    if (at == std::string::npos) return std::nan("");
    const char* p = json.c_str() + at + key.size() + 4;
    if (std::string(p, 4) == "null") return kInf;
    return std::strtod(p, nullptr);
}

TEST(Compare, IdenticalImagesGiveZero) {
    const test::TempDir tempDir("cmp-same");
    const std::string& dir = tempDir.path();
    std::string a = write(dir, "a.exr", baseFrame()), b = write(dir, "b.exr", baseFrame());
    CliRun r = runStreyes("compare " + a + " " + b + " --json --fail 0", false);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* key : {"rmse_rgb", "rmse_a", "mean_abs", "max_abs", "share_differing", "share_over_threshold"})
        EXPECT_EQ(jsonNumber(r.output, "\"overall\"", key), 0.0) << key;
    EXPECT_EQ(jsonNumber(r.output, "\"overall\"", "coverage_mismatch"), 0.0);
    EXPECT_EQ(jsonNumber(r.output, "\"overall\"", "psnr"), kInf);  // null: identical
    EXPECT_EQ(jsonNumber(r.output, "\"overall\"", "pixels"), 32.0);
    EXPECT_NE(r.output.find("\"compared\": true"), std::string::npos);  // Z compared, background +inf agrees
}

TEST(Compare, KnownChangeGivesItsKnownErrors) {
    const test::TempDir tempDir("cmp-known");
    const std::string& dir = tempDir.path();
    FrameImage fb = baseFrame();
    px(fb, 1, 1, 0) = 1.0f;   // R +0.5
    px(fb, 2, 3, 1) = 0.0f;   // G -0.25
    px(fb, 4, 0, 3) = 0.5f;   // A -0.5
    zAt(fb, 5, 2) = 2.5f;     // depth: relative difference 0.2
    zAt(fb, 6, 2) = kInf;     // surface in A, background in B
    std::string a = write(dir, "a.exr", baseFrame()), b = write(dir, "b.exr", fb);
    CliRun r = runStreyes("compare " + a + " " + b + " --json --threshold 0.3", false);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string all = "\"overall\"";
    EXPECT_NEAR(jsonNumber(r.output, all, "rmse_rgb"), std::sqrt((0.25 + 0.0625) / 96.0), 1e-8);
    EXPECT_NEAR(jsonNumber(r.output, all, "rmse_a"), std::sqrt(0.25 / 32.0), 1e-8);
    EXPECT_NEAR(jsonNumber(r.output, all, "psnr"), 10 * std::log10(96.0 / 0.3125), 1e-6);
    EXPECT_NEAR(jsonNumber(r.output, all, "mean_abs"), 0.75 / 96.0, 1e-9);
    EXPECT_EQ(jsonNumber(r.output, all, "max_abs"), 0.5);
    EXPECT_EQ(jsonNumber(r.output, all, "max_abs_a"), 0.5);
    EXPECT_NEAR(jsonNumber(r.output, all, "share_differing"), 3.0 / 32.0, 1e-9);
    EXPECT_NEAR(jsonNumber(r.output, all, "share_over_threshold"), 2.0 / 32.0, 1e-9);  // R +0.5 and A -0.5
    EXPECT_EQ(jsonNumber(r.output, all, "coverage_mismatch"), 1.0);
    EXPECT_EQ(jsonNumber(r.output, all, "depth_mismatch"), 1.0);
    EXPECT_NEAR(jsonNumber(r.output, all, "max_rel_diff"), 0.2, 1e-7);

    // --fail: the RMSE of A (0.088) is the larger; exit 1 just below it, 0 just above.
    CliRun fail = runStreyes("compare " + a + " " + b + " --fail 0.088");
    EXPECT_EQ(fail.exitCode, 1) << fail.output;
    EXPECT_NE(fail.output.find("FAIL"), std::string::npos) << fail.output;
    EXPECT_EQ(runStreyes("compare " + a + " " + b + " --fail 0.089").exitCode, 0);
}

TEST(Compare, NaNAndInfAreCountedAndFail) {
    const test::TempDir tempDir("cmp-nan");
    const std::string& dir = tempDir.path();
    FrameImage fb = baseFrame();
    px(fb, 0, 0, 0) = std::nanf("");
    px(fb, 1, 0, 1) = kInf;
    zAt(fb, 2, 0) = std::nanf("");
    zAt(fb, 3, 0) = -kInf;
    std::string a = write(dir, "a.exr", baseFrame()), b = write(dir, "b.exr", fb);
    CliRun r = runStreyes("compare " + a + " " + b + " --json", false);
    ASSERT_EQ(r.exitCode, 0) << r.output;  // measured; failing is --fail's job
    EXPECT_EQ(jsonNumber(r.output, "\"overall\"", "pixels_skipped"), 2.0);
    EXPECT_EQ(jsonNumber(r.output, "\"overall\"", "rmse_rgb"), 0.0);  // the rest is unchanged
    const nlohmann::json overall = nlohmann::json::parse(r.output).at("overall");
    EXPECT_EQ(overall.at("nonfinite").at("b"),
              nlohmann::json::parse(R"({"color_nan": 1, "color_inf": 1, "z_nan": 1, "z_neg_inf": 1})"))
        << r.output;
    // A's +inf background Z is not an error.
    EXPECT_EQ(overall.at("nonfinite").at("a"),
              nlohmann::json::parse(R"({"color_nan": 0, "color_inf": 0, "z_nan": 0, "z_neg_inf": 0})"));
    // The table run says so on stderr, naming the file; --fail fails on it whatever the threshold.
    CliRun t = runStreyes("compare " + a + " " + b + " --fail 100");
    EXPECT_EQ(t.exitCode, 1) << t.output;
    EXPECT_NE(t.output.find("'" + b + "' holds 1 NaN and 1 infinite values"), std::string::npos) << t.output;
}

TEST(Compare, SizeOrChannelMismatchIsAnError) {
    const test::TempDir tempDir("cmp-mismatch");
    const std::string& dir = tempDir.path();
    FrameImage wide;
    wide.resize(16, 8);
    std::string a = write(dir, "a.exr", baseFrame()), big = write(dir, "big.exr", wide);
    CliRun size = runStreyes("compare " + a + " " + big);
    EXPECT_EQ(size.exitCode, 2) << size.output;
    EXPECT_NE(size.output.find("is 8x4 but"), std::string::npos) << size.output;
    EXPECT_NE(size.output.find("is 16x8"), std::string::npos) << size.output;
    EXPECT_EQ(size.output.find("rmse"), std::string::npos) << "a number was printed: " << size.output;

    std::string rgba = write(dir, "rgba.exr", baseFrame(), "rgba");
    CliRun ch = runStreyes("compare " + a + " " + rgba);
    EXPECT_EQ(ch.exitCode, 2) << ch.output;
    EXPECT_NE(ch.output.find("has channels R,G,B,A,Z but"), std::string::npos) << ch.output;

    CliRun missing = runStreyes("compare " + a + " " + dir + "/nope.exr");
    EXPECT_EQ(missing.exitCode, 2);
    EXPECT_NE(missing.output.find("nope.exr' does not exist"), std::string::npos) << missing.output;
    CliRun notAnImage = runStreyes("compare " + a + " " + test::writeFile(dir, "text.exr", "not an image"));
    EXPECT_EQ(notAnImage.exitCode, 2) << notAnImage.output;
}

TEST(Compare, ResizeMeasuresALowerResolutionAtTheReferenceSize) {
    // A preview at half the size, uniformly the same colour: resampled, it matches exactly.
    const test::TempDir tempDir("cmp-resize");
    const std::string& dir = tempDir.path();
    FrameImage full, half;
    full.resize(8, 4);
    half.resize(4, 2);
    for (FrameImage* f : {&full, &half})
        for (size_t i = 0; i < f->rgba.size(); ++i) f->rgba[i] = (i % 4 == 3) ? 1.0f : 0.5f;
    std::string a = write(dir, "a.exr", full), b = write(dir, "b.exr", half);
    CliRun r = runStreyes("compare " + a + " " + b + " --resize --json", false);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(jsonNumber(r.output, "\"overall\"", "rmse_rgb"), 0.0);
    EXPECT_EQ(jsonNumber(r.output, "\"overall\"", "pixels"), 32.0);
    EXPECT_NE(r.output.find("\"compared\": false"), std::string::npos);  // Z is not compared after resampling
}

TEST(Compare, FramePatternsPerFrameAndOverall) {
    const test::TempDir tempDir("cmp-frames");
    const std::string& dir = tempDir.path();
    FrameImage changed = baseFrame();
    px(changed, 0, 0, 2) = 0.25f;  // B -0.5 in frame 2 only
    for (int f = 1; f <= 3; ++f) {
        write(dir, "a." + std::to_string(1000 + f).substr(1) + ".exr", baseFrame());
        if (f < 3) write(dir, "b." + std::to_string(1000 + f).substr(1) + ".exr", f == 2 ? changed : baseFrame());
    }
    // Frame 3 exists for A but not for B: an error naming the file, unless --frames leaves it out.
    CliRun gap = runStreyes("compare " + dir + "/a.###.exr " + dir + "/b.###.exr");
    EXPECT_EQ(gap.exitCode, 2) << gap.output;
    EXPECT_NE(gap.output.find("b.003.exr' does not exist"), std::string::npos) << gap.output;

    CliRun r = runStreyes("compare " + dir + "/a.###.exr " + dir + "/b.###.exr --frames 1-2 --json", false);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(jsonNumber(r.output, "\"frame\": 1,", "rmse_rgb"), 0.0);
    EXPECT_NEAR(jsonNumber(r.output, "\"frame\": 2,", "rmse_rgb"), std::sqrt(0.25 / 96.0), 1e-8);
    EXPECT_NEAR(jsonNumber(r.output, "\"overall\"", "rmse_rgb"), std::sqrt(0.25 / 192.0), 1e-8);  // pooled
    EXPECT_EQ(jsonNumber(r.output, "\"overall\"", "frames"), 2.0);

    EXPECT_EQ(runStreyes("compare " + dir + "/a.###.exr " + dir + "/b.001.exr").exitCode, 2);  // pattern vs file
    EXPECT_EQ(runStreyes("compare " + dir + "/none.####.exr " + dir + "/b.###.exr").exitCode, 2);
}

}  // namespace
}  // namespace streyes
