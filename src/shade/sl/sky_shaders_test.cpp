// The sun and sky shaders (shaders/preethamsky.sl, shaders/sunlight.sl) against Preetham, Shirley
// and Smits, "A Practical Analytic Model for Daylight" (1999), worked out here in double from the
// paper's formulas: the sky's zenith luminance and chromaticity, the Perez ratio away from the
// zenith, and the sun's colour through the appendix's Rayleigh and aerosol transmittances.
#include <gtest/gtest.h>

#include <cmath>

#include "preetham_reference.h"
#include "shade/vm/color_spaces.h"
#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

constexpr double kPi = 3.14159265358979323846;

using preetham_ref::preethamSky;
using preetham_ref::Sky;

// A direction at zenith angle theta and azimuth phi about +y (the zenith), phi from +z towards +x.
Vec3f direction(double theta, double phi) {
    return Vec3f{float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)), float(std::sin(theta) * std::cos(phi))};
}

double angleBetween(Vec3f a, Vec3f b) {
    const double c = (double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z) /
                     std::sqrt((double(a.x) * a.x + double(a.y) * a.y + double(a.z) * a.z) *
                               (double(b.x) * b.x + double(b.y) * b.y + double(b.z) * b.z));
    return std::acos(std::max(-1.0, std::min(1.0, c)));
}

// The sky shader seen along `views` (the eye at the origin), under a sun along `sun`: xyY per view.
std::vector<Sky> shadeSky(double turbidity, Vec3f sun, const std::vector<Vec3f>& views) {
    TestGrid g(int(views.size()));
    g.setVarying(Global::P, 3, [&](int i) { return views[size_t(i)] * 10.0f; });
    g.setVarying(Global::I, 3, [&](int i) { return views[size_t(i)] * 10.0f; });
    g.setVarying(Global::N, 3, [&](int i) { return views[size_t(i)] * -1.0f; });
    g.setVec(Global::Cs, {1, 1, 1});
    g.setVec(Global::Os, {1, 1, 1});
    ShaderInstance sky(compileShaderFile(test::shaderPath("preethamsky")));
    sky.set("turbidity", BaseType::Float, {float(turbidity)});
    sky.set("intensity", BaseType::Float, {1});
    sky.set("from", BaseType::Point, {sun.x, sun.y, sun.z});
    sky.set("to", BaseType::Point, {0, 0, 0});
    ShadingVM vm;
    vm.run(sky, g.grid, {});
    ValueRef ci = vm.result(Global::Ci);
    std::vector<Sky> out;
    for (int i = 0; i < g.n(); ++i) {
        const float rgb[3] = {ci.at(0, i), ci.at(1, i), ci.at(2, i)};
        float xyY[3];
        fromRgb(ColorSpace::XYY, rgb, xyY);
        out.push_back({xyY[0], xyY[1], xyY[2]});
    }
    return out;
}

void expectSky(const Sky& got, const Sky& want, const std::string& where) {
    SCOPED_TRACE(where);
    ASSERT_TRUE(std::isfinite(got.Y) && std::isfinite(got.x) && std::isfinite(got.y));
    EXPECT_NEAR(got.Y, want.Y, 2e-4 * want.Y);
    EXPECT_NEAR(got.x, want.x, 2e-4);
    EXPECT_NEAR(got.y, want.y, 2e-4);
}

// Looking straight up, the sky is the paper's zenith: Y_z(T, thetaS), x_z, y_z (the Perez ratio is
// F(0, thetaS) / F(0, thetaS) = 1 there). Elsewhere it is the zenith's times F(theta, gamma) / F(0,
// thetaS), which the views below sample: towards the sun, away from it, across, near the horizon.
TEST(SkyShaders, PreethamSkyIsThePapersZenithAndPerezRatio) {
    for (double T : {2.0, 3.0, 6.0}) {
        for (double thetaSDeg : {20.0, 50.0, 75.0}) {
            const double thetaS = thetaSDeg * kPi / 180;
            const Vec3f sun = direction(thetaS, 0.4);
            const std::vector<Vec3f> views = {
                direction(0, 0),           direction(0.6, 0.4),       direction(0.6, 0.4 + kPi),
                direction(1.2, 0.4 + 1.5), direction(1.5, 2.5),       direction(thetaS + 0.1, 0.4)};
            const std::vector<Sky> got = shadeSky(T, sun, views);
            ASSERT_EQ(got.size(), views.size());
            for (size_t i = 0; i < views.size(); ++i) {
                const double theta = angleBetween(views[i], Vec3f{0, 1, 0});
                const Sky want = preethamSky(T, thetaS, theta, angleBetween(views[i], sun));
                expectSky(got[i], want, "T " + std::to_string(T) + ", thetaS " + std::to_string(thetaSDeg) + ", view " +
                                            std::to_string(i));
            }
            // The zenith's value is the paper's Y_z itself (a closed form of T and thetaS alone).
            const double chi = (4.0 / 9 - T / 120) * (kPi - 2 * thetaS);
            EXPECT_NEAR(got[0].Y, (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192, 2e-4 * got[0].Y);
        }
    }
}

// Below the horizon the sky is the horizon's (cos theta clamped at 0.001), and it is brighter towards
// the sun than away from it at the same height (the circumsolar peak).
TEST(SkyShaders, PreethamSkyBelowTheHorizonAndAroundTheSun) {
    const double thetaS = 60 * kPi / 180;
    const Vec3f sun = direction(thetaS, 0);
    const std::vector<Sky> got = shadeSky(3, sun, {direction(kPi / 2 + 0.3, 1.0), direction(thetaS, 0.05),
                                                   direction(thetaS, kPi)});
    const Sky horizon = preethamSky(3, thetaS, std::acos(0.001), angleBetween(direction(kPi / 2 + 0.3, 1.0), sun));
    expectSky(got[0], horizon, "below the horizon");
    EXPECT_GT(got[1].Y, 3 * got[2].Y);
}

// The sun light's colour: Cl = intensity * tau_R(lambda) tau_a(lambda) at lambda = 0.65, 0.57 and
// 0.475 micrometres, through the relative optical mass of Kasten's formula the paper uses.
Vec3f sunColor(double T, double thetaS) {
    const double c = std::cos(thetaS), deg = thetaS * 180 / kPi;
    const double m = 1 / (c + 0.15 * std::pow(93.885 - deg, -1.253));
    const double beta = 0.04608 * T - 0.04586;
    auto tau = [&](double lambda) {
        return std::exp(-0.008735 * std::pow(lambda, -4.08) * m) * std::exp(-beta * std::pow(lambda, -1.3) * m);
    };
    return {float(tau(0.65)), float(tau(0.57)), float(tau(0.475))};
}

// What the sun light brings a surface facing it (the sum of Cl over its illuminance).
Vec3f shadeSun(double T, double thetaS, float intensity) {
    TestGrid g(1);
    const Vec3f s = direction(thetaS, 1.1);
    g.setVarying(Global::P, 3, [](int) { return Vec3f{0, 0, 5}; });
    g.setVarying(Global::N, 3, [&](int) { return s; });
    ShaderInstance surface(test::compile("surface sumlight() { Ci = 0; illuminance(P, N, PI / 2) Ci += Cl; }"));
    ShaderInstance sun(compileShaderFile(test::shaderPath("sunlight")));
    sun.set("turbidity", BaseType::Float, {float(T)});
    sun.set("intensity", BaseType::Float, {intensity});
    sun.set("from", BaseType::Point, {s.x, s.y, s.z});
    sun.set("to", BaseType::Point, {0, 0, 0});
    std::vector<LightRef> lights{{&sun, Matrix4()}};
    ShadingVM vm;
    vm.run(surface, g.grid, lights);
    return test::at3(vm.result(Global::Ci), 0);
}

TEST(SkyShaders, SunlightColourFollowsThePapersTransmittance) {
    for (double T : {2.0, 4.0, 8.0})
        for (double deg : {0.0, 30.0, 60.0, 80.0, 88.0}) {
            SCOPED_TRACE("T " + std::to_string(T) + ", thetaS " + std::to_string(deg));
            const Vec3f got = shadeSun(T, deg * kPi / 180, 2.5f), want = sunColor(T, deg * kPi / 180) * 2.5f;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 2e-5f + 2e-4f * want[c]) << c;
        }
    // The ordering: the sun reddens and dims towards the horizon, and with turbidity.
    const Vec3f zenith = shadeSun(3, 0, 1), low = shadeSun(3, 80 * kPi / 180, 1), hazy = shadeSun(8, 0, 1);
    EXPECT_GT(zenith.z, low.z);
    EXPECT_GT(zenith.x, low.x);
    EXPECT_GT(low.x / low.z, 1.5f * zenith.x / zenith.z);
    EXPECT_GT(zenith.x, zenith.y);
    EXPECT_GT(zenith.y, zenith.z);
    EXPECT_GT(zenith.z, hazy.z);
    EXPECT_LT(zenith.x, 1.0f);
    // A sun below the horizon lights nothing.
    const Vec3f night = shadeSun(3, 95 * kPi / 180, 1);
    EXPECT_EQ(night.x, 0.0f);
    EXPECT_EQ(night.y, 0.0f);
    EXPECT_EQ(night.z, 0.0f);
}

}  // namespace
}  // namespace streyes::sl
