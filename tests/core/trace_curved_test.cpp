// Curved bodies in the ray tracer: they are traced as the micropolygons the split loop dices
// them into (trace/tessellate.h), so rays see what the rasterizer draws, and they cast shadows.
#include <gtest/gtest.h>

#include <cmath>

#include "nurbs_rib.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::orthoHeader;
using test::RenderResult;
using test::renderRib;

constexpr double kPi = 3.14159265358979323846;

bool warned(const RenderResult& r, const char* what) {
    for (const std::string& w : r.warnings)
        if (w.find(what) != std::string::npos) return true;
    return false;
}

// One surface on a 64 x 64 orthographic image (a unit a pixel), constant coloured.
std::string curvedScene(const std::string& body) {
    return orthoHeader(64, 64, "PixelSamples 4 4\n") + "Color [0.2 0.4 0.6]\nAttributeBegin\n" + body +
           "AttributeEnd\nWorldEnd\n";
}

const char* kCube = R"(SubdivisionMesh "catmull-clark" [4 4 4 4 4 4]
  [0 1 3 2 2 3 5 4 4 5 7 6 6 7 1 0 1 7 5 3 6 0 2 4]
  ["crease" "corner"] [2 1 1 1] [1 3 6] [1.5 10]
  "P" [-1 -1 1  1 -1 1  -1 1 1  1.8 1.4 1.3  -1 1 -1  1 1 -1  -1 -1 -1  1 -1 -1]
)";

// A bicubic patch over [8, 56]^2 whose inner control points bulge towards the camera.
std::string bicubic() {
    std::string p = "Patch \"bicubic\" \"P\" [";
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const bool inner = i > 0 && i < 3 && j > 0 && j < 3;
            p += std::to_string(8 + 16 * i) + " " + std::to_string(8 + 16 * j) + " " + (inner ? "10 " : "30 ");
        }
    return p + "]\n";
}

struct Shape {
    const char* name;
    std::string body;
    double area;  // analytic covered area in pixels, or 0 when none is at hand
};

std::vector<Shape> shapes() {
    return {{"sphere", "Translate 32 32 30\nSphere 20 -20 20 360\n", kPi * 400},
            {"bicubic patch", bicubic(), 48.0 * 48.0},
            {"subdivision surface", "Translate 32 32 40\nRotate 30 1 1 0\nScale 12 12 12\n" + std::string(kCube), 0},
            {"NURBS sphere", "Translate 32 32 40\n" + test::nurbsSphere(20), kPi * 400}};
}

// The ray tracer sees the rasterizer's micropolygons: the same samples hit or miss, and hit the
// same surface at the same depth, and the covered area is the analytic one. Depths agree to 1%:
// on micropolygons seen edge-on at a silhouette the rasterizer's depth and the exact bilinear
// one part by up to half a unit (measured: within 1e-3 on all but 1.2% of the sphere's samples,
// nine in ten of those within 5 pixels of its silhouette, the rest at the pole, where the
// micropolygons are triangles; hits and misses agree on every sample).
TEST(TraceCurved, RaytracedCurvedBodiesAgreeWithTheRasterizer) {
    for (const Shape& s : shapes()) {
        const std::string rib = curvedScene(s.body);
        test::SampleRecord raster = test::renderSamples(rib, test::optionsFor(Algorithm::Spacetime));
        test::SampleRecord traced = test::renderSamples(rib, test::optionsFor(Algorithm::Raytrace));
        test::SampleAgreement agree = test::compareSamples(raster, traced, 1e-3f, 1e-2f);
        ASSERT_EQ(agree.samples, size_t(64 * 64 * 16)) << s.name;
        EXPECT_GE(double(agree.hitOrMiss) / double(agree.samples), 0.999) << s.name;
        EXPECT_GE(agree.share(), 0.99) << s.name << ": " << agree.samples - agree.sameSurface << " of "
                                       << agree.samples << " samples differ";
        RenderResult r = renderRib(rib, test::optionsFor(Algorithm::Spacetime));
        RenderResult t = renderRib(rib, test::optionsFor(Algorithm::Raytrace));
        const double ra = test::alphaSum(r), ta = test::alphaSum(t);
        EXPECT_GT(ta, 400) << s.name;  // not empty
        EXPECT_NEAR(ta, ra, 0.005 * ra) << s.name;
        if (s.area > 0) {
            EXPECT_NEAR(ta, s.area, 0.005 * s.area) << s.name;
        }
        EXPECT_FALSE(warned(t, "ray tracer")) << s.name;
        EXPECT_GT(t.stats.counters.traceBodies, 100u) << s.name;  // its micropolygons
    }
}

// A sphere far larger than the image would make some 18 million micropolygons: it is left out of
// ray tracing with one warning (its split tree is counted only up to the cap), and a small
// sphere beside it is still traced.
TEST(TraceCurved, HugeBodyIsLeftOutWithAWarning) {
    const std::string rib = orthoHeader(16, 16, "PixelSamples 8 8\n") + "Translate 8 8 2000\nSphere 1200 -1200 1200 360\n" +
                            "Translate 0 0 -1900\nSphere 4 -4 4 360\nWorldEnd\n";
    RenderResult r = renderRib(rib, test::optionsFor(Algorithm::Raytrace));
    EXPECT_TRUE(warned(r, "left out of ray tracing"));
    EXPECT_GT(r.stats.counters.traceBodies, 0u);
    EXPECT_LT(r.stats.counters.traceBodies, 1000u);
    EXPECT_NEAR(test::alphaSum(r), 16 * kPi, 0.03 * 16 * kPi);  // the small sphere alone (a 25-gon)
}

// A sphere around the eye: its pieces across and behind the eye plane cannot be diced (they are
// left out of ray tracing, with a warning), and what is in front is traced like the rasterizer
// draws it: every pixel covered.
TEST(TraceCurved, SphereAroundTheEyeIsTracedInFront) {
    const std::string rib = "Format 16 16 1\nProjection \"perspective\" \"fov\" [60]\nWorldBegin\n"
                            "Surface \"constant\"\nSphere 5 -5 5 360\nWorldEnd\n";
    RenderResult r = renderRib(rib, test::optionsFor(Algorithm::Raytrace));
    EXPECT_TRUE(warned(r, "behind the camera"));
    EXPECT_NEAR(test::alphaSum(r), 256.0, 1e-3);
    EXPECT_LT(test::maxAbsDifference(r, renderRib(rib, test::optionsFor(Algorithm::Spacetime))), 1e-5f);
}

// A white matte floor at z = 40 lit by a distant light along (1, 0, 1) with intensity sqrt 2
// (exactly 1 where lit); a sphere of radius 8 centred at (20, 20, 10) in its way. The light is
// parallel, so the shadow is the sphere's projection along (1, 0, 1) onto the floor: an ellipse
// centred 30 pixels to the right, semi-axes 8 sqrt 2 (x) and 8 (y), area 64 pi sqrt 2, clear of
// the sphere's own silhouette (x <= 28). `motion` moves the sphere that far in y over the shutter.
std::string sphereShadowScene(double motion = 0) {
    std::string move;
    if (motion != 0)
        move = "MotionBegin [0 1]\nTranslate 0 0 0\nTranslate 0 " + std::to_string(motion) + " 0\nMotionEnd\n";
    return orthoHeader(96, 40, "PixelSamples 8 8\nShutter 0 1\n") +
           "Attribute \"light\" \"shadows\" \"on\"\n"
           "LightSource \"distantlight\" 1 \"intensity\" [1.41421356] \"from\" [0 0 0] \"to\" [1 0 1]\n"
           "Surface \"matte\" \"Ka\" [0]\n" + test::square(0, 96, 0, 40, 40) +
           "AttributeBegin\nSurface \"constant\"\nColor [0.5 0.5 0.5]\n" + move +
           "Translate 20 20 10\nSphere 8 -8 8 360\nAttributeEnd\nWorldEnd\n";
}

// The shadowed area of the floor right of the sphere: one minus brightness, summed.
double shadowArea(const RenderResult& r) {
    double a = 0;
    for (int y = 0; y < 40; ++y)
        for (int x = 30; x < 96; ++x) a += 1.0 - double(r.channel(0, x, y, 0));
    return a;
}

// Per sample in every algorithm (the rasterizer's default tests a still occluder at the floor's
// vertices: still_shadow_test.cpp holds that one to the same ellipse).
TEST(TraceCurved, SphereCastsItsAnalyticShadow) {
    const double expected = 64 * kPi * std::sqrt(2.0);
    std::string rib = sphereShadowScene();
    rib.insert(rib.find("WorldBegin"), "Option \"trace\" \"string shadowtest\" [\"sample\"]\n");
    for (Algorithm a : {Algorithm::Spacetime, Algorithm::Raytrace, Algorithm::RaytraceFrames}) {
        RenderResult r = renderRib(rib, test::optionsFor(a));
        EXPECT_NEAR(shadowArea(r), expected, 0.01 * expected) << algorithmName(a);
        EXPECT_NEAR(r.channel(0, 50, 20, 0), 0.0f, 1e-6f) << algorithmName(a);  // the ellipse's centre
        EXPECT_NEAR(r.channel(0, 50, 34, 0), 1.0f, 1e-5f) << algorithmName(a);  // clear of it
        EXPECT_FALSE(warned(r, "ray tracer")) << algorithmName(a);
        EXPECT_GT(r.stats.counters.shadowRays, 0u) << algorithmName(a);
    }
}

// A moving curved occluder keeps the pixels independent of the thread count in every mode.
TEST(TraceCurved, ThreadCountDoesNotChangePixelsWithACurvedOccluder) {
    const std::string rib = sphereShadowScene(6);
    for (Algorithm a : {Algorithm::Raytrace, Algorithm::RaytraceFrames, Algorithm::Spacetime}) {
        RenderOptions one = test::optionsFor(a), two = test::optionsFor(a);
        one.threads = 1;
        two.threads = 2;
        one.bucketSize = two.bucketSize = 8;
        RenderResult r1 = renderRib(rib, one), r2 = renderRib(rib, two);
        EXPECT_TRUE(test::identicalPixels(r1, r2)) << algorithmName(a);
        EXPECT_EQ(test::differingCounts(r1.stats.counters, r2.stats.counters), std::vector<std::string>{})
            << algorithmName(a);
        // The moving sphere's shadow still covers the same area, smeared in y.
        EXPECT_NEAR(shadowArea(r1), 64 * kPi * std::sqrt(2.0), 0.02 * 64 * kPi * std::sqrt(2.0)) << algorithmName(a);
    }
}

}  // namespace
}  // namespace streyes
