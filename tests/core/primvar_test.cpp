// Primitive variables bound to shader parameters: constant ones on any primitive, varying ones
// interpolated over bilinear patches and polygons, "s", "t" and "st" as the shaders' texture
// coordinates, against the values they must give; type mismatches and what is not bound yet.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "test_util.h"

namespace streyes {
namespace {

// A folder of shaders and the option that finds them.
struct Shaders {
    test::TempDir dir{"primvars"};
    Shaders() {
        add("kd", "surface kd(float Kd = 1) { Oi = 1; Ci = Kd * Cs; }\n");
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
    // A varying one on a quadric is not bound yet: said once, and the surface still renders.
    const test::RenderResult r = test::renderRib(sh.header(16, 16) + "Surface \"kd\"\nTranslate 8 8 10\n"
                                                 "Sphere 6 -6 6 360 \"varying float Kd\" [0 0 0 0]\nWorldEnd\n");
    int warned = 0;
    for (const std::string& w : r.warnings) warned += w.find("'Kd'") != std::string::npos && w.find("not bound") != std::string::npos;
    EXPECT_EQ(warned, 1);
    EXPECT_GT(test::alphaSum(r), 10.0);
}

}  // namespace
}  // namespace streyes
