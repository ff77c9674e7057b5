// Primitive variables bound to shader parameters: constant ones on any primitive, varying ones
// interpolated over bilinear patches and polygons, "s", "t" and "st" as the shaders' texture
// coordinates, against the values they must give; type mismatches and what is not bound yet.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

// A folder of shaders and the option that finds them.
struct Shaders {
    test::TempDir dir{"primvars"};
    Shaders() {
        add("kd", "surface kd(float Kd = 1) { Oi = 1; Ci = Kd * Cs; }\n");
        add("vkd", "surface vkd(varying float Kd = 1) { Oi = 1; Ci = Kd * Cs; }\n");
        add("tint", "surface tint(varying color tint = 0) { Oi = 1; Ci = tint; }\n");
        add("st", "surface st() { Oi = 1; Ci = color(s, t, 0); }\n");
        add("label", "surface label(string label = \"\") { Oi = 1; Ci = label == \"on\" ? color(1, 0, 0) : color(0, 0, 1); }\n");
    }
    void add(const std::string& name, const std::string& source) const {
        std::ofstream(dir.path() + "/" + name + ".sl") << source;
    }
    std::string header(int w, int h) const {
        return test::orthoHeader(w, h, "PixelSamples 4 4\nOption \"searchpath\" \"shader\" \"" + dir.path() + ":@\"\n");
    }
};

std::string patch(double x0, double x1, double y0, double y1, const std::string& params) {
    auto n = [](double v) { return std::to_string(v); };
    return "Patch \"bilinear\" \"P\" [" + n(x0) + " " + n(y0) + " 5  " + n(x1) + " " + n(y0) + " 5  " + n(x0) + " " + n(y1) +
           " 5  " + n(x1) + " " + n(y1) + " 5] " + params + "\n";
}

std::array<float, 3> rgb(const test::RenderResult& r, int x, int y) {
    return {r.channel(0, x, y, 0), r.channel(0, x, y, 1), r.channel(0, x, y, 2)};
}

// Two 16 x 16 quads side by side: their six points (0 1 2 along the bottom, 3 4 5 along the top),
// and the same as a two-face subdivision mesh with its boundary interpolated.
const std::string kTwoQuadPoints = "\"P\" [0 0 5  16 0 5  32 0 5  0 16 5  16 16 5  32 16 5]";
const std::string kTwoQuadSubdivision =
    "SubdivisionMesh \"catmull-clark\" [4 4] [0 1 4 3  1 2 5 4] [\"interpolateboundary\"] [0 0] [] [] " + kTwoQuadPoints;

TEST(Primvars, AConstantVariableOverridesTheShaderParameterPerPrimitive) {
    const Shaders sh;
    // Two patches in one attribute state, each with its own Kd; a third with none: the default.
    const std::string rib = sh.header(48, 16) + "Surface \"kd\"\nColor [1 1 1]\n" +
                            patch(0, 16, 0, 16, "\"constant float Kd\" [0.25]") +
                            patch(16, 32, 0, 16, "\"uniform float Kd\" [0.5]") + patch(32, 48, 0, 16, "") + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_FLOAT_EQ(r.channel(0, 8, 8, 0), 0.25f);
    EXPECT_FLOAT_EQ(r.channel(0, 24, 8, 0), 0.5f);
    EXPECT_FLOAT_EQ(r.channel(0, 40, 8, 0), 1.0f);
    // On a quadric and a polygon mesh (constant over the whole primitive) too.
    const std::string shapes = sh.header(32, 16) + "Surface \"kd\"\nColor [1 1 1]\n" +
                               "AttributeBegin\nTranslate 8 8 10\nSphere 6 -6 6 360 \"constant float Kd\" [0.125]\nAttributeEnd\n" +
                               "PointsPolygons [4] [0 1 2 3] \"P\" [16 0 5  32 0 5  32 16 5  16 16 5] \"constant float Kd\" [0.75]\n"
                               "WorldEnd\n";
    const test::RenderResult s = test::renderRib(shapes);
    EXPECT_FLOAT_EQ(s.channel(0, 8, 8, 0), 0.125f);
    EXPECT_FLOAT_EQ(s.channel(0, 24, 8, 0), 0.75f);
}

// A varying colour over a patch is bilinear in (u, v): a pixel's mean over its square is the value
// at its centre, the micropolygons' linear pieces off by (du dv)/4 of the twist at most.
TEST(Primvars, AVaryingColourIsInterpolatedOverThePatch) {
    const Shaders sh;
    const Color k[4] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};  // (u,v) = (0,0) (1,0) (0,1) (1,1)
    std::string values;
    for (const Color& c : k) values += std::to_string(c.x) + " " + std::to_string(c.y) + " " + std::to_string(c.z) + " ";
    const std::string rib = sh.header(32, 32) + "Surface \"tint\"\n" + patch(0, 32, 0, 32, "\"varying color tint\" [" + values + "]") +
                            "WorldEnd\n";
    for (const Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        const test::RenderResult r = test::renderRib(rib, test::optionsFor(a));
        for (int y : {1, 9, 16, 30})
            for (int x : {0, 7, 20, 31}) {
                // Scene y = 32 - raster y; u = x / 32, v = y_scene / 32 at the pixel centre.
                const float u = (float(x) + 0.5f) / 32, v = (32 - (float(y) + 0.5f)) / 32;
                const Color want = lerp(lerp(k[0], k[1], u), lerp(k[2], k[3], u), v);
                const std::array<float, 3> got = rgb(r, x, y);
                EXPECT_NEAR(got[0], want.x, 1e-3f) << algorithmName(a) << " " << x << "," << y;
                EXPECT_NEAR(got[1], want.y, 1e-3f) << algorithmName(a) << " " << x << "," << y;
                EXPECT_NEAR(got[2], want.z, 1e-3f) << algorithmName(a) << " " << x << "," << y;
            }
    }
}

// "st" replaces the texture coordinates: s, t doubled over the patch; "s" alone on a Polygon of four
// vertices follows its vertices (listed around the edge, not in patch order).
TEST(Primvars, StGivesTheShadersTextureCoordinates) {
    const Shaders sh;
    const test::RenderResult r = test::renderRib(sh.header(32, 32) + "Surface \"st\"\n" +
                                                 patch(0, 32, 0, 32, "\"st\" [0 0  2 0  0 2  2 2]") + "WorldEnd\n");
    // A pixel is the mean of its 16 samples, whose mean position lies within ~0.03 px of its centre.
    EXPECT_NEAR(r.channel(0, 8, 24, 0), 2 * 8.5f / 32, 2e-3f);          // s = 2u
    EXPECT_NEAR(r.channel(0, 8, 24, 1), 2 * (32 - 24.5f) / 32, 2e-3f);  // t = 2v
    // Around the edge: (0,0) (32,0) (32,32) (0,32) with s = 0 1 1 0: s runs with x.
    const test::RenderResult p = test::renderRib(sh.header(32, 32) + "Surface \"st\"\n" +
                                                 "Polygon \"P\" [0 0 5  32 0 5  32 32 5  0 32 5] \"varying float s\" [0 1 1 0]\n" +
                                                 "WorldEnd\n");
    for (int x : {3, 16, 29}) EXPECT_NEAR(p.channel(0, x, 10, 0), (float(x) + 0.5f) / 32, 1e-3f) << x;
}

// Without "s", "t" or "st" a polygon's texture coordinates are its object-space x and y (RI Spec
// 3.2, "Polygons"; Aqsis 1.8.4 the same), not each face's own (u, v): under Scale 2 2 1, pixel
// (x, row) of the 32 x 16 view sees object (x + 0.5, 16 - row - 0.5) / 2, whatever the request
// (a quad read as a patch, a two-quad mesh, a pentagon cut into faces) and the algorithm, within
// 0.02 (a pixel's 16 samples average within ~0.03 pixel of its centre; a face's own (u, v) would
// stay within [0, 1]). The built-in surfaces read neither: nothing is added to them. An object's
// instance takes them under its own shader.
TEST(Primvars, APolygonsTextureCoordinatesAreItsObjectXAndY) {
    const Shaders sh;
    const std::vector<std::string> requests = {
        "Polygon \"P\" [0 0 5  16 0 5  16 8 5  0 8 5]\n",
        "PointsPolygons [4 4] [0 1 4 3  1 2 5 4] \"P\" [0 0 5  8 0 5  16 0 5  0 8 5  8 8 5  16 8 5]\n",
        "GeneralPolygon [5] \"P\" [0 0 5  16 0 5  16 8 5  8 9 5  0 8 5]\n",
    };
    for (const std::string& request : requests) {
        const std::string rib = sh.header(32, 16) + "Surface \"st\"\nScale 2 2 1\n" + request + "WorldEnd\n";
        for (const Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
            SCOPED_TRACE(request + algorithmName(a));
            const test::RenderResult r = test::renderRib(rib, test::optionsFor(a));
            for (int x : {1, 9, 15, 16, 23, 30})
                for (int row : {1, 8, 14}) {
                    EXPECT_NEAR(r.channel(0, x, row, 0), (float(x) + 0.5f) / 2, 0.02f) << x << " " << row;
                    EXPECT_NEAR(r.channel(0, x, row, 1), (16 - float(row) - 0.5f) / 2, 0.02f) << x << " " << row;
                }
        }
        Log log;
        const Scene plain = parseRibString("WorldBegin\nSurface \"plastic\"\n" + request + "WorldEnd\n", "p.rib", log);
        ASSERT_EQ(plain.polygonMeshes.size(), 1u);
        EXPECT_TRUE(plain.polygonMeshes[0].primvars.params.empty()) << request;
    }
    // An object's polygons, defined under no shader, instanced under one that reads s and t.
    const test::RenderResult r = test::renderRib(sh.header(32, 16) + "ObjectBegin 1\n" + requests[1] +
                                                 "ObjectEnd\nSurface \"st\"\nScale 2 2 1\nObjectInstance 1\nWorldEnd\n");
    for (int x : {1, 15, 16, 30}) {
        EXPECT_NEAR(r.channel(0, x, 8, 0), (float(x) + 0.5f) / 2, 0.02f) << "instance " << x;
        EXPECT_NEAR(r.channel(0, x, 8, 1), (16 - 8.5f) / 2, 0.02f) << "instance " << x;
    }
}

// On a quadric the four values are the corners of its (u, v) domain: a disk's v runs from the rim
// (0) to the centre (1), so "varying float Kd" [1 1 0 0] is the distance from the centre over the radius.
TEST(Primvars, AVaryingValueOnAQuadricFollowsItsParameters) {
    const Shaders sh;
    const test::RenderResult r = test::renderRib(sh.header(32, 32) + "Surface \"vkd\"\nColor [1 1 1]\nTranslate 16 16 0\n"
                                                 "Disk 5 16 360 \"varying float Kd\" [1 1 0 0]\nWorldEnd\n");
    for (int x : {17, 20, 24, 28}) {
        const float d = std::hypot(float(x) + 0.5f - 16, 16 - (15 + 0.5f));  // row 15: scene y 16.5
        EXPECT_NEAR(r.channel(0, x, 15, 0), d / 16, 0.02f) << x;
    }
}

// A polygon mesh: uniform values per polygon, vertex values by point, facevarying ones by each
// polygon's own corner (a seam: the two quads give their shared points different s), also where a
// polygon is cut into several faces (a pentagon).
TEST(Primvars, APolygonMeshBindsUniformVertexAndFacevaryingValues) {
    const Shaders sh;
    sh.add("mesh", "surface mesh(float Kd = 1; varying color tint = 0) { Oi = 1; Ci = color(Kd, s, comp(tint, 2)); }\n");
    // Two quads side by side, 16 x 16 each, sharing the points 1 and 4.
    const std::string rib = sh.header(32, 16) + "Surface \"mesh\"\n" +
                            "PointsPolygons [4 4] [0 1 4 3  1 2 5 4] " + kTwoQuadPoints +
                            " \"uniform float Kd\" [0.25 0.75]"
                            " \"facevarying float s\" [0 1 1 0  1 0 0 1]"
                            " \"vertex color tint\" [0 0 0  0 0 0.5  0 0 1  0 0 0  0 0 0.5  0 0 1]\nWorldEnd\n";
    for (const Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        const test::RenderResult r = test::renderRib(rib, test::optionsFor(a));
        const std::string name = algorithmName(a);
        EXPECT_FLOAT_EQ(r.channel(0, 8, 8, 0), 0.25f) << name;   // Kd of the first quad
        EXPECT_FLOAT_EQ(r.channel(0, 24, 8, 0), 0.75f) << name;  // and of the second
        // s rises over the first quad and falls over the second (the seam at x = 16).
        EXPECT_NEAR(r.channel(0, 4, 8, 1), 4.5f / 16, 2e-3f) << name;
        EXPECT_NEAR(r.channel(0, 20, 8, 1), 1 - 4.5f / 16, 2e-3f) << name;
        // tint's blue by point: 0 at x = 0, 0.5 at x = 16, 1 at x = 32.
        EXPECT_NEAR(r.channel(0, 8, 8, 2), 8.5f / 32, 2e-3f) << name;
        EXPECT_NEAR(r.channel(0, 28, 8, 2), 28.5f / 32, 2e-3f) << name;
    }
    // A pentagon (cut into a triangle and a quad) with a vertex value: continuous across the cut.
    const test::RenderResult p = test::renderRib(
        sh.header(32, 32) + "Surface \"mesh\"\nPolygon \"P\" [0 0 5  32 0 5  32 32 5  16 40 5  0 32 5]"
                            " \"vertex color tint\" [0 0 0  0 0 1  0 0 1  0 0 0.5  0 0 0]\nWorldEnd\n");
    for (int x : {2, 10, 16, 22, 30}) EXPECT_NEAR(p.channel(0, x, 24, 2), (float(x) + 0.5f) / 32, 2e-3f) << x;
}

// Patch meshes and subdivision meshes: a value per face (uniform), varying values at each face's
// corners, as "Cs" is read on them.
TEST(Primvars, PatchAndSubdivisionMeshesBindPerFaceValues) {
    const Shaders sh;
    sh.add("mesh", "surface mesh(float Kd = 1; varying color tint = 0) { Oi = 1; Ci = color(Kd, comp(tint, 1), comp(tint, 2)); }\n");
    const test::RenderResult pm = test::renderRib(
        sh.header(32, 16) + "Surface \"mesh\"\nPatchMesh \"bilinear\" 3 \"nonperiodic\" 2 \"nonperiodic\" " + kTwoQuadPoints +
                            " \"uniform float Kd\" [0.25 0.75] "
                            "\"varying color tint\" [0 0 0  0 0 0.5  0 0 1  0 1 0  0 1 0.5  0 1 1]\nWorldEnd\n");
    EXPECT_FLOAT_EQ(pm.channel(0, 8, 8, 0), 0.25f);
    EXPECT_FLOAT_EQ(pm.channel(0, 24, 8, 0), 0.75f);
    EXPECT_NEAR(pm.channel(0, 8, 8, 2), 8.5f / 32, 2e-3f);           // blue by x across both patches
    EXPECT_NEAR(pm.channel(0, 28, 8, 2), 28.5f / 32, 2e-3f);
    EXPECT_NEAR(pm.channel(0, 8, 4, 1), (16 - 4.5f) / 16, 2e-3f);    // green by scene y
    // A subdivision mesh of two quads (its boundary interpolated): the uniform value per control face.
    const test::RenderResult sd = test::renderRib(
        sh.header(32, 16) + "Surface \"mesh\"\n" + kTwoQuadSubdivision + " \"uniform float Kd\" [0.25 0.75]\nWorldEnd\n");
    EXPECT_FLOAT_EQ(sd.channel(0, 8, 8, 0), 0.25f);
    EXPECT_FLOAT_EQ(sd.channel(0, 24, 8, 0), 0.75f);
    // Facevarying: bilinear over each control face, discontinuous between faces. s rises over the
    // first quad and falls over the second (a seam at their shared edge); as "Cs" does.
    const std::string mesh = kTwoQuadSubdivision + " \"facevarying float s\" [0 1 1 0  1 0 0 1] "
                             "\"facevarying color Cs\" [1 0 0  1 0 0  1 0 0  1 0 0  0 1 0  0 1 0  0 1 0  0 1 0]\n";
    for (const Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        const test::RenderResult r = test::renderRib(sh.header(32, 16) + "Surface \"st\"\n" + mesh + "WorldEnd\n", test::optionsFor(a));
        // A flat mesh: its limit surface lies on the control quads (in x, y), and s is each face's
        // own bilinear, so about x / 16 on the first and 2 - x / 16 on the second.
        EXPECT_NEAR(r.channel(0, 4, 8, 0), 4.5f / 16, 0.03f) << algorithmName(a);
        EXPECT_NEAR(r.channel(0, 28, 8, 0), 2 - 28.5f / 16, 0.03f) << algorithmName(a);
        EXPECT_GT(r.channel(0, 15, 8, 0), 0.85f) << algorithmName(a);  // both sides of the seam near 1
        EXPECT_GT(r.channel(0, 16, 8, 0), 0.85f) << algorithmName(a);
        const test::RenderResult c = test::renderRib(sh.header(32, 16) + "Surface \"constant\"\n" + mesh + "WorldEnd\n",
                                                     test::optionsFor(a));
        EXPECT_EQ(rgb(c, 4, 8), (std::array<float, 3>{1, 0, 0})) << algorithmName(a);  // facevarying Cs per face
        EXPECT_EQ(rgb(c, 28, 8), (std::array<float, 3>{0, 1, 0})) << algorithmName(a);
    }
}

// A bicubic patch's vertex variables follow its basis as P does (sticky.rib's "vertex point Pref"):
// a flat Bezier patch with evenly spaced control points (x = 32 u) and Pref's x controls 0 0 1 1
// along u gives Pref.x = 3u^2 - 2u^3 (smoothstep), not the bilinear blend of its corners (u), which
// differs by up to 0.1; Pref's y controls evenly spaced give v, linear. In both renderers.
TEST(Primvars, ABicubicPatchsVertexVariableFollowsItsBasis) {
    const Shaders sh;
    sh.add("pref", "surface pref(varying point Pref = 0) { Oi = 1; point q = transform(\"object\", Pref); "
                   "Ci = color(xcomp(q), ycomp(q), 0); }\n");
    std::string P, pref;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            P += std::to_string(32.0 * i / 3) + " " + std::to_string(16.0 * j / 3) + " 5  ";
            pref += std::string(i < 2 ? "0 " : "1 ") + std::to_string(j / 3.0) + " 0  ";
        }
    const std::string rib = sh.header(32, 16) + "Surface \"pref\"\nPatch \"bicubic\" \"P\" [" + P +
                            "] \"vertex point Pref\" [" + pref + "]\nWorldEnd\n";
    for (const Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        const test::RenderResult r = test::renderRib(rib, test::optionsFor(a));
        EXPECT_TRUE(r.warnings.empty()) << algorithmName(a) << ": " << (r.warnings.empty() ? "" : r.warnings.front());
        for (int x : {2, 6, 12, 16, 25, 30}) {
            const float u = (float(x) + 0.5f) / 32;
            EXPECT_NEAR(r.channel(0, x, 8, 0), 3 * u * u - 2 * u * u * u, 2e-3f) << algorithmName(a) << " x " << x;
        }
        for (int y : {1, 5, 12}) EXPECT_NEAR(r.channel(0, 20, y, 1), (16 - (float(y) + 0.5f)) / 16, 2e-3f) << algorithmName(a);
    }
}

// Points, vectors and normals are given in object space: a point moves with the primitive's
// transform; "N" replaces the shading normal, transformed as a normal (by the inverse transpose:
// under Scale 2 1 1 a normal (0.6, 0, 0.8) leans back to (0.3, 0, 0.8); on the patch's own side,
// as Ng, which faceforward() consults); "Os" is the opacity the shader starts from.
TEST(Primvars, PointsNormalsAndOpacityComeFromObjectSpace) {
    const Shaders sh;
    sh.add("dist", "surface dist(point center = 0) { Oi = 1; Ci = length(P - center) / 16; }\n");
    const test::RenderResult d = test::renderRib(sh.header(32, 32) + "Surface \"dist\"\nTranslate 16 16 0\n" +
                                                 patch(-16, 16, -16, 16, "\"constant point center\" [0 0 5]") + "WorldEnd\n");
    for (int x : {20, 24, 28})  // away from the cone's tip, where a pixel's mean is not its centre's value
        EXPECT_NEAR(d.channel(0, x, 15, 0), std::hypot(float(x) + 0.5f - 16, 0.5f) / 16, 2e-3f) << x;
    const std::string lit = "LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\nSurface \"matte\" \"Ka\" [0]\n";
    const test::RenderResult n = test::renderRib(sh.header(32, 32) + lit + "Translate 16 16 0\nScale 2 1 1\n" +
                                                 patch(-8, 8, -16, 16, "\"constant normal N\" [0.6 0 0.8]") + "WorldEnd\n");
    EXPECT_NEAR(n.channel(0, 16, 16, 0), 0.8f / std::sqrt(0.09f + 0.64f), 1e-4f);
    const test::RenderResult flat = test::renderRib(sh.header(32, 32) + lit + "Translate 16 16 0\nScale 2 1 1\n" +
                                                    patch(-8, 8, -16, 16, "") + "WorldEnd\n");
    EXPECT_NEAR(flat.channel(0, 16, 16, 0), 1.0f, 1e-4f);
    const test::RenderResult o = test::renderRib(sh.header(32, 16) + "Surface \"constant\"\n" +
                                                 patch(0, 32, 0, 16, "\"varying color Os\" [0 0 0  1 1 1  0 0 0  1 1 1]") +
                                                 "WorldEnd\n");
    for (int x : {3, 16, 29}) EXPECT_NEAR(o.alpha(0, x, 8), (float(x) + 0.5f) / 32, 2e-3f) << x;
    EXPECT_GT(o.stats.counters.sampleFragments, 0u);
}

TEST(Primvars, StringsAndTheBuiltInShading) {
    const Shaders sh;
    const test::RenderResult r = test::renderRib(sh.header(32, 16) + "Surface \"label\"\n" +
                                                 patch(0, 16, 0, 16, "\"constant string label\" [\"on\"]") +
                                                 patch(16, 32, 0, 16, "\"constant string label\" [\"off\"]") + "WorldEnd\n");
    EXPECT_EQ(rgb(r, 8, 8), (std::array<float, 3>{1, 0, 0}));
    EXPECT_EQ(rgb(r, 24, 8), (std::array<float, 3>{0, 0, 1}));
    // matte's Kd from a primitive variable equals matte's Kd from the Surface call (the primitive
    // runs the shader's source; the other the built-in C++ of the same shader).
    const std::string lit = "Format 32 32 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 2 2\nWorldBegin\n"
                            "LightSource \"distantlight\" 1 \"from\" [0 1 -1] \"to\" [0 0 0]\n";
    const std::string sphere = "Translate 0 0 5\nSphere 1.5 -1.5 1.5 360";
    const test::RenderResult byCall = test::renderRib(lit + "Surface \"matte\" \"Kd\" [0.3]\n" + sphere + "\nWorldEnd\n");
    const test::RenderResult byPrimvar =
        test::renderRib(lit + "Surface \"matte\"\n" + sphere + " \"constant float Kd\" [0.3]\nWorldEnd\n");
    EXPECT_LT(test::maxAbsDifference(byCall, byPrimvar), 1e-4f);
    EXPECT_GT(byPrimvar.stats.counters.pointsShadedSurface, 0u);
    EXPECT_GT(test::alphaSum(byPrimvar), 100.0);
}

TEST(Primvars, ATypeMismatchNamesThePrimitiveVariable) {
    const Shaders sh;
    const std::string rib = sh.header(16, 16) + "Surface \"kd\"\n" + patch(0, 16, 0, 16, "\"constant color Kd\" [1 0 0]") + "WorldEnd\n";
    try {
        test::renderRib(rib);
        FAIL() << "a colour bound to a float parameter must be an error";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("test.rib:"), std::string::npos) << what;
        EXPECT_NE(what.find("primitive variable \"Kd\""), std::string::npos) << what;
    }
    // A varying one on Points is not bound yet: said once, and the points still render.
    const test::RenderResult r = test::renderRib(sh.header(16, 16) + "Surface \"kd\"\n"
                                                 "Points \"P\" [4 8 5  12 8 5] \"constantwidth\" [6] \"varying float Kd\" [0 0]\nWorldEnd\n");
    int warned = 0;
    for (const std::string& w : r.warnings) warned += w.find("'Kd'") != std::string::npos && w.find("not bound") != std::string::npos;
    EXPECT_EQ(warned, 1);
    EXPECT_GT(test::alphaSum(r), 10.0);
}

}  // namespace
}  // namespace streyes
