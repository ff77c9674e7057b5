// End-to-end renders checked against analytic answers.
#include <gtest/gtest.h>

#include <cmath>

#include "test_util.h"

namespace streyes {
namespace {

using test::orthoHeader;
using test::overlap;
using test::RenderResult;
using test::renderRib;
using test::square;

// The analytic answers hold for every algorithm: the rasterizer's and the ray tracer's.
class EveryAlgorithm : public ::testing::TestWithParam<Algorithm> {
  protected:
    RenderOptions options() const { return test::optionsFor(GetParam()); }
};
INSTANTIATE_TEST_SUITE_P(Render, EveryAlgorithm,
                         ::testing::Values(Algorithm::Spacetime, Algorithm::SpacetimeOcclusion, Algorithm::Frames,
                                           Algorithm::FramesOcclusion, Algorithm::Raytrace, Algorithm::RaytraceFrames),
                         [](const ::testing::TestParamInfo<Algorithm>& info) { return test::testName(info.param); });

TEST_P(EveryAlgorithm, StaticSquareCoverageIsAnalytic) {
    // Square x in [8.3, 20.6], y in [4.2, 11.7] -> raster rows [4.3, 11.8].
    RenderResult r = renderRib(orthoHeader(32, 16, "PixelSamples 8 8\n") + "Color [0.2 0.4 0.6]\n" +
                                   square(8.3, 20.6, 4.2, 11.7, 5) + "WorldEnd\n",
                               options());
    const double sx = 1.0 / 8;  // stratified: the estimate is within one stratum of the truth
    for (int y = 0; y < 16; ++y) {
        for (int x = 0; x < 32; ++x) {
            double cover = overlap(x, 8.3, 20.6) * overlap(y, 4.3, 11.8);
            float a = r.alpha(0, x, y);
            if (cover == 1.0 || cover == 0.0) {
                EXPECT_EQ(a, float(cover)) << x << "," << y;
            } else {
                EXPECT_NEAR(a, cover, 2 * sx) << x << "," << y;
            }
            if (cover == 1.0) {
                EXPECT_NEAR(r.channel(0, x, y, 0), 0.2f, 1e-5f);
                EXPECT_NEAR(r.channel(0, x, y, 1), 0.4f, 1e-5f);
                EXPECT_NEAR(r.channel(0, x, y, 2), 0.6f, 1e-5f);
                EXPECT_FLOAT_EQ(r.z(0, x, y), 5.0f);
            }
            if (cover == 0.0) {
                EXPECT_TRUE(std::isinf(r.z(0, x, y)));
            }
        }
    }
    // Interior edge pixels: exactly the stratified error bound.
    EXPECT_NEAR(r.alpha(0, 8, 7), 0.7, sx);
    EXPECT_NEAR(r.alpha(0, 20, 7), 0.6, sx);
    EXPECT_NEAR(r.alpha(0, 12, 4), 0.7, sx);
    EXPECT_NEAR(r.alpha(0, 12, 11), 0.8, sx);
}

TEST_P(EveryAlgorithm, SquareMovingOneWidthGivesLinearRamp) {
    // A 4-pixel square moves 4 pixels (one width) during the shutter [0, 1] of frame 0.
    const int spp = 256;
    RenderResult r = renderRib(orthoHeader(32, 4, "PixelSamples 16 16\nShutter 0 1\n") +
                                   "MotionBegin [0 1]\nTranslate 0 0 0\nTranslate 4 0 0\nMotionEnd\n" +
                                   square(8, 12, 0, 4, 5) + "WorldEnd\n",
                               options());
    for (int x = 0; x < 32; ++x) {
        // Time-averaged coverage of pixel x: the ramp 1/8, 3/8, 5/8, 7/8, 7/8, 5/8, 3/8, 1/8.
        double expected = 0;
        const int steps = 20000;
        for (int i = 0; i < steps; ++i) {
            double t = (i + 0.5) / steps;
            expected += overlap(x, 8 + 4 * t, 12 + 4 * t) / steps;
        }
        double sigma = std::sqrt(expected * (1 - expected) / spp);
        for (int y = 0; y < 4; ++y) EXPECT_NEAR(r.alpha(0, x, y), expected, 3 * sigma + 1e-6) << "pixel " << x;
    }
    EXPECT_NEAR(r.alpha(0, 10, 1), 0.625, 0.1);
    EXPECT_NEAR(r.alpha(0, 13, 1), 0.625, 0.1);
}

const char* kTwoDepths = R"(Format 32 32 1
Projection "perspective" "fov" [90]
PixelSamples 4 4
WorldBegin
Surface "constant"
AttributeBegin
  Color [0 1 0]
  Patch "bilinear" "P" [-8 -8 10  8 -8 10  -8 8 10  8 8 10]
AttributeEnd
AttributeBegin
  Color [1 0 0]
  Patch "bilinear" "P" [-3 -3 5  3 -3 5  -3 3 5  3 3 5]
AttributeEnd
WorldEnd
)";

TEST_P(EveryAlgorithm, NearerPatchWinsAndZIsItsDepth) {
    RenderResult r = renderRib(kTwoDepths, options());
    // Centre: the red patch at z = 5 in front of the green one at z = 10.
    EXPECT_NEAR(r.channel(0, 16, 16, 0), 1.0f, 1e-5f);
    EXPECT_NEAR(r.channel(0, 16, 16, 1), 0.0f, 1e-5f);
    EXPECT_FLOAT_EQ(r.z(0, 16, 16), 5.0f);
    // Red spans raster [6.4, 25.6]; green [3.2, 28.8]. Pixel 4 sees only green.
    EXPECT_NEAR(r.channel(0, 4, 16, 1), 1.0f, 1e-5f);
    EXPECT_NEAR(r.channel(0, 4, 16, 0), 0.0f, 1e-5f);
    EXPECT_FLOAT_EQ(r.z(0, 4, 16), 10.0f);
    // Corner: background.
    EXPECT_EQ(r.alpha(0, 0, 0), 0.0f);
    EXPECT_TRUE(std::isinf(r.z(0, 0, 0)));
}

TEST(Render, DrawOrderDoesNotDecideVisibility) {
    std::string swapped = kTwoDepths;
    size_t a = swapped.find("AttributeBegin"), b = swapped.find("AttributeBegin", a + 1), e = swapped.find("WorldEnd");
    swapped = swapped.substr(0, a) + swapped.substr(b, e - b) + swapped.substr(a, b - a) + swapped.substr(e);
    RenderResult r1 = renderRib(kTwoDepths), r2 = renderRib(swapped);
    EXPECT_NEAR(r2.channel(0, 16, 16, 0), 1.0f, 1e-5f);
    EXPECT_FLOAT_EQ(r2.z(0, 16, 16), 5.0f);
    EXPECT_LT(test::maxAbsDifference(r1, r2), 1e-5f);
}

// A small animation with motion in x, y and depth, rotation and a light.
const char* kMovingScene = R"(Format 48 32 1
Projection "perspective" "fov" [60]
PixelSamples 3 3
Shutter 0 0.5
Option "streyes" "int frames" [0 5]
WorldBegin
LightSource "distantlight" 1 "from" [0 1 -1] "to" [0 0 0]
LightSource "ambientlight" 2 "intensity" [0.2]
Surface "matte"
AttributeBegin
  Color [0.8 0.7 0.2]
  Patch "bilinear" "P" [-6 -2 12  6 -2 12  -6 -2 4  6 -2 4]
AttributeEnd
AttributeBegin
  Color [0.2 0.5 0.9]
  MotionBegin [0 5]
    Translate -2 0 8
    Translate 2 1 10
  MotionEnd
  MotionBegin [0 5]
    Rotate 0 0 0 1
    Rotate 90 0 0 1
  MotionEnd
  Patch "bilinear" "P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]
AttributeEnd
WorldEnd
)";

TEST_P(EveryAlgorithm, ThreadCountDoesNotChangePixels) {
    RenderOptions one = options(), two = options();
    one.threads = 1;
    two.threads = 2;
    one.bucketSize = two.bucketSize = 8;
    RenderResult a = renderRib(kMovingScene, one), b = renderRib(kMovingScene, two);
    ASSERT_EQ(a.frames.size(), 6u);
    EXPECT_TRUE(test::identicalPixels(a, b));
    EXPECT_EQ(test::differingCounts(a.stats.counters, b.stats.counters), std::vector<std::string>{});
    EXPECT_GT(a.stats.counters.gridsDiced + a.stats.counters.eyeRays, 0u);
}

TEST(Render, SeedDecidesThePixels) {
    RenderOptions s1, s1again, s2;
    s1.seed = s1again.seed = 1;
    s2.seed = 2;
    RenderResult a = renderRib(kMovingScene, s1), b = renderRib(kMovingScene, s1again), c = renderRib(kMovingScene, s2);
    EXPECT_TRUE(test::identicalPixels(a, b));
    EXPECT_FALSE(test::identicalPixels(a, c));  // the comparison can fail
}

// Moving geometry is cut at each frame's exposure in both, still geometry is diced the same
// way in both (its splits depend on the body, not the bucket): the same micropolygons meet the
// same samples, so spacetime differs from Catmull's per-frame loop only in how often it works.
TEST(Render, SpacetimeAndFramesGiveTheSamePixels) {
    RenderOptions st, fr;
    fr.algorithm = Algorithm::Frames;
    RenderResult a = renderRib(kMovingScene, st), b = renderRib(kMovingScene, fr);
    ASSERT_EQ(a.frames.size(), b.frames.size());
    EXPECT_TRUE(test::identicalPixels(a, b));
    EXPECT_GT(a.stats.counters.sampleHits, 0u);
}

const char* kStillScene = R"(Format 40 30 1
Projection "perspective" "fov" [50]
PixelSamples 2 2
Shutter 0 0.5
WorldBegin
Surface "defaultsurface"
Patch "bilinear" "P" [-6 -2 12  6 -2 12  -6 -2 4  6 -2 4]
Patch "bilinear" "P" [-1 -1 6  1 -1 6  -1 1 7  1 1 7]
WorldEnd
)";

TEST(Render, StillSceneIsSplitOnceInSpacetimeAndPerFrameInFrames) {
    auto run = [](Algorithm alg, int last) {
        RenderOptions o;
        o.algorithm = alg;
        o.hasFrames = true;
        o.firstFrame = 0;
        o.lastFrame = last;
        return renderRib(kStillScene, o).stats.counters;
    };
    RenderCounters st1 = run(Algorithm::Spacetime, 0), st16 = run(Algorithm::Spacetime, 15);
    RenderCounters fr1 = run(Algorithm::Frames, 0), fr16 = run(Algorithm::Frames, 15);
    ASSERT_GT(st1.gridsDiced, 0u);
    ASSERT_GT(st1.splits(), 0u);
    EXPECT_EQ(st16.gridsDiced, st1.gridsDiced);
    EXPECT_EQ(st16.splits(), st1.splits());
    EXPECT_EQ(fr16.gridsDiced, 16 * fr1.gridsDiced);
    EXPECT_EQ(fr16.splits(), 16 * fr1.splits());
    EXPECT_EQ(st1.gridsDiced, fr1.gridsDiced);
    // Samples sit at the same places in every frame: spacetime samples the still scene once for
    // all 16 frames, per-frame Catmull once a frame.
    EXPECT_EQ(st16.sampleTests, st1.sampleTests);
    EXPECT_EQ(st16.sampleHits, st1.sampleHits);
    EXPECT_EQ(fr16.sampleHits, 16 * fr1.sampleHits);
}

TEST(Render, MotionSegmentsAreDicedOnlyInTheFramesTheyReach) {
    // A sphere moves during frames 0-4, then holds still: two roots (curved primitives keep one
    // mesh per motion segment), [0, 4] moving and [4, 7.5] still. With shutter [0, 0.5], frame 4's
    // exposure [4, 4.5] touches the moving one only at its end, which the still one covers: it
    // must not be diced again there.
    const std::string rib = "Format 16 16 1\nProjection \"orthographic\"\nScreenWindow 0 16 0 16\nShutter 0 0.5\n"
                            "PixelSamples 2 2\nWorldBegin\nSurface \"constant\"\n"
                            "MotionBegin [0 4]\nTranslate 0 0 0\nTranslate 4 0 0\nMotionEnd\n"
                            "Translate 4 6 5\nSphere 1.5 -1.5 1.5 360\nWorldEnd\n";
    RenderOptions o;
    o.algorithm = Algorithm::Frames;
    o.hasFrames = true;
    o.firstFrame = 0;
    o.lastFrame = 7;
    o.bucketSize = 32;  // one bucket
    RenderResult r = renderRib(rib, o);
    EXPECT_EQ(r.stats.counters.rootBodies, 2u);
    EXPECT_EQ(r.stats.counters.gridsDiced, 8u);  // one per frame, not two in frame 4
    EXPECT_GT(r.alpha(4, 8, 10), 0.5f);          // held at x = 8 from frame 4 on
    EXPECT_EQ(r.alpha(4, 4, 10), 0.0f);
}

TEST(Render, PatchThroughTheEyePlaneRendersItsVisiblePart) {
    // A floor at y = -1 from behind the camera (z = -10) to z = 50.
    RenderResult r = renderRib(R"(Format 32 32 1
Projection "perspective" "fov" [90]
Clipping 0.1 1000
PixelSamples 2 2
WorldBegin
Surface "constant"
Patch "bilinear" "P" [-20 -1 -10  20 -1 -10  -20 -1 50  20 -1 50]
WorldEnd
)");
    const FrameImage& img = r.frame(0);
    for (float v : img.rgba) ASSERT_TRUE(std::isfinite(v));
    EXPECT_GT(r.stats.counters.eyeSplits, 0u);
    EXPECT_EQ(r.stats.counters.culledEyeLimit, 0u);
    // The floor fills every row below screen y = -1/50 (raster row 16.32), nothing above the horizon.
    for (int x = 0; x < 32; ++x) {
        EXPECT_NEAR(r.alpha(0, x, 31), 1.0f, 1e-6f) << x;
        EXPECT_NEAR(r.alpha(0, x, 20), 1.0f, 1e-6f) << x;
        EXPECT_EQ(r.alpha(0, x, 10), 0.0f) << x;
    }
    // Bottom row: screen y from -0.9375 to -1, so the floor's depth there is 1/|y| in [1, 1.067];
    // Z is the nearest of the pixel's samples.
    EXPECT_GE(r.z(0, 16, 31), 1.0f - 1e-4f);
    EXPECT_LE(r.z(0, 16, 31), 1.0667f);
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// The frames a render keeps together before memory is counted (render farms size blocks by it).
TEST(Render, FrameBlockLimitFollowsPixelsAndBucketSamples) {
    Scene s;
    s.settings.pixelSamplesX = s.settings.pixelSamplesY = 2;
    RenderOptions o;
    // ~4 GiB of RGBA + Z floats: 3840x2160 holds 25 frames, 1920x1080 and 640x360 every one of 64.
    o.xres = 3840, o.yres = 2160;
    EXPECT_EQ(frameBlockLimit(s, o), 25);
    EXPECT_EQ(frameBlockLimit(s, o), int(4.0 * (1 << 30) / (3840.0 * 2160 * 20)));
    o.xres = 1920, o.yres = 1080;
    EXPECT_EQ(frameBlockLimit(s, o), 64);
    o.xres = 7680, o.yres = 4320;  // 8K: 6 frames
    EXPECT_EQ(frameBlockLimit(s, o), 6);
    o.xres = 640, o.yres = 360;
    EXPECT_EQ(frameBlockLimit(s, o), 64);
    o.maxFrameBlock = 8;
    EXPECT_EQ(frameBlockLimit(s, o), 8);
    // ~16 M samples a spacetime bucket: 1024 samples a pixel on 34x34-pixel buckets (32-pixel tiles,
    // gaussian 2x2: one pixel of guard band) hold 14 frames; per-frame buckets do not count.
    o.maxFrameBlock = 64;
    o.bucketSize = 32;
    o.samples = 1024;
    EXPECT_EQ(frameBlockLimit(s, o), int((1 << 24) / (34.0 * 34 * 1024)));
    o.algorithm = Algorithm::Frames;
    EXPECT_EQ(frameBlockLimit(s, o), 64);
}

}  // namespace
}  // namespace streyes
