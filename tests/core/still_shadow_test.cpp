// Ray-traced shadows at the shading rate (docs/ARCHITECTURE.md, "Shadows"): a still grid under
// still lights tests the occluders that stand still through the shot once per vertex, and its
// samples test only the moving ones. Against the analytic shadow and the per-sample test
// (Option "trace" "string shadowtest" "sample"); frame-block invariance and thread counts with a
// moving occluder over a still floor; no per-sample ray where nothing moves.
#include <gtest/gtest.h>

#include <cmath>

#include "test_util.h"

namespace streyes {
namespace {

using test::orthoHeader;
using test::RenderResult;
using test::renderRib;

constexpr double kPi = 3.14159265358979323846;

// A white matte floor at z = 40 lit by a distant light along (1, 0, 1) with intensity sqrt 2
// (exactly 1 where lit); a sphere of radius 8 centred at (20, 20, 10) in its way: its shadow is
// the ellipse centred at (50, 20), semi-axes 8 sqrt 2 (x) and 8 (y), area 64 pi sqrt 2, clear of
// the sphere's own silhouette (x <= 28). (trace_curved_test.cpp's scene, with `options` added.)
std::string sphereShadowScene(const std::string& options = "") {
    return orthoHeader(96, 40, "PixelSamples 8 8\nShutter 0 1\n" + options) +
           "Attribute \"light\" \"shadows\" \"on\"\n"
           "LightSource \"distantlight\" 1 \"intensity\" [1.41421356] \"from\" [0 0 0] \"to\" [1 0 1]\n"
           "Surface \"matte\" \"Ka\" [0]\n" + test::square(0, 96, 0, 40, 40) +
           "AttributeBegin\nSurface \"constant\"\nColor [0.5 0.5 0.5]\n"
           "Translate 20 20 10\nSphere 8 -8 8 360\nAttributeEnd\nWorldEnd\n";
}
const char* kPerSample = "Option \"trace\" \"string shadowtest\" [\"sample\"]\n";

double shadowArea(const RenderResult& r) {
    double a = 0;
    for (int y = 0; y < 40; ++y)
        for (int x = 30; x < 96; ++x) a += 1.0 - double(r.channel(0, x, y, 0));
    return a;
}

// How far pixel (x, y)'s centre lies from the shadow ellipse's edge, in pixels (approximately:
// the ellipse's implicit distance scaled by its smaller semi-axis).
double fromShadowEdge(int x, int y) {
    const double dx = (x + 0.5 - 50) / (8 * std::sqrt(2.0)), dy = (y + 0.5 - 20) / 8;
    return std::fabs(std::sqrt(dx * dx + dy * dy) - 1) * 8;
}

// The shading-rate shadow: the floor's vertices (one a pixel at ShadingRate 1) see the light or
// not, and a micropolygon across the edge blends the two, so the edge is a one-pixel ramp where
// the per-sample shadow is a jittered step. Against the ellipse's 284.35 pixels: per sample
// 282.86 (-0.5%), at the shading rate 279.01 (-1.9%: the ramp loses about 0.085 pixel along the
// 63-pixel outline). Bounds: 1% per sample; 2.5% at the shading rate, and 2% between the two: a
// micropolygon's width of edge lost or gained (63 pixels, 22%) fails them. Away from the edge
// (more than two pixels: a micropolygon and the filter's pixel) the two are the same light or
// shadow exactly.
TEST(StillShadow, SphereShadowAtTheShadingRateIsTheAnalyticEllipse) {
    const double expected = 64 * kPi * std::sqrt(2.0);
    for (Algorithm a : {Algorithm::Spacetime, Algorithm::FramesOcclusion}) {
        SCOPED_TRACE(algorithmName(a));
        const RenderResult vertex = renderRib(sphereShadowScene(), test::optionsFor(a));
        const RenderResult sample = renderRib(sphereShadowScene(kPerSample), test::optionsFor(a));
        EXPECT_NEAR(shadowArea(vertex), expected, 0.025 * expected);
        EXPECT_NEAR(shadowArea(sample), expected, 0.01 * expected);
        EXPECT_NEAR(shadowArea(vertex), shadowArea(sample), 0.02 * expected);
        EXPECT_EQ(vertex.channel(0, 50, 20, 0), 0.0f);  // the ellipse's centre
        EXPECT_NEAR(vertex.channel(0, 50, 34, 0), 1.0f, 1e-5f);
        size_t far = 0;
        for (int y = 0; y < 40; ++y)
            for (int x = 30; x < 96; ++x) {
                if (fromShadowEdge(x, y) <= 2) continue;
                ++far;
                EXPECT_NEAR(vertex.channel(0, x, y, 0), sample.channel(0, x, y, 0), 1e-5f) << x << " " << y;
            }
        EXPECT_GT(far, 2000u);
        // Nothing moves: the still floor's samples cast no ray; its vertices did, and its grids
        // carry their shadows in their colour.
        EXPECT_EQ(vertex.stats.counters.shadowRays, 0u);
        EXPECT_GT(vertex.stats.counters.shadowFoldedGrids, 0u);
        EXPECT_EQ(sample.stats.counters.shadowFoldedGrids, 0u);
        EXPECT_GT(vertex.stats.counters.shadowVertexRays, 0u);
        EXPECT_GT(sample.stats.counters.shadowRays, 0u);
        EXPECT_EQ(sample.stats.counters.shadowVertexRays, 0u);
    }
}

// The sphere's shadow with a square moving over the floor's left end (x 2 to 6, up and down, at
// z = 35: the light's rays from x 7 to 11 of the floor cross its path): the floor's grids there
// test it per sample, frame by frame, and the rest (the ellipse's) fold their shadows into their
// colour and share the still layer. The ellipse is as analytic as without the mover, the same as
// the per-sample test away from its edge, and frame 2 alone is frame 2 of frames 0-3.
std::string sphereShadowWithMover(const std::string& options = "") {
    std::string rib = sphereShadowScene("Option \"streyes\" \"int frames\" [0 3]\n" + options);
    rib.insert(rib.find("WorldEnd"), "AttributeBegin\nSurface \"constant\"\nMotionBegin [0 1 2 3]\n"
                                     "Translate 0 2 0\nTranslate 0 12 0\nTranslate 0 22 0\nTranslate 0 30 0\nMotionEnd\n" +
                                         test::square(2, 6, 0, 4, 35) + "AttributeEnd\n");
    return rib;
}

TEST(StillShadow, FoldedShadowsBesideAMoverKeepTheAnalyticEllipse) {
    const double expected = 64 * kPi * std::sqrt(2.0);
    const RenderOptions options = test::optionsFor(Algorithm::SpacetimeOcclusion);
    const RenderResult vertex = renderRib(sphereShadowWithMover(), options);
    const RenderResult sample = renderRib(sphereShadowWithMover(kPerSample), options);
    ASSERT_EQ(vertex.frames.size(), 4u);
    ASSERT_EQ(sample.frames.size(), 4u);
    EXPECT_GT(vertex.stats.counters.shadowFoldedGrids, 0u);
    EXPECT_GT(vertex.stats.counters.shadowRays, 0u);  // where the mover may come between
    for (int f = 0; f < 4; ++f) {
        SCOPED_TRACE(f);
        double area = 0, areaSample = 0;
        size_t far = 0;
        for (int y = 0; y < 40; ++y)
            for (int x = 30; x < 96; ++x) {
                area += 1.0 - double(vertex.channel(f, x, y, 0));
                areaSample += 1.0 - double(sample.channel(f, x, y, 0));
                if (fromShadowEdge(x, y) <= 2) continue;
                ++far;
                EXPECT_NEAR(vertex.channel(f, x, y, 0), sample.channel(f, x, y, 0), 1e-5f) << x << " " << y;
            }
        EXPECT_GT(far, 2000u);
        EXPECT_NEAR(area, expected, 0.025 * expected);
        EXPECT_NEAR(areaSample, expected, 0.01 * expected);
        // The mover's own shadow, under it at the floor's left end: as dark per vertex as per sample.
        double moverShadow = 0, moverShadowSample = 0;
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 20; ++x) {
                moverShadow += 1.0 - double(vertex.channel(f, x, y, 0));
                moverShadowSample += 1.0 - double(sample.channel(f, x, y, 0));
            }
        EXPECT_GT(moverShadowSample, 8.0);
        EXPECT_NEAR(moverShadow, moverShadowSample, 0.1 * moverShadowSample);
    }
    const test::ShotAndFrame r = test::renderShotAndFrame(sphereShadowWithMover(), options, 0, 3, 2);
    EXPECT_TRUE(r.samePixels(2));
    EXPECT_GT(r.alone.stats.counters.shadowFoldedGrids, 0u);
}

// An unknown value warns and keeps the default.
TEST(StillShadow, UnknownShadowTestWarnsAndTestsAtTheShadingRate) {
    const RenderResult r =
        renderRib(sphereShadowScene("Option \"trace\" \"string shadowtest\" [\"sometimes\"]\n"), test::optionsFor(Algorithm::Spacetime));
    bool warned = false;
    for (const std::string& w : r.warnings) warned = warned || w.find("shadowtest") != std::string::npos;
    EXPECT_TRUE(warned);
    EXPECT_EQ(r.stats.counters.shadowRays, 0u);
    EXPECT_GT(r.stats.counters.shadowVertexRays, 0u);
}

// A still floor under a still light, an occluder that moves (keyed every frame, so its shadow
// moves from frame to frame) and one that stands still: the still floor's vertices test the still
// occluder once for the block, its samples the moving one at their own times. Frame 3 rendered
// alone is frame 3 of frames 0-5 rendered together, bit for bit.
const char* kMovingOverStill = R"(Format 48 32 1
Projection "perspective" "fov" [60]
PixelSamples 3 3
Shutter 0 0.5
Option "streyes" "int frames" [0 5]
WorldBegin
Attribute "light" "shadows" "on"
LightSource "distantlight" 1 "from" [1 4 -1] "to" [0 0 0]
LightSource "pointlight" 2 "from" [-3 3 2] "intensity" [8]
Surface "matte"
AttributeBegin
  Color [0.8 0.7 0.2]
  Patch "bilinear" "P" [-6 -2 12  6 -2 12  -6 -2 4  6 -2 4]
AttributeEnd
AttributeBegin
  Color [0.2 0.5 0.9]
  MotionBegin [0 1 2 3 4 5]
    Translate -3 0 8
    Translate -2 0.3 8
    Translate -1 0 8.5
    Translate 0 0.4 8
    Translate 1 0 7.5
    Translate 2 0.2 8
  MotionEnd
  Patch "bilinear" "P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]
AttributeEnd
AttributeBegin
  Color [0.9 0.2 0.2]
  Translate 2 -1 7
  Sphere 0.8 -0.8 0.8 360
AttributeEnd
WorldEnd
)";

TEST(StillShadow, FrameAloneIsTheFrameInItsBlockWithAMovingOccluder) {
    for (Algorithm a : {Algorithm::Spacetime, Algorithm::SpacetimeOcclusion, Algorithm::Frames}) {
        SCOPED_TRACE(algorithmName(a));
        const test::ShotAndFrame r = test::renderShotAndFrame(kMovingOverStill, test::optionsFor(a), 0, 5, 3);
        EXPECT_TRUE(r.samePixels(3));
        // Both halves of the test ran: still occluders at vertices, the moving one per sample.
        EXPECT_GT(r.shot.stats.counters.shadowVertexRays, 0u);
        EXPECT_GT(r.shot.stats.counters.shadowRays, 0u);
        // And the frames differ (the moving shadow is seen).
        EXPECT_GT(test::differingPixels(r.shot.frame(2), r.shot.frame(3), 0.01f), 0u);
    }
}

TEST(StillShadow, ThreadCountDoesNotChangePixelsOrCounts) {
    for (Algorithm a : {Algorithm::Spacetime, Algorithm::FramesOcclusion}) {
        SCOPED_TRACE(algorithmName(a));
        RenderOptions one = test::optionsFor(a), two = test::optionsFor(a);
        one.threads = 1;
        two.threads = 2;
        one.bucketSize = two.bucketSize = 8;
        const RenderResult r1 = renderRib(kMovingOverStill, one), r2 = renderRib(kMovingOverStill, two);
        EXPECT_TRUE(test::identicalPixels(r1, r2));
        EXPECT_EQ(test::differingCounts(r1.stats.counters, r2.stats.counters), std::vector<std::string>{});
        EXPECT_GT(r1.stats.counters.shadowVertexRays, 0u);
    }
}

// The per-sample test holds the shading-rate one to account: in this scene (a perspective floor,
// two lights, a moving and a still occluder) the two differ only at shadow edges.
TEST(StillShadow, ShadingRateAndPerSampleShadowsDifferOnlyAtEdges) {
    std::string perSample = kMovingOverStill;
    perSample.insert(perSample.find("WorldBegin"), kPerSample);
    const RenderResult vertex = renderRib(kMovingOverStill, test::optionsFor(Algorithm::Spacetime));
    const RenderResult sample = renderRib(perSample, test::optionsFor(Algorithm::Spacetime));
    ASSERT_EQ(vertex.frames.size(), sample.frames.size());
    // Pixels differing by more than 0.02, per frame: at most those along the shadows' edges (the
    // moving patch's and the sphere's shadow outlines under two lights, about 90 pixels a frame).
    for (size_t f = 0; f < vertex.frames.size(); ++f) {
        const size_t differ = test::differingPixels(vertex.frames[f], sample.frames[f], 0.02f);
        EXPECT_LT(differ, 120u) << "frame " << f;
    }
    EXPECT_LT(test::meanAbsDifference(vertex, sample), 0.01f);
    EXPECT_GT(sample.stats.counters.shadowRays, vertex.stats.counters.shadowRays);
}

}  // namespace
}  // namespace streyes
