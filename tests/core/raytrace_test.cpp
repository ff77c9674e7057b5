// The ray tracer against analytic answers and against the rasterizer, sample by sample; shadows
// (motion-blurred on still geometry) in both; the paper's counters.
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

// ---- The ray tracer and the rasterizer see the same surfaces through the same samples --------------

// The square of render_test's StaticSquareCoverageIsAnalytic, `shift` pixels to the right.
std::string staticSquare(double shift = 0) {
    return orthoHeader(32, 16, "PixelSamples 8 8\n") + "Color [0.2 0.4 0.6]\n" +
           square(8.3 + shift, 20.6 + shift, 4.2, 11.7, 5) + "WorldEnd\n";
}

std::string readSourceFile(const std::string& relative) {
    FILE* f = std::fopen(test::sourcePath(relative).c_str(), "rb");
    std::string text;
    char buf[4096];
    size_t n;
    while (f && (n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
    if (f) std::fclose(f);
    return text;
}

void expectSamplesAgree(const std::string& rib, const char* what) {
    test::SampleRecord raster = test::renderSamples(rib, test::optionsFor(Algorithm::Spacetime));
    test::SampleRecord traced = test::renderSamples(rib, test::optionsFor(Algorithm::Raytrace));
    test::SampleAgreement agree = test::compareSamples(raster, traced);
    ASSERT_GT(agree.samples, 1000u) << what;
    EXPECT_GE(double(agree.hitOrMiss) / double(agree.samples), 0.999) << what;
    EXPECT_GE(agree.share(), 0.999) << what << ": " << agree.samples - agree.sameSurface << " of " << agree.samples
                                    << " samples differ";
    size_t hits = 0;
    for (const SampleHit& h : traced.hits) hits += !h.empty();
    EXPECT_GT(hits, agree.samples / 10) << what;  // the scenes are not empty
}

TEST(Raytrace, StaticSquareSamplesAgreeWithTheRasterizer) { expectSamplesAgree(staticSquare(), "static square"); }

TEST(Raytrace, MovingRampSamplesAgreeWithTheRasterizer) {
    expectSamplesAgree(readSourceFile("scenes/ramp.rib"), "scenes/ramp.rib");
}

TEST(Raytrace, OverlappingPatchSamplesAgreeWithTheRasterizer) {
    expectSamplesAgree(readSourceFile("scenes/overlap.rib"), "scenes/overlap.rib");
}

// The comparison can fail: a square moved by a pixel disagrees on far more than 0.1% of samples.
TEST(Raytrace, SampleComparisonSeesAMovedSquare) {
    test::SampleAgreement agree = test::compareSamples(
        test::renderSamples(staticSquare()), test::renderSamples(staticSquare(1), test::optionsFor(Algorithm::Raytrace)));
    EXPECT_LT(agree.share(), 0.99);
}

// A perspective animation with a still floor, a twisted patch moving on a bent path and
// turning, a triangle that starts moving at frame 3 (keys 3 and 5, held before: a still body
// and a moving one) and lights; shadows on.
const char* kAnimation = R"(Format 40 30 1
Projection "perspective" "fov" [60]
PixelSamples 3 3
Shutter 0 0.5
Option "streyes" "int frames" [0 5]
WorldBegin
LightSource "ambientlight" 1 "intensity" [0.2]
Attribute "light" "shadows" "on"
LightSource "distantlight" 2 "from" [1 4 -1] "to" [0 0 0]
LightSource "pointlight" 3 "from" [-3 3 2] "intensity" [8]
Surface "plastic"
AttributeBegin
  Color [0.8 0.7 0.2]
  Patch "bilinear" "P" [-6 -2 12  6 -2 12  -6 -2 4  6 -2 4]
AttributeEnd
AttributeBegin
  Color [0.2 0.5 0.9]
  MotionBegin [0 2.5 5]
    Translate -3 0.5 9
    Translate 0 -0.5 7
    Translate 3 0.5 10
  MotionEnd
  MotionBegin [0 5]
    Rotate -30 1 0 0
    Rotate 60 1 0.5 0
  MotionEnd
  Patch "bilinear" "P" [-1.2 -1 0.3  1 -1 0  -1 1 0  1 1.2 -0.3]
AttributeEnd
AttributeBegin
  Color [0.9 0.2 0.2]
  MotionBegin [3 5]
    Translate 1 -1 7
    Translate 0 -1 7
  MotionEnd
  Polygon "P" [0 0 0  1 0 0  0.5 1 0.5]
AttributeEnd
WorldEnd
)";

// The ray tracer shades each sample at its hit and time; the rasterizer shades a grid's vertices
// at the grid's t0 and t1 and interpolates linearly in space and time. So colours agree as far as
// shading changes across a micropolygon and over a grid's time span:
// - the frames rasterizer's grids span one exposure (0.5 frames, in which the twisted patch turns
//   9 degrees): colours within 0.01 (measured: 12 of 64,800 samples beyond it);
// - the spacetime rasterizer's grids of the twisted patch span 2.5 frames (its motion keys), in
//   which it turns 45 degrees: up to 0.14 on it (measured), so within 0.15.
// In both, 5 floor samples differ by up to 0.4: at shadow edges, where the two hit points (0.2%
// apart in depth, below) send shadow rays that pass either side of the occluder's edge. So 99.9%
// of samples must agree (65 samples may not, about 7 pixels): a wrong colour by more than the
// tolerance on a surface seen in more than 7 pixels fails.
// Depth within 1%: the rasterizer interpolates z linearly in raster space across a micropolygon,
// which is 0.2-0.3% off on the floor where it recedes fastest.
// Depth of field: the ray tracer's eye rays leave each sample's lens point, and the rasterizer's
// shadow rays leave the hit rebuilt along that ray: the same samples see the same surfaces, in the
// same light and shadow, as without a lens (a hit rebuilt through the pinhole instead would move
// the floor's shadow edges by up to a lens radius).
TEST(Raytrace, DepthOfFieldSamplesAgreeWithTheRasterizer) {
    std::string rib = kAnimation;
    rib.insert(rib.find("PixelSamples"), "DepthOfField 2 1 8\n");
    test::SampleRecord traced = test::renderSamples(rib, test::optionsFor(Algorithm::Raytrace));
    test::SampleRecord raster = test::renderSamples(rib, test::optionsFor(Algorithm::Frames));
    test::SampleAgreement agree = test::compareSamples(raster, traced, 0.01f, 1e-2f);
    EXPECT_GE(agree.share(), 0.999) << agree.samples - agree.sameSurface << " of " << agree.samples << " samples differ";
    // And the lens is there: through a pinhole the samples see otherwise.
    test::SampleRecord pinhole = test::renderSamples(kAnimation, test::optionsFor(Algorithm::Raytrace));
    EXPECT_LT(test::compareSamples(pinhole, traced, 0.01f, 1e-2f).share(), 0.99);
}

TEST(Raytrace, AnimationSamplesAgreeWithTheRasterizer) {
    test::SampleRecord traced = test::renderSamples(kAnimation, test::optionsFor(Algorithm::Raytrace));
    for (const auto& [algorithm, colorTolerance] :
         {std::pair{Algorithm::Frames, 0.01f}, std::pair{Algorithm::Spacetime, 0.15f}}) {
        test::SampleRecord raster = test::renderSamples(kAnimation, test::optionsFor(algorithm));
        test::SampleAgreement agree = test::compareSamples(raster, traced, colorTolerance, 1e-2f);
        EXPECT_GE(agree.share(), 0.999) << algorithmName(algorithm) << ": " << agree.samples - agree.sameSurface
                                        << " of " << agree.samples << " samples differ";
    }
    // Same samples, so the images agree closely too: every pixel within 0.15 (measured 0.11).
    EXPECT_LE(test::maxAbsDifference(renderRib(kAnimation, test::optionsFor(Algorithm::Spacetime)),
                                     renderRib(kAnimation, test::optionsFor(Algorithm::Raytrace))),
              0.15f);
}

// One spacetime hierarchy or one per frame: the same exact nearest hits, the same pixels.
TEST(Raytrace, FrameByFrameHierarchiesGiveTheSamePixels) {
    RenderResult st = renderRib(kAnimation, test::optionsFor(Algorithm::Raytrace));
    RenderResult fr = renderRib(kAnimation, test::optionsFor(Algorithm::RaytraceFrames));
    ASSERT_EQ(st.frames.size(), 6u);
    EXPECT_TRUE(test::identicalPixels(st, fr));
    EXPECT_EQ(st.stats.counters.eyeRays, fr.stats.counters.eyeRays);
    EXPECT_EQ(st.stats.counters.shadowRays, fr.stats.counters.shadowRays);
    EXPECT_GT(st.stats.counters.shadowRays, 0u);
    EXPECT_GT(st.stats.counters.rayBodyTests, 0u);
    // Patches with more than two motion keys are one body each in the split loop; the ray
    // tracer holds their segments.
    EXPECT_GT(st.stats.counters.traceBodies, st.stats.counters.rootBodies);
}

TEST(Raytrace, ThreadCountDoesNotChangePixelsWithShadows) {
    for (Algorithm a : {Algorithm::Raytrace, Algorithm::RaytraceFrames, Algorithm::Spacetime}) {
        RenderOptions one = test::optionsFor(a), two = test::optionsFor(a);
        one.threads = 1;
        two.threads = 2;
        one.bucketSize = two.bucketSize = 8;
        RenderResult r1 = renderRib(kAnimation, one), r2 = renderRib(kAnimation, two);
        EXPECT_TRUE(test::identicalPixels(r1, r2)) << algorithmName(a);
        EXPECT_EQ(test::differingCounts(r1.stats.counters, r2.stats.counters), std::vector<std::string>{})
            << algorithmName(a);
        EXPECT_GT(r1.stats.counters.rayBodyTests, 0u) << algorithmName(a);
    }
}

// ---- The paper's counters ------------------------------------------------------------------------------

const char* kStillScene = R"(Format 40 30 1
Projection "perspective" "fov" [50]
PixelSamples 2 2
Shutter 0 0.5
WorldBegin
Surface "defaultsurface"
Patch "bilinear" "P" [-6 -2 12  6 -2 12  -6 -2 4  6 -2 4]
Patch "bilinear" "P" [-1 -1 6  1 -1 6  -1 1 7  1 1 7]
Patch "bilinear" "P" [-3 -1 8  -2 -1 8  -3 1 8  -2 1 8]
Patch "bilinear" "P" [2 -1 9  3 -1 9  2 1 9  3 1 9]
Patch "bilinear" "P" [0 1.5 9  1 1.5 9  0 2.5 9  1 2.5 9]
Patch "bilinear" "P" [-2 1 10  -1 1 10  -2 2 10  -1 2 10]
WorldEnd
)";

TEST(Raytrace, StillSceneHierarchyIsBuiltOnceInSpacetimeAndPerFrameInFrames) {
    auto run = [](Algorithm a) {
        RenderOptions o = test::optionsFor(a);
        o.hasFrames = true;
        o.firstFrame = 0;
        o.lastFrame = 7;
        o.hierarchy.maxLeafBodies = 1;  // six bodies: make the hierarchy more than one node
        return renderRib(kStillScene, o).stats.counters;
    };
    RenderCounters st = run(Algorithm::Raytrace), fr = run(Algorithm::RaytraceFrames);
    ASSERT_GT(st.boundingVolumes, 1u);
    EXPECT_EQ(fr.boundingVolumes, 8 * st.boundingVolumes);  // the same 3D hierarchy, 8 times
    EXPECT_EQ(st.eyeRays, fr.eyeRays);
    EXPECT_EQ(st.rayBodyTests, fr.rayBodyTests);  // and so the same tests
    EXPECT_GT(st.rayBodyTests, 0u);
    EXPECT_LT(st.rayBodyTests, 2 * st.eyeRays);   // the hierarchy spares most of 6 tests a ray
    EXPECT_EQ(st.shadowRays, 0u);
    EXPECT_EQ(st.gridsDiced, 0u);                 // no split loop
}

// ---- Shadows ---------------------------------------------------------------------------------------------

// A white matte floor at z = 10 facing an orthographic camera (one unit a pixel), lit by a
// distant light travelling along (1, 0, 1) with intensity sqrt 2: exactly 1 where lit. A square
// at z = 5 casts its shadow 5 pixels to the right of itself; it moves 4 pixels during the
// shutter, so the shadow sweeps [13, 17] -> [17, 21] and each floor pixel's brightness is one
// minus the time-averaged coverage of the shadow: a linear blur ramp. The floor is one still
// patch, shaded once per vertex by the rasterizer: only the per-sample shadow ray can blur it.
std::string shadowScene(bool moving) {
    return orthoHeader(32, 4, "PixelSamples 16 16\nShutter 0 1\n") +
           "Attribute \"light\" \"shadows\" \"on\"\n"
           "LightSource \"distantlight\" 1 \"intensity\" [1.41421356] \"from\" [0 0 0] \"to\" [1 0 1]\n"
           "Surface \"matte\" \"Ka\" [0]\n" + square(0, 32, 0, 4, 10) +
           "Color [0.5 0.5 0.5]\n" +
           (moving ? "MotionBegin [0 1]\nTranslate 0 0 0\nTranslate 4 0 0\nMotionEnd\n" : "") +
           square(8, 12, 0, 4, 5) + "WorldEnd\n";
}

class ShadowAlgorithm : public ::testing::TestWithParam<Algorithm> {};
INSTANTIATE_TEST_SUITE_P(Raytrace, ShadowAlgorithm,
                         ::testing::Values(Algorithm::Spacetime, Algorithm::SpacetimeOcclusion, Algorithm::Frames,
                                           Algorithm::FramesOcclusion, Algorithm::Raytrace, Algorithm::RaytraceFrames),
                         [](const ::testing::TestParamInfo<Algorithm>& info) { return test::testName(info.param); });

// The rasterizers test a still occluder's shadow on the still floor at its vertices (one a pixel,
// at integer x): the vertex at x = 17, on the shadow's edge, is in shadow and the one at 18 lit,
// so pixel 17 is the linear ramp between them, 0.5 over the pixel; the ray tracer tests each
// sample, and pixel 17 is lit. Option "trace" "shadowtest" "sample" gives the rasterizers' the
// ray tracer's step (still_shadow_test.cpp).
TEST_P(ShadowAlgorithm, StillOccluderCastsAHardShadow) {
    RenderResult r = renderRib(shadowScene(false), test::optionsFor(GetParam()));
    const bool shadingRate = !raytraces(GetParam());
    for (int y = 0; y < 4; ++y) {
        for (int x : {0, 5, 7, 20, 31}) EXPECT_NEAR(r.channel(0, x, y, 0), 1.0f, 1e-5f) << x;  // lit floor
        EXPECT_NEAR(r.channel(0, 17, y, 0), shadingRate ? 0.5f : 1.0f, shadingRate ? 1e-3f : 1e-5f);
        for (int x : {13, 14, 15, 16}) EXPECT_EQ(r.channel(0, x, y, 0), 0.0f) << x;      // its shadow
        for (int x : {8, 11}) EXPECT_NEAR(r.channel(0, x, y, 0), 0.5f, 1e-5f) << x;      // the occluder, lit
    }
}

TEST_P(ShadowAlgorithm, MovingOccluderShadowIsTheAnalyticBlurRamp) {
    RenderResult r = renderRib(shadowScene(true), test::optionsFor(GetParam()));
    const int spp = 256;
    double worst = 0;
    for (int x = 16; x <= 21; ++x) {  // floor the occluder never hides; its shadow passes over
        double shadowed = 0;
        const int steps = 20000;
        for (int i = 0; i < steps; ++i) {
            const double t = (i + 0.5) / steps;
            shadowed += overlap(x, 13 + 4 * t, 17 + 4 * t) / steps;
        }
        const double expected = 1 - shadowed;
        const double sigma = std::sqrt(expected * (1 - expected) / spp);
        for (int y = 0; y < 4; ++y) {
            EXPECT_NEAR(r.channel(0, x, y, 0), expected, 3 * sigma + 1e-6) << "pixel " << x;
            worst = std::max(worst, std::fabs(r.channel(0, x, y, 0) - expected));
        }
    }
    // The ramp is 1/8 3/8 5/8 7/8 in shadow from x = 17 to 20 (pixel 16 is 7/8 shadowed too).
    EXPECT_NEAR(r.channel(0, 18, 1, 0), 1 - 0.625, 0.1);
    EXPECT_NEAR(r.channel(0, 20, 1, 0), 1 - 0.125, 0.1);
    EXPECT_GT(r.stats.counters.shadowRays, 0u);
}

// Rays are cast only during the exposures of the frames rendered, so the ray tracer takes only
// what exists then: one frame of a shot whose occluder is keyed every frame holds that frame's
// motion segment (and the still floor), not the shot's sixteen, and gives the pixels it gives
// rendered with the whole shot.
TEST(Raytrace, OneFrameOfALongShotTracesOnlyItsOwnTime) {
    std::string keys = "MotionBegin [", moves;
    for (int k = 0; k <= 16; ++k) {
        keys += std::to_string(k) + (k < 16 ? " " : "]\n");
        // A zigzag of a thousandth in depth: keys on a straight line would be one segment
        // (bodies/motion_segments.h, keysOf). It moves the shadow by as much.
        moves += "Translate " + std::to_string(k) + " 0 " + (k % 2 ? "0.001" : "0") + "\n";
    }
    const std::string rib = "Option \"streyes\" \"int frames\" [0 15]\n" +
                            orthoHeader(32, 4, "PixelSamples 4 4\nShutter 0 0.5\n") +
                            "Attribute \"light\" \"shadows\" \"on\"\n"
                            "LightSource \"distantlight\" 1 \"intensity\" [1.41421356] \"from\" [0 0 0] \"to\" [1 0 1]\n"
                            "Surface \"matte\" \"Ka\" [0]\n" + square(0, 32, 0, 4, 10) + keys + moves +
                            "MotionEnd\n" + square(0, 4, 0, 4, 5) + "WorldEnd\n";
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        SCOPED_TRACE(algorithmName(a));
        const test::ShotAndFrame r = test::renderShotAndFrame(rib, test::optionsFor(a), 0, 15, 5);
        const RenderResult &shot = r.shot, &alone = r.alone;
        EXPECT_EQ(shot.stats.counters.traceBodies, 17u);  // the floor and the occluder's 16 segments
        EXPECT_EQ(alone.stats.counters.traceBodies, 2u);  // the floor and frame 5's segment
        EXPECT_TRUE(r.samePixels(5));
        // Frame 5: the occluder moves from x 5-9 to 5.5-9.5, its shadow from 10-14 to 10.5-14.5.
        for (int y = 0; y < 4; ++y) {
            EXPECT_EQ(alone.channel(5, 11, y, 0), 0.0f);  // shadowed throughout
            EXPECT_NEAR(alone.channel(5, 20, y, 0), 1.0f, 1e-5f);  // lit
        }
    }
}

// A light that casts shadows but has nothing in its way gives the light it gives without them:
// the shading split into shadowed parts adds back up.
TEST(Raytrace, UnblockedShadowLightAddsUpToThePlainLight) {
    const std::string lit = std::string(kAnimation), shadowsOn = "Attribute \"light\" \"shadows\" \"on\"\n";
    std::string plain = lit;
    plain.replace(plain.find(shadowsOn), shadowsOn.size(), "");
    // Only the floor and a light above it: nothing can shadow the floor.
    auto floorOnly = [](std::string s) {
        const size_t a = s.find("AttributeBegin\n  Color [0.2"), e = s.find("WorldEnd");
        return s.substr(0, a) + s.substr(e);
    };
    for (Algorithm a : {Algorithm::Spacetime, Algorithm::Raytrace}) {
        RenderResult withShadows = renderRib(floorOnly(lit), test::optionsFor(a));
        RenderResult without = renderRib(floorOnly(plain), test::optionsFor(a));
        // (The rasterizer's still floor tests its vertices; the ray tracer, each sample.)
        EXPECT_GT(withShadows.stats.counters.shadowRays + withShadows.stats.counters.shadowVertexRays, 0u)
            << algorithmName(a);
        EXPECT_EQ(without.stats.counters.shadowRays + without.stats.counters.shadowVertexRays, 0u) << algorithmName(a);
        EXPECT_LT(test::maxAbsDifference(withShadows, without), 1e-5f) << algorithmName(a);
    }
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// A floor lit by `light` with a box-shaped blocker between them (perspective, one frame).
std::string blockerScene(const std::string& light) {
    return "Format 64 48 1\nProjection \"perspective\" \"fov\" [50]\nPixelSamples 3 3\nTranslate 0 -2 8\nWorldBegin\n"
           "LightSource \"ambientlight\" 1 \"intensity\" [0.1]\n" +
           light +
           "Surface \"matte\"\nPatch \"bilinear\" \"P\" [-6 0 -6  6 0 -6  -6 0 6  6 0 6]\n"
           "Polygon \"P\" [-0.8 2 -0.8  0.8 2 -0.8  0.8 2 0.8  -0.8 2 0.8]\nWorldEnd\n";
}

// "shadowname" "raytrace" on a standard light (RenderMan's convention for ray-traced shadows) gives
// the same shadows as Attribute "light" "shadows" "on": the renderer traces them per sample and the
// shader's shadow("raytrace") reads 0. A shadow map's name no pass makes and no file holds: a
// warning, no shadow (the light's .sl source runs: its pixels are the built-in light's within the
// 1e-4 the two are held to).
TEST(Raytrace, ShadownameRaytraceCastsTheSameShadowsAsTheAttribute) {
    const char* lights[] = {
        "LightSource \"spotlight\" 2 \"point from\" [0 5 0] \"point to\" [0 0 0] \"float coneangle\" [1] \"intensity\" [30]",
        "LightSource \"pointlight\" 2 \"point from\" [0.5 5 0.5] \"intensity\" [30]",
        "LightSource \"distantlight\" 2 \"point from\" [0.3 5 0] \"point to\" [0 0 0]"};
    for (const char* light : lights) {
        const test::RenderResult byAttribute =
            test::renderRib(blockerScene(std::string("Attribute \"light\" \"shadows\" \"on\"\n") + light + "\n"));
        const test::RenderResult byName = test::renderRib(blockerScene(std::string(light) + " \"string shadowname\" [\"raytrace\"]\n"));
        const test::RenderResult unshadowed = test::renderRib(blockerScene(std::string(light) + "\n"));
        EXPECT_GT(byName.stats.counters.shadowRays + byName.stats.counters.shadowVertexRays, 0u) << light;
        EXPECT_EQ(byName.warnings, std::vector<std::string>{}) << light;  // a parameter the light takes
        EXPECT_TRUE(test::identicalPixels(byAttribute, byName)) << light;
        // The shadow is there: the floor under the blocker is darker than unshadowed.
        EXPECT_LT(byName.channel(0, 32, 37, 0), 0.5f * unshadowed.channel(0, 32, 37, 0)) << light;
        const test::RenderResult map = test::renderRib(blockerScene(std::string(light) + " \"string shadowname\" [\"light.shad\"]\n"));
        EXPECT_EQ(map.stats.counters.shadowRays, 0u) << light;
        EXPECT_LT(test::maxAbsDifference(map, unshadowed), 1e-4f) << light;
        int warned = 0;
        for (const std::string& w : map.warnings)
            warned += w.find("shadow map \"light.shad\" is written by no pass of this render") != std::string::npos;
        EXPECT_EQ(warned, 1) << light;
    }
}

}  // namespace
}  // namespace streyes
