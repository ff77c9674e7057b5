// Shading Language shaders in the renderer: what a surface sees (s, t, P, N), the standard
// shaders against closed forms, the built-in shading against the shipped sources, and bad
// shaders and bindings.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

// A folder holding `name`.sl with `source`, and the RIB option that puts it first on the path.
// An orthographic W x H view of [0, W] x [0, H] (one unit a pixel), box filter, `extra` options.
std::string view(int w, int h, const std::string& extra) {
    return "Format " + std::to_string(w) + " " + std::to_string(h) + " 1\nProjection \"orthographic\"\n" +
           "ScreenWindow 0 " + std::to_string(w) + " 0 " + std::to_string(h) + "\nPixelFilter \"box\" 1 1\n" +
           "PixelSamples 4 4\n" + extra;
}

TEST(ShadingLanguage, SurfaceSeesSAndTOverThePatch) {
    test::ShaderDir shaders;
    shaders.add("st", "surface st() { Ci = color(s, t, 0); Oi = 1; }\n");
    // A 64 x 64 patch split and diced into many grids: s and t must run 0..1 across all of them.
    const std::string rib = view(64, 64, shaders.option()) + "WorldBegin\nSurface \"st\"\n" + test::square(0, 64, 0, 64, 5) +
                            "WorldEnd\n";
    test::RenderResult r = test::renderRib(rib);
    ASSERT_GT(r.stats.counters.pointsShadedSurface, 0u);
    EXPECT_EQ(r.stats.counters.pointsShadedBuiltin, 0u);
    float worst = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            // Pixel (x, y) covers u in [x, x+1]/64 and (raster y down) v in [63 - y, 64 - y]/64: the
            // box-filtered mean of a linear function is its value at the centre.
            const float s = (float(x) + 0.5f) / 64, t = (63.5f - float(y)) / 64;
            worst = std::max({worst, test::absDifference(r.channel(0, x, y, 0), s),
                              test::absDifference(r.channel(0, x, y, 1), t)});
        }
    EXPECT_LT(worst, 2e-3f);  // micropolygons are flat-shaded at ShadingRate 1: half a pixel's slope
}

TEST(ShadingLanguage, MatteUnderADistantLightIsLambertOnASphere) {
    // A sphere of radius 40 facing an orthographic camera, lit along the view: N.L is the
    // cosine of the angle from the axis, sqrt(1 - (x^2 + y^2) / r^2).
    const std::string rib = view(100, 100, "Option \"shading\" \"string builtin\" \"off\"\nShadingRate 0.25\n") +
                            "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n"
                            "Surface \"matte\" \"Ka\" 0 \"Kd\" 1\nTranslate 50 50 100\nSphere 40 -40 40 360\nWorldEnd\n";
    test::RenderResult r = test::renderRib(rib);
    EXPECT_EQ(r.stats.counters.pointsShadedBuiltin, 0u);
    EXPECT_GT(r.stats.counters.lightShaderRuns, 0u);
    float worst = 0;
    int checked = 0;
    for (int y = 0; y < 100; ++y)
        for (int x = 0; x < 100; ++x) {
            const double dx = x + 0.5 - 50, dy = y + 0.5 - 50, d2 = (dx * dx + dy * dy) / (40.0 * 40.0);
            if (d2 > 0.8) continue;  // near the rim the cosine changes fast within a pixel
            worst = std::max(worst, test::absDifference(r.channel(0, x, y, 0), float(std::sqrt(1 - d2))));
            ++checked;
        }
    EXPECT_GT(checked, 3500);
    EXPECT_LT(worst, 5e-3f);
}

TEST(ShadingLanguage, SpotlightConeAndFalloff) {
    // A spotlight 100 units in front of a wall at z = 200, pointing at it along +z: on the wall at
    // radius rho, cos = d / sqrt(d^2 + rho^2), d = 100; lit by cos^2 / dist^2 * smoothstep(cos 30,
    // cos 25, cos) (spotlight.sl, the RI Spec's).
    const std::string rib = view(200, 200, "") +
                            "WorldBegin\nLightSource \"spotlight\" 1 \"from\" [100 100 100] \"to\" [100 100 200] "
                            "\"intensity\" 10000 \"coneangle\" 0.5236 \"conedeltaangle\" 0.0873\n"
                            "Surface \"matte\" \"Ka\" 0 \"Kd\" 1\n" + test::square(0, 200, 0, 200, 200) + "WorldEnd\n";
    test::RenderResult r = test::renderRib(rib);
    auto expected = [](double rho) {
        const double d = 100, dist2 = d * d + rho * rho, c = d / std::sqrt(dist2);
        const double lo = std::cos(0.5236), hi = std::cos(0.5236 - 0.0873);
        double s = std::clamp((c - lo) / (hi - lo), 0.0, 1.0);
        s = s * s * (3 - 2 * s);
        return c * c / dist2 * s * 10000 * c;  // times N.L = cos for the wall facing the light
    };
    float worstInside = 0, worstOutside = 0;
    for (int y = 0; y < 200; y += 3)
        for (int x = 0; x < 200; x += 3) {
            const double rho = std::hypot(x + 0.5 - 100, y + 0.5 - 100);
            const double e = expected(rho);
            const float got = r.channel(0, x, y, 0);
            if (std::abs(rho - 100 * std::tan(0.5236 - 0.0436)) < 6) continue;  // the soft edge itself
            if (rho < 40) worstInside = std::max(worstInside, test::absDifference(got, float(e)) / float(e));
            if (rho > 62) worstOutside = std::max(worstOutside, std::abs(got));
        }
    EXPECT_LT(worstInside, 0.01f);  // relative, on the beam's core
    EXPECT_EQ(worstOutside, 0.0f);  // dark outside the cone
}

// The built-in constant, matte, plastic and defaultsurface, under ambient, distant and point
// lights (one casting shadows), against their Shading Language sources.
TEST(ShadingLanguage, BuiltinShadingGivesTheShippedShadersPixels) {
    const std::string world =
        "WorldBegin\nLightSource \"ambientlight\" 1 \"intensity\" 0.2\n"
        "LightSource \"distantlight\" 2 \"from\" [0 0 0] \"to\" [0.3 -0.4 1] \"intensity\" 0.8\n"
        "Attribute \"light\" \"shadows\" \"on\"\n"
        "LightSource \"pointlight\" 3 \"from\" [20 50 40] \"intensity\" 4000\n"
        "Attribute \"light\" \"shadows\" \"off\"\n"
        "AttributeBegin\nSurface \"plastic\" \"roughness\" 0.2\nColor [1 0.5 0.2]\n"
        "Translate 30 60 100\nSphere 25 -25 25 360\nAttributeEnd\n"
        "AttributeBegin\nSurface \"matte\" \"Kd\" 0.7\nTranslate 70 40 100\nSphere 25 -25 25 360\nAttributeEnd\n"
        "AttributeBegin\nSurface \"constant\"\nColor [0 1 0]\n" + test::square(0, 10, 0, 10, 90) + "AttributeEnd\n"
        "AttributeBegin\nSurface \"defaultsurface\"\n" + test::square(0, 100, 0, 100, 150) + "AttributeEnd\nWorldEnd\n";
    test::RenderResult builtin = test::renderRib(view(100, 100, "") + world);
    test::RenderResult language = test::renderRib(view(100, 100, "Option \"shading\" \"string builtin\" \"off\"\n") + world);
    EXPECT_EQ(builtin.stats.counters.pointsShadedSurface, 0u);
    EXPECT_EQ(language.stats.counters.pointsShadedBuiltin, 0u);
    EXPECT_GT(builtin.stats.counters.shadowRays + builtin.stats.counters.shadowVertexRays, 0u);
    EXPECT_LT(test::maxAbsDifference(builtin, language), 1e-4f);
    EXPECT_GT(test::meanAbsDifference(builtin, test::renderRib(view(100, 100, "") + "WorldBegin\nWorldEnd\n")), 0.05f);
}

// defaultsurface is Pixar's: 0.2 + 0.8 (N.I)^2. A square turned 60 degrees from the view
// (orthographic: I along z) is 0.2 + 0.8/4 = 0.4 in the built-in, the shipped shader and the ray
// tracer (|N.I| would give 0.6).
TEST(ShadingLanguage, DefaultSurfaceIsPixarsSquaredCosine) {
    const std::string world = "WorldBegin\nSurface \"defaultsurface\"\nTranslate 32 32 50\nRotate 60 0 1 0\n"
                              "Patch \"bilinear\" \"P\" [-40 -40 0  40 -40 0  -40 40 0  40 40 0]\nWorldEnd\n";
    for (const std::string& extra : {std::string(), std::string("Option \"shading\" \"string builtin\" \"off\"\n")})
        for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
            const test::RenderResult r = test::renderRib(view(64, 64, extra) + world, test::optionsFor(a));
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.channel(0, 32, 32, c), 0.4f, 1e-4f) << extra << algorithmName(a);
        }
}

TEST(ShadingLanguage, RayTracerShadesShaderSurfacesAsTheRasterizer) {
    test::ShaderDir shaders;
    shaders.add("stripes", "surface stripes(float n = 4) { Ci = mod(floor(s * n), 2) == 0 ? color(1, 0, 0) : color(0, 0, 1); }\n");
    const std::string rib = view(64, 64, shaders.option()) + "WorldBegin\nSurface \"stripes\" \"n\" 8\n" +
                            test::square(0, 64, 0, 64, 5) + "WorldEnd\n";
    test::RenderResult raster = test::renderRib(rib);
    test::RenderResult traced = test::renderRib(rib, test::optionsFor(Algorithm::Raytrace));
    // Stripes 8 pixels wide: red in the first, blue in the second.
    EXPECT_GT(raster.channel(0, 3, 30, 0), 0.99f);
    EXPECT_GT(raster.channel(0, 11, 30, 2), 0.99f);
    // Away from the stripes' edges (where micropolygons blend the two colours) they agree.
    float worst = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            if (x % 8 != 0 && x % 8 != 7)
                for (int c = 0; c < 4; ++c)
                    worst = std::max(worst, test::absDifference(raster.channel(0, x, y, c), traced.channel(0, x, y, c)));
    EXPECT_LT(worst, 1e-4f);
}

TEST(ShadingLanguage, ParametersFromRibReachTheShader) {
    test::ShaderDir shaders;
    shaders.add("tint", "surface tint(color c = 0; float k = 1; string mode = \"a\") {\n"
                        "  Ci = k * c; if (mode == \"half\") Ci *= 0.5; }\n");
    const std::string rib = view(8, 8, shaders.option()) + "Declare \"k\" \"uniform float\"\nWorldBegin\n" +
                            "Surface \"tint\" \"color c\" [0.2 0.4 0.6] \"k\" 2 \"mode\" \"half\"\n" +
                            test::square(0, 8, 0, 8, 5) + "WorldEnd\n";
    test::RenderResult r = test::renderRib(rib);
    EXPECT_NEAR(r.channel(0, 4, 4, 0), 0.2f, 1e-6f);
    EXPECT_NEAR(r.channel(0, 4, 4, 1), 0.4f, 1e-6f);
    EXPECT_NEAR(r.channel(0, 4, 4, 2), 0.6f, 1e-6f);
}

TEST(ShadingLanguage, ShaderReadingTimeIsShadedPerFrameAndBlockInvariant) {
    test::ShaderDir shaders;
    shaders.add("pulse", "surface pulse() { Ci = color(time / 8, 0, 0); }\n");
    const std::string rib = view(8, 8, shaders.option() + "Shutter 0 0\n") + "WorldBegin\nSurface \"pulse\"\n" +
                            test::square(0, 8, 0, 8, 5) + "WorldEnd\n";
    RenderOptions o;
    o.hasFrames = true;
    o.firstFrame = 0;
    o.lastFrame = 7;
    test::RenderResult block = test::renderRib(rib, o);
    for (int f = 0; f <= 7; ++f) {
        EXPECT_NEAR(block.channel(f, 4, 4, 0), float(f) / 8, 1e-6f) << "frame " << f;
        RenderOptions one = o;
        one.firstFrame = one.lastFrame = f;
        test::RenderResult alone = test::renderRib(rib, one);
        EXPECT_EQ(alone.channel(f, 4, 4, 0), block.channel(f, 4, 4, 0));
    }
}

TEST(ShadingLanguage, DivisionByZeroNeverReachesTheFrame) {
    test::ShaderDir shaders;
    shaders.add("bad", "surface bad() { float z = 0; Ci = color(1 / z, sqrt(-1), log(-2)); }\n");
    test::RenderResult r = test::renderRib(view(8, 8, shaders.option()) + "WorldBegin\nSurface \"bad\"\n" +
                                           test::square(0, 8, 0, 8, 5) + "WorldEnd\n");
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(r.channel(0, x, y, c), 0.0f);
    EXPECT_GT(r.stats.counters.shadingSanitised, 0u);
    int warned = 0;
    for (const std::string& w : r.warnings) warned += w.find("NaN or infinite") != std::string::npos;
    EXPECT_EQ(warned, 1);
}

TEST(ShadingLanguage, BadShadersAndBindingsNameTheirPlace) {
    test::ShaderDir shaders;
    shaders.add("broken", "surface broken() {\n  Ci = undefinedthing;\n}\n");
    shaders.add("lit", "light lit() { illuminate(point(0, 0, 0)) { Cl = 1; } }\n");
    shaders.add("takes", "surface takes(float k = 1) { Ci = k; }\n");
    const std::string head = view(8, 8, shaders.option()) + "WorldBegin\n";
    const std::string patch = test::square(0, 8, 0, 8, 5) + "WorldEnd\n";
    // Under --strict: a light shader named by Surface and a parameter the shader does not have
    // are what the peers warn about and render without (below); the rest are errors anyway.
    auto error = [&](const std::string& world) {
        try {
            test::renderRib(head + world + patch, {}, true);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string broken = error("Surface \"broken\"\n");
    EXPECT_NE(broken.find("broken.sl:2:8:"), std::string::npos) << broken;
    EXPECT_NE(error("Surface \"lit\"\n").find("is a light shader, not a surface shader"), std::string::npos);
    const std::string wrongType = error("Surface \"takes\" \"color k\" [1 0 0]\n");
    EXPECT_NE(wrongType.find("test.rib:8:"), std::string::npos) << wrongType;  // the RIB line of the parameter
    EXPECT_NE(wrongType.find("is uniform float, not color"), std::string::npos) << wrongType;
    const std::string count = error("Surface \"takes\" \"k\" [1 2]\n");
    EXPECT_NE(count.find("takes 1 value, not 2"), std::string::npos) << count;
    const std::string unknown = error("Surface \"takes\" \"uniform float q\" 1\n");
    EXPECT_NE(unknown.find("has no parameter \"q\""), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("test.rib:8:"), std::string::npos) << unknown;
    // Without --strict both are warnings (issue 46: they were errors until then): the light
    // shader is not used as a surface (the default look), the unknown parameter is left out.
    const test::RenderResult lenient = test::renderRib(head + "Surface \"lit\"\n" + patch);
    ASSERT_FALSE(lenient.warnings.empty());
    EXPECT_NE(lenient.warnings[0].find("is a light shader, not a surface shader: using defaultsurface"), std::string::npos)
        << lenient.warnings[0];
    // A displacement shader named by Surface (Aqsis's repel.rib: "lumpy") is not run at all: it
    // neither moves the surface (Aqsis runs it as the surface, so P moves and pieces past the
    // bound are lost) nor colours it; the picture is defaultsurface's.
    shaders.add("bumpy", "displacement bumpy() { P += 3 * normalize(N); N = calculatenormal(P); }\n");
    const test::RenderResult bumpy = test::renderRib(head + "Surface \"bumpy\"\n" + patch);
    ASSERT_FALSE(bumpy.warnings.empty());
    EXPECT_NE(bumpy.warnings[0].find("is a displacement shader, not a surface shader: using defaultsurface"),
              std::string::npos)
        << bumpy.warnings[0];
    EXPECT_TRUE(test::identicalPixels(bumpy, test::renderRib(head + "Surface \"defaultsurface\"\n" + patch)));
    const test::RenderResult without = test::renderRib(head + "Surface \"takes\" \"uniform float q\" 1\n" + patch);
    const test::RenderResult plain = test::renderRib(head + "Surface \"takes\"\n" + patch);
    ASSERT_FALSE(without.warnings.empty());
    EXPECT_NE(without.warnings[0].find("has no parameter \"q\": ignored"), std::string::npos) << without.warnings[0];
    EXPECT_TRUE(test::identicalPixels(without, plain));
    // A shader that is nowhere: a warning, and the default look.
    test::RenderResult r = test::renderRib(head + "Surface \"nowhere\"\n" + patch);
    ASSERT_FALSE(r.warnings.empty());
    EXPECT_NE(r.warnings[0].find("surface shader \"nowhere\" not found"), std::string::npos) << r.warnings[0];
    EXPECT_GT(r.channel(0, 4, 4, 0), 0.9f);  // defaultsurface, facing the eye
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// A displacement shader that moves every point by a constant camera-space offset.
const char* kShift = "displacement shift(float dx = 0; float dz = 0) { P += vector(dx, 0, dz); N = calculatenormal(P); }\n";

TEST(ShadingLanguage, DisplacementByAConstantMovesThePlane) {
    test::ShaderDir shaders;
    shaders.add("shift", kShift);
    // A red plane over [0, 32] x [0, 64] at z = 10, moved 16 pixels right and 2 units back. Small
    // buckets: those right of x = 32 see the plane only through its displacement bound.
    const std::string rib = view(64, 64, shaders.option()) + "WorldBegin\nColor [1 0 0]\nSurface \"constant\"\n" +
                            "Attribute \"displacementbound\" \"sphere\" 16.5\n"
                            "Displacement \"shift\" \"dx\" 16 \"dz\" 2\n" + test::square(0, 32, 0, 64, 10) + "WorldEnd\n";
    RenderOptions o;
    o.bucketSize = 8;
    test::RenderResult r = test::renderRib(rib, o);
    for (int y = 0; y < 64; y += 5)
        for (int x = 0; x < 64; ++x) {
            const float want = x >= 16 && x < 48 ? 1.0f : 0.0f;
            ASSERT_EQ(r.alpha(0, x, y), want) << x << " " << y;
            if (want > 0) {
                ASSERT_EQ(r.z(0, x, y), 12.0f) << x << " " << y;
            }
        }
}

TEST(ShadingLanguage, OcclusionCullingStaysExactWithDisplacement) {
    test::ShaderDir shaders;
    shaders.add("shift", kShift);
    // A red plane at z = 10 displaced to z = 4, in front of a blue one at z = 5: culling by the
    // undisplaced bound would hide the red plane behind the blue one.
    const std::string rib = view(64, 64, shaders.option()) + "WorldBegin\nSurface \"constant\"\n" +
                            "AttributeBegin\nColor [0 0 1]\n" + test::square(0, 64, 0, 64, 5) + "AttributeEnd\n" +
                            "AttributeBegin\nColor [1 0 0]\nAttribute \"displacementbound\" \"sphere\" 6\n"
                            "Displacement \"shift\" \"dz\" -6\n" + test::square(8, 40, 8, 40, 10) + "AttributeEnd\nWorldEnd\n";
    for (Algorithm plain : {Algorithm::Spacetime, Algorithm::Frames}) {
        const Algorithm culled = plain == Algorithm::Spacetime ? Algorithm::SpacetimeOcclusion : Algorithm::FramesOcclusion;
        test::RenderResult a = test::renderRib(rib, test::optionsFor(plain));
        test::RenderResult b = test::renderRib(rib, test::optionsFor(culled));
        EXPECT_TRUE(test::identicalPixels(a, b)) << test::testName(culled);
        EXPECT_EQ(b.channel(0, 20, 40, 0), 1.0f);  // the red plane shows in front
        EXPECT_EQ(b.channel(0, 50, 10, 2), 1.0f);  // the blue one around it
    }
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

TEST(ShadingLanguage, FogMixesTowardsTheBackgroundOverTheDistance) {
    // A red plane 10 units away in fog of distance 10: d = 1 - exp(-1) of the way to blue.
    const std::string world = "WorldBegin\nColor [1 0 0]\nSurface \"constant\"\n"
                              "Atmosphere \"fog\" \"distance\" 10 \"background\" [0 0 1]\n" +
                              test::square(0, 8, 0, 8, 10) + "WorldEnd\n";
    const float d = 1 - std::exp(-1.0f);
    for (const char* builtin : {"on", "off"}) {
        test::RenderResult r = test::renderRib(view(8, 8, std::string("Option \"shading\" \"string builtin\" \"") + builtin + "\"\n") + world);
        EXPECT_NEAR(r.channel(0, 4, 4, 0), 1 - d, 1e-5f) << builtin;
        EXPECT_NEAR(r.channel(0, 4, 4, 1), 0, 1e-6f) << builtin;
        EXPECT_NEAR(r.channel(0, 4, 4, 2), d, 1e-5f) << builtin;
    }
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

TEST(ShadingLanguage, ImagerPaintsBehindWhatWasRendered) {
    test::ShaderDir shaders;
    shaders.add("backdrop", "imager backdrop(color bg = 0) { Ci += (1 - alpha) * bg; alpha = 1; }\n");
    const std::string rib = view(8, 8, shaders.option() + "Imager \"backdrop\" \"bg\" [0 0 1]\n") +
                            "WorldBegin\nColor [1 0 0]\nSurface \"constant\"\n" + test::square(0, 4, 0, 8, 10) + "WorldEnd\n";
    test::RenderResult r = test::renderRib(rib);
    for (int x = 0; x < 8; ++x) {
        SCOPED_TRACE(x);
        EXPECT_EQ(r.channel(0, x, 3, 0), x < 4 ? 1.0f : 0.0f);
        EXPECT_EQ(r.channel(0, x, 3, 2), x < 4 ? 0.0f : 1.0f);
        EXPECT_EQ(r.alpha(0, x, 3), 1.0f);
    }
}

// The shipped `background` imager (shaders/background.sl), as exporters write it: a half-covered
// pixel is its colour plus half the background, and every pixel is opaque.
TEST(ShadingLanguage, ShippedBackgroundImagerFillsWhatIsNotCovered) {
    const std::string rib = view(8, 8, "Imager \"background\" \"color background\" [0.2 0.4 0.6]\n") +
                            "WorldBegin\nColor [1 0 0]\nSurface \"constant\"\n" + test::square(0, 4.5, 0, 8, 10) +
                            "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    for (int x = 0; x < 8; ++x) {
        SCOPED_TRACE(x);
        const float covered = x < 4 ? 1.0f : x == 4 ? 0.5f : 0.0f;
        EXPECT_NEAR(r.channel(0, x, 3, 0), covered + (1 - covered) * 0.2f, 1e-6f);
        EXPECT_NEAR(r.channel(0, x, 3, 1), (1 - covered) * 0.4f, 1e-6f);
        EXPECT_NEAR(r.channel(0, x, 3, 2), (1 - covered) * 0.6f, 1e-6f);
        EXPECT_EQ(r.alpha(0, x, 3), 1.0f);
    }
}

// Aqsis's background.sl (Larry Gritz's) names its colour "bgcolor", as RhinoMan's files write it; the
// shipped imager reads both names (their product), without a warning.
TEST(ShadingLanguage, ShippedBackgroundImagerReadsBgcolor) {
    const std::string rib = view(8, 8, "Imager \"background\" \"color bgcolor\" [0.2 0.4 0.6]\n") +
                            "WorldBegin\nColor [1 0 0]\nSurface \"constant\"\n" + test::square(0, 4, 0, 8, 10) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    EXPECT_NEAR(r.channel(0, 6, 3, 0), 0.2f, 1e-6f);
    EXPECT_NEAR(r.channel(0, 6, 3, 1), 0.4f, 1e-6f);
    EXPECT_NEAR(r.channel(0, 6, 3, 2), 0.6f, 1e-6f);
    EXPECT_EQ(r.alpha(0, 6, 3), 1.0f);
    EXPECT_EQ(r.channel(0, 2, 3, 0), 1.0f);
}

// Surface "null" (depth passes write it) is Aqsis's default surface, without a warning: the
// defaultsurface picture.
TEST(ShadingLanguage, NullSurfaceIsTheDefaultSurfaceSilently) {
    auto render = [&](const std::string& surface) {
        return test::renderRib(view(8, 8, "") + "WorldBegin\nSurface \"" + surface + "\"\n" +
                               test::square(0, 8, 0, 8, 10) + "WorldEnd\n");
    };
    const test::RenderResult null = render("null"), def = render("defaultsurface");
    EXPECT_TRUE(null.warnings.empty()) << null.warnings.front();
    EXPECT_GT(def.channel(0, 3, 3, 0), 0.5f);
    for (int x = 0; x < 8; ++x) EXPECT_EQ(null.channel(0, x, 3, 0), def.channel(0, x, 3, 0)) << x;
}

// A shader that cannot be found warns once, saying what the render does without it; the frame
// renders: the square with defaultsurface, no imager (so the background stays clear).
TEST(ShadingLanguage, MissingShadersWarnWithWhatTheRenderDoesInstead) {
    const std::string rib = view(8, 8, "Imager \"noimager\"\n") +
                            "WorldBegin\nLightSource \"nolight\" 1\nDisplacement \"nodisplacement\"\n"
                            "Atmosphere \"noatmosphere\"\nSurface \"nosurface\"\n" + test::square(0, 4, 0, 8, 10) +
                            "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    auto warned = [&](const std::string& name, const std::string& instead) {
        for (const std::string& w : r.warnings)
            if (w.find("\"" + name + "\" not found") != std::string::npos && w.find("): " + instead) != std::string::npos)
                return true;
        return false;
    };
    EXPECT_TRUE(warned("noimager", "no imager runs"));
    EXPECT_TRUE(warned("nolight", "the light is dark"));
    EXPECT_TRUE(warned("nodisplacement", "the surface is not displaced"));
    EXPECT_TRUE(warned("noatmosphere", "no atmosphere"));
    EXPECT_TRUE(warned("nosurface", "using defaultsurface"));
    EXPECT_EQ(r.alpha(0, 2, 3), 1.0f);  // the square
    EXPECT_EQ(r.alpha(0, 6, 3), 0.0f);  // no imager filled the rest
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// option() reads the Format and Option "user"; attribute() the primitive's own attributes.
TEST(ShadingLanguage, OptionAndAttributeReadTheScene) {
    test::ShaderDir shaders;
    shaders.add("probe",
                "surface probe() {\n"
                "  float fmt[3] = {0, 0, 0}, rate = 0;\n"
                "  string pass = \"\", name = \"\";\n"
                "  float ok = option(\"Format\", fmt) + option(\"user:pass\", pass) + attribute(\"ShadingRate\", rate) +\n"
                "             attribute(\"identifier:name\", name) + option(\"user:nosuch\", rate);\n"
                "  Ci = color(ok / 4, fmt[0] / 100 * (pass == \"beauty\" ? 1 : 0), rate * (name == \"left\" ? 1 : 0.25));\n"
                "  Oi = 1;\n"
                "}\n");
    const std::string rib = view(32, 16, shaders.option() + "Option \"user\" \"string pass\" [\"beauty\"]\n") +
                            "WorldBegin\nSurface \"probe\"\n"
                            "AttributeBegin\nAttribute \"identifier\" \"name\" [\"left\"]\nShadingRate 0.5\n" +
                            test::square(0, 16, 0, 16, 5) + "AttributeEnd\n" +
                            "AttributeBegin\nAttribute \"identifier\" \"name\" [\"right\"]\nShadingRate 2\n" +
                            test::square(16, 32, 0, 16, 5) + "AttributeEnd\nWorldEnd\n";
    test::RenderResult r = test::renderRib(rib);
    EXPECT_NEAR(r.channel(0, 8, 8, 0), 1.0f, 1e-6f);
    EXPECT_NEAR(r.channel(0, 8, 8, 1), 0.32f, 1e-6f);
    EXPECT_NEAR(r.channel(0, 8, 8, 2), 0.5f, 1e-6f);
    EXPECT_NEAR(r.channel(0, 24, 8, 0), 1.0f, 1e-6f);
    EXPECT_NEAR(r.channel(0, 24, 8, 2), 0.5f, 1e-6f);  // 2 * 0.25
}

// Option "shading" "specular": PRMan's highlight by default, the RI Spec's on request; the
// built-in plastic follows it as the shipped plastic.sl does.
TEST(ShadingLanguage, SpecularOptionChoosesTheHighlight) {
    const std::string world =
        "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0.3 -0.4 1] \"intensity\" 0.8\n"
        "Surface \"plastic\" \"roughness\" 0.2\nTranslate 50 50 100\nSphere 40 -40 40 360\nWorldEnd\n";
    const std::string off = "Option \"shading\" \"string builtin\" \"off\"\n";
    const std::string spec = "Option \"shading\" \"string specular\" \"rispec\"\n";
    test::RenderResult prman = test::renderRib(view(100, 100, "") + world);
    test::RenderResult prmanSl = test::renderRib(view(100, 100, off) + world);
    test::RenderResult rispec = test::renderRib(view(100, 100, spec) + world);
    test::RenderResult rispecSl = test::renderRib(view(100, 100, spec + off) + world);
    EXPECT_EQ(prmanSl.stats.counters.pointsShadedBuiltin, 0u);
    EXPECT_LT(test::maxAbsDifference(prman, prmanSl), 1e-4f);
    EXPECT_LT(test::maxAbsDifference(rispec, rispecSl), 1e-4f);
    // The spec's highlight is wider: 8 times the exponent's reciprocal.
    EXPECT_GT(test::meanAbsDifference(prman, rispec), 0.01f);
    EXPECT_THROW(test::renderRib(view(8, 8, "Option \"shading\" \"string specular\" \"phong\"\n") + "WorldBegin\nWorldEnd\n"),
                 InputError);
}

// A shader found along Option "searchpath" "shader" includes a header from the same path; the
// header's #warning and a run-time error (an index outside its array) are warned once each.
TEST(ShadingLanguage, ShadersIncludeAlongTheSearchPathAndWarnAtRunTime) {
    test::ShaderDir shaders;
    std::ofstream(shaders.dir.path() + "/tints.h") << "#define TINT(c, k) ((c) * (k))\n#warning tints.h is old\n";
    shaders.add("tinted",
                "#include <tints.h>\n"
                "surface tinted(float k = 0.5) {\n"
                "  float a[2] = {1, 2};\n"
                "  Ci = TINT(color(1, 0.5, 0.25), k) * a[5];\n"
                "  Oi = 1;\n"
                "}\n");
    test::RenderResult r = test::renderRib(view(64, 64, shaders.option()) + "WorldBegin\nSurface \"tinted\"\n" +
                                           test::square(0, 64, 0, 64, 5) + "WorldEnd\n");
    EXPECT_NEAR(r.channel(0, 8, 8, 0), 1.0f, 1e-6f);  // 0.5 * a[1]
    EXPECT_NEAR(r.channel(0, 8, 8, 2), 0.25f, 1e-6f);
    size_t said = 0;
    for (const std::string& w : r.warnings) said += w.find("tinted.sl:4:") != std::string::npos && w.find("array index 5") != std::string::npos;
    EXPECT_EQ(said, 1u);
    EXPECT_GT(r.stats.counters.shadingIndicesClamped, 1u);  // every grid did it; one warning
    // The compiler's warnings are the render's too, once.
    size_t compiled = 0;
    for (const std::string& w : r.warnings) compiled += w.find("tints.h:2:1: warning: #warning tints.h is old") != std::string::npos;
    EXPECT_EQ(compiled, 1u);
}

}  // namespace
}  // namespace streyes
