// The shipped shaders (shaders/*.sl): every one compiles; the standard ones give the closed
// forms of RI Spec 3.2 (Lambert, the specular peak, the spotlight's cone).
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

TEST(SlShaders, EveryShippedShaderCompiles) {
    namespace fs = std::filesystem;
    int count = 0;
    for (const auto& e : fs::directory_iterator(std::string(STREYES_SOURCE_DIR) + "/shaders")) {
        if (e.path().extension() != ".sl") continue;
        SCOPED_TRACE(e.path().string());
        ProgramPtr p;
        EXPECT_NO_THROW(p = compileShaderFile(e.path().string()));
        if (p) {
            EXPECT_EQ(p->name, e.path().stem().string());
        }
        ++count;
    }
    EXPECT_GE(count, 18);
}

}  // namespace
}  // namespace streyes::sl

namespace streyes::sl {
namespace {

using test::TestGrid;

ProgramPtr shipped(const std::string& name) { return compileShaderFile(test::shaderPath(name)); }

constexpr float kPi = 3.14159265358979f;

// RenderMan's faceforward(N, I) with Ng = N.
Vec3f faceForward(Vec3f n, Vec3f i) { return dot(n, i) < 0 ? n : n * -1.0f; }

// n points on the plane z = 5 seen from the eye at the origin, normals tilted by angle(i)
// about the y axis (towards the eye at 0).
TestGrid tiltedNormals(int n, float (*angle)(int, int)) {
    TestGrid g(n);
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{0.01f * float(i), 0, 5}; });
    g.setVarying(Global::N, 3, [&](int i) {
        float a = angle(i, n);
        return Vec3f{std::sin(a), 0, -std::cos(a)};
    });
    g.setVec(Global::Cs, {0.8f, 0.6f, 0.4f});
    return g;
}

TEST(SlShaders, MatteUnderDistantLightIsLambert) {
    TestGrid g = tiltedNormals(41, [](int i, int n) { return (float(i) / float(n - 1) - 0.5f) * 3.0f; });
    ShaderInstance matte(shipped("matte"));
    ShaderInstance sun(shipped("distantlight"));
    sun.set("intensity", BaseType::Float, {1.5f});
    sun.set("from", BaseType::Point, {0, 0, 0});
    sun.set("to", BaseType::Point, {0, 0, 1});  // light travels +z: it comes from the eye's side
    std::vector<LightRef> lights{{&sun, Matrix4()}};
    ShadingVM vm;
    vm.run(matte, g.grid, lights);
    ValueRef ci = vm.result(Global::Ci);
    int lit = 0;
    for (int i = 0; i < g.n(); ++i) {
        Vec3f P = test::at3(g.grid.globals[size_t(Global::P)], i), N = test::at3(g.grid.globals[size_t(Global::N)], i);
        Vec3f Nf = faceForward(normalize(N), P);  // I = P: the eye at the origin; Ng = N
        float lambert = 1.5f * std::max(0.0f, dot(Nf, Vec3f{0, 0, -1}));
        EXPECT_NEAR(ci.at(0, i), 0.8f * lambert, 1e-5f) << i;
        EXPECT_NEAR(ci.at(1, i), 0.6f * lambert, 1e-5f) << i;
        EXPECT_NEAR(ci.at(2, i), 0.4f * lambert, 1e-5f) << i;
        lit += lambert > 0.1f;
    }
    EXPECT_GT(lit, 30);
}

TEST(SlShaders, MatteWithAmbientLight) {
    TestGrid g = tiltedNormals(5, [](int, int) { return 0.3f; });
    ShaderInstance matte(shipped("matte"));
    matte.set("Ka", BaseType::Float, {0.5f});
    ShaderInstance amb(shipped("ambientlight"));
    amb.set("lightcolor", BaseType::Color, {0.2f, 0.4f, 1.0f});
    std::vector<LightRef> lights{{&amb, Matrix4()}};
    ShadingVM vm;
    vm.run(matte, g.grid, lights);
    ValueRef ci = vm.result(Global::Ci);
    EXPECT_NEAR(ci.at(0, 2), 0.8f * 0.5f * 0.2f, 1e-6f);
    EXPECT_NEAR(ci.at(2, 2), 0.4f * 0.5f * 1.0f, 1e-6f);
}

// Plastic's highlight peaks where N is the half vector of L and V, with value Ks (N.H = 1), and
// falls off as (N.H)^(k / roughness): k = 8 is PRMan's highlight (the default), k = 1 the RI
// Spec's formula (Option "shading" "specular" "rispec"). Its width at half the peak is
// 2 acos(0.5^(roughness / k)) in the angle of N: 15.1 degrees at roughness 0.1 for PRMan's,
// 42.2 for the spec's.
void plasticHighlight(float k) {
    SCOPED_TRACE("exponent " + std::to_string(k) + " / roughness");
    const int n = 721;  // N every quarter degree
    TestGrid g(n);
    auto angleAt = [&](int i) { return (float(i) / float(n - 1) - 0.5f) * kPi; };  // -90 .. 90 degrees about y
    auto normalAt = [&](int i) { return Vec3f{std::sin(angleAt(i)), 0, -std::cos(angleAt(i))}; };
    g.setVarying(Global::P, 3, [](int) { return Vec3f{0, 0, 5}; });
    g.setVarying(Global::N, 3, normalAt);
    g.setVec(Global::Cs, {1, 1, 1});
    ShaderInstance plastic(shipped("plastic"));
    ShaderInstance sun(shipped("distantlight"));
    // Light towards the surface from the upper right: L (towards the light) = normalize(1, 0, -1).
    sun.set("from", BaseType::Point, {1, 0, -1});
    sun.set("to", BaseType::Point, {0, 0, 0});
    std::vector<LightRef> lights{{&sun, Matrix4()}};
    ShadingVM vm;
    if (k != 8) vm.setSpecularExponent(k);
    vm.run(plastic, g.grid, lights);
    ValueRef ci = vm.result(Global::Ci);
    const Vec3f L = normalize(Vec3f{1, 0, -1}), V{0, 0, -1}, H = normalize(L + V);
    const float roughness = 0.1f;
    int best = -1;
    float bestSpec = -1, lo = 1e9f, hi = -1e9f;
    for (int i = 1; i < n - 1; ++i) {  // not the two normals perpendicular to the view
        Vec3f N = normalAt(i);
        float ndl = dot(N, L);
        if (std::fabs(ndl) < 1e-4f) continue;  // the cone's edge: either side is right
        float spec = ndl > 0 ? std::pow(std::max(0.0f, dot(N, H)), k / roughness) : 0.0f;
        EXPECT_NEAR(ci.at(0, i), 0.5f * std::max(0.0f, ndl) + 0.5f * spec, 2e-5f) << i;
        float measured = ci.at(0, i) - 0.5f * std::max(0.0f, ndl);
        if (measured > bestSpec) {
            bestSpec = measured;
            best = i;
        }
        if (measured >= 0.25f) {  // at least half the peak (Ks / 2)
            lo = std::min(lo, angleAt(i));
            hi = std::max(hi, angleAt(i));
        }
    }
    // H is 22.5 degrees from -z towards +x, and the peak is Ks * 1.
    EXPECT_NEAR(angleAt(best) * 180.0f / kPi, 22.5f, 0.25f);
    EXPECT_NEAR(bestSpec, 0.5f, 1e-4f);
    const float halfWidth = std::acos(std::pow(0.5f, roughness / k));
    const float step = kPi / float(n - 1);
    EXPECT_NEAR(hi - lo, 2 * halfWidth, 2 * step);
    EXPECT_NEAR(0.5f * (hi + lo), kPi / 8, step);
}

TEST(SlShaders, PlasticHighlightIsPRMansAndTheSpecsOnRequest) {
    plasticHighlight(8);
    plasticHighlight(1);
}

// RI Spec 3.2's spotlight: cos^beamdistribution / d^2, times smoothstep between the cosines of
// coneangle and coneangle - conedeltaangle; nothing outside the cone.
TEST(SlShaders, SpotlightConeAndFalloff) {
    const int n = 121;
    TestGrid g(n);
    // Points on the plane z = 4 along x, seen by a spot at the origin looking down +z.
    auto x = [](int i) { return float(i) * 0.025f; };  // 0 .. 3: 0 .. 36.9 degrees
    g.setVarying(Global::P, 3, [&](int i) { return Vec3f{x(i), 0, 4}; });
    g.setVec(Global::N, {0, 0, -1});
    g.setVec(Global::Cs, {1, 1, 1});
    ShaderInstance matte(shipped("matte"));
    ShaderInstance spot(shipped("spotlight"));
    spot.set("intensity", BaseType::Float, {10});
    std::vector<LightRef> lights{{&spot, Matrix4()}};
    ShadingVM vm;
    vm.run(matte, g.grid, lights);
    ValueRef ci = vm.result(Global::Ci);
    const float cosOut = std::cos(30 * kPi / 180), cosIn = std::cos(25 * kPi / 180);
    int inside = 0, between = 0, outside = 0;
    for (int i = 0; i < n; ++i) {
        Vec3f p{x(i), 0, 4};
        float d2 = dot(p, p), c = p.z / std::sqrt(d2);
        float t = std::min(1.0f, std::max(0.0f, (c - cosOut) / (cosIn - cosOut)));
        float smooth = t * t * (3 - 2 * t);
        float expected = c >= cosOut ? 10 * c * c / d2 * smooth * c : 0.0f;  // times N.L = cos
        EXPECT_NEAR(ci.at(0, i), expected, 1e-5f) << "x = " << x(i);
        if (c >= cosIn) ++inside;
        else if (c >= cosOut) ++between;
        else ++outside;
    }
    EXPECT_GT(inside, 10);
    EXPECT_GT(between, 5);
    EXPECT_GT(outside, 5);
}

TEST(SlShaders, PointLightFallsOffWithDistanceSquared) {
    TestGrid g(3);
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{0, 0, float(i + 1)}; });
    g.setVec(Global::N, {0, 0, -1});
    g.setVec(Global::Cs, {1, 1, 1});
    ShaderInstance matte(shipped("matte"));
    ShaderInstance bulb(shipped("pointlight"));
    bulb.set("intensity", BaseType::Float, {4});
    Matrix4 lightSpace = Matrix4::translate({0, 0, -1});  // the light 1 unit behind the eye
    std::vector<LightRef> lights{{&bulb, lightSpace}};
    ShadingVM vm;
    vm.run(matte, g.grid, lights);
    ValueRef ci = vm.result(Global::Ci);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(ci.at(0, i), 4.0f / float((i + 2) * (i + 2)), 1e-6f);
}

TEST(SlShaders, DescribePrintsTypeNameAndParameters) {
    std::ostringstream out, err;
    EXPECT_EQ(describeShader(test::shaderPath("plastic"), out, err), 0);
    const std::string s = out.str();
    EXPECT_NE(s.find("surface \"plastic\""), std::string::npos) << s;
    EXPECT_NE(s.find("\"Kd\" \"uniform float\""), std::string::npos) << s;
    EXPECT_NE(s.find("Default value: 0.5"), std::string::npos) << s;
    EXPECT_NE(s.find("\"specularcolor\" \"uniform color\""), std::string::npos) << s;
    std::ostringstream out2, err2;
    EXPECT_EQ(describeShader(test::shaderPath("spotlight"), out2, err2), 0);
    EXPECT_NE(out2.str().find("Default value: 0.523599"), std::string::npos) << out2.str();  // radians(30)
    std::ostringstream out3, err3;
    EXPECT_EQ(describeShader("/nonexistent/x.sl", out3, err3), 2);
    EXPECT_NE(err3.str().find("cannot read"), std::string::npos);
}

}  // namespace
}  // namespace streyes::sl
