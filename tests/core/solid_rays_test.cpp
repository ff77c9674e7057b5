// Shaders' rays through solids (SolidBegin ... SolidEnd): trace(), gather() and transmission() see
// a solid's boundary only where it bounds the solid's result, as eye rays and shadow rays do. A
// floor whose shader casts its rays along one direction sees the solid as a parallel projection:
// the solids of the shadow tests (solid_shadows_test.cpp), built about the axis along that
// direction, show areas with closed forms. And a solid's output variables are those of the
// surface its colour comes from.
#include <gtest/gtest.h>

#include <cmath>

#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::RenderResult;
using test::renderRib;

constexpr double kPi = 3.14159265358979323846;
const double kRoot2 = std::sqrt(2.0);

// A floor at z = 120 seen by an orthographic camera, one unit a pixel; its shader casts rays along
// (-1, 0, -1) (towards the camera and left). The solids are centred at C = (36, 40, 40) about the
// axis through C along that direction: a disc of radius rho across the axis shows as an ellipse of
// area pi rho^2 sqrt 2 centred at (116, 40), which lies in x >= 64, where the camera sees the floor
// alone.
constexpr int kW = 160, kH = 80;
constexpr double kCx = 36, kCy = 40, kCz = 40, kFloor = 120;
constexpr double kR = 16;  // the sphere A every case starts from

std::string num(double v) { return std::to_string(v); }

// The floor's shaders: red and green of what the ray meets (its members are red and green).
const char* kMirror = "surface mirror() { Ci = trace(P, vector(-1, 0, -1)); Oi = 1; }\n";
// The same through environment("raytrace").
const char* kEnvMirror = "surface envmirror() { Ci = color environment(\"raytrace\", vector(-1, 0, -1)); Oi = 1; }\n";
// One gather() ray along the axis: red 1 where it hits, green and blue the hit's red and green.
const char* kGatherer = R"(
surface gatherer() {
    color c = 0;
    Ci = 0;
    gather("illuminance", P, vector(-1, 0, -1), 0, 1, "surface:Ci", c) {
        Ci = color(1, comp(c, 0), comp(c, 1));
    }
    Oi = 1;
}
)";
// What the segment from P 200 units along the axis lets through.
const char* kSeeThrough = "surface seethrough() { Ci = transmission(P, P + 200 * normalize(vector(-1, 0, -1))); Oi = 1; }\n";

struct RayShaders {
    test::ShaderDir dir;
    RayShaders() {
        dir.add("mirror", kMirror);
        dir.add("envmirror", kEnvMirror);
        dir.add("gatherer", kGatherer);
        dir.add("seethrough", kSeeThrough);
    }
    std::string header(const std::string& floorShader, const std::string& options = "",
                       const std::string& samples = "4 4") const {
        return test::orthoHeader(kW, kH, "PixelSamples " + samples + "\nShutter 0 0\n" + dir.option() + options) +
               "AttributeBegin\nSurface \"" + floorShader + "\"\n" + test::square(0, kW, 0, kH, kFloor) +
               "AttributeEnd\n";
    }
};

// Turned about its centre so that its poles, where its micropolygons' fans close, send no ray to a
// point of the floor's shading grid (a ray exactly through a pole slips through the fan: a plain
// sphere's too).
std::string sphereAt(double x, double y, double z, double r, const std::string& color, const std::string& extra = "") {
    return "SolidBegin \"primitive\"\nAttributeBegin\nSurface \"constant\"\nColor [" + color + "]\n" + extra +
           "Translate " + num(x) + " " + num(y) + " " + num(z) + "\nRotate 30 1 0 0\nSphere " + num(r) + " " + num(-r) +
           " " + num(r) + " 360\nAttributeEnd\nSolidEnd\n";
}
const char* kRed = "1 0 0";
const char* kGreen = "0 1 0";
// The point of the axis at signed distance s from C, towards the floor.
double axisX(double s) { return kCx + s / kRoot2; }
double axisZ(double s) { return kCz + s / kRoot2; }
std::string solid(const std::string& op, const std::string& members) {
    return "SolidBegin \"" + op + "\"\n" + members + "SolidEnd\n";
}

// Channel c summed over x >= 64: the area (in pixels) the rays see a colour over.
double channelSum(const RenderResult& r, int c, int frame = 0) {
    double a = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 64; x < kW; ++x) a += double(r.channel(frame, x, y, c));
    return a;
}

// A less B, B of radius r centred c from C along the axis, r^2 > R^2 + c^2 (B holds A's rim across
// the axis): what is left is A's cap on the side away from B, whose outline across the axis is the
// circle where the two spheres meet, rho^2 = R^2 - y0^2, y0 = (R^2 - r^2 + c^2) / 2c.
double capArea(double r, double c) {
    const double y0 = (kR * kR - r * r + c * c) / (2 * c);
    return kPi * (kR * kR - y0 * y0) * kRoot2;
}
std::string sphereA(const std::string& extra = "") { return sphereAt(kCx, kCy, kCz, kR, kRed, extra); }
// B towards the floor: the floor's rays look into the bite, whose wall is B's inside.
std::string biteFacingTheFloor(double r, double c, const std::string& extra = "") {
    return sphereAt(axisX(c), kCy, axisZ(c), r, kGreen, extra);
}
// B away from the floor: the rays meet A's cap from outside.
std::string biteAway(double r, double c) { return sphereAt(axisX(-c), kCy, axisZ(-c), r, kGreen); }

// Shaded per eye ray (the ray tracer), or at the rasterizer's shading rate: micropolygons a
// quarter pixel in area, so that the ramp across the outline between shaded points loses little.
struct Mode {
    Algorithm algorithm;
    const char* options;
    double tolerance;  // of an area
};
const Mode kModes[] = {{Algorithm::SpacetimeOcclusion, "ShadingRate 0.25\n", 0.01}, {Algorithm::Raytrace, "", 0.01}};

TEST(SolidRays, TraceSeesTheCavityWallThroughTheBite) {
    const RayShaders s;
    const double want = capArea(24, 12);
    ASSERT_NEAR(want, 898.4, 0.5);
    for (const Mode& m : kModes)
        for (const char* shader : {"mirror", "envmirror"}) {
            SCOPED_TRACE(std::string(algorithmName(m.algorithm)) + " " + shader);
            const RenderResult r = renderRib(s.header(shader, m.options) +
                                                 solid("difference", sphereA() + biteFacingTheFloor(24, 12)) + "WorldEnd\n",
                                             test::optionsFor(m.algorithm));
            ASSERT_GT(r.stats.counters.shaderRays, 0u);
            // Rays within the circle where the spheres meet enter the result through B's inside (green);
            // outside it they cross A inside B, none of the result. A's cap towards the floor (red),
            // what a ray meets first as plain surfaces, is removed.
            EXPECT_NEAR(channelSum(r, 1), want, m.tolerance * want);
            EXPECT_LT(channelSum(r, 0), 1e-3 * want);
            // As plain surfaces B's whole disc would show (green), 2.6 times the cavity's.
            EXPECT_GT(kPi * 24 * 24 * kRoot2, 2.5 * want);
        }
}

TEST(SolidRays, TraceSeesTheCapFromOutside) {
    const RayShaders s;
    const double want = capArea(24, 12);
    for (const Mode& m : kModes) {
        SCOPED_TRACE(algorithmName(m.algorithm));
        const RenderResult r = renderRib(
            s.header("mirror", m.options) + solid("difference", sphereA() + biteAway(24, 12)) + "WorldEnd\n",
            test::optionsFor(m.algorithm));
        EXPECT_NEAR(channelSum(r, 0), want, m.tolerance * want);  // A's cap, red
        EXPECT_LT(channelSum(r, 1), 1e-3 * want);                  // never B
        EXPECT_GT(kPi * kR * kR * kRoot2 - want, 0.2 * want);     // A's whole disc, as plain surfaces
    }
}

// A union and an intersection of two spheres side by side across the axis: the discs' union and
// their lens, and where a ray meets a member's surface inside the other (the union's inside, the
// lens's outside) it goes on.
TEST(SolidRays, TraceSeesUnionAndIntersection) {
    const RayShaders s;
    const double d = 16;
    const double lens = 2 * kR * kR * std::acos(d / (2 * kR)) - 0.5 * d * std::sqrt(4 * kR * kR - d * d);
    for (const Mode& m : kModes) {
        SCOPED_TRACE(algorithmName(m.algorithm));
        const std::string members =
            sphereAt(kCx, kCy - d / 2, kCz, kR, kRed) + sphereAt(kCx, kCy + d / 2, kCz, kR, kGreen);
        const RenderResult u =
            renderRib(s.header("mirror", m.options) + solid("union", members) + "WorldEnd\n", test::optionsFor(m.algorithm));
        const RenderResult i = renderRib(s.header("mirror", m.options) + solid("intersection", members) + "WorldEnd\n",
                                         test::optionsFor(m.algorithm));
        const double both = (2 * kPi * kR * kR - lens) * kRoot2;
        EXPECT_NEAR(channelSum(u, 0) + channelSum(u, 1), both, m.tolerance * both);
        EXPECT_NEAR(channelSum(i, 0) + channelSum(i, 1), lens * kRoot2, m.tolerance * lens * kRoot2);
        // The lens shows each sphere's face where it lies inside the other: green (the upper
        // sphere's) below the axis, red above, mirror images but along the ridge where the faces
        // meet, which the rays graze (its length in pixels: one row along it).
        const double ridge = 2 * std::sqrt(kR * kR - d * d / 4) * kRoot2;
        EXPECT_NEAR(channelSum(i, 0), channelSum(i, 1), ridge);
        EXPECT_GT(std::min(channelSum(i, 0), channelSum(i, 1)), 0.45 * lens * kRoot2);
    }
}

TEST(SolidRays, GatherHitsTheResult) {
    const RayShaders s;
    const double want = capArea(24, 12);
    for (const Mode& m : kModes) {
        SCOPED_TRACE(algorithmName(m.algorithm));
        const RenderResult r = renderRib(s.header("gatherer", m.options) +
                                             solid("difference", sphereA() + biteFacingTheFloor(24, 12)) + "WorldEnd\n",
                                         test::optionsFor(m.algorithm));
        EXPECT_NEAR(channelSum(r, 0), want, m.tolerance * want);  // hits
        EXPECT_LT(channelSum(r, 1), 1e-3 * want);                  // none on A (red)
        EXPECT_NEAR(channelSum(r, 2), want, m.tolerance * want);  // all on B's inside (green)
    }
}

// Members with opacity 0.5: a ray through the cavity crosses two surfaces of the result (B's inside,
// then A's cap) and lets 1/4 through; one beside it inside B crosses none, and one outside A none
// (it crosses B alone, no surface of the result). As plain surfaces, 4 and 2 of them. Checked on
// the pixels clear of the outlines (rho0 and B's 24 across the axis): all but a few
// (a ray that meets the tessellated sphere where two of its grids overlap crosses a surface more,
// a plain sphere's too).
TEST(SolidRays, TransmissionCrossesTheResultOnly) {
    const RayShaders s;
    const double y0 = (kR * kR - 24.0 * 24.0 + 12.0 * 12.0) / 24.0, rho0 = std::sqrt(kR * kR - y0 * y0);
    const double want = 0.75 * capArea(24, 12);
    const std::string half = "Opacity [0.5 0.5 0.5]\n";
    for (const Mode& m : kModes) {
        SCOPED_TRACE(algorithmName(m.algorithm));
        const RenderResult r = renderRib(
            s.header("seethrough", m.options) +
                solid("difference", sphereA(half) + biteFacingTheFloor(24, 12, half)) + "WorldEnd\n",
            test::optionsFor(m.algorithm));
        double blocked = 0;
        int cavity = 0, cavityRight = 0, ring = 0, ringRight = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 64; x < kW; ++x) {
                const double v = double(r.channel(0, x, y, 0));
                blocked += 1.0 - v;
                // Where the pixel centre's ray runs, across the axis (the floor's ellipses' centre
                // is (116, 40); raster y down).
                const double dx = (x + 0.5 - 116) / kRoot2, dy = kH - y - 0.5 - kCy, rho = std::sqrt(dx * dx + dy * dy);
                if (rho < rho0 - 1) ++cavity, cavityRight += std::fabs(v - 0.25) < 1e-4;
                if (rho > rho0 + 1 && rho < 24 - 1) ++ring, ringRight += v == 1.0;
            }
        EXPECT_NEAR(blocked, want, m.tolerance * want);
        EXPECT_GT(cavity, 400);
        EXPECT_GT(ring, 1000);
        EXPECT_GE(cavityRight, cavity - 3);
        EXPECT_GE(ringRight, ring - 3);
    }
}

// B moves along the axis (c = 9, 10, 11, 12 at frames 0-3): each frame's cavity is its closed
// form's, frame 2 alone is frame 2 of the block, bit for bit, and one thread or two the same.
std::string movingBite(const RayShaders& s, const std::string& shader, const std::string& options) {
    std::string keys;
    for (int f = 0; f < 4; ++f) {
        const double c = 9 + f;
        keys += "Translate " + num(axisX(c)) + " " + num(kCy) + " " + num(axisZ(c)) + "\n";
    }
    const std::string b = "SolidBegin \"primitive\"\nAttributeBegin\nSurface \"constant\"\nColor [0 1 0]\nShadingRate 2\n"
                          "MotionBegin [0 1 2 3]\n" +
                          keys + "MotionEnd\nSphere 24 -24 24 360\nAttributeEnd\nSolidEnd\n";
    return s.header(shader, "Option \"streyes\" \"int frames\" [0 3]\n" + options, "2 2") +
           solid("difference", sphereA() + b) + "WorldEnd\n";
}

TEST(SolidRays, MovingMemberFrameAloneEqualsFrameInBlock) {
    const RayShaders s;
    for (const Mode& m : kModes) {
        SCOPED_TRACE(algorithmName(m.algorithm));
        const test::ShotAndFrame r =
            test::renderShotAndFrame(movingBite(s, "mirror", m.options), test::optionsFor(m.algorithm), 0, 3, 2);
        EXPECT_TRUE(r.samePixels(2));
        EXPECT_NEAR(channelSum(r.shot, 1, 0), capArea(24, 9), 0.015 * capArea(24, 9));
        EXPECT_NEAR(channelSum(r.shot, 1, 2), capArea(24, 11), 0.015 * capArea(24, 11));
        EXPECT_GT(capArea(24, 11) - capArea(24, 9), 0.5 * capArea(24, 9));
    }
}

TEST(SolidRays, ThreadCountDoesNotChangePixels) {
    const RayShaders s;
    for (const Mode& m : kModes) {
        SCOPED_TRACE(algorithmName(m.algorithm));
        RenderOptions one = test::optionsFor(m.algorithm), two = one;
        one.threads = 1;
        two.threads = 2;
        one.bucketSize = two.bucketSize = 16;
        one.hasFrames = two.hasFrames = true;  // frames 1 and 2
        one.firstFrame = two.firstFrame = 1;
        one.lastFrame = two.lastFrame = 2;
        test::halfResolutionUnderSanitizers(one, kW, kH);
        test::halfResolutionUnderSanitizers(two, kW, kH);
        for (const char* shader : {"mirror", "gatherer"}) {
            const std::string rib = movingBite(s, shader, m.options);
            EXPECT_TRUE(test::identicalPixels(renderRib(rib, one), renderRib(rib, two))) << shader;
        }
    }
}

// The value of channel `name` at pixel (x, y), or NaN when the frame has no such channel.
float aovAt(const FrameImage& f, const std::string& name, int x, int y) {
    for (size_t c = 0; c < f.aovNames.size(); ++c)
        if (f.aovNames[c] == name) return f.aov[(size_t(y) * size_t(f.width) + size_t(x)) * f.aovNames.size() + c];
    return std::nanf("");
}

// The camera looks into a bite taken out of A's front (B of radius 10, 12 in front of C): B's inside
// (green) where the spheres meet, A (red) around it, a blue floor behind. Every pixel is covered,
// the members are opaque and their Ci is their Cs: the output variable Cs of each pixel is its
// colour, whether B stands still or moves across the exposure (the moving sampler).
TEST(SolidRays, OutputVariablesComeFromTheSurfaceTheColourShows) {
    for (const bool moving : {false, true}) {
        SCOPED_TRACE(moving ? "moving" : "still");
        const std::string b =
            moving ? "SolidBegin \"primitive\"\nAttributeBegin\nColor [0 1 0]\nMotionBegin [0 1]\nTranslate 36 40 28\n"
                     "Translate 42 40 28\nMotionEnd\nSphere 10 -10 10 360\nAttributeEnd\nSolidEnd\n"
                   : sphereAt(kCx, kCy, kCz - 12, 10, kGreen);
        const std::string rib =
            test::orthoHeader(kW, kH,
                              "PixelSamples 3 3\nShutter 0 1\nDisplay \"out.exr\" \"openexr\" \"rgba\"\n"
                              "Display \"+aov.exr\" \"openexr\" \"Cs\"\n") +
            "AttributeBegin\nColor [0 0 1]\n" + test::square(0, kW, 0, kH, kFloor) + "AttributeEnd\n" +
            solid("difference", sphereA() + b) + "WorldEnd\n";
        const RenderResult r = renderRib(rib);
        const FrameImage& f = r.frame(0);
        ASSERT_EQ(f.aovNames, (std::vector<std::string>{"Cs.R", "Cs.G", "Cs.B"}));
        int red = 0, green = 0, mixed = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(aovAt(f, std::string("Cs.") + "RGB"[c], x, y), r.channel(0, x, y, c), 1e-5f)
                        << x << " " << y << " " << c;
                red += r.channel(0, x, y, 0) == 1.0f;
                green += r.channel(0, x, y, 1) == 1.0f;
                mixed += r.channel(0, x, y, 1) > 0.1f && r.channel(0, x, y, 1) < 0.9f;
            }
        // The bite's wall: the disc where the spheres meet (z = 40 - 12.5), radius sqrt(256 - 12.5^2)
        // = 9.99, 313 pixels; A's disc less it, 491 (less the pixels along the outlines).
        EXPECT_GT(red, moving ? 300 : 400);  // the moving bite sweeps more of A
        EXPECT_GT(green, moving ? 100 : 250);
        EXPECT_GT(mixed, moving ? 20 : 0);
    }
}

}  // namespace
}  // namespace streyes
