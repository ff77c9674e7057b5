// Shaders that cast rays (occlusion(), indirectdiffuse(), trace(), transmission()) against
// closed forms, and what a frame's rays may depend on: the frame's own time, never its block.
//
// Every scene is seen by an orthographic camera along +z, one unit a pixel (raster x = x,
// raster y = H - y): a floor at depth 100, and what its rays meet behind it, out of the camera's
// sight (behind the floor, or edge-on to the view).
#include <gtest/gtest.h>

#include <cmath>

#include "form_factor_util.h"
#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

std::string patch(const double p[12]) {
    std::string s = "Patch \"bilinear\" \"P\" [";
    for (int i = 0; i < 12; ++i) s += (i ? " " : "") + std::to_string(p[i]);
    return s + "]\n";
}

// Lambert's form factor from (px, py, pz) on the floor to a polygon (tests/form_factor_util.h).
double formFactor(const double px, const double py, const double pz, const std::vector<std::array<double, 3>>& poly) {
    return test::lambertFormFactor({px, py, pz}, poly);
}

constexpr int kW = 32, kH = 32;
constexpr double kFloor = 100, kRoof = 116;
// The walls stand a hair outside the floor: the floor's border vertices would otherwise lie in
// them, and rays starting on a surface do not see it.
constexpr double kX0 = -0.05, kX1 = kW + 0.05;

// The box over the floor [0, 32]^2: a roof at depth 116 and walls at x = 0 and x = 32 (nearly);
// open at y = 0 and y = 32. Edge-on to the camera or behind the floor: unseen.
std::string halfOpenBox() {
    const double wall0[12] = {kX0, 0, kFloor, kX0, kH, kFloor, kX0, 0, kRoof, kX0, kH, kRoof};
    const double wall1[12] = {kX1, 0, kFloor, kX1, kH, kFloor, kX1, 0, kRoof, kX1, kH, kRoof};
    return test::square(kX0, kX1, 0, kH, kRoof) + patch(wall0) + patch(wall1);
}

double analyticOcclusion(double x, double y) {
    const std::vector<std::array<double, 3>> roof = {{{kX0, 0, kRoof}, {kX1, 0, kRoof}, {kX1, kH, kRoof}, {kX0, kH, kRoof}}};
    const std::vector<std::array<double, 3>> w0 = {{{kX0, 0, kFloor}, {kX0, kH, kFloor}, {kX0, kH, kRoof}, {kX0, 0, kRoof}}};
    const std::vector<std::array<double, 3>> w1 = {{{kX1, 0, kFloor}, {kX1, kH, kFloor}, {kX1, kH, kRoof}, {kX1, 0, kRoof}}};
    return formFactor(x, y, kFloor, roof) + formFactor(x, y, kFloor, w0) + formFactor(x, y, kFloor, w1);
}

TEST(ShaderRays, OcclusionUnderAHalfOpenBoxIsTheFormFactor) {
    test::ShaderDir shaders;
    // The floor's rays go to +z, away from the camera, into the box.
    shaders.add("ao", "surface ao(float samples = 1024) {\n"
                      "  Ci = occlusion(P, normal(0, 0, 1), samples, \"bias\", 0.001); Oi = 1;\n}\n");
    const std::string rib = test::orthographicView(kW, kH, shaders.option() + "ShadingRate 0.25\n") + "WorldBegin\n" +
                            "AttributeBegin\nSurface \"constant\"\n" + halfOpenBox() + "AttributeEnd\n" +
                            "Surface \"ao\"\n" + test::square(0, kW, 0, kH, kFloor) + "WorldEnd\n";
    test::RenderResult r = test::renderRib(rib);
    ASSERT_GT(r.stats.counters.shaderRays, 0u);
    const int s = 1024;
    double sum = 0, want = 0;
    int outside = 0;
    double worstSigmas = 0;
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            // The pixel's mean of the closed form (4 x 4 points): near the walls it changes fast.
            double a = 0;
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) a += analyticOcclusion(px + (i + 0.5) / 4, kH - py - 1 + (j + 0.5) / 4);
            a /= 16;
            const double got = r.channel(0, px, py, 0);
            sum += got;
            want += a;
            const double se = std::sqrt(std::max(a * (1 - a), 1e-4) / s);
            worstSigmas = std::max(worstSigmas, std::fabs(got - a) / se);
            outside += std::fabs(got - a) > 4 * se;
        }
    const double n = double(kW * kH);
    EXPECT_NEAR(sum / n, want / n, 0.01 * want / n) << "mean " << sum / n << " against " << want / n;
    EXPECT_EQ(outside, 0) << "worst pixel " << worstSigmas << " standard errors off";
    EXPECT_GT(want / n, 0.5);  // the box covers most of the sky: a dropped face would show
}

TEST(ShaderRays, OcclusionWithoutOccludersIsZeroAndMaxdistCuts) {
    test::ShaderDir shaders;
    shaders.add("ao", "surface ao(float d = 1e30) { Ci = occlusion(P, normal(0, 0, 1), 64, \"maxdist\", d); }\n");
    const std::string head = test::orthographicView(8, 8, shaders.option()) + "WorldBegin\n";
    const std::string floor = test::square(0, 8, 0, 8, kFloor);
    const std::string roof = "AttributeBegin\nSurface \"constant\"\n" + test::square(-1e5, 1e5, -1e5, 1e5, 110) + "AttributeEnd\n";
    // Nothing above: 0. A roof 10 away covering the sky (but for rays within 0.006 degrees of the
    // horizon): 1, unless maxdist stops short of it.
    EXPECT_EQ(test::renderRib(head + "Surface \"ao\"\n" + floor + "WorldEnd\n").channel(0, 4, 4, 0), 0.0f);
    EXPECT_EQ(test::renderRib(head + roof + "Surface \"ao\"\n" + floor + "WorldEnd\n").channel(0, 4, 4, 0), 1.0f);
    EXPECT_EQ(test::renderRib(head + roof + "Surface \"ao\" \"d\" 9\n" + floor + "WorldEnd\n").channel(0, 4, 4, 0), 0.0f);
}

// A mirror tilted 45 degrees about x (depth 100 + y) sends the camera's rays up (+y) to a checker
// in the plane y = 64: pixel (x, y) sees the checker at (x, depth 100 + y).
TEST(ShaderRays, MirrorMadeWithTraceShowsTheCheckerWhereTheGeometrySays) {
    test::ShaderDir shaders;
    shaders.add("mirror", "surface mirror() { Ci = trace(P, reflect(normalize(I), normalize(N))); Oi = 1; }\n");
    std::string checker = "AttributeBegin\nSurface \"constant\"\n";
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            const double x0 = 8 * i, z0 = kFloor + 8 * j;
            const double p[12] = {x0, 64, z0, x0 + 8, 64, z0, x0, 64, z0 + 8, x0 + 8, 64, z0 + 8};
            checker += "Color [" + std::string((i + j) % 2 ? "1 0 0" : "0 0 1") + "]\n" + patch(p);
        }
    checker += "AttributeEnd\n";
    const double mirror[12] = {0, 0, kFloor, kW, 0, kFloor, 0, kH, kFloor + kH, kW, kH, kFloor + kH};
    const std::string rib = test::orthographicView(kW, kH, shaders.option()) + "WorldBegin\n" + checker + "Surface \"mirror\"\n" +
                            patch(mirror) + "WorldEnd\n";
    test::RenderResult r = test::renderRib(rib);
    int checked = 0;
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            const int y = kH - 1 - py;  // the pixel covers [px, px+1] x [y, y+1]
            // Pixels touching a square's edge mix the two sides (their vertices straddle it).
            if (px % 8 == 0 || px % 8 == 7 || y % 8 == 0 || y % 8 == 7) continue;
            const bool red = (px / 8 + y / 8) % 2;
            EXPECT_EQ(r.channel(0, px, py, 0), red ? 1.0f : 0.0f) << px << " " << py;
            EXPECT_EQ(r.channel(0, px, py, 2), red ? 0.0f : 1.0f) << px << " " << py;
            ++checked;
        }
    EXPECT_EQ(checked, 16 * 36);
}

TEST(ShaderRays, TransmissionThroughASheetOfOpacityHalfIsHalf) {
    test::ShaderDir shaders;
    shaders.add("tr", "surface tr() { Ci = transmission(P, P + vector(0, 0, 50)); Oi = 1; }\n");
    // The sheet, behind the floor, covers its left half.
    const std::string rib = test::orthographicView(16, 8, shaders.option()) + "WorldBegin\nAttributeBegin\nOpacity [0.5 0.5 0.5]\n" +
                            test::square(-10, 8, -10, 18, 120) + "AttributeEnd\nSurface \"tr\"\n" +
                            test::square(0, 16, 0, 8, kFloor) + "WorldEnd\n";
    test::RenderResult r = test::renderRib(rib);
    for (int py = 0; py < 8; ++py)
        for (int px = 0; px < 16; ++px) {
            if (px == 7 || px == 8) continue;  // the sheet's edge
            for (int c = 0; c < 3; ++c) EXPECT_EQ(r.channel(0, px, py, c), px < 8 ? 0.5f : 1.0f) << px << " " << py;
        }
}

TEST(ShaderRays, IndirectDiffuseOfAWhitePlaneUnderAWhiteSurroundingIsOne) {
    test::ShaderDir shaders;
    shaders.add("gi", "surface gi(float samples = 64) {\n"
                      "  Ci = Cs * indirectdiffuse(P, normal(0, 0, 1), samples); Oi = 1;\n}\n");
    // A white box around the floor's sky (constant: it gives exactly its colour); the walls run
    // from the eye plane, so that every ray over the floor meets the box.
    const double L = 1000;
    const double wx0[12] = {-L, -L, 0, -L, L, 0, -L, -L, L, -L, L, L};
    const double wx1[12] = {L, -L, 0, L, L, 0, L, -L, L, L, L, L};
    const double wy0[12] = {-L, -L, 0, L, -L, 0, -L, -L, L, L, -L, L};
    const double wy1[12] = {-L, L, 0, L, L, 0, -L, L, L, L, L, L};
    const std::string box = "AttributeBegin\nSurface \"constant\"\nColor [1 1 1]\n" + test::square(-L, L, -L, L, L) +
                            patch(wx0) + patch(wx1) + patch(wy0) + patch(wy1) + "AttributeEnd\n";
    const std::string floor = "Surface \"gi\"\nColor [1 1 1]\n" + test::square(0, 8, 0, 8, kFloor);
    test::RenderResult lit = test::renderRib(test::orthographicView(8, 8, shaders.option()) + "WorldBegin\n" + box + floor + "WorldEnd\n");
    test::RenderResult dark = test::renderRib(test::orthographicView(8, 8, shaders.option()) + "WorldBegin\n" + floor + "WorldEnd\n");
    for (int py = 0; py < 8; ++py)
        for (int px = 0; px < 8; ++px)
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(lit.channel(0, px, py, c), 1.0f, 1e-5f) << px << " " << py;
                EXPECT_EQ(dark.channel(0, px, py, c), 0.0f);  // rays that meet nothing bring nothing
            }
}

TEST(ShaderRays, IndirectDiffuseOfHalfASkyIsHalf) {
    // A white wall over half the hemisphere (the plane x = 4.5, from either side, fills half of it,
    // cosine-weighted, but for the sliver above its top): 1/2 within the noise of 256 stratified
    // samples. (A wall through the floor's vertices would hide from them: their rays start on it.)
    test::ShaderDir shaders;
    shaders.add("gi", "surface gi() { Ci = indirectdiffuse(P, normal(0, 0, 1), 256, \"bias\", 0.001); }\n");
    const double L = 1000;
    const double wall[12] = {4.5, -L, 0, 4.5, L, 0, 4.5, -L, L, 4.5, L, L};
    const std::string rib = test::orthographicView(8, 8, shaders.option()) + "WorldBegin\nAttributeBegin\nSurface \"constant\"\n" +
                            patch(wall) + "AttributeEnd\nSurface \"gi\"\n" + test::square(0, 8, 0, 8, kFloor) + "WorldEnd\n";
    test::RenderResult r = test::renderRib(rib);
    for (int py = 0; py < 8; ++py)
        for (int px = 0; px < 8; ++px) EXPECT_NEAR(r.channel(0, px, py, 0), 0.5f, 4 * 0.5f / 16) << px << " " << py;
}

// A square moving over the floor's sky, frame by frame: each frame's occlusion (by occlusion() or
// a gather() loop) is its own (it
// changes where the square goes) and the same whatever block renders it; a still scene's is the
// same in every frame, bit for bit; occlusion culling changes no pixel (the identity at eps = 0).
std::string movingOccluder(bool moves) {
    std::string rib = "Shutter 0 0\nFrameBegin 0\nWorldBegin\nAttributeBegin\nSurface \"constant\"\n";
    if (moves) rib += "MotionBegin [0 3]\nTranslate 0 0 0\nTranslate 24 0 0\nMotionEnd\n";
    rib += test::square(-4, 4, 0, 8, 104) + "AttributeEnd\nSurface \"ao\"\n" + test::square(0, 32, 0, 8, kFloor) +
           "WorldEnd\nFrameEnd\n";
    return rib;
}

TEST(ShaderRays, AMovingOccludersOcclusionChangesPerFrameAndNotWithTheBlock) {
    test::ShaderDir shaders;
    // occlusion(), and the same with a gather() loop counting its hits.
    for (const char* ao : {"surface ao() { Ci = 1 - occlusion(P, normal(0, 0, 1), 32); }\n",
                           "surface ao() { float h = 0; vector d = 0;\n"
                           "  gather(\"\", P, normal(0, 0, 1), PI / 2, 32, \"ray:direction\", d) h += 1;\n"
                           "  Ci = 1 - h / 32; }\n"})
    for (bool moves : {true, false}) {
        shaders.add("ao", ao);
        SCOPED_TRACE(std::string(ao) + (moves ? "moving" : "still"));
        // One sample a pixel, at its centre in every frame: a still scene's frames may be compared.
        const std::string rib = test::orthographicView(32, 8, shaders.option() + "Hider \"hidden\" \"jitter\" [0]\nPixelSamples 1 1\n") + movingOccluder(moves);
        RenderOptions o;
        o.hasFrames = true;
        o.hasShot = true;
        o.shotFirst = 0;
        o.shotLast = 3;
        for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Spacetime, Algorithm::Frames, Algorithm::Raytrace}) {
            SCOPED_TRACE(test::testName(a));
            o.algorithm = a;
            test::ShotAndFrame r = test::renderShotAndFrame(rib, o, 0, 3, 2);
            EXPECT_TRUE(r.samePixels(2)) << "frame 2 alone differs from frame 2 of the shot";
            o.firstFrame = 0, o.lastFrame = 3, o.maxFrameBlock = 1;
            const test::RenderResult apart = test::renderRib(rib, o);
            o.maxFrameBlock = 64;
            EXPECT_TRUE(test::identicalPixels(r.shot, apart)) << "blocks of one frame differ from one block";
            if (a == Algorithm::SpacetimeOcclusion) {
                o.algorithm = Algorithm::Spacetime;
                EXPECT_TRUE(test::identicalPixels(r.shot, test::renderRib(rib, o))) << "occlusion culling changed pixels";
            }
            // Under the square (x in [-4, 4] + 8 t) the floor is darker; frame 0 has it at pixel 2,
            // frame 3 at pixel 26.
            const float at2f0 = r.shot.channel(0, 2, 4, 0), at2f3 = r.shot.channel(3, 2, 4, 0);
            const float at26f0 = r.shot.channel(0, 26, 4, 0), at26f3 = r.shot.channel(3, 26, 4, 0);
            if (moves) {
                EXPECT_LT(at2f0, at2f3 - 0.2f);
                EXPECT_LT(at26f3, at26f0 - 0.2f);
            } else {
                // The same samples' positions in every frame (jitter 0), summed in an order that
                // may differ: equal to rounding. A pattern that changed per frame would differ by
                // the noise of 32 rays (~0.05).
                for (int f = 1; f <= 3; ++f) {
                    test::RenderResult a0, af;
                    a0.frames = {r.shot.frame(0)};
                    af.frames = {r.shot.frame(f)};
                    af.frames[0].frame = 0;
                    EXPECT_LT(test::maxAbsDifference(a0, af), 1e-6f) << "frame " << f << " of a still scene differs from frame 0 by " << test::maxAbsDifference(a0, af);
                }
            }
        }
    }
}

// An opaque sphere moving from x = 4 (frame 0) to x = 28 (frame 3), turned so that its poles lie
// off the view axis, coloured by the side its normal turns to the floor's rays (z > 0: away from
// them, the far side). The floor's trace() ray from (16, 4) grazes its rim in frame 2 where four
// micropolygons meet, two of the near side and two of the far: equally near, so which one is
// shaded must not depend on the hierarchy the frame's rays go through (built over the block).
TEST(ShaderRays, ARayGrazingAMovingSurfaceWhereFacetsMeetIsTheSameWhateverTheBlock) {
    test::ShaderDir shaders;
    shaders.add("see", "surface see() { Ci = trace(P, normalize(I)); Oi = 1; }\n");
    shaders.add("side", "surface side() { Ci = zcomp(normalize(N)) > 0 ? color(1) : color(0.25); Oi = 1; }\n");
    const std::string rib = test::orthographicView(32, 8, shaders.option() + "Hider \"hidden\" \"jitter\" [0]\nPixelSamples 1 1\n") +
                            "Shutter 0 0\nFrameBegin 0\nWorldBegin\nAttributeBegin\nSurface \"side\"\n" +
                            "MotionBegin [0 3]\nTranslate 4 4 150\nTranslate 28 4 150\nMotionEnd\nRotate 90 1 0 0\n" +
                            "Sphere 4 -4 4 360\nAttributeEnd\nSurface \"see\"\n" + test::square(0, 32, 0, 8, kFloor) +
                            "WorldEnd\nFrameEnd\n";
    RenderOptions o;
    o.hasFrames = true;
    o.hasShot = true;
    o.shotFirst = 0;
    o.shotLast = 3;
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Frames, Algorithm::Raytrace, Algorithm::RaytraceFrames}) {
        SCOPED_TRACE(test::testName(a));
        o.algorithm = a;
        const test::ShotAndFrame r = test::renderShotAndFrame(rib, o, 0, 3, 2);
        EXPECT_TRUE(r.samePixels(2)) << "frame 2 alone differs from frame 2 of the shot";
        // The sphere is seen where it is in frame 2 (centre x = 20): its near side, 0.25.
        EXPECT_EQ(r.shot.channel(2, 20, 4, 0), 0.25f);
        EXPECT_EQ(r.shot.channel(2, 4, 4, 0), 0.0f);  // where it was in frame 0, nothing
    }
}

TEST(ShaderRays, WrongArgumentsAreErrorsAtTheirPlace) {
    test::ShaderDir shaders;
    const std::string head = test::orthographicView(4, 4, shaders.option()) + "WorldBegin\n";
    const std::string floor = test::square(0, 4, 0, 4, kFloor) + "WorldEnd\n";
    struct Case {
        const char* source;
        const char* where;
        const char* what;
    } cases[] = {
        {"surface bad() {\n  Ci = trace(P, Cs);\n}\n", ":2:17", "cannot use a color"},
        {"surface bad() {\n  Ci = occlusion(P, N, \"many\");\n}\n", ":2:24", "option"},
        {"surface bad() {\n  Ci = occlusion(P, N, 16, \"maxdist\", \"far\");\n}\n", ":2:39", "needs a float"},
        {"surface bad() {\n  Ci = indirectdiffuse(P, N, 16, \"nosuch\", 1);\n}\n", ":2:34", "unknown indirectdiffuse option"},
        {"surface bad() {\n  Ci = transmission(P);\n}\n", ":2:8", "transmission takes"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.source);
        shaders.add("bad", c.source);
        std::string err;
        try {
            test::renderRib(head + "Surface \"bad\"\n" + floor);
        } catch (const InputError& e) {
            err = e.what();
        }
        EXPECT_NE(err.find("bad.sl" + std::string(c.where)), std::string::npos) << err;
        EXPECT_NE(err.find(c.what), std::string::npos) << err;
    }
}

}  // namespace
}  // namespace streyes
