// Output variables (AOVs) rendered: N, P and Z of a sphere against the analytic surface, s and t
// of a patch against its parameterisation, motion vectors of a rigidly moving square against its
// raster velocity, and colour unchanged bit for bit by asking for them.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "streyes/error.h"
#include "test_util.h"

namespace streyes {
namespace {

// The value of channel `name` at pixel (x, y), or NaN when the frame has no such channel.
float aovAt(const FrameImage& f, const std::string& name, int x, int y) {
    for (size_t c = 0; c < f.aovNames.size(); ++c)
        if (f.aovNames[c] == name) return f.aov[(size_t(y) * size_t(f.width) + size_t(x)) * f.aovNames.size() + c];
    return std::nanf("");
}

// A unit sphere 5 units in front of a perspective camera (fov 40 over 48 rows), box filter: a
// pixel's value is the mean of its own samples.
const char* kSphere = R"(Format 64 48 1
Projection "perspective" "fov" 40
PixelSamples 4 4
PixelFilter "box" 1 1
Display "out.exr" "openexr" "rgba"
Display "+aov.exr" "openexr" "N,P,z"
DisplayChannel "varying normal N"
DisplayChannel "point P"
WorldBegin
ShadingRate 0.25
Translate 0 0 5
Sphere 1 -1 1 360
WorldEnd
)";

TEST(AovRender, SphereNormalAndPositionMatchTheAnalyticSurface) {
    const test::RenderResult r = test::renderRib(kSphere);
    const FrameImage& f = r.frame(0);
    ASSERT_EQ(f.aovNames, (std::vector<std::string>{"N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z"}));
    // The ray through the pixel centre (camera space: x right, y up, looking down +z; raster y
    // down), met with the sphere |p - (0,0,5)| = 1.
    const double t = std::tan(20.0 * M_PI / 180.0);  // half the fov across the 48 rows
    int checked = 0;
    double worstP = 0, worstN = 0, worstZ = 0, worstRadius = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            if (r.alpha(0, x, y) < 1.0f) continue;  // whole pixels only: no silhouette
            const double dx = (x + 0.5 - 32.0) / 24.0 * t, dy = -(y + 0.5 - 24.0) / 24.0 * t;
            // |s d - c|^2 = 1 with d = (dx, dy, 1), c = (0, 0, 5).
            const double a = dx * dx + dy * dy + 1, b = -2 * 5.0, c = 25.0 - 1.0;
            const double disc = b * b - 4 * a * c;
            if (disc <= 0) continue;
            const double s = (-b - std::sqrt(disc)) / (2 * a);
            const double px = s * dx, py = s * dy, pz = s;
            const double nx = px, ny = py, nz = pz - 5.0;  // the outward normal of a unit sphere
            // Within 37 degrees of facing the eye: towards the silhouette a pixel's samples spread
            // over much of the curved surface, and their mean leaves it.
            if (nz > -0.8) continue;
            const double P[3] = {aovAt(f, "P.X", x, y), aovAt(f, "P.Y", x, y), aovAt(f, "P.Z", x, y)};
            const double N[3] = {aovAt(f, "N.X", x, y), aovAt(f, "N.Y", x, y), aovAt(f, "N.Z", x, y)};
            worstP = std::max({worstP, std::fabs(P[0] - px), std::fabs(P[1] - py), std::fabs(P[2] - pz)});
            worstN = std::max({worstN, std::fabs(N[0] - nx), std::fabs(N[1] - ny), std::fabs(N[2] - nz)});
            worstRadius = std::max(worstRadius, std::fabs(std::hypot(P[0], P[1], P[2] - 5.0) - 1.0));
            worstZ = std::max(worstZ, std::fabs(double(r.z(0, x, y)) - pz));
            EXPECT_LE(r.z(0, x, y), P[2] + 1e-4);  // the nearest sample: no farther than their mean
            ++checked;
        }
    EXPECT_GT(checked, 250);
    // A pixel's mean over its 16 jittered samples against the centre's ray (measured 1.4e-3): the
    // samples' mean position off the centre, the surface's curvature over a pixel (0.06 units
    // across) and the micropolygons' facets (0.75e-3 off the radius).
    EXPECT_LT(worstP, 3e-3) << checked;
    EXPECT_LT(worstN, 3e-3);
    EXPECT_LT(worstRadius, 1.5e-3);
    // Z: the nearest of the pixel's samples, within the pixel's depth range (0.06 x 0.75 across).
    EXPECT_LT(worstZ, 4e-2);
}

TEST(AovRender, NormalsAtTheSilhouetteAreTheSurfacesNotMixedWithTheBackground) {
    const test::RenderResult r = test::renderRib(kSphere);
    const FrameImage& f = r.frame(0);
    int edges = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const float a = r.alpha(0, x, y);
            const double n = std::hypot(aovAt(f, "N.X", x, y), aovAt(f, "N.Y", x, y), aovAt(f, "N.Z", x, y));
            if (a == 0) {
                EXPECT_EQ(n, 0.0);  // nothing hit: 0
            } else if (a < 1) {
                ++edges;
                // Unit normals averaged over a few degrees of the surface, not scaled by coverage.
                EXPECT_GT(n, 0.9) << x << " " << y << " alpha " << a;
            }
        }
    EXPECT_GT(edges, 50);
}

TEST(AovRender, PatchSAndTFollowItsParameterisation) {
    // A bilinear patch over [-1, 1]^2 seen orthographically, 32 pixels across: s runs along x, t
    // down the image (the patch's second row of points is the lower one).
    const std::string rib = R"(Format 32 32 1
Projection "orthographic"
ScreenWindow -1 1 -1 1
PixelSamples 4 4
PixelFilter "box" 1 1
Display "+st.exr" "openexr" "s,t"
WorldBegin
Translate 0 0 5
Patch "bilinear" "P" [-1 1 0  1 1 0  -1 -1 0  1 -1 0]
WorldEnd
)";
    const test::RenderResult r = test::renderRib(rib);
    const FrameImage& f = r.frame(0);
    ASSERT_EQ(f.aovNames, (std::vector<std::string>{"s", "t"}));
    double worst = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            ASSERT_EQ(r.alpha(0, x, y), 1.0f);
            // s = (x + 0.5) / 32 at the pixel centre; the pixel's mean of a linear function is its
            // value at the mean of the 16 jittered sample positions, within a stratum's jitter.
            worst = std::max({worst, std::fabs(aovAt(f, "s", x, y) - (x + 0.5) / 32.0),
                              std::fabs(aovAt(f, "t", x, y) - (y + 0.5) / 32.0)});
        }
    EXPECT_LT(worst, 0.1 / 32);  // a tenth of a pixel's step
}

TEST(AovRender, MotionVectorsAreTheRasterVelocity) {
    // An orthographic view 40 pixels over 4 units (10 pixels a unit). A square moves by (1, 0.5)
    // units a frame over frames 0 and 1: (10, -5) pixels a frame, raster y down. A still square
    // above it has none. Motion blur (Shutter 0 1) leaves no pixel whole: every covered one counts.
    const std::string rib = R"(Format 40 40 1
Projection "orthographic"
ScreenWindow -2 2 -2 2
Shutter 0 1
PixelSamples 4 4
PixelFilter "box" 1 1
Display "+motion.####.exr" "openexr" "rgba,motion"
WorldBegin
AttributeBegin
MotionBegin [0 2]
Translate -1.2 -0.6 5
Translate 0.8 0.4 5
MotionEnd
Patch "bilinear" "P" [-0.5 0.5 0  0.5 0.5 0  -0.5 -0.5 0  0.5 -0.5 0]
AttributeEnd
AttributeBegin
Translate 1.2 1.5 6
Patch "bilinear" "P" [-0.4 0.4 0  0.4 0.4 0  -0.4 -0.4 0  0.4 -0.4 0]
AttributeEnd
WorldEnd
)";
    RenderOptions o;
    o.hasFrames = true;
    o.firstFrame = 0, o.lastFrame = 1;
    const test::RenderResult r = test::renderRib(rib, o);
    for (int fr = 0; fr <= 1; ++fr) {
        const FrameImage& f = r.frame(fr);
        ASSERT_EQ(f.aovNames, (std::vector<std::string>{"motion.X", "motion.Y"}));
        int moving = 0, still = 0;
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 40; ++x) {
                if (r.alpha(fr, x, y) == 0) continue;
                const float mx = aovAt(f, "motion.X", x, y), my = aovAt(f, "motion.Y", x, y);
                if (y < 10) {  // the still square, above the moving one's reach (rows 11 on)
                    EXPECT_EQ(mx, 0.0f);
                    EXPECT_EQ(my, 0.0f);
                    ++still;
                } else {
                    EXPECT_NEAR(mx, 10.0f, 1e-3f) << x << " " << y;
                    EXPECT_NEAR(my, -5.0f, 1e-3f) << x << " " << y;
                    ++moving;
                }
            }
        EXPECT_GT(moving, 100);
        EXPECT_GT(still, 50);
    }
}

TEST(AovRender, MotionUnderAClosedShutterReadsZeroAndIsWarnedAbout) {
    // Each frame an instant: the pieces carry no motion (documented; motion needs an open shutter).
    const std::string rib = R"(Format 20 20 1
Projection "orthographic"
ScreenWindow -2 2 -2 2
Shutter 0 0
Display "+m.exr" "openexr" "motion"
WorldBegin
MotionBegin [0 2]
Translate -1 0 5
Translate 1 0 5
MotionEnd
Patch "bilinear" "P" [-0.5 0.5 0  0.5 0.5 0  -0.5 -0.5 0  0.5 -0.5 0]
WorldEnd
)";
    const test::RenderResult r = test::renderRib(rib);
    int warned = 0;
    for (const std::string& w : r.warnings) warned += w.find("open shutter") != std::string::npos && w.find(":5") != std::string::npos;
    EXPECT_EQ(warned, 1);
    EXPECT_GT(test::alphaSum(r), 20.0);
    for (float v : r.frame(0).aov) EXPECT_EQ(v, 0.0f);
}

TEST(AovRender, ColourIsBitIdenticalWithAndWithoutOutputVariables) {
    // Moving and still geometry, shaded: asking for every variable changes no colour or depth bit.
    const std::string body = R"(WorldBegin
LightSource "distantlight" 1 "from" [0 1 -1] "to" [0 0 0]
Surface "plastic"
AttributeBegin
MotionBegin [0 1]
Translate -0.5 0 5
Translate 0.5 0.2 5
MotionEnd
Sphere 1 -1 1 360
AttributeEnd
AttributeBegin
Translate 0.8 -0.5 7
Patch "bilinear" "P" [-1 1 0  1 1 0  -1 -1 0  1 -1 0]
AttributeEnd
WorldEnd
)";
    const std::string head = "Format 48 40 1\nProjection \"perspective\" \"fov\" 50\nShutter 0 1\n";
    for (Algorithm a : {Algorithm::Frames, Algorithm::Spacetime, Algorithm::SpacetimeOcclusion}) {
        RenderOptions o = test::optionsFor(a);
        o.hasFrames = true;
        o.firstFrame = 0, o.lastFrame = 2;
        const test::RenderResult plain = test::renderRib(head + "Display \"a.exr\" \"openexr\" \"rgbaz\"\n" + body, o);
        const test::RenderResult withAovs = test::renderRib(
            head + "Display \"a.exr\" \"openexr\" \"rgbaz\"\nDisplay \"+b.exr\" \"openexr\" \"N,P,s,t,Ci,Oi,motion\"\n" + body,
            o);
        ASSERT_EQ(withAovs.frame(0).aovNames.size(), 16u);
        EXPECT_TRUE(plain.frame(0).aov.empty());
        EXPECT_TRUE(test::identicalPixels(plain, withAovs)) << test::testName(a);
        EXPECT_GT(test::alphaSum(plain, 1), 100.0);
    }
    RenderOptions o;
    o.hasFrames = true;
    o.firstFrame = 0, o.lastFrame = 2;
    const test::RenderResult withAovs = test::renderRib(
        head + "Display \"a.exr\" \"openexr\" \"rgbaz\"\nDisplay \"+b.exr\" \"openexr\" \"N,P,s,t,Ci,Oi,motion\"\n" + body, o);
    // Ci is the colour where coverage is whole (a mean over the hits, colour a mean over all).
    const FrameImage& f = withAovs.frame(1);
    int whole = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            if (withAovs.alpha(1, x, y) < 1) continue;
            ++whole;
            EXPECT_NEAR(aovAt(f, "Ci.R", x, y), withAovs.channel(1, x, y, 0), 1e-5f);
            EXPECT_EQ(aovAt(f, "Oi.G", x, y), 1.0f);
        }
    EXPECT_GT(whole, 100);
}

TEST(AovRender, ShadowedRendersKeepTheirColourAndCarryTheVariables) {
    // Lights that cast shadows make every frame's samples its own (dense records): the variables
    // go with them, and colour keeps its bits.
    const std::string body = R"(WorldBegin
AttributeBegin
Attribute "light" "shadows" "on"
LightSource "distantlight" 1 "from" [0 2 0] "to" [0 0 1]
AttributeEnd
Surface "matte"
AttributeBegin
MotionBegin [0 1]
Translate -0.3 0.6 4
Translate 0.3 0.6 4
MotionEnd
Sphere 0.4 -0.4 0.4 360
AttributeEnd
AttributeBegin
Translate 0 -0.5 5
Rotate 90 1 0 0
Patch "bilinear" "P" [-4 -4 0  4 -4 0  -4 4 0  4 4 0]
AttributeEnd
WorldEnd
)";
    const std::string head = "Format 40 32 1\nProjection \"perspective\" \"fov\" 60\nShutter 0 1\n";
    const test::RenderResult plain = test::renderRib(head + "Display \"a.exr\" \"openexr\" \"rgbaz\"\n" + body);
    const test::RenderResult withAovs =
        test::renderRib(head + "Display \"a.exr\" \"openexr\" \"rgbaz\"\nDisplay \"+b.exr\" \"openexr\" \"N,P\"\n" + body);
    EXPECT_TRUE(test::identicalPixels(plain, withAovs));
    const FrameImage& f = withAovs.frame(0);
    // The floor (y = -0.5, facing up towards y): its normal and height where it alone is seen.
    int floor = 0;
    for (int y = 22; y < 29; ++y)  // below the sphere (rows 15 and up), above the floor's near edge
        for (int x = 0; x < 40; ++x) {
            if (withAovs.alpha(0, x, y) < 1) continue;
            ++floor;
            EXPECT_NEAR(std::fabs(aovAt(f, "N.Y", x, y)), 1.0f, 1e-5f);
            EXPECT_NEAR(aovAt(f, "P.Y", x, y), -0.5f, 1e-5f);
        }
    EXPECT_GT(floor, 100);
}

TEST(AovRender, SurfaceShaderOutputsAreWrittenWhereDeclared) {
    const test::TempDir dir("aov-shader");
    std::ofstream(dir.path() + "/withaov.sl") << R"(surface withaov(output varying color halfCs = 0;
                                                                  output varying float height = 0;) {
    halfCs = Cs * 0.5;
    height = ycomp(P);
    Oi = Os;
    Ci = Cs * Oi;
}
)";
    // A square over the whole image, orthographic: height is camera y, 1 at the top row's top.
    const std::string rib = "Option \"searchpath\" \"shader\" [\"" + dir.path() + R"(:@"]
Format 16 16 1
Projection "orthographic"
PixelFilter "box" 1 1
DisplayChannel "color halfCs"
DisplayChannel "varying float height"
Display "+sh.exr" "openexr" "rgba,halfCs,height"
WorldBegin
AttributeBegin
Color [1 0.5 0.25]
Surface "withaov"
Translate 0 0 5
Patch "bilinear" "P" [-1 1 0  1 1 0  -1 -1 0  1 -1 0]
AttributeEnd
WorldEnd
)";
    const test::RenderResult r = test::renderRib(rib);
    const FrameImage& f = r.frame(0);
    ASSERT_EQ(f.aovNames, (std::vector<std::string>{"halfCs.R", "halfCs.G", "halfCs.B", "height"}));
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            EXPECT_EQ(aovAt(f, "halfCs.R", x, y), 0.5f);
            EXPECT_EQ(aovAt(f, "halfCs.G", x, y), 0.25f);
            EXPECT_EQ(aovAt(f, "halfCs.B", x, y), 0.125f);
            // The mean of the 4 jittered samples' heights, within a stratum of the centre's.
            EXPECT_NEAR(aovAt(f, "height", x, y), 1.0 - (y + 0.5) / 8.0, 0.25 / 8.0);
        }
}

TEST(AovRender, BadModesAndUnknownVariablesNameTheLine) {
    const std::string head = "Format 8 8 1\n";
    std::string e = test::ribError(head + "Display \"a.exr\" \"openexr\" \"rgba,Nx\"\n");
    EXPECT_NE(e.find("bad.rib:2"), std::string::npos) << e;
    EXPECT_NE(e.find("\"Nx\""), std::string::npos) << e;
    e = test::ribError(head + "Display \"a.exr\" \"openexr\" \"rgba,\"\n");
    EXPECT_NE(e.find("bad.rib:2"), std::string::npos) << e;
    e = test::ribError(head + "\nDisplayChannel \"color N\"\n");
    EXPECT_NE(e.find("bad.rib:3"), std::string::npos) << e;
    EXPECT_NE(e.find("normal"), std::string::npos) << e;
    // A shader output needs a type a shader output can have; a mode naming an undeclared one fails.
    e = test::ribError(head + "DisplayChannel \"string label\"\n");
    EXPECT_NE(e.find("bad.rib:2"), std::string::npos) << e;
    EXPECT_NE(e.find("label"), std::string::npos) << e;
    e = test::ribError(head + "DisplayChannel \"float myOutput\"\nDisplay \"+m.exr\" \"openexr\" \"myOutput,other\"\n");
    EXPECT_NE(e.find("bad.rib:3"), std::string::npos) << e;
    EXPECT_NE(e.find("\"other\""), std::string::npos) << e;
    e = test::ribError(head + "DisplayChannel \"float myOutput\"\nDisplayChannel \"color myOutput\"\n");
    EXPECT_NE(e.find("bad.rib:3"), std::string::npos) << e;
    // Declared with parameters the renderer does not use: read, warned about once.
    const test::RenderResult r = test::renderRib(head + "DisplayChannel \"normal N\" \"string filter\" \"box\"\n"
                                                         "DisplayChannel \"float s\" \"string filter\" \"box\"\n"
                                                         "Display \"+n.exr\" \"openexr\" \"N\"\nWorldBegin\nWorldEnd\n");
    int warned = 0;
    for (const std::string& w : r.warnings) warned += w.find("DisplayChannel") != std::string::npos;
    EXPECT_EQ(warned, 1);
}

TEST(AovRender, TheRayTracerRefusesOutputVariables) {
    const std::string rib = "Format 8 8 1\nDisplay \"+n.exr\" \"openexr\" \"N\"\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n";
    try {
        test::renderRib(rib, test::optionsFor(Algorithm::Raytrace));
        FAIL() << "rendered";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(":2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("raytrace"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// Display mode "Cs" (the surface colour the shader was given: Aqsis's multipass example writes
// it) and a mode that declares a shader output inline, "float myval" (PRMan's and Aqsis's form):
// a square of Color (0.25, 0.5, 0.75) whose surface writes myval = 0.625, left half of the frame.
TEST(AovRender, CsAndAnInlineDeclaredShaderOutput) {
    const test::TempDir dir("aov-shaders");
    std::ofstream(dir.path() + "/myval.sl")
        << "surface myval(output varying float myval = 0) { myval = 0.625; Ci = Cs; Oi = Os; }\n";
    const std::string rib = "Option \"searchpath\" \"shader\" \"" + dir.path() + ":@\"\n" +
                            "Format 8 4 1\nProjection \"orthographic\"\nScreenWindow -2 2 -1 1\nPixelFilter \"box\" 1 1\n"
                            "Display \"out.exr\" \"openexr\" \"rgba\"\nDisplay \"+cs.exr\" \"openexr\" \"Cs\"\n"
                            "Display \"+v.exr\" \"openexr\" \"float myval\"\n"
                            "WorldBegin\nSurface \"myval\"\nColor [0.25 0.5 0.75]\n"
                            "Polygon \"P\" [-2.5 -1.5 5  0 -1.5 5  0 1.5 5  -2.5 1.5 5]\nWorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    const FrameImage& f = r.frame(0);
    ASSERT_EQ(f.aovNames, (std::vector<std::string>{"Cs.R", "Cs.G", "Cs.B", "myval"}));
    for (int x = 0; x < 8; ++x) {
        SCOPED_TRACE(x);
        const bool in = x < 4;
        EXPECT_EQ(aovAt(f, "Cs.R", x, 2), in ? 0.25f : 0.0f);
        EXPECT_EQ(aovAt(f, "Cs.G", x, 2), in ? 0.5f : 0.0f);
        EXPECT_EQ(aovAt(f, "Cs.B", x, 2), in ? 0.75f : 0.0f);
        EXPECT_EQ(aovAt(f, "myval", x, 2), in ? 0.625f : 0.0f);
    }
}

}  // namespace
}  // namespace streyes
