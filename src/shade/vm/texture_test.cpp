// texture(), environment() and shadow() through a test double of TextureSource: the lookup
// asks for what the shader said, where it said, and returns what the source gives.
#include <gtest/gtest.h>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

// A texture whose channel c at (s, t) is c * 100 + s + 10 t; environment maps give the
// direction's x; shadows are 1 where the ray towards the light crosses x = 0.
class FakeTextures : public TextureSource {
  public:
    struct Call {
        std::string name;
        TextureOptions options;
        std::vector<float> s, t, dsdu, dtdv;
        std::vector<float> R0, from0;
        int active = 0;
    };
    std::vector<Call> calls;

    bool texture(const std::string& name, const TextureOptions& o, const TextureQuery& q, float* const* out) override {
        if (name == "missing.tx") return false;
        Call c{name, o, {}, {}, {}, {}, {}, {}, 0};
        for (int i = 0; i < q.n; ++i) {
            if (q.active && !q.active[i]) continue;
            ++c.active;
            c.s.push_back(q.s[i]);
            c.t.push_back(q.t[i]);
            c.dsdu.push_back(q.dsdu[i]);
            c.dtdv.push_back(q.dtdv[i]);
            for (int ch = 0; ch < o.channels; ++ch) out[ch][i] = float(o.firstChannel + ch) * 100 + q.s[i] + 10 * q.t[i];
        }
        calls.push_back(c);
        return true;
    }
    bool environment(const std::string& name, const TextureOptions& o, const DirectionQuery& q, float* const* out) override {
        Call c{name, o, {}, {}, {}, {}, {}, {}, 0};
        for (int i = 0; i < q.n; ++i) {
            c.R0.push_back(q.R[0][i]);
            for (int ch = 0; ch < o.channels; ++ch) out[ch][i] = q.R[0][i];
        }
        calls.push_back(c);
        return true;
    }
    bool shadow(const std::string& name, const TextureOptions& o, const DirectionQuery& q, float* const* out) override {
        Call c{name, o, {}, {}, {}, {}, {}, {}, 0};
        for (int i = 0; i < q.n; ++i) {
            if (q.lightFrom[0]) c.from0.push_back(q.lightFrom[0][i]);
            const float x0 = q.R[0][i], x1 = q.lightFrom[0] ? q.lightFrom[0][i] : x0;
            out[0][i] = (x0 < 0) != (x1 < 0) ? 1.0f : 0.0f;  // a wall at x = 0
        }
        calls.push_back(c);
        return true;
    }
};

TEST(VmTexture, LookupsAtTheRightCoordinatesWithOptions) {
    const int nu = 4, nv = 2;
    TestGrid g(nu, nv);  // s = u, t = v by default
    const char* src = R"(
        surface s(output varying float a = 0; output varying color b = 0; output varying float c = 0;
                  output varying float d = 0; output varying float missing = 0) {
            a = texture("map.tx", s * 2, t);
            b = color texture("map.tx"[1], "blur", .25, "width", 2, "filter", "gaussian");
            c = texture("map.tx", 0, 0, 1, 0, 0, 1, 1, 1);
            if (s > .5) d = texture("map.tx");
            missing = texture("missing.tx", "fill", .75);
            Ci = 0;
        })";
    ShaderInstance inst(test::compile(src));
    FakeTextures tex;
    ShadingVM vm;
    vm.setTextureSource(&tex);
    vm.run(inst, g.grid);
    ASSERT_EQ(tex.calls.size(), 4u);  // the missing map is refused, not recorded
    ValueRef a = vm.output("a"), b = vm.output("b"), c = vm.output("c"), d = vm.output("d");
    for (int k = 0; k < g.n(); ++k) {
        float s = float(k % (nu + 1)) / nu, t = float(k / (nu + 1)) / nv;
        EXPECT_FLOAT_EQ(a.at(0, k), 2 * s + 10 * t);
        for (int ch = 0; ch < 3; ++ch) EXPECT_FLOAT_EQ(b.at(ch, k), float(1 + ch) * 100 + s + 10 * t);
        EXPECT_FLOAT_EQ(c.at(0, k), 0.5f + 10 * 0.5f);  // the corners' centre
        EXPECT_FLOAT_EQ(d.at(0, k), s > .5f ? s + 10 * t : 0.0f);
        EXPECT_FLOAT_EQ(vm.output("missing").at(0, k), 0.75f);
    }
    // The footprint: s * 2 changes by 2 du across a micropolygon, t by dv.
    EXPECT_FLOAT_EQ(tex.calls[0].dsdu[1], 2.0f / nu);
    EXPECT_FLOAT_EQ(tex.calls[0].dtdv[1], 1.0f / nv);
    // Options and channels as asked.
    const TextureOptions& o = tex.calls[1].options;
    EXPECT_EQ(o.firstChannel, 1);
    EXPECT_EQ(o.channels, 3);
    EXPECT_FLOAT_EQ(o.sblur, .25f);
    EXPECT_FLOAT_EQ(o.tblur, .25f);
    EXPECT_FLOAT_EQ(o.swidth, 2);
    EXPECT_EQ(o.filter, "gaussian");
    // Four corners: the centre and the corners' differences.
    EXPECT_FLOAT_EQ(tex.calls[2].dsdu[0], 1);
    EXPECT_FLOAT_EQ(tex.calls[2].dtdv[0], 1);
    // Under a varying if: only the points that run are asked for.
    EXPECT_EQ(tex.calls[3].active, 2 * (nv + 1));
    EXPECT_EQ(vm.stats().textureErrors, 1u);
}

TEST(VmTexture, EnvironmentAndShadowThroughTheLight) {
    TestGrid g(4);
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{float(i) - 1.5f, 0, 5}; });
    g.setVec(Global::N, {0, 0, -1});
    g.setVec(Global::Cs, {1, 1, 1});
    ShaderInstance surf(test::compile(R"(
        surface s(output varying float env = 0) {
            env = environment("sky.env", vector(xcomp(P), 1, 0));
            Ci = diffuse(N);
        })"));
    // A point light at x = 2 whose shadow() lets the source trace towards it.
    ShaderInstance light(test::compile(R"(
        light shadowed(point from = point "shader" (0, 0, 0); string shadowname = "wall") {
            illuminate(from) {
                Cl = (1 - shadow(shadowname, Ps)) * 25 / (L . L);
            }
        })"));
    std::vector<LightRef> lights{{&light, Matrix4::translate({2, 0, 0})}};
    FakeTextures tex;
    ShadingVM vm;
    vm.setTextureSource(&tex);
    vm.run(surf, g.grid, lights);
    ValueRef env = vm.output("env"), ci = vm.result(Global::Ci);
    for (int i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(env.at(0, i), float(i) - 1.5f);
    // Points with x < 0 are behind the wall at x = 0 from the light at x = 2: black.
    for (int i = 0; i < 4; ++i) {
        const float x = float(i) - 1.5f;
        Vec3f L{2 - x, 0, -5};
        float expect = x < 0 ? 0.0f : 25.0f / dot(L, L) * (5 / length(L));
        EXPECT_NEAR(ci.at(0, i), expect, 1e-5f) << i;
    }
    ASSERT_EQ(tex.calls.size(), 2u);
    EXPECT_EQ(tex.calls[1].name, "wall");
    ASSERT_EQ(tex.calls[1].from0.size(), 4u);
    EXPECT_FLOAT_EQ(tex.calls[1].from0[0], 2.0f);  // the light's position, in current space
    // shadow("raytrace") never reaches the source: the renderer traces those rays per sample.
    ShaderInstance traced(test::compile(R"(
        light traced(point from = point "shader" (0, 0, 0); string shadowname = "raytrace") {
            illuminate(from) {
                Cl = (1 - shadow(shadowname, Ps)) * 25 / (L . L);
            }
        })"));
    FakeTextures none;
    vm.setTextureSource(&none);
    vm.run(surf, g.grid, {{&traced, Matrix4::translate({2, 0, 0})}});
    ci = vm.result(Global::Ci);
    for (int i = 0; i < 4; ++i) {
        const float x = float(i) - 1.5f;
        Vec3f L{2 - x, 0, -5};
        EXPECT_NEAR(ci.at(0, i), 25.0f / dot(L, L) * (5 / length(L)), 1e-5f) << i;  // unshadowed
    }
    ASSERT_EQ(none.calls.size(), 1u);  // the environment() only
    EXPECT_EQ(vm.stats().textureErrors, 0u);
}

TEST(VmTexture, NoSourceGivesTheFill) {
    TestGrid g(2);
    ShaderInstance inst(test::compile("surface s(output varying float a = 0) { a = texture(\"x.tx\", 0, 0, \"fill\", 2); Ci = 0; }"));
    ShadingVM vm;
    vm.run(inst, g.grid);
    EXPECT_FLOAT_EQ(vm.output("a").at(0, 1), 2.0f);
    EXPECT_EQ(vm.stats().textureErrors, 1u);
}

}  // namespace
}  // namespace streyes::sl
