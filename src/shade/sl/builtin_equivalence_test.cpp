// The shipped constant, matte, plastic and defaultsurface with ambientlight, distantlight and pointlight give
// the numbers of the renderer's built-in shading (src/shade/shading.cpp) when N = Ng: the
// built-in turns N towards the eye by N itself, RenderMan's faceforward by Ng.
#include <gtest/gtest.h>

#include <random>

#include "shade/vm/vm_test_util.h"
#include "shade/shading.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

TEST(SlShaders, StandardShadersReproduceTheBuiltInShading) {
    const int n = 300;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> d(-1, 1);
    std::vector<Vec3f> P(n), N(n), Cs(n);
    for (int i = 0; i < n; ++i) {
        P[size_t(i)] = {3 * d(rng), 3 * d(rng), 6 + 2 * d(rng)};
        N[size_t(i)] = {d(rng), d(rng), d(rng)};
        Cs[size_t(i)] = {0.5f + 0.5f * d(rng), 0.5f + 0.5f * d(rng), 0.5f + 0.5f * d(rng)};
    }
    TestGrid g(n);
    g.grid.set(Global::P, ValueRef::aos(P.data()));
    g.grid.set(Global::N, ValueRef::aos(N.data()));
    g.grid.set(Global::Ng, ValueRef::aos(N.data()));
    g.grid.set(Global::Cs, ValueRef::aos(Cs.data()));
    const Color Os{0.9f, 0.8f, 0.7f};
    g.grid.set(Global::Os, ValueRef::uniform(Os));

    // Lights, built-in and shader: ambient, distant (towards +x+z), point at (-2, 3, 1).
    const Vec3f toDistant = normalize(Vec3f{1, 0.5f, -1});  // from the surface towards the light
    const Vec3f bulb{-2, 3, 1};
    std::vector<CameraLight> builtin{
        {LightKind::Ambient, {0.1f, 0.2f, 0.3f}, {}, {}, -1},
        {LightKind::Distant, {0.9f, 0.8f, 0.7f}, {}, toDistant, -1},
        {LightKind::Point, {20, 18, 16}, bulb, {}, -1},
    };
    ShaderInstance amb(compileShaderFile(test::shaderPath("ambientlight")));
    amb.set("lightcolor", BaseType::Color, {0.1f, 0.2f, 0.3f});
    ShaderInstance sun(compileShaderFile(test::shaderPath("distantlight")));
    sun.set("lightcolor", BaseType::Color, {0.9f, 0.8f, 0.7f});
    sun.set("from", BaseType::Point, {toDistant.x, toDistant.y, toDistant.z});
    sun.set("to", BaseType::Point, {0, 0, 0});
    ShaderInstance pt(compileShaderFile(test::shaderPath("pointlight")));
    pt.set("intensity", BaseType::Float, {2});
    pt.set("lightcolor", BaseType::Color, {10, 9, 8});
    std::vector<LightRef> lights{{&amb, Matrix4()}, {&sun, Matrix4()}, {&pt, Matrix4::translate({-2, 3, 1})}};

    struct Case {
        const char* name;
        SurfaceKind kind;
    };
    for (Case c : {Case{"constant", SurfaceKind::Constant}, Case{"matte", SurfaceKind::Matte},
                   Case{"plastic", SurfaceKind::Plastic}, Case{"defaultsurface", SurfaceKind::Default}}) {
        SCOPED_TRACE(c.name);
        Material m;
        m.kind = c.kind;
        m.Os = Os;
        m.lights = {0, 1, 2};
        ShaderInstance inst(compileShaderFile(test::shaderPath(c.name)));
        if (c.kind == SurfaceKind::Matte) {
            m.Ka = 0.7f;
            m.Kd = 0.9f;
            inst.set("Ka", BaseType::Float, {0.7f});
            inst.set("Kd", BaseType::Float, {0.9f});
        }
        if (c.kind == SurfaceKind::Plastic) {  // the built-in's defaults are the shader's
            m.Ka = 1;
            m.Kd = 0.5f;
            m.Ks = 0.5f;
            m.roughness = 0.1f;
        }
        ShadingVM vm;
        vm.run(inst, g.grid, lights);
        ValueRef ci = vm.result(Global::Ci);
        float worst = 0;
        for (int i = 0; i < n; ++i) {
            Color want = shadePoint(m, Cs[size_t(i)], P[size_t(i)], N[size_t(i)], false, builtin);
            for (int k = 0; k < 3; ++k) {
                float diff = std::fabs(ci.at(k, i) - want[k]);
                worst = std::max(worst, diff / std::max(1.0f, std::fabs(want[k])));
            }
        }
        EXPECT_LT(worst, 2e-5f);
    }
}

}  // namespace
}  // namespace streyes::sl
