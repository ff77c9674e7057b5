// The sky as an environment without a map (Option "environment:NAME", shade/shader_environment.h):
// indirectdiffuse() of a plane facing the zenith under shaders/preethamsky.sl gives the cosine-
// weighted mean of the paper's sky over the hemisphere, (1/pi) \int L cos(theta) dw, worked out
// here by quadrature from the paper's formulas (tests/preetham_reference.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "preetham_reference.h"
#include "shade/vm/color_spaces.h"
#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The zenith is -z (towards the orthographic camera, which looks along +z); the sun 40 degrees
// from it.
const Vec3d kZenith{0, 0, -1};
const Vec3d kSun = normalize(Vec3d{std::sin(40 * kPi / 180), 0, -std::cos(40 * kPi / 180)});
constexpr double kTurbidity = 3, kIntensity = 0.06;

Vec3d skyIrradianceByQuadrature() {
    const Vec3d e1{1, 0, 0}, e2{0, 1, 0};
    const double thetaS = std::acos(dot(kSun, kZenith));
    const int nt = 600, np = 1200;
    const double dt = 0.5 * kPi / nt, dp = 2 * kPi / np;
    Vec3d sum{0, 0, 0};
    for (int i = 0; i < nt; ++i) {
        const double theta = (i + 0.5) * dt;
        for (int j = 0; j < np; ++j) {
            const double phi = (j + 0.5) * dp;
            const Vec3d d = e1 * (std::sin(theta) * std::cos(phi)) + e2 * (std::sin(theta) * std::sin(phi)) +
                            kZenith * std::cos(theta);
            const double gamma = std::acos(std::clamp(dot(d, kSun), -1.0, 1.0));
            const preetham_ref::Sky s = preetham_ref::preethamSky(kTurbidity, thetaS, theta, gamma);
            const float xyY[3] = {float(s.x), float(s.y), float(std::max(s.Y, 0.0))};
            float rgb[3];
            sl::toRgb(sl::colorSpaceNamed("xyY"), xyY, rgb);
            const double w = std::cos(theta) * std::sin(theta) * dt * dp / kPi;
            sum = sum + Vec3d{rgb[0], rgb[1], rgb[2]} * (kIntensity * w);
        }
    }
    return sum;
}

TEST(SkyEnvironment, IndirectDiffuseUnderTheSkyIsItsCosineWeightedIntegral) {
    test::ShaderDir shaders;
    shaders.add("skylit", "surface skylit() {\n"
                          "  normal Nf = faceforward(normalize(N), I);\n"
                          "  Ci = indirectdiffuse(P, Nf, 256, \"environmentmap\", \"sky\", \"environmentspace\", \"world\");\n"
                          "  Oi = 1;\n}\n");
    char sky[400];
    std::snprintf(sky, sizeof sky,
                  "Option \"environment:sky\" \"string shader\" [\"preethamsky\"] \"float turbidity\" [%g] "
                  "\"float intensity\" [%g] \"point from\" [%.17g %.17g %.17g] \"point to\" [0 0 0] \"vector up\" [0 0 -1]\n",
                  kTurbidity, kIntensity, kSun.x, kSun.y, kSun.z);
    const test::RenderResult r = test::renderRib(test::orthoHeader(16, 16, shaders.option() + sky) +
                                                 "Surface \"skylit\"\n" + test::square(0, 16, 0, 16, 10) + "WorldEnd\n");
    const Vec3d want = skyIrradianceByQuadrature();
    Vec3d got{0, 0, 0};
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (int c = 0; c < 3; ++c) got[c] += double(r.channel(0, x, y, c)) / 256;
    for (int c = 0; c < 3; ++c) {
        EXPECT_GT(want[c], 0.05) << c;  // a sky of some brightness, not black
        EXPECT_NEAR(got[c], want[c], 0.01 * want[c]) << c;
    }
    // The sky is bluer than it is red.
    EXPECT_GT(want[2], want[0]);
}

}  // namespace
}  // namespace streyes
