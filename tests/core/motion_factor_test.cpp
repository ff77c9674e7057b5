// GeometricApproximation "motionfactor": a surface moving b pixels in one exposure is diced at
// ShadingRate * max(1, motionfactor * b / 16), as RenderMan coarsens fast movers. Still surfaces
// and slow movers are untouched, pixels never depend on the frame block, and occlusion culling at
// tolerance 0 stays exact.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bodies/material.h"
#include "test_util.h"

namespace streyes {
namespace {

// A 32 x 32 square on a 160 x 64 orthographic frame, moving `motion` pixels right during each
// frame's open shutter (frames 0-2), under `extra` attributes.
std::string movingSquare(double motion, const std::string& extra) {
    return test::orthoHeader(160, 64, "Shutter 0 1\n") + extra + "Color 1 0.5 0.25\nMotionBegin [0 3]\nTranslate 0 0 0\n" +
           "Translate " + std::to_string(3 * motion) + " 0 0\nMotionEnd\n" + test::square(8, 40, 16, 48, 5) + "WorldEnd\n";
}

RenderOptions threeFrames(Algorithm a = Algorithm::SpacetimeOcclusion) {
    RenderOptions o = test::optionsFor(a);
    o.hasFrames = true;
    o.firstFrame = 0;
    o.lastFrame = 2;
    o.samples = 4;
    return o;
}

TEST(MotionFactor, TheRuleRaisesTheRateByTheBlurOverSixteenPixels) {
    EXPECT_EQ(motionDicingRate(1, 0, 64), 1.0f);      // off
    EXPECT_EQ(motionDicingRate(1, 1, 8), 1.0f);       // slow: never finer than ShadingRate
    EXPECT_EQ(motionDicingRate(1, 1, 64), 4.0f);      // 64 / 16
    EXPECT_EQ(motionDicingRate(0.5f, 2, 32), 2.0f);   // 0.5 * 2 * 32 / 16
    EXPECT_EQ(motionDicingRate(1, 1, 0), 1.0f);       // still
}

// A square moving 32 pixels an exposure under motionfactor 2 is diced at rate 4: a quarter of the
// micropolygons, and since a flat square is the same square at any rate, the same coverage.
TEST(MotionFactor, AFastFlatSquareIsDicedAtTheRaisedRateAndCoversTheSame) {
    const test::RenderResult fine = test::renderRib(movingSquare(32, ""), threeFrames());
    const test::RenderResult coarse =
        test::renderRib(movingSquare(32, "GeometricApproximation \"motionfactor\" 2\n"), threeFrames());
    const double ratio = double(coarse.stats.counters.micropolygons) / double(fine.stats.counters.micropolygons);
    EXPECT_NEAR(ratio, 0.25, 0.05) << fine.stats.counters.micropolygons << " -> " << coarse.stats.counters.micropolygons;
    for (int f = 0; f <= 2; ++f) {
        EXPECT_NEAR(test::alphaSum(coarse, f), test::alphaSum(fine, f), 1e-3 * test::alphaSum(fine, f)) << "frame " << f;
        EXPECT_NEAR(test::alphaSum(fine, f), 32.0 * 32.0, 0.01 * 32.0 * 32.0) << "frame " << f;  // the square's area
    }
    EXPECT_LT(test::maxAbsDifference(fine, coarse), 1e-4f);  // constant colour: only the dicing differs
}

// Slow movers (blur under 16 / motionfactor pixels) and still surfaces are diced as without it,
// bit for bit: flat and curved.
TEST(MotionFactor, StillAndSlowSurfacesKeepTheirPixels) {
    const std::string factor = "GeometricApproximation \"motionfactor\" 1\n";
    const RenderOptions o = threeFrames();
    EXPECT_TRUE(test::identicalPixels(test::renderRib(movingSquare(8, ""), o), test::renderRib(movingSquare(8, factor), o)));
    const std::string sphere = "Format 64 48 1\nProjection \"perspective\" \"fov\" [40]\nShutter 0 1\n";
    const std::string world = "WorldBegin\nLightSource \"distantlight\" 1\nSurface \"matte\"\nTranslate 0 0 6\nSphere 1.5 -1.5 1.5 360\nWorldEnd\n";
    const test::RenderResult a = test::renderRib(sphere + world, o), b = test::renderRib(sphere + factor + world, o);
    EXPECT_TRUE(test::identicalPixels(a, b));
    EXPECT_EQ(a.stats.counters.micropolygons, b.stats.counters.micropolygons);
}

// A sphere under a camera moving about 22 pixels an exposure, under motionfactor 4 (rate about
// 5.5): its whole mesh is diced at one raised rate (faces meet), with under half the
// micropolygons, and the same silhouette within sampling noise.
TEST(MotionFactor, AFastCurvedSurfaceIsDicedCoarserAsOneMesh) {
    const std::string head = "Format 96 72 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 4 4\nShutter 0 1\n";
    const std::string body = "MotionBegin [0 1]\nTranslate 0 0 6\nTranslate -1 0 6\nMotionEnd\nWorldBegin\n"
                             "LightSource \"distantlight\" 1 \"from\" [0 0 -1] \"to\" [0 0 0]\nSurface \"matte\"\n"
                             "Sphere 1.5 -1.5 1.5 360\nWorldEnd\n";
    RenderOptions o = test::optionsFor(Algorithm::Spacetime);
    o.hasFrames = true;
    o.firstFrame = o.lastFrame = 0;
    const test::RenderResult fine = test::renderRib(head + body, o);
    const test::RenderResult coarse = test::renderRib(head + "GeometricApproximation \"motionfactor\" 4\n" + body, o);
    EXPECT_LT(coarse.stats.counters.micropolygons * 2, fine.stats.counters.micropolygons);
    const double area = test::alphaSum(fine, 0);
    EXPECT_GT(area, 500.0);
    EXPECT_NEAR(test::alphaSum(coarse, 0), area, 0.01 * area);
    EXPECT_LT(test::meanAbsDifference(fine, coarse), 0.01f);
}

// The rate is the piece's own (its motion per exposure), so a frame's pixels are the same alone
// and in a block, and culling at tolerance 0 changes nothing.
TEST(MotionFactor, FrameBlockInvariantAndExactUnderOcclusionCulling) {
    const std::string rib = movingSquare(40, "GeometricApproximation \"motionfactor\" 1\n");
    RenderOptions o = threeFrames(Algorithm::Spacetime);
    const test::RenderResult block = test::renderRib(rib, o);
    o.algorithm = Algorithm::SpacetimeOcclusion;
    EXPECT_TRUE(test::identicalPixels(block, test::renderRib(rib, o)));
    o.firstFrame = o.lastFrame = 1;
    const test::RenderResult alone = test::renderRib(rib, o);
    test::RenderResult middle;
    middle.frames = {block.frame(1)};
    EXPECT_TRUE(test::identicalPixels(middle, alone));
}

TEST(MotionFactor, BadValuesNameTheLineAndOtherApproximationsWarn) {
    const std::string bad = test::ribError(test::orthoHeader(8, 8) + "GeometricApproximation \"motionfactor\" -1\nWorldEnd\n");
    EXPECT_NE(bad.find("bad.rib:7"), std::string::npos) << bad;
    EXPECT_NE(bad.find("motionfactor"), std::string::npos) << bad;
    const test::RenderResult r =
        test::renderRib(test::orthoHeader(8, 8) + "GeometricApproximation \"flatness\" 0.5\n" + test::square(0, 8, 0, 8, 5) + "WorldEnd\n");
    bool warned = false;
    for (const std::string& w : r.warnings) warned = warned || w.find("\"flatness\" is not modelled") != std::string::npos;
    EXPECT_TRUE(warned);
    EXPECT_NEAR(test::alphaSum(r, 0), 64.0, 1e-3);
}

}  // namespace
}  // namespace streyes
