// Ray-traced shadows of solids (SolidBegin ... SolidEnd): a shadow ray is blocked where it goes in
// or out of the solid's result, not at every member's surface. Solids built about one axis along
// the light cast shadows whose areas have closed forms: a sphere less a larger sphere that takes
// all but its far cap (a disc), a sphere less a closed cylinder through it (an annulus), two
// spheres' intersection (a lens); a convex solid does not shadow itself; a moving member keeps a
// frame alone equal to the frame in a block; the thread count changes nothing. Shadows at the
// shading rate (per vertex) and per sample, in the rasterizer and the ray tracer.
#include <gtest/gtest.h>

#include <cmath>

#include "test_util.h"

namespace streyes {
namespace {

using test::RenderResult;
using test::renderRib;

constexpr double kPi = 3.14159265358979323846;
const double kRoot2 = std::sqrt(2.0);

// A white matte floor at z = 120 under a distant light along (1, 0, 1) (intensity sqrt 2: exactly
// 1 where lit), seen by an orthographic camera, one unit a pixel. The solids are centred at
// C = (36, 40, 40) about the axis through C along the light: a disc of radius rho across the axis
// casts an ellipse of area pi rho^2 sqrt 2 centred at (116, 40), which lies in x >= 64, where the
// camera sees the floor alone.
constexpr int kW = 160, kH = 80;
constexpr double kCx = 36, kCy = 40, kCz = 40, kFloor = 120;
constexpr double kR = 16;  // the sphere A every case starts from

std::string num(double v) { return std::to_string(v); }

std::string header(const std::string& options, bool shadows = true, const std::string& samples = "4 4") {
    return test::orthoHeader(kW, kH, "PixelSamples " + samples + "\nShutter 0 0\n" + options) +
           (shadows ? "Attribute \"light\" \"shadows\" \"on\"\n" : "") +
           "LightSource \"distantlight\" 1 \"intensity\" [1.41421356] \"from\" [0 0 0] \"to\" [1 0 1]\n"
           "Surface \"matte\" \"Ka\" [0]\n" +
           test::square(0, kW, 0, kH, kFloor);
}
std::string sphereAt(double x, double y, double z, double r, const std::string& surface = "Surface \"constant\"\n") {
    return "SolidBegin \"primitive\"\nAttributeBegin\n" + surface + "Translate " + num(x) + " " + num(y) + " " +
           num(z) + "\nSphere " + num(r) + " " + num(-r) + " " + num(r) + " 360\nAttributeEnd\nSolidEnd\n";
}
std::string sphereA() { return sphereAt(kCx, kCy, kCz, kR); }
// The point of the axis at signed distance s from C, towards the floor.
double axisX(double s) { return kCx + s / kRoot2; }
double axisZ(double s) { return kCz + s / kRoot2; }
// A closed cylinder of radius a along the axis, from -h to h about C (Rotate 45 about y turns z
// into the light's direction).
std::string cylinder(double a, double h) {
    return "SolidBegin \"primitive\"\nAttributeBegin\nSurface \"constant\"\nTranslate " + num(kCx) + " " + num(kCy) +
           " " + num(kCz) + "\nRotate 45 0 1 0\nDisk " + num(h) + " " + num(a) + " 360\nCylinder " + num(a) + " " +
           num(-h) + " " + num(h) + " 360\nDisk " + num(-h) + " " + num(a) + " -360\nAttributeEnd\nSolidEnd\n";
}
std::string solid(const std::string& op, const std::string& members) {
    return "SolidBegin \"" + op + "\"\n" + members + "SolidEnd\n";
}

// The shadow's area in pixels: how much light the floor loses where the camera sees it alone.
double shadowArea(const RenderResult& r, int frame = 0) {
    double a = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 64; x < kW; ++x) a += 1.0 - double(r.channel(frame, x, y, 0));
    return a;
}

// A less B, B of radius r centred c before C along the axis (towards the light), r^2 > R^2 + c^2
// (B holds A's rim across the axis): what is left is A's far cap below B, whose outline across the
// axis is the circle where the two spheres meet, rho^2 = R^2 - y0^2, y0 = (R^2 - r^2 + c^2) / 2c.
double capArea(double r, double c) {
    const double y0 = (kR * kR - r * r + c * c) / (2 * c);
    return kPi * (kR * kR - y0 * y0) * kRoot2;
}
std::string biteFacingTheLight(double r, double c) { return sphereAt(axisX(-c), kCy, axisZ(-c), r); }

// The area two discs of radius R with centres d apart share.
double lensArea(double d) { return 2 * kR * kR * std::acos(d / (2 * kR)) - 0.5 * d * std::sqrt(4 * kR * kR - d * d); }

// Shadows at the shading rate blend lit and shadowed vertices across a micropolygon at the edge,
// a ramp that loses area along the outline (StillShadow.SphereShadowAtTheShadingRateIsTheAnalyticEllipse:
// a sphere's -1.9%); the lens, with two tips, loses 2.5%. Per sample (and in the ray tracer, whose
// shadow rays are the same) within 1%; measured: within 0.4% in every case.
struct Mode {
    Algorithm algorithm;
    const char* options;
    double tolerance;  // of a shadow's area
};
const Mode kModes[] = {{Algorithm::SpacetimeOcclusion, "", 0.03},
                       {Algorithm::SpacetimeOcclusion, "Option \"trace\" \"string shadowtest\" [\"sample\"]\n", 0.01},
                       {Algorithm::Raytrace, "", 0.01}};

void expectShadowArea(const std::string& body, double want, const std::string& what) {
    for (const Mode& m : kModes) {
        const RenderResult r = renderRib(header(m.options) + body + "WorldEnd\n", test::optionsFor(m.algorithm));
        EXPECT_NEAR(shadowArea(r), want, m.tolerance * want)
            << what << " " << algorithmName(m.algorithm) << (*m.options ? " per sample" : "");
    }
}

TEST(SolidShadows, DifferenceBittenTowardsTheLightCastsItsCap) {
    const double want = capArea(24, 12);
    ASSERT_NEAR(want, 898.4, 0.5);  // rho^2 = 256 - (176 / 24)^2
    expectShadowArea(solid("difference", sphereA() + biteFacingTheLight(24, 12)), want, "A - B");
    // B's shadow whole (what its members cast as plain surfaces) is nearly three times that.
    EXPECT_GT(kPi * 24 * 24 * kRoot2 - want, 1.5 * want);
}

TEST(SolidShadows, DifferenceWithACylinderThroughItCastsAnAnnulus) {
    const double want = kPi * (kR * kR - 6 * 6) * kRoot2;
    ASSERT_NEAR(want, 977.5, 0.5);
    expectShadowArea(solid("difference", sphereA() + cylinder(6, 24)), want, "A - cylinder");
    EXPECT_GT(kPi * kR * kR * kRoot2 - want, 0.1 * want);  // A's whole disc
}

TEST(SolidShadows, IntersectionCastsTheLens) {
    const double d = 16;  // the spheres' centres apart, across the light
    const double want = lensArea(d) * kRoot2;
    ASSERT_NEAR(lensArea(d), 2 * 256 * kPi / 3 - 8 * std::sqrt(768.0), 1e-9);
    expectShadowArea(solid("intersection", sphereAt(kCx, kCy - d / 2, kCz, kR) + sphereAt(kCx, kCy + d / 2, kCz, kR)),
                     want, "A * B");
    // A union casts the discs' union: each member's outline once (no more dark where they overlap).
    expectShadowArea(solid("union", sphereAt(kCx, kCy - d / 2, kCz, kR) + sphereAt(kCx, kCy + d / 2, kCz, kR)),
                     (2 * kPi * kR * kR - lensArea(d)) * kRoot2, "A + B");
}

// The lens is convex: no point of it is shadowed by the lens. Its face's shadow rays start on one
// member's surface inside the other, whose far side they cross (as plain surfaces that far side
// would shadow the face). Where the face is sphere S (S's half of the lens, away from the ridge
// where the spheres meet: the plane y = 40 holds the light's direction, so rays from it run along
// both spheres at once), its pixels are those of S alone, which shadows itself only where any
// sphere's micropolygons do (near its terminator).
TEST(SolidShadows, AConvexSolidDoesNotShadowItself) {
    const std::string matte = "Surface \"matte\" \"Ka\" [0]\n";
    const std::string below = sphereAt(kCx, kCy - 8, kCz, kR, matte), above = sphereAt(kCx, kCy + 8, kCz, kR, matte);
    auto plain = [](std::string s) {  // a sphere outside SolidBegin
        s = s.substr(s.find('\n') + 1);
        return s.substr(0, s.rfind("SolidEnd"));
    };
    // Whether pixel (x, y) lies inside the disc of radius R - 1 about (kCx, cy) (raster y down).
    auto inDisc = [](int x, int y, double cy) {
        const double dx = x + 0.5 - kCx, dy = (kH - y - 0.5) - cy;
        return dx * dx + dy * dy < (kR - 1) * (kR - 1);
    };
    for (const Mode& m : kModes) {
        SCOPED_TRACE(std::string(algorithmName(m.algorithm)) + (*m.options ? " per sample" : ""));
        const RenderOptions o = test::optionsFor(m.algorithm);
        const RenderResult lens = renderRib(header(m.options) + solid("intersection", below + above) + "WorldEnd\n", o);
        const RenderResult aloneBelow = renderRib(header(m.options) + plain(below) + "WorldEnd\n", o);
        const RenderResult aloneAbove = renderRib(header(m.options) + plain(above) + "WorldEnd\n", o);
        int compared = 0, lit = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < 60; ++x) {
                const double yc = kH - y - 0.5;
                if (std::fabs(yc - kCy) < 2.5 || !inDisc(x, y, kCy - 8) || !inDisc(x, y, kCy + 8)) continue;
                // The face is the sphere whose centre lies farther: below's for y > 40.
                const RenderResult& alone = yc > kCy ? aloneBelow : aloneAbove;
                ++compared;
                EXPECT_NEAR(lens.channel(0, x, y, 0), alone.channel(0, x, y, 0), 1e-5f) << x << " " << y;
                // Lit: its rays left the other sphere through its far side, which would block them.
                lit += alone.channel(0, x, y, 0) > 0.2f;
            }
        EXPECT_GT(compared, 120);  // 160
        EXPECT_GT(lit, 100);
    }
}

// B bites A from the light's side and moves along the axis (c = 9, 10, 11, 12 at frames 0-3): each
// frame's shadow is its closed form's, and frame 2 alone is frame 2 of the block, bit for bit.
std::string movingBite(const std::string& options) {
    std::string keys;
    for (int f = 0; f < 4; ++f) {
        const double c = 9 + f;
        keys += "Translate " + num(axisX(-c)) + " " + num(kCy) + " " + num(axisZ(-c)) + "\n";
    }
    // ShadingRate 2: fewer micropolygons to trace for the moving sphere (the hierarchy's build
    // over its four frames was most of the test's time).
    const std::string b = "SolidBegin \"primitive\"\nAttributeBegin\nSurface \"constant\"\nShadingRate 2\nMotionBegin [0 1 2 3]\n" +
                          keys + "MotionEnd\nSphere 24 -24 24 360\nAttributeEnd\nSolidEnd\n";
    return header("Option \"streyes\" \"int frames\" [0 3]\n" + options, true, "2 2") + solid("difference", sphereA() + b) +
           "WorldEnd\n";
}

TEST(SolidShadows, MovingMemberFrameAloneEqualsFrameInBlock) {
    for (const Mode& m : kModes) {
        SCOPED_TRACE(std::string(algorithmName(m.algorithm)) + (*m.options ? " per sample" : ""));
        const test::ShotAndFrame r = test::renderShotAndFrame(movingBite(m.options), test::optionsFor(m.algorithm), 0, 3, 2);
        EXPECT_TRUE(r.samePixels(2));
        EXPECT_NEAR(shadowArea(r.shot, 0), capArea(24, 9), 0.015 * capArea(24, 9));
        EXPECT_NEAR(shadowArea(r.shot, 2), capArea(24, 11), 0.015 * capArea(24, 11));
        EXPECT_GT(capArea(24, 11) - capArea(24, 9), 0.5 * capArea(24, 9));
    }
}

TEST(SolidShadows, ThreadCountDoesNotChangePixels) {
    for (const Mode& m : kModes) {
        SCOPED_TRACE(std::string(algorithmName(m.algorithm)) + (*m.options ? " per sample" : ""));
        RenderOptions one = test::optionsFor(m.algorithm), two = one;
        one.threads = 1;
        two.threads = 2;
        one.bucketSize = two.bucketSize = 16;
        one.hasFrames = two.hasFrames = true;  // frames 1 and 2
        one.firstFrame = two.firstFrame = 1;
        one.lastFrame = two.lastFrame = 2;
        test::halfResolutionUnderSanitizers(one, kW, kH);
        test::halfResolutionUnderSanitizers(two, kW, kH);
        const std::string rib = movingBite(m.options);
        EXPECT_TRUE(test::identicalPixels(renderRib(rib, one), renderRib(rib, two)));
    }
}

}  // namespace
}  // namespace streyes
