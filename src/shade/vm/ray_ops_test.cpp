// The ray-traced calls as the interpreter makes them (a RaySource double records what it is
// asked), and fresnel() and refract() against the Fresnel equations and Snell's law.
#include <gtest/gtest.h>

#include <cmath>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

// Answers occlusion with P.x / 10, the rest with D; keeps the last query's options.
class RecordingRays final : public RaySource {
  public:
    RayOptions last;
    double time = -1;
    int calls = 0, activeSeen = 0;
    void occlusion(const RayOptions& o, const RayQuery& q, float* const* out) override {
        note(o, q);
        for (int i = 0; i < q.n; ++i) out[0][i] = q.P[0][i] / 10;
    }
    void indirectdiffuse(const RayOptions& o, const RayQuery& q, float* const* out) override { copyD(o, q, out); }
    void trace(const RayOptions& o, const RayQuery& q, float* const* out) override { copyD(o, q, out); }
    void transmission(const RayOptions& o, const RayQuery& q, float* const* out) override { copyD(o, q, out); }

  private:
    void note(const RayOptions& o, const RayQuery& q) {
        last = o;
        time = q.time;
        ++calls;
        activeSeen = 0;
        for (int i = 0; i < q.n; ++i) activeSeen += !q.active || q.active[i];
    }
    void copyD(const RayOptions& o, const RayQuery& q, float* const* out) {
        note(o, q);
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < q.n; ++i) out[c][i] = q.D[c][i];
    }
};

TestGrid lineOfPoints() {
    TestGrid g(3, 0);  // 4 points
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{float(i), 0, 0}; });
    g.setVarying(Global::N, 3, [](int) { return Vec3f{0, 0, 1}; });
    g.grid.time = 12.25;
    return g;
}

TEST(VmRays, CallsReachTheSourceWithTheirOptionsAndTime) {
    TestGrid g = lineOfPoints();
    ShaderInstance s(test::compile(
        "surface t() {\n"
        "  float o = occlusion(P, N, 8, \"maxdist\", 5, \"coneangle\", 0.5, \"bias\", 0.25, \"adaptive\", 1);\n"
        "  Ci = color(o, 0, 0);\n}\n"));
    RecordingRays rays;
    ShadingVM vm;
    vm.setRaySource(&rays);
    vm.run(s, g.grid);
    EXPECT_EQ(rays.calls, 1);
    EXPECT_EQ(rays.time, 12.25);
    EXPECT_EQ(rays.last.samples, 8);
    EXPECT_EQ(rays.last.maxdist, 5);
    EXPECT_EQ(rays.last.coneangle, 0.5f);
    EXPECT_EQ(rays.last.bias, 0.25f);
    const ValueRef ci = vm.result(Global::Ci);
    for (int i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(ci.at(0, i), float(i) / 10);
}

TEST(VmRays, VaryingConditionsAskOnlyForThePointsThatRun) {
    TestGrid g = lineOfPoints();
    ShaderInstance s(test::compile(
        "surface t() {\n  Ci = 7;\n  if (xcomp(P) > 1.5) Ci = trace(P, vector(1, 2, 3));\n}\n"));
    RecordingRays rays;
    ShadingVM vm;
    vm.setRaySource(&rays);
    vm.run(s, g.grid);
    EXPECT_EQ(rays.activeSeen, 2);
    const ValueRef ci = vm.result(Global::Ci);
    EXPECT_EQ(test::at3(ci, 0), (Vec3f{7, 7, 7}));
    EXPECT_EQ(test::at3(ci, 3), (Vec3f{1, 2, 3}));
}

TEST(VmRays, WithoutASourceTheyGiveWhatNothingHitGives) {
    TestGrid g = lineOfPoints();
    ShaderInstance s(test::compile(
        "surface t() {\n  Ci = occlusion(P, N, 4) + indirectdiffuse(P, N, 4) + trace(P, N)\n"
        "       + environment(\"raytrace\", N) + 10 * transmission(P, P + N);\n}\n"));
    ShadingVM vm;
    vm.run(s, g.grid);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(test::at3(vm.result(Global::Ci), i), (Vec3f{10, 10, 10}));
    EXPECT_EQ(vm.stats().raysMissing, 5u);
}

// Aqsis's map form reads the map through the texture source (none here: 0, counted as a texture
// error, no ray); the map name "raytrace" is the traced form.
TEST(VmRays, AqsisMapFormAndEnvironmentRaytrace) {
    TestGrid g = lineOfPoints();
    ShaderInstance s(test::compile(
        "surface t() {\n  float o = occlusion(\"occlmap.sm\", P, N, 0, \"samples\", 64, \"blur\", 0.1);\n"
        "  float r = occlusion(\"raytrace\", P, N, 0, \"samples\", 64);\n"
        "  Ci = color(o + r, 0, 0) + color environment(\"raytrace\", vector(0, 5, 0));\n}\n"));
    RecordingRays rays;
    ShadingVM vm;
    vm.setRaySource(&rays);
    vm.run(s, g.grid);
    EXPECT_EQ(rays.calls, 2);
    EXPECT_EQ(vm.stats().textureErrors, 1u);
    const ValueRef ci = vm.result(Global::Ci);
    EXPECT_EQ(test::at3(ci, 2), (Vec3f{0.2f, 5, 0}));
}

TEST(VmRays, WrongArgumentsAreCompileErrorsAtTheirColumn) {
    EXPECT_NE(test::compileError("surface t() { Ci = trace(P, Cs); }").find("test.sl:1:29"), std::string::npos);
    EXPECT_NE(test::compileError("surface t() { Ci = occlusion(P); }").find("occlusion takes"), std::string::npos);
    EXPECT_NE(test::compileError("surface t() { Ci = occlusion(P, N, 4, \"maxdist\"); }").find("has no value"),
              std::string::npos);
    EXPECT_NE(test::compileError("surface t() { string s = \"bias\"; Ci = occlusion(P, N, 4, s, 1); }")
                  .find("string literal"),
              std::string::npos);
    EXPECT_NE(test::compileError("surface t() { Ci = transmission(P, P, 3); }").find("option"), std::string::npos);
    EXPECT_EQ(test::compileError("surface t() { Ci = indirectdiffuse(P, N, 4, \"environmentmap\", \"sky.tx\"); }"), "");
}

// The output options: indirectdiffuse's "occlusion" takes a float variable, occlusion's
// "environmentcolor" a color variable; neither is the other's.
TEST(VmRays, OutputOptionsTakeAVariableOfTheirType) {
    EXPECT_EQ(test::compileError("surface t() { float o; Ci = indirectdiffuse(P, N, 4, \"occlusion\", o); }"), "");
    EXPECT_EQ(test::compileError("surface t() { color e; Ci = occlusion(P, N, 4, \"environmentcolor\", e); }"), "");
    EXPECT_NE(test::compileError("surface t() { Ci = indirectdiffuse(P, N, 4, \"occlusion\", 0.5); }").find("must be a variable"),
              std::string::npos);
    EXPECT_NE(test::compileError("surface t() { color o; Ci = indirectdiffuse(P, N, 4, \"occlusion\", o); }").find("needs a float"),
              std::string::npos);
    EXPECT_NE(test::compileError("surface t() { float e; Ci = occlusion(P, N, 4, \"environmentcolor\", e); }").find("needs a color"),
              std::string::npos);
    EXPECT_NE(test::compileError("surface t() { float o; Ci = occlusion(P, N, 4, \"occlusion\", o); }").find("unknown"),
              std::string::npos);
}

// Without a ray source (nothing traced) the "occlusion" output is 0, as the result is black: the
// variable's own value (-1) does not survive the call.
TEST(VmRays, TheOcclusionOutputIsWrittenWithoutASource) {
    TestGrid g(4, 0);
    ShaderInstance s(test::compile("surface t() { float o = -1; color c = indirectdiffuse(P, N, 4, \"occlusion\", o); Ci = color(o, comp(c, 0), 0); }"));
    ShadingVM vm;
    vm.run(s, g.grid, {});
    const ValueRef ci = vm.result(Global::Ci);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(test::at3(ci, i), (Vec3f{0, 0, 0})) << i;
}

// A light's Ns is the surface's normal turned to face the eye (Aqsis's occlusion example lights a
// floor whose N points away from the camera through it).
TEST(VmRays, LightsSeeNsFacingTheEye) {
    TestGrid g(1, 0);
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{float(i), 0, 5}; });
    g.setVarying(Global::N, 3, [](int i) { return i == 0 ? Vec3f{0, 0, 1} : Vec3f{0, 0, -1}; });
    g.setVarying(Global::I, 3, [](int i) { return Vec3f{float(i), 0, 5}; });
    ShaderInstance light(test::compile(
        "light l() { illuminate(point(0, 0, 0)) { Cl = color(xcomp(Ns), ycomp(Ns), zcomp(Ns)); } }"));
    ShaderInstance surface(test::compile("surface s() { Ci = 0; illuminance(P) { Ci += Cl; } }"));
    ShadingVM vm;
    vm.run(surface, g.grid, {LightRef(&light, Matrix4())});
    const ValueRef ci = vm.result(Global::Ci);
    EXPECT_EQ(test::at3(ci, 0), (Vec3f{0, 0, -1}));  // N faced away from the eye: turned
    EXPECT_EQ(test::at3(ci, 1), (Vec3f{0, 0, -1}));  // N faced the eye already
}

// The Fresnel equations for unpolarised light going from index 1 into index 1/eta (eta = n1/n2,
// as the RI Spec's fresnel takes it): the mean of the s and p reflectances.
double fresnelReflectance(double cosI, double eta) {
    const double sin2T = eta * eta * (1 - cosI * cosI);
    if (sin2T >= 1) return 1;
    const double cosT = std::sqrt(1 - sin2T);
    const double rs = (eta * cosI - cosT) / (eta * cosI + cosT);
    const double rp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

TEST(VmRays, FresnelAndRefractFollowTheFresnelEquationsAndSnellsLaw) {
    // I comes down at angle theta_i to N = +z, in the x-z plane.
    const int n = 89;
    TestGrid g(n);
    g.setVarying(Global::I, 3, [](int i) {
        const float a = float(i) * 3.14159265f / 180;
        return Vec3f{std::sin(a), 0, -std::cos(a)};
    });
    g.setVarying(Global::N, 3, [](int) { return Vec3f{0, 0, 1}; });
    for (float eta : {1 / 1.5f, 1.5f}) {
        SCOPED_TRACE(eta);
        ShaderInstance s(test::compile(
            "surface t(float eta = 1; output varying float kr = 0, kt = 0;\n"
            "          output varying vector R = 0, T = 0, Rf = 0) {\n"
            "  fresnel(I, N, eta, kr, kt, R, T);\n  Rf = refract(I, N, eta);\n}\n"));
        s.set("eta", SlType(BaseType::Float), {eta});
        ShadingVM vm;
        vm.run(s, g.grid);
        const ValueRef kro = vm.output("kr"), kto = vm.output("kt"), t = vm.output("T"), r = vm.output("Rf");
        ASSERT_TRUE(kro.valid() && kto.valid() && t.valid() && r.valid());
        for (int i = 0; i < n; ++i) {
            const double a = double(i) * M_PI / 180;
            const double kr = fresnelReflectance(std::cos(a), eta);
            EXPECT_NEAR(kro.at(0, i), kr, 2e-5) << i << " degrees";
            EXPECT_NEAR(kto.at(0, i), 1 - kr, 2e-5) << i << " degrees";
            // Snell: sin theta_t = eta sin theta_i, going on down; none past the critical angle.
            const double sinT = eta * std::sin(a);
            const Vec3f want = sinT >= 1 ? Vec3f{0, 0, 0} : Vec3f{float(sinT), 0, -float(std::sqrt(1 - sinT * sinT))};
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(r.at(c, i), want[c], 2e-6) << i << " degrees";
                EXPECT_NEAR(t.at(c, i), want[c], 2e-6) << i << " degrees";  // fresnel's T is refract's
            }
        }
    }
}

}  // namespace
}  // namespace streyes::sl
