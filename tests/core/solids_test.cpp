// Solids (SolidBegin ... SolidEnd): spheres combined by difference, union and intersection cover
// the closed forms' screen areas, in the rasterizer and the ray tracer alike; the visible surface
// of a difference is the subtracted solid's inside where it bites; a nested tree, a see-through
// member and a moving one (a frame alone equals the frame in a block); occlusion culling at ε = 0
// changes no pixel; bad input is an error or a warning as the peers have it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "test_util.h"

namespace streyes {
namespace {

// Spheres seen by an orthographic camera, one unit a pixel (test::orthoHeader): their centres at
// depth 100, so that a line of sight meets two of them in chords centred on the same depth.
constexpr int kW = 128, kH = 128;
constexpr double kR1 = 40, kR2 = 32, kD = 40;  // A's and B's radii, B's centre kD to the right of A's
constexpr double kAx = 52, kAy = 64, kZ = 100;

std::string sphere(double x, double y, double z, double r, const std::string& color, const std::string& extra = "") {
    return "AttributeBegin\nColor [" + color + "]\n" + extra + "Translate " + std::to_string(x) + " " +
           std::to_string(y) + " " + std::to_string(z) + "\nSphere " + std::to_string(r) + " " +
           std::to_string(-r) + " " + std::to_string(r) + " 360\nAttributeEnd\n";
}
std::string primitive(const std::string& body) { return "SolidBegin \"primitive\"\n" + body + "SolidEnd\n"; }
std::string solid(const std::string& op, const std::string& members) {
    return "SolidBegin \"" + op + "\"\n" + members + "SolidEnd\n";
}
std::string sphereA(const std::string& extra = "") { return primitive(sphere(kAx, kAy, kZ, kR1, "1 0 0", extra)); }
std::string sphereB(const std::string& extra = "") { return primitive(sphere(kAx + kD, kAy, kZ, kR2, "0 1 0", extra)); }
std::string scene(const std::string& body, const std::string& extra = "PixelSamples 4 4\n") {
    return test::orthoHeader(kW, kH, extra) + body + "WorldEnd\n";
}

// The area two discs of radii r1, r2 with centres d apart share.
double lens(double r1, double r2, double d) {
    return r1 * r1 * std::acos((d * d + r1 * r1 - r2 * r2) / (2 * d * r1)) +
           r2 * r2 * std::acos((d * d + r2 * r2 - r1 * r1) / (2 * d * r2)) -
           0.5 * std::sqrt((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2));
}
// A - B seen along the chords: a line of sight through disc A misses A - B exactly where B's chord
// holds A's, R2^2 - (x - d)^2 >= R1^2 - x^2, i.e. x >= x0 = (R1^2 - R2^2 + d^2) / 2d: the disc
// less the circular segment beyond x0 (the plane where the spheres meet, seen edge-on).
double differenceArea(double d = kD) {
    const double x0 = (kR1 * kR1 - kR2 * kR2 + d * d) / (2 * d);
    const double segment = kR1 * kR1 * std::acos(x0 / kR1) - x0 * std::sqrt(kR1 * kR1 - x0 * x0);
    return M_PI * kR1 * kR1 - segment;
}

const Algorithm kRendered[] = {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace};

void expectArea(const std::string& rib, double want, const std::string& what) {
    for (const Algorithm a : kRendered) {
        const test::RenderResult r = test::renderRib(rib, test::optionsFor(a));
        const double area = test::alphaSum(r);
        EXPECT_NEAR(area, want, 0.01 * want) << what << " " << algorithmName(a);
    }
}

TEST(Solids, DifferenceOfTwoSpheresCoversTheClosedForm) {
    const double want = differenceArea();
    ASSERT_NEAR(want, 4507.4, 0.5);  // 1600 pi less the segment beyond x0 = 27.2
    expectArea(scene(solid("difference", sphereA() + sphereB())), want, "A - B");
    // Drawn as plain surfaces they cover both discs: the difference is not that.
    const double both = M_PI * (kR1 * kR1 + kR2 * kR2) - lens(kR1, kR2, kD);
    EXPECT_GT(both - want, 0.3 * want);
}

TEST(Solids, UnionAndIntersectionCoverTheClosedForms) {
    const double shared = lens(kR1, kR2, kD);
    expectArea(scene(solid("union", sphereA() + sphereB())), M_PI * (kR1 * kR1 + kR2 * kR2) - shared, "A + B");
    expectArea(scene(solid("intersection", sphereA() + sphereB())), shared, "A * B");
}

// difference(A, union(B, C)): C bites A from the left as B does from the right (B and C apart).
TEST(Solids, NestedTreeCoversTheClosedForm) {
    const std::string c = primitive(sphere(kAx - kD, kAy, kZ, kR2, "0 0 1"));
    const double segment = M_PI * kR1 * kR1 - differenceArea();
    expectArea(scene(solid("difference", sphereA() + solid("union", sphereB() + c))),
               M_PI * kR1 * kR1 - 2 * segment, "A - (B + C)");
}

// Where a small sphere B (green) bites into A's (red) front, a line of sight through both sees B's
// inside (the wall of the cavity), not B's outside as plain surfaces would; where B's back lies in
// front of A's front, B is outside A and A's front is seen.
TEST(Solids, TheSubtractedSolidsInsideIsTheCavitysWall) {
    const std::string b = primitive(sphere(kAx, kAy, kZ - 45, 20, "0 1 0"));
    const std::string rib = scene(solid("difference", sphereA() + b));
    const int cx = int(kAx), cy = kH - int(kAy);  // pixel (52, 64) has the axis at its corner
    for (const Algorithm a : kRendered) {
        const test::RenderResult r = test::renderRib(rib, test::optionsFor(a));
        const std::string name = algorithmName(a);
        // On the axis: B's back at 75, A's front at 60: the cavity's wall, green.
        EXPECT_NEAR(r.channel(0, cx, cy, 1), 1, 1e-5) << name;
        EXPECT_NEAR(r.channel(0, cx, cy, 0), 0, 1e-5) << name;
        // 19 px off the axis (the pixel covers 19..20): B's back (55 + sqrt(400 - r^2) <= 61.3) in
        // front of A's front (>= 64.8): A, red.
        EXPECT_NEAR(r.channel(0, cx + 19, cy, 0), 1, 1e-5) << name;
        EXPECT_NEAR(r.channel(0, cx + 19, cy, 1), 0, 1e-5) << name;
        // Z is the surface seen: the cavity's wall at 55 + 20 on the axis, A's front at
        // 100 - sqrt(1600 - r^2) (64.8 to 65.5 over the pixel; the nearest sample's is kept).
        EXPECT_NEAR(r.z(0, cx, cy), 75, 0.2) << name;
        EXPECT_NEAR(r.z(0, cx + 19, cy), 64.9, 0.15) << name;
    }
    // Plain surfaces would show B's front, green, there.
    const test::RenderResult plain = test::renderRib(scene(sphereA() + b));
    EXPECT_GT(plain.channel(0, cx + 19, cy, 1), 0.9);  // a sample of B's edge may miss
}

// Depthfilter "midpoint" of a depth pass: the mean of the two nearest surfaces of the result. On
// the axis of TheSubtractedSolidsInsideIsTheCavitysWall's bite, the cavity's wall (B's back, 75)
// and A's back (140), where plain surfaces would give B's front and A's front, 47.5; 19 pixels off
// it the line crosses B's surfaces outside A, and then A's chord, centred on 100.
TEST(Solids, MidpointDepthIsTheResultsTwoNearestSurfaces) {
    const std::string midpointPass = "PixelSamples 4 4\nHider \"hidden\" \"depthfilter\" \"midpoint\"\n";
    const std::string b = primitive(sphere(kAx, kAy, kZ - 45, 20, "0 1 0"));
    const std::string rib = scene(solid("difference", sphereA() + b), midpointPass);
    RenderOptions depth;
    depth.depthPass = true;
    const test::RenderResult r = test::renderRib(rib, depth);
    const int cx = int(kAx), cy = kH - int(kAy);
    // The pixel's depth is its samples' nearest: within sqrt 2 of the axis, 107.5 less up to 0.08.
    EXPECT_NEAR(r.z(0, cx, cy), 107.5, 0.3);
    EXPECT_NEAR(r.z(0, cx + 19, cy), 100, 0.3);
    // Where the line meets A alone, its chord's middle; outside A nothing (one surface or none).
    EXPECT_NEAR(r.z(0, cx - 30, cy), 100, 0.3);
    EXPECT_EQ(r.z(0, cx, cy - 45), std::numeric_limits<float>::infinity());
    // Without the solid: B's front and A's front.
    const test::RenderResult plain = test::renderRib(scene(sphereA() + b, midpointPass), depth);
    EXPECT_NEAR(plain.z(0, cx, cy), 47.5, 0.3);
}

// A half-transparent A less an opaque B: outside B's disc both of A's surfaces are seen (0.5 red
// over 0.5 red: 0.75), over B's cavity A's front over B's inside (0.5 red + 0.5 green), and beyond
// the plane where they meet nothing.
TEST(Solids, SeeThroughMemberComposites) {
    const std::string rib = scene(solid("difference", sphereA("Opacity [0.5 0.5 0.5]\n") + sphereB()));
    const int y = kH - int(kAy);
    for (const Algorithm a : kRendered) {
        const test::RenderResult r = test::renderRib(rib, test::optionsFor(a));
        const std::string name = algorithmName(a);
        EXPECT_NEAR(r.channel(0, 56, y, 0), 0.75, 1e-5) << name;
        EXPECT_NEAR(r.alpha(0, 56, y), 0.75, 1e-5) << name;
        EXPECT_NEAR(r.channel(0, 70, y, 0), 0.5, 1e-5) << name;
        EXPECT_NEAR(r.channel(0, 70, y, 1), 0.5, 1e-5) << name;
        EXPECT_NEAR(r.alpha(0, 70, y), 1, 1e-5) << name;
        EXPECT_EQ(r.alpha(0, 86, y), 0) << name;
    }
}

// B moves across A over frames 0..3 (A is still): a frame alone equals that frame rendered in the
// block, in the rasterizer and the ray tracer; each frame's area is the closed form's for its B.
TEST(Solids, MovingMemberFrameAloneEqualsFrameInBlock) {
    const std::string b = primitive("AttributeBegin\nColor [0 1 0]\nMotionBegin [0 3]\nTranslate " +
                                    std::to_string(kAx + 60) + " " + std::to_string(kAy) + " " + std::to_string(kZ) +
                                    "\nTranslate " + std::to_string(kAx + 30) + " " + std::to_string(kAy) + " " +
                                    std::to_string(kZ) + "\nMotionEnd\nSphere " + std::to_string(kR2) + " " +
                                    std::to_string(-kR2) + " " + std::to_string(kR2) + " 360\nAttributeEnd\n");
    const std::string rib = test::orthoHeader(kW, kH, "PixelSamples 3 3\nShutter 0 0\nOption \"streyes\" \"int frames\" [0 3]\n") +
                            solid("difference", sphereA() + b) + "WorldEnd\n";
    for (const Algorithm a : kRendered) {
        const test::ShotAndFrame r = test::renderShotAndFrame(rib, test::optionsFor(a), 0, 3, 2);
        EXPECT_TRUE(r.samePixels(2)) << algorithmName(a);
        // Frame 2: B at d = 40 (60 - 10 a frame): the still difference's area.
        EXPECT_NEAR(test::alphaSum(r.shot, 2), differenceArea(), 0.01 * differenceArea()) << algorithmName(a);
        // Frame 0: d = 60, a thinner bite.
        EXPECT_NEAR(test::alphaSum(r.shot, 0), differenceArea(60), 0.01 * differenceArea(60)) << algorithmName(a);
        EXPECT_GT(test::alphaSum(r.shot, 0) - test::alphaSum(r.shot, 2), 100);
    }
}

// A solid in front of a wall that hides a field of squares: at ε = 0 occlusion culling changes no
// pixel (no surface of a solid counts as cover on its own: B's front is no surface of A - B) and
// still culls behind the wall; the frames baseline agrees.
TEST(Solids, OcclusionCullingStaysExact) {
    std::string body = solid("difference", sphereA() + sphereB());
    body += "AttributeBegin\nColor [0.2 0.2 0.9]\n" + test::square(0, kW, 0, kH, 200) + "AttributeEnd\n";
    for (int i = 0; i < 8; ++i) body += test::square(i * 16 + 2, i * 16 + 12, 10, 20, 300 + i);
    const std::string rib = scene(body);
    const test::RenderResult plain = test::renderRib(rib, test::optionsFor(Algorithm::Spacetime));
    RenderOptions culled = test::optionsFor(Algorithm::SpacetimeOcclusion);
    culled.tolerance = 0;
    const test::RenderResult occl = test::renderRib(rib, culled);
    EXPECT_TRUE(test::identicalPixels(plain, occl));
    EXPECT_GT(occl.stats.counters.culledOcclusion + occl.stats.counters.culledHidden, 0u);
    EXPECT_TRUE(test::identicalPixels(plain, test::renderRib(rib, test::optionsFor(Algorithm::Frames))));
    // Beyond the plane where A and B meet, the wall is seen through the bite.
    EXPECT_NEAR(occl.channel(0, 86, kH - int(kAy), 2), 0.9, 1e-5);
}

TEST(Solids, BadInputIsAnErrorNamingItsLine) {
    const std::string head = test::orthoHeader(16, 16);
    struct Case {
        std::string rib, says;
    } cases[] = {
        {head + "SolidEnd\nWorldEnd\n", "bad.rib:7: SolidEnd: SolidEnd without a matching SolidBegin"},
        {head + "SolidBegin \"primitive\"\nWorldEnd\n", "SolidBegin is never closed"},
        {head + "SolidBegin \"subtract\"\nSolidEnd\nWorldEnd\n", "unknown solid operation \"subtract\""},
        {head + "AttributeBegin\nSolidBegin \"union\"\nAttributeEnd\nSolidEnd\nWorldEnd\n",
         "AttributeEnd does not match the SolidBegin at line 8"},
        {head + "SolidBegin \"union\"\nAttributeBegin\nSolidEnd\nAttributeEnd\nWorldEnd\n",
         "SolidEnd does not match the AttributeBegin at line 8"},
        {"SolidBegin \"primitive\"\nSolidEnd\n" + head + "WorldEnd\n", "SolidBegin belongs between WorldBegin and WorldEnd"},
    };
    for (const Case& c : cases) {
        const std::string e = test::ribError(c.rib);
        EXPECT_NE(e.find(c.says), std::string::npos) << "got: " << e;
        EXPECT_NE(e.find("bad.rib:"), std::string::npos) << e;
    }
}

// What Aqsis warns about and renders: geometry directly inside a non-primitive solid (a plain
// surface) and a solid inside a primitive one (a solid of its own). Once each; --strict refuses.
TEST(Solids, WhatThePeersAcceptWarnsOnceAndRenders) {
    const std::string loose = scene(solid("union", sphere(kAx, kAy, kZ, kR1, "1 0 0") + sphere(kAx, kAy, kZ, 10, "0 1 0")));
    const test::RenderResult r = test::renderRib(loose);
    int warned = 0;
    for (const std::string& w : r.warnings) warned += w.find("directly inside SolidBegin \"union\"") != std::string::npos;
    EXPECT_EQ(warned, 1);
    EXPECT_NEAR(test::alphaSum(r), M_PI * kR1 * kR1, 0.01 * M_PI * kR1 * kR1);  // drawn as plain surfaces
    EXPECT_NE(test::ribError(loose, true).find("directly inside SolidBegin"), std::string::npos);
    const std::string nested = scene(solid("primitive", sphere(kAx, kAy, kZ, kR1, "1 0 0") + sphereB()));
    const test::RenderResult n = test::renderRib(nested);
    warned = 0;
    for (const std::string& w : n.warnings) warned += w.find("inside SolidBegin \"primitive\"") != std::string::npos;
    EXPECT_EQ(warned, 1);
}

}  // namespace
}  // namespace streyes
