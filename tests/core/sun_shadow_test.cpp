// The sun light's ray-traced shadows (shaders/sunlight.sl; geom/lights.h): parallel to its
// from - to as a distant light's (not towards its "from" point, where a light shader's go), and
// spread over its angular radius ("angle") into a penumbra. The scene is still_shadow_test.cpp's:
// a sphere of radius 8 at (20, 20, 10) over a white matte floor at z = 40, the light along (1, 0, 1),
// whose shadow is the ellipse centred at (50, 20) of area 64 pi sqrt 2.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "geom/lights.h"
#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::orthoHeader;
using test::RenderResult;
using test::renderRib;

constexpr double kPi = 3.14159265358979323846;

// The floor lit by `light` (a LightSource's name and parameters) with shadows on, under the sphere.
std::string shadowScene(const std::string& light, const std::string& options = "") {
    return orthoHeader(96, 40, "PixelSamples 8 8\nShutter 0 1\n" + options) +
           "Attribute \"light\" \"shadows\" \"on\"\nLightSource " + light + "\n"
           "Surface \"matte\" \"Ka\" [0]\n" + test::square(0, 96, 0, 40, 40) +
           "AttributeBegin\nSurface \"constant\"\nColor [0.5 0.5 0.5]\n"
           "Translate 20 20 10\nSphere 8 -8 8 360\nAttributeEnd\nWorldEnd\n";
}

// The zenith ("up") is -z, so the sun stands 45 degrees high and lights the floor.
std::string sunShadowScene(double angle, const std::string& options = "", const std::string& shader = "sunlight") {
    return shadowScene("\"" + shader + "\" 1 \"intensity\" [2] \"from\" [0 0 0] \"to\" [1 0 1] \"up\" [0 0 -1] \"angle\" [" +
                           std::to_string(angle) + "]",
                       options);
}

// The floor's shadow (1 - light / the light where nothing is in the way), summed over pixels, and
// the pixels in a penumbra (between 10% and 90% shadow).
struct ShadowMeasure {
    double area = 0;
    int partial = 0;
};
ShadowMeasure measure(const RenderResult& r) {
    ShadowMeasure m;
    const double lit = r.channel(0, 90, 2, 0);
    EXPECT_GT(lit, 0.1);
    for (int y = 0; y < 40; ++y)
        for (int x = 30; x < 96; ++x) {
            const double s = 1.0 - double(r.channel(0, x, y, 0)) / lit;
            EXPECT_TRUE(s > -1e-4 && s < 1 + 1e-4) << x << " " << y << ": " << s;
            m.area += s;
            m.partial += s > 0.1 && s < 0.9;
        }
    return m;
}

// With no angle the sun's shadow is the distant light's ellipse (a shadow cast towards the light's
// "from" point, the origin, would fall on the floor's left, not there); with 3 degrees its edge
// spreads into a penumbra 2 x 42 tan 3 = 4.4 pixels wide (the floor lies 42 units from the sphere
// along the light) while the umbra's centre stays dark and the shadow's area stays the ellipse's
// (each direction of the cone casts an ellipse of nearly its area).
TEST(SunShadow, ParallelToTheSunAndSoftOverItsDisc) {
    const double ellipse = 64 * kPi * std::sqrt(2.0);
    const RenderResult hard = renderRib(sunShadowScene(0));
    const RenderResult soft = renderRib(sunShadowScene(3));
    const RenderResult softSample = renderRib(sunShadowScene(3, "Option \"trace\" \"string shadowtest\" [\"sample\"]\n"));
    const ShadowMeasure h = measure(hard), s = measure(soft), ss = measure(softSample);
    EXPECT_NEAR(h.area, ellipse, 0.025 * ellipse);
    EXPECT_NEAR(s.area, ellipse, 0.04 * ellipse);
    EXPECT_NEAR(ss.area, s.area, 0.03 * ellipse);
    EXPECT_EQ(hard.channel(0, 50, 20, 0), 0.0f);
    EXPECT_EQ(soft.channel(0, 50, 20, 0), 0.0f);
    // The outline is about 63 pixels long: a one-pixel ramp against a 4.4-pixel penumbra.
    EXPECT_LT(h.partial, 130);
    EXPECT_GT(s.partial, 2 * h.partial);
    EXPECT_GT(ss.partial, 2 * h.partial);
    // Each cone direction is a ray per vertex; the hard sun one.
    EXPECT_GT(soft.stats.counters.shadowVertexRays, 12 * hard.stats.counters.shadowVertexRays);
}

// What decides is what the shader does, not its name: a copy of sunlight.sl under another name
// casts the sun's shadow, bit for bit.
TEST(SunShadow, ARenamedCopyOfTheSunCastsTheSameShadow) {
    test::ShaderDir shaders;
    std::ifstream in(test::sourcePath("shaders/sunlight.sl"));
    std::stringstream text;
    text << in.rdbuf();
    std::string source = text.str();
    const size_t at = source.find("light sunlight(");
    ASSERT_NE(at, std::string::npos);
    source.replace(at, 15, "light mysun(");
    shaders.add("mysun", source);
    const RenderResult sun = renderRib(sunShadowScene(3, shaders.option()));
    const RenderResult copy = renderRib(sunShadowScene(3, shaders.option(), "mysun"));
    EXPECT_EQ(copy.channel(0, 50, 20, 0), 0.0f);  // the parallel shadow's umbra
    EXPECT_GT(measure(copy).partial, 130);         // and its penumbra
    EXPECT_TRUE(test::identicalPixels(sun, copy));
}

// solar(axis, 0): hard shadows parallel to the axis (the distant light's ellipse, a one-pixel
// edge); a light that illuminates from a point casts its shadow away from that point (off the
// picture: the origin's shadow of the sphere falls about (80, 80)), not the parallel one.
TEST(SunShadow, SolarLightsAreDirectionalAndIlluminateLightsAreNot) {
    test::ShaderDir shaders;
    shaders.add("hardsun", "light hardsun(float intensity = 1; point from = point \"shader\" (0, 0, 0);\n"
                           "  point to = point \"shader\" (0, 0, 1);) {\n"
                           "  solar(to - from, 0) { Cl = intensity; }\n}\n");
    shaders.add("lamp", "light lamp(float intensity = 1; point from = point \"shader\" (0, 0, 0);\n"
                        "  point to = point \"shader\" (0, 0, 1);) {\n"
                        "  illuminate(from) { Cl = intensity; }\n}\n");
    const std::string params = " 1 \"intensity\" [2] \"from\" [0 0 0] \"to\" [1 0 1]";
    const RenderResult hard = renderRib(shadowScene("\"hardsun\"" + params, shaders.option()));
    const ShadowMeasure h = measure(hard);
    const double ellipse = 64 * kPi * std::sqrt(2.0);
    EXPECT_NEAR(h.area, ellipse, 0.025 * ellipse);
    EXPECT_LT(h.partial, 130);
    EXPECT_EQ(hard.channel(0, 50, 20, 0), 0.0f);
    const RenderResult lamp = renderRib(shadowScene("\"lamp\"" + params, shaders.option()));
    EXPECT_GT(lamp.channel(0, 50, 20, 0), 0.1f);
    EXPECT_GT(lamp.stats.counters.shadowVertexRays, 0u);  // it does trace shadows
}

// The light set takes a light shader marked directional as a distant light: its direction
// against the solar axis in camera space, its cone the tangent of the solar angle, and every cone
// direction within the cone, spread about its axis.
TEST(SunShadow, TheLightSetTakesTheSunAsADirectionalLight) {
    LightDesc d;
    d.type = "anysun";
    d.castsShadows = true;
    LightSet set({d}, MotionTransform());
    set.setDirectional(0, {-3, -4, 0}, 0.27 * kPi / 180);  // solar(to - from, radians(0.27))
    std::vector<CameraLight> ls;
    set.at(0, ls);
    ASSERT_EQ(ls.size(), 1u);
    const CameraLight& l = ls[0];
    EXPECT_TRUE(l.parallel);
    EXPECT_FALSE(shadowsTowardsPoint(l));
    EXPECT_NEAR(l.direction.x, 0.6f, 1e-6f);  // against the axis
    EXPECT_NEAR(l.direction.y, 0.8f, 1e-6f);
    EXPECT_NEAR(l.coneTan, std::tan(0.27 * kPi / 180), 1e-9);
    ASSERT_EQ(coneShadowSamples(l), kConeShadowSamples);
    Vec3f mean{0, 0, 0};
    for (int j = 0; j < kConeShadowSamples; ++j) {
        const Vec3f c = coneShadowDirection(l, j);
        EXPECT_NEAR(length(c), 1.0f, 1e-6f);
        EXPECT_LE(std::acos(std::min(1.0f, dot(c, l.direction))), 0.27 * kPi / 180 * 1.001);
        mean = mean + c / float(kConeShadowSamples);
    }
    EXPECT_GT(dot(normalize(mean), l.direction), std::cos(0.05 * 0.27 * kPi / 180));
    CameraLight hard = l;
    hard.coneTan = 0;
    EXPECT_EQ(coneShadowSamples(hard), 1);
    EXPECT_EQ(coneShadowDirection(hard, 0).x, l.direction.x);
}

}  // namespace
}  // namespace streyes
