// NuPatch and TrimCurve end to end, against analytic answers: a NURBS disc's and sphere's
// silhouettes, a trimmed hole's area, a moving patch's blur; and the reader's errors for bad
// parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "nurbs_rib.h"
#include "scene/rib_parser.h"
#include "streyes/rib.h"
#include "streyes/sequence.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::RenderResult;
using test::renderRib;

using test::alphaSum;

// Area of the unit-pixel [px, px+1] x [py, py+1] inside the circle of radius r about (cx, cy), by
// 256 x 256 point sampling (error far below a sample of the render).
double pixelInCircle(int px, int py, double cx, double cy, double r) {
    int in = 0;
    for (int j = 0; j < 256; ++j)
        for (int i = 0; i < 256; ++i) {
            const double x = px + (i + 0.5) / 256 - cx, y = py + (j + 0.5) / 256 - cy;
            in += x * x + y * y <= r * r;
        }
    return in / 65536.0;
}

TEST(NurbsRender, DiscSilhouetteIsTheCircle) {
    // Radius 20 pixels about (32, 32), seen straight on (orthographic, a unit is a pixel).
    const std::string rib = test::orthoHeader(64, 64, "PixelSamples 8 8\nShadingRate 0.25\n") +
                            "Translate 32 32 0\n" + test::nurbsDisc(20, 5) + "WorldEnd\n";
    RenderResult r = renderRib(rib);
    const double expected = M_PI * 400;
    EXPECT_NEAR(alphaSum(r, 0), expected, 5e-4 * expected);  // measured 0.035 %
    // Pixel by pixel against the circle (raster y runs down: raster y = 64 - y).
    double worst = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            worst = std::max(worst, std::fabs(r.alpha(0, x, y) - pixelInCircle(x, 63 - y, 32, 32, 20)));
    EXPECT_LT(worst, 0.08);  // 64 stratified samples a pixel: an edge misses by a few (measured 0.036)
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
}

// umin umax vmin vmax select part of the surface: u from 0.25 to 1 is three quarters of the
// circle (the knots sit at the quarters), v from 0.5 to 1 the outer half of the radius.
TEST(NurbsRender, RangeSelectsPartOfTheSurface) {
    std::string disc = test::nurbsDisc(20, 5);
    const std::string ranges = "0 1 2 2 [0 0 1 1] 0 1 ";
    const size_t at = disc.find(ranges);
    ASSERT_NE(at, std::string::npos);
    disc.replace(at, ranges.size(), "0.25 1 2 2 [0 0 1 1] 0.5 1 ");
    ASSERT_NE(disc.find("0 0 0 0.25 0.25 0.5 0.5 0.75 0.75 1 1 1] 0.25 1 2 2"), std::string::npos);
    const std::string rib = test::orthoHeader(64, 64, "PixelSamples 8 8\nShadingRate 0.25\n") +
                            "Translate 32 32 0\n" + disc + "WorldEnd\n";
    RenderResult r = renderRib(rib);
    const double expected = 0.75 * (M_PI * 400 - M_PI * 100);
    EXPECT_NEAR(alphaSum(r, 0), expected, 1e-3 * expected);
    EXPECT_EQ(r.alpha(0, 32 + 5, 32 - 15), 0.0f);  // x > 0, y > 0 (raster y down): the quarter left out
    EXPECT_EQ(r.alpha(0, 32 - 15, 32 - 5), 1.0f);  // x < 0, y > 0: kept
    EXPECT_EQ(r.alpha(0, 32, 32), 0.0f);           // the inner half of the radius is left out
}

// Varying Cs sits at the knots and is bilinear between them: a strip of two spans (knots at 0,
// 0.25 and 1 of u, so the middle colour sits a quarter of the way along), red, green and blue
// along u, darker along v.
TEST(NurbsRender, VaryingColourIsBilinearBetweenTheKnots) {
    const std::string rib = test::orthoHeader(64, 16, "PixelSamples 4 4\n") +
                            "NuPatch 3 2 [0 0 0.25 1 1] 0 1 2 2 [0 0 1 1] 0 1 "
                            "\"Cs\" [1 0 0  0 1 0  0 0 1  0.5 0 0  0 0.5 0  0 0 0.5] "
                            "\"P\" [0 0 5  16 0 5  64 0 5  0 16 5  16 16 5  64 16 5]\nWorldEnd\n";
    RenderResult r = renderRib(rib);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    // Pixel centres: x + 0.5 along u (x = 64 u between the knots' points at 0, 16, 64), raster
    // row 8 is y = 7.5 of 16 (v = 0.47).
    auto expect = [&](int x, Color c) {
        const float v = 7.5f / 16, shade = 1 - 0.5f * v;
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(r.channel(0, x, 8, ch), c[ch] * shade, 2e-3f) << "x " << x;
    };
    expect(4, Color{1 - 4.5f / 16, 4.5f / 16, 0});                 // in the first span
    expect(40, Color{0, 1 - (40.5f - 16) / 48, (40.5f - 16) / 48});  // in the second
}

// A shader sees u and v over [umin, umax] x [vmin, vmax], not the unit square (RenderMan's rule
// for NURBS): u from 2 to 4 across the patch, v from 0.5 to 1.
TEST(NurbsRender, ShadersSeeThePatchsOwnParameters) {
    test::TempDir dir("nurbs-shader");
    std::ofstream(dir.path() + "/showuv.sl") << "surface showuv() { Ci = color(u / 4, v, 0); Oi = 1; }\n";
    const std::string rib = test::orthoHeader(64, 16, "PixelSamples 4 4\nOption \"searchpath\" \"shader\" \"" +
                                                          dir.path() + ":@\"\n") +
                            "Surface \"showuv\"\n"
                            "NuPatch 2 2 [2 2 4 4] 2 4 2 2 [0.5 0.5 1 1] 0.5 1 \"P\" [0 0 5  64 0 5  0 16 5  64 16 5]\n"
                            "WorldEnd\n";
    RenderResult r = renderRib(rib);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    // Pixel centre x + 0.5 is u = 2 + 2 (x + 0.5) / 64; raster row 8 is y = 7.5, v = 0.5 + 0.5 * 7.5 / 16.
    // (A grid's shader takes each vertex's u, v from its row and column, while a vertex on a
    // piece's side sits on its line's lattice: by a piece's edge, as at x = 32, v is off by up
    // to half a row, 0.007 here. That is how every curved surface is shaded, not the NuPatch.)
    for (int x : {3, 32, 60}) {
        EXPECT_NEAR(r.channel(0, x, 8, 0), (2 + 2 * (x + 0.5f) / 64) / 4, 2e-3f) << "x " << x;
        EXPECT_NEAR(r.channel(0, x, 8, 1), 0.5f + 0.5f * 7.5f / 16, 1e-2f) << "x " << x;
    }
}

// Projected area of a sphere of radius r centred at c (camera space), pixels at distance f per
// unit (as CurvedRender.SphereSilhouetteAreaPerFrameInPerspective).
double sphereImageArea(Vec3d c, double r, double f) {
    const double D = length(c), a = std::asin(r / D), th = std::acos(c.z / D);
    const double sa = std::sin(a), ca = std::cos(a), ct = std::cos(th);
    return M_PI * f * f * sa * sa * ca / std::pow(ct * ct - sa * sa, 1.5);
}

TEST(NurbsRender, SphereSilhouetteInPerspective) {
    RenderResult r = renderRib(R"(Format 64 64 1
Projection "perspective" "fov" 40
PixelSamples 4 4
PixelFilter "box" 1 1
ShadingRate 0.25
WorldBegin
Surface "constant"
Translate 0.6 -0.4 6
Rotate 30 1 0.5 0
)" + test::nurbsSphere(1.5) + "WorldEnd\n");
    const double f = 32 / std::tan(20 * M_PI / 180);
    const double expected = sphereImageArea({0.6, -0.4, 6}, 1.5, f);
    EXPECT_NEAR(alphaSum(r, 0), expected, 0.0015 * expected);  // measured 0.09 %: chords inside the limb
    EXPECT_GT(r.stats.counters.gridsDiced, 4u);
}

TEST(NurbsRender, TrimmedHoleTakesItsArea) {
    // A 40 x 40 pixel square with a hole of radius 10 pixels (0.25 in u, v) at its middle.
    // Micropolygons of a quarter pixel: the hole's edge is resolved to an eighth of a pixel.
    const std::string header = test::orthoHeader(64, 64, "PixelSamples 8 8\nShadingRate 0.0625\n");
    const std::string square = test::nurbsSquare(12, 52, 12, 52, 5);
    RenderResult trimmed = renderRib(header + test::trimCircle(0.5, 0.5, 0.25) + square + "WorldEnd\n");
    const double expected = 1600 - M_PI * 100;
    EXPECT_NEAR(alphaSum(trimmed, 0), expected, 0.8);  // 0.25 % of the hole (measured 0.25 pixel)
    EXPECT_EQ(trimmed.alpha(0, 32, 32), 0.0f);  // the middle of the hole
    EXPECT_EQ(trimmed.alpha(0, 14, 14), 1.0f);  // a corner of the square
    // Off-centre and small (radius 3 pixels, 0.075): the area follows the trim, not the grid.
    RenderResult small = renderRib(header + test::trimCircle(0.3, 0.6, 0.075) + square + "WorldEnd\n");
    EXPECT_NEAR(alphaSum(small, 0), 1600 - M_PI * 9, 0.6);  // measured 0.2 pixel
    // TrimCurve is attribute state: it ends with its AttributeEnd, and [] turns it off.
    RenderResult scoped = renderRib(header + "AttributeBegin\n" + test::trimCircle(0.5, 0.5, 0.25) +
                                    "AttributeEnd\n" + square + "WorldEnd\n");
    EXPECT_NEAR(alphaSum(scoped, 0), 1600, 1e-3);
    // Pieces wholly inside the hole are not diced: a micropolygon each instead of a grid (the
    // hole is a fifth of the square; the pieces of 4 x 4 pixels wholly inside it, about half of
    // that: measured 23,212 micropolygons against 25,600).
    EXPECT_LT(double(trimmed.stats.counters.micropolygons), 0.95 * double(scoped.stats.counters.micropolygons));
    RenderResult cleared = renderRib(header + test::trimCircle(0.5, 0.5, 0.25) +
                                     "TrimCurve [] [] [] [] [] [] [] [] []\n" + square + "WorldEnd\n");
    EXPECT_NEAR(alphaSum(cleared, 0), 1600, 1e-3);
}

// A still patch under a moving light is shaded at both ends of the exposure (its grid is made
// moving after dicing): its hole stays a hole.
TEST(NurbsRender, TrimmedHoleStaysUnderAMovingLight) {
    const std::string rib = test::orthoHeader(64, 64, "PixelSamples 8 8\nShadingRate 0.0625\nShutter 0 1\n") +
                            "TransformBegin\nMotionBegin [0 1]\nTranslate -20 0 0\nTranslate 20 0 0\nMotionEnd\n"
                            "LightSource \"pointlight\" 1 \"from\" [32 32 -10] \"intensity\" [400]\nTransformEnd\n"
                            "Surface \"matte\"\n" +
                            test::trimCircle(0.5, 0.5, 0.25) + test::nurbsSquare(12, 52, 12, 52, 5) + "WorldEnd\n";
    RenderResult r = renderRib(rib);
    EXPECT_NEAR(alphaSum(r, 0), 1600 - M_PI * 100, 0.8);
    EXPECT_EQ(r.alpha(0, 32, 32), 0.0f);
}

TEST(NurbsRender, MovingPatchBlursAlongItsPath) {
    // The disc moves 16 pixels right during the exposure: its coverage keeps its area and its
    // centroid lies half way.
    std::string keys = test::orthoHeader(96, 64, "PixelSamples 8 8\nShutter 0 1\nShadingRate 0.25\n") +
                       "Translate 40 32 0\n" +
                       "MotionBegin [0 1]\n" + test::nurbsDisc(12, 5);
    // The second key: the same disc, its points 16 pixels along x (Pw: (x + 16) w).
    const test::NurbsCircle c;
    std::ostringstream moved;
    moved.precision(17);
    moved << "NuPatch 9 3 " << test::NurbsCircle::knots() << " 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [";
    for (double rho : {0.0, 12.0})
        for (int i = 0; i < 9; ++i)
            moved << (c.x[i] * rho + 16) * c.w[i] << " " << c.y[i] * rho * c.w[i] << " " << 5 * c.w[i] << " " << c.w[i]
                  << "  ";
    keys += moved.str() + "]\nMotionEnd\nWorldEnd\n";
    RenderResult r = renderRib(keys);
    double sum = 0, mx = 0;
    const FrameImage& img = r.frame(0);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            sum += r.alpha(0, x, y);
            mx += r.alpha(0, x, y) * (x + 0.5);
        }
    EXPECT_NEAR(sum, M_PI * 144, 4e-3 * M_PI * 144);  // each sample at its own time: noisier than a still edge
    EXPECT_NEAR(mx / sum, 48.0, 0.05);
    // Not a still disc at either end: the middle column is covered only part of the time.
    EXPECT_GT(r.alpha(0, 48, 32), 0.99f);
    EXPECT_LT(r.alpha(0, 29, 32), 0.9f);
    EXPECT_GT(r.alpha(0, 29, 32), 0.1f);
}

// scenes/nurbs.rib (every request of this file in use: trims, rational surfaces moving by their
// transforms and by their own keys) renders without a warning, and shows its objects.
TEST(NurbsRender, ExampleSceneRendersWithoutWarnings) {
    RenderOptions o;
    o.xres = 64, o.yres = 36, o.samples = 1;
    o.hasFrames = true, o.firstFrame = 1, o.lastFrame = 2;
    RenderResult r = test::renderFile(test::sourcePath("scenes/nurbs.rib"), o);
    EXPECT_TRUE(r.warnings.empty()) << (r.warnings.empty() ? "" : r.warnings[0]);
    ASSERT_EQ(r.frames.size(), 2u);
    EXPECT_GT(alphaSum(r, 2), 0.5 * 64 * 36);  // the floor fills most of the frame
    EXPECT_LT(alphaSum(r, 2), 0.95 * 64 * 36);  // but not its holes nor the sky
    EXPECT_GT(r.stats.counters.gridsDiced, 20u);
}

// Frame sequences merge a NuPatch that stays the same from frame to frame into one run, and
// start a new run where its trim changes (TrimCurve is part of the patch's data).
TEST(NurbsRender, SequencesMergeStillPatchesAndSeeTrimChanges) {
    auto frame = [](int f, double hole) {
        return "FrameBegin " + std::to_string(f) + "\nFormat 64 64 1\nWorldBegin\nSurface \"constant\"\n" +
               test::trimCircle(0.5, 0.5, 0.25) + test::nurbsSquare(-0.5, 0.5, -0.5, 0.5, 3) +
               test::trimCircle(0.5, 0.5, hole) + test::nurbsSquare(-0.9, -0.6, -0.5, 0.5, 3) + "WorldEnd\nFrameEnd\n";
    };
    Log log;
    SequenceBuilder b(log);
    for (int f = 1; f <= 4; ++f) {
        Scene scene;
        RibParser p(scene, log);
        p.setFrameHandler([&](Scene&& s) { b.add(std::move(s)); });
        p.parseString(frame(f, f < 3 ? 0.25 : 0.1), "frame" + std::to_string(f) + ".rib");
        p.finish();
    }
    const Sequence seq = b.finish();
    EXPECT_EQ(seq.stats.runs, 3u);  // the first patch over frames 1-4; the second over 1-2 and 3-4
    ASSERT_EQ(seq.scene.nuPatches.size(), 3u);
    EXPECT_EQ(seq.stats.stillRuns, 3u);
}

// ---- Bad parameters: exit 2 naming file:line -------------------------------------------------
std::string errorOf(const std::string& world) { return test::ribError("WorldBegin\n" + world + "WorldEnd\n"); }

void expectError(const std::string& world, const std::string& message) {
    const std::string e = errorOf(world);
    EXPECT_NE(e.find("bad.rib:2: NuPatch"), std::string::npos) << e;
    EXPECT_NE(e.find(message), std::string::npos) << e;
}

const char* kSquareP = "\"P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n";

TEST(NurbsRender, BadNuPatchParametersNameFileAndLine) {
    EXPECT_EQ(errorOf(std::string("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 ") + kSquareP), "");
    expectError(std::string("NuPatch 2 0 [0 0] 0 1 2 2 [0 0 1 1] 0 1 ") + kSquareP, "u order must be 1 to 32, got 0");
    expectError(std::string("NuPatch 2 2 [0 0 1] 0 1 2 2 [0 0 1 1] 0 1 ") + kSquareP,
                "u knots: 3 values, expected 4");
    expectError(std::string("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 1 0.5 1] 0 1 ") + kSquareP,
                "v knots must not decrease: knot 2 is 0.5 after 1");
    expectError(std::string("NuPatch 2 2 [0 0 1 1] 0 1.5 2 2 [0 0 1 1] 0 1 ") + kSquareP,
                "u range [0, 1.5] must be a non-empty part of the knots' range [0, 1]");
    expectError(std::string("NuPatch 2 2 [0 0 1 1] -1 1 2 2 [0 0 1 1] 0 1 ") + kSquareP, "u range [-1, 1]");
    expectError(std::string("NuPatch 2 3 [0 0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 ") + kSquareP,
                "u: 2 control points are fewer than the order 3");
    expectError("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"P\" [0 0 0 1 0 0 0 1 0]\n",
                "parameter 'P' has 9 numbers, expected 12");
    expectError("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [0 0 0 1 1 0 0 1 0 1 0 -1 1 1 0 1]\n",
                "\"Pw\" vertex 2 has weight -1: NuPatch weights must be positive");
    expectError(std::string("NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Cs\" [1 0 0 0 1 0] ") + kSquareP,
                "parameter 'Cs' has 6 numbers");
}

TEST(NurbsRender, BadTrimCurveParametersNameFileAndLine) {
    auto trimError = [](const std::string& args) { return errorOf("TrimCurve " + args + "\n"); };
    const std::string ok = "[1] [2] [0 0 1 2 3 3] [0] [3] [4] [0 1 1 0] [0 0 1 1] [1 1 1 1]";
    EXPECT_EQ(trimError(ok), "");
    EXPECT_NE(trimError("[1] [2] [0 0 1 2 3 3] [0] [3] [4] [0 1 1] [0 0 1 1] [1 1 1 1]")
                  .find("bad.rib:2: TrimCurve: u has 3 values, expected 4"),
              std::string::npos);
    EXPECT_NE(trimError("[1] [2] [0 0 2 1 3 3] [0] [3] [4] [0 1 1 0] [0 0 1 1] [1 1 1 1]")
                  .find("trim curve 0 knots must not decrease"),
              std::string::npos);
    EXPECT_NE(trimError("[1] [0] [0 0 1 2 3 3] [0] [3] [4] [0 1 1 0] [0 0 1 1] [1 1 1 1]")
                  .find("order must hold whole numbers of at least 1"),
              std::string::npos);
    EXPECT_NE(trimError("[1] [2] [0 0 1 2 3 3] [0] [4] [4] [0 1 1 0] [0 0 1 1] [1 1 1 1]")
                  .find("trim curve 0 range [0, 4]"),
              std::string::npos);
    EXPECT_NE(trimError("[1] [2] [0 0 1 2 3 3] [0] [3] [4] [0 1 1 0] [0 0 1 1] [1 0 1 1]").find("has weight 0"),
              std::string::npos);
}

TEST(NurbsRender, MotionKeysMustShareKnotsAndWeights) {
    const std::string e = errorOf(std::string("MotionBegin [0 1]\nNuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 ") +
                                  kSquareP + "NuPatch 2 2 [0 0 2 2] 0 2 2 2 [0 0 1 1] 0 1 " + kSquareP + "MotionEnd\n");
    EXPECT_NE(e.find("must have the same sizes, orders, knots, ranges and weights"), std::string::npos) << e;
}

}  // namespace
}  // namespace streyes
