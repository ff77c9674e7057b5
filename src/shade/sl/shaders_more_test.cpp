// The other shipped shaders: volumes (fog, depthcue), displacement (bumpy), the forest's bark,
// leaf, ground and sky; and an imager shader.
#include <gtest/gtest.h>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

ProgramPtr shipped(const std::string& name) { return compileShaderFile(test::shaderPath(name)); }

TEST(SlShaders, FogAndDepthcue) {
    TestGrid g(3);
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{0, 0, float(i) * 2}; });
    g.setVarying(Global::I, 3, [](int i) { return Vec3f{0, 0, float(i) * 2}; });
    g.setVec(Global::Ci, {1, 1, 1});
    g.setVec(Global::Oi, {0.5f, 0.5f, 0.5f});
    ShaderInstance fog(shipped("fog"));
    fog.set("distance", BaseType::Float, {2});
    fog.set("background", BaseType::Color, {0, 0, 1});
    ShadingVM vm;
    vm.run(fog, g.grid);
    for (int i = 0; i < 3; ++i) {
        float d = 1 - std::exp(-float(i) * 2 / 2);
        EXPECT_NEAR(vm.result(Global::Ci).at(0, i), 1 - d, 1e-6f);
        EXPECT_NEAR(vm.result(Global::Ci).at(2, i), 1.0f, 1e-6f);
        EXPECT_NEAR(vm.result(Global::Oi).at(0, i), 0.5f * (1 - d) + d, 1e-6f);
    }
    ShaderInstance cue(shipped("depthcue"));
    g.grid.nearClip = 0;
    g.grid.farClip = 4;  // depth(P) = z / 4
    vm.run(cue, g.grid);
    EXPECT_NEAR(vm.result(Global::Ci).at(0, 1), 0.5f, 1e-6f);  // depth .5, background 0
    EXPECT_NEAR(vm.result(Global::Ci).at(0, 2), 0.0f, 1e-6f);  // depth 1
}

class ConstantTexture : public TextureSource {
  public:
    bool texture(const std::string&, const TextureOptions& o, const TextureQuery& q, float* const* out) override {
        for (int i = 0; i < q.n; ++i)
            for (int c = 0; c < o.channels; ++c) out[c][i] = 0.5f;
        return true;
    }
    bool environment(const std::string&, const TextureOptions&, const DirectionQuery&, float* const*) override { return false; }
    bool shadow(const std::string&, const TextureOptions&, const DirectionQuery&, float* const*) override { return false; }
};

TEST(SlShaders, BumpyDisplacesAlongTheNormal) {
    const int nu = 4, nv = 4;
    TestGrid g(nu, nv);
    g.setVarying(Global::P, 3, [&](int k) { return Vec3f{float(k % (nu + 1)), float(k / (nu + 1)), 10}; });
    g.setVec(Global::N, {0, 0, -2});
    ShaderInstance bumpy(shipped("bumpy"));
    bumpy.set("Km", BaseType::Float, {2});
    bumpy.setStrings("texturename", {"bumps.tx"});
    ConstantTexture tex;
    ShadingVM vm;
    vm.setTextureSource(&tex);
    vm.run(bumpy, g.grid);
    ValueRef P = vm.result(Global::P), N = vm.result(Global::N);
    for (int k = 0; k < g.n(); ++k) {
        EXPECT_FLOAT_EQ(P.at(2, k), 9.0f);  // 10 + 2 * .5 * (0, 0, -1)
        // The plane x-y still: calculatenormal = Du(P) x Dv(P) = (nu, 0, 0) x (0, nv, 0).
        EXPECT_NEAR(N.at(2, k), float(nu * nv), 1e-4f);
    }
}

TestGrid forestGrid() {
    const int nu = 16, nv = 16;
    TestGrid g(nu, nv);  // s = u, t = v
    g.setVarying(Global::P, 3, [&](int k) { return Vec3f{float(k % (nu + 1)) * 0.3f, 2, 5 + float(k / (nu + 1)) * 0.3f}; });
    g.setVec(Global::N, {0, 0, -1});
    g.setVec(Global::Cs, {1, 1, 1});
    g.grid.setSpace(Space::World, Matrix4());
    return g;
}

TEST(SlShaders, ForestShadersGiveColoursInRangeAndVary) {
    TestGrid g = forestGrid();
    ShaderInstance sun(shipped("distantlight")), amb(shipped("ambientlight"));
    sun.set("from", BaseType::Point, {0, 0, 0});
    sun.set("to", BaseType::Point, {0, 0, 1});
    amb.set("intensity", BaseType::Float, {0.2f});
    std::vector<LightRef> lights{{&sun, Matrix4()}, {&amb, Matrix4()}};
    for (const char* name : {"bark", "leaf", "ground", "sky"}) {
        SCOPED_TRACE(name);
        ShaderInstance inst(shipped(name));
        ShadingVM vm;
        vm.run(inst, g.grid, lights);
        ValueRef ci = vm.result(Global::Ci);
        float lo = 1e9f, hi = -1e9f;
        for (int i = 0; i < g.n(); ++i)
            for (int c = 0; c < 3; ++c) {
                EXPECT_GE(ci.at(c, i), 0.0f);
                EXPECT_LE(ci.at(c, i), 1.5f);
                lo = std::min(lo, ci.at(c, i));
                hi = std::max(hi, ci.at(c, i));
            }
        EXPECT_GT(hi - lo, 0.02f);  // a pattern, not a flat colour
        EXPECT_EQ(vm.stats().sanitised, 0u);
    }
}

TEST(SlShaders, LeafIsCutOutByOpacity) {
    TestGrid g = forestGrid();
    ShaderInstance leaf(shipped("leaf"));
    ShadingVM vm;
    vm.run(leaf, g.grid);
    ValueRef oi = vm.result(Global::Oi);
    const int w = 17;
    EXPECT_EQ(oi.at(0, 0), 0.0f);                 // a corner (s = 0, t = 0): no leaf
    EXPECT_EQ(oi.at(0, w - 1), 0.0f);             // s = 1, t = 0
    EXPECT_EQ(oi.at(0, 8 * w + 0), 0.0f);         // the side at mid-length
    EXPECT_EQ(oi.at(0, 8 * w + 8), 1.0f);         // the middle of the leaf
}

TEST(SlShaders, AnImagerShader) {
    ProgramPtr p = test::compile(R"(
        imager background(color background = color(0, 0, 1)) {
            Ci += (1 - alpha) * background;
            Oi = 1;
            alpha = 1;
        })");
    TestGrid g(2);
    g.setVec(Global::Ci, {0.5f, 0, 0});
    g.setVarying(Global::alpha, 1, [](int i) { return Vec3f{float(i), 0, 0}; });
    ShaderInstance inst(p);
    ShadingVM vm;
    vm.run(inst, g.grid);
    EXPECT_FLOAT_EQ(vm.result(Global::Ci).at(2, 0), 1.0f);
    EXPECT_FLOAT_EQ(vm.result(Global::Ci).at(2, 1), 0.0f);
    EXPECT_FLOAT_EQ(vm.result(Global::alpha).at(0, 0), 1.0f);
}

TEST(SlShaders, FunctionsWithIlluminanceAndVaryingParameters) {
    const char* src = R"(
        color mydiffuse(normal Nn) {
            color C = 0;
            illuminance(P, Nn, PI / 2) C += Cl * (normalize(L) . Nn);
            return C;
        }
        void accumulate(varying float x; output float total) { total += x; }
        surface s() {
            float t = 0;
            accumulate(1, t);
            accumulate(u, t);
            Ci = mydiffuse(normalize(N)) - diffuse(normalize(N)) + t;
        })";
    TestGrid g(3);
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{float(i), 0, 5}; });
    g.setVec(Global::N, {0.2f, 0.1f, -1});
    g.setVarying(Global::u, 1, [](int i) { return Vec3f{float(i) * 0.25f, 0, 0}; });
    ShaderInstance bulb(shipped("pointlight"));
    bulb.set("intensity", BaseType::Float, {7});
    std::vector<LightRef> lights{{&bulb, Matrix4::translate({1, 2, 0})}};
    ShaderInstance inst(test::compile(src));
    ShadingVM vm;
    vm.run(inst, g.grid, lights);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(vm.result(Global::Ci).at(0, i), 1 + float(i) * 0.25f, 1e-5f);
}

TEST(SlShaders, MatrixFunctions) {
    const char* src = R"(
        surface s(output point moved = 0; output float c = 0; output float d = 0; output point r = 0) {
            matrix m = 1;
            m = translate(m, vector(1, 2, 3));
            m = scale(m, point(2, 2, 2));
            moved = transform(m, point(1, 1, 1));
            setcomp(m, 0, 0, 5);
            c = comp(m, 0, 0);
            d = determinant(rotate(matrix 1, PI / 3, vector(0, 0, 1)));
            r = transform(rotate(matrix 1, PI / 2, vector(0, 0, 1)), point(1, 0, 0));
            Ci = 0;
        })";
    TestGrid g(1);
    ShaderInstance inst(test::compile(src));
    ShadingVM vm;
    vm.run(inst, g.grid);
    // RenderMan order: the transform made last applies first: scale, then translate.
    Vec3f moved = test::at3(vm.output("moved"), 0);
    EXPECT_NEAR(moved.x, 3, 1e-5f);
    EXPECT_NEAR(moved.y, 4, 1e-5f);
    EXPECT_NEAR(moved.z, 5, 1e-5f);
    EXPECT_FLOAT_EQ(vm.output("c").at(0, 0), 5);
    EXPECT_NEAR(vm.output("d").at(0, 0), 1, 1e-5f);
    Vec3f r = test::at3(vm.output("r"), 0);
    EXPECT_NEAR(std::fabs(r.y), 1, 1e-5f);  // a quarter turn about z takes x to +-y
    EXPECT_NEAR(r.x, 0, 1e-5f);
}

}  // namespace
}  // namespace streyes::sl
