// Lights whose results do not depend on the point (an ambient light, a distant light without
// shadows) are run once and their results given again to later grids while everything uniform
// they could read is the same (ShadingVM::runLight): the surfaces' results must be those of a
// run bit for bit, and any change of what the light reads must run it again.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

// An nu x nv grid at depth z, tilted by `tilt`: other points and normals for every grid.
TestGrid sheet(int nu, int nv, float z, float tilt) {
    TestGrid g(nu, nv);
    g.setVarying(Global::P, 3, [&](int k) {
        const float u = float(k % (nu + 1)) / float(nu), v = float(k / (nu + 1)) / float(nv);
        return Vec3f{u - 0.5f, v - 0.5f, z + tilt * u};
    });
    g.setVarying(Global::N, 3, [&](int k) { return Vec3f{tilt * 0.3f, 0.1f * float(k % 3), -1}; });
    g.setVec(Global::Cs, {0.8f, 0.6f, 0.4f});
    return g;
}

// Ci of `surface` over `g` from a VM that has run nothing before (its lights are run).
std::vector<float> fresh(const ShaderInstance& surface, const TestGrid& g, const std::vector<LightRef>& lights) {
    ShadingVM vm;
    vm.run(surface, g.grid, lights);
    EXPECT_EQ(vm.stats().lightReuses, 0u);
    const ValueRef ci = vm.result(Global::Ci);
    std::vector<float> out;
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < g.n(); ++i) out.push_back(ci.at(c, i));
    return out;
}

// Ci of the last run of `vm` equals `want` bit for bit (NaN included).
void expectSameBits(const ShadingVM& vm, const TestGrid& g, const std::vector<float>& want) {
    const ValueRef ci = vm.result(Global::Ci);
    ASSERT_EQ(want.size(), size_t(3 * g.n()));
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < g.n(); ++i) {
            const float got = ci.at(c, i), w = want[size_t(c * g.n() + i)];
            EXPECT_EQ(std::memcmp(&got, &w, sizeof(float)), 0) << "component " << c << " point " << i << ": " << got << " vs " << w;
        }
}

struct ForestLights {
    ShaderInstance amb{compileShaderFile(test::shaderPath("ambientlight"))};
    ShaderInstance sun{compileShaderFile(test::shaderPath("distantlight"))};
    ShaderInstance bulb{compileShaderFile(test::shaderPath("pointlight"))};
    std::vector<LightRef> refs;
    ForestLights() {
        amb.set("intensity", BaseType::Float, {0.35f});
        amb.set("lightcolor", BaseType::Color, {0.75f, 0.85f, 1});
        sun.set("from", BaseType::Point, {-4, 5, 3});
        sun.set("to", BaseType::Point, {0, 0, 0});
        bulb.set("intensity", BaseType::Float, {3});
        refs = {{&amb, Matrix4::rotate(30, {0, 1, 0})}, {&sun, Matrix4::rotate(30, {0, 1, 0})},
                {&bulb, Matrix4::translate({1, 2, -1})}};
    }
};

TEST(VmPointFreeLights, ReusedResultsAreTheRunsBitForBit) {
    ForestLights lights;
    for (const char* name : {"matte", "plastic", "leaf", "bark"}) {
        SCOPED_TRACE(name);
        ShaderInstance surface(compileShaderFile(test::shaderPath(name)));
        ShadingVM vm;
        int grids = 0;
        // Grids of other sizes, places and normals: the lights' results are broadcast to each.
        for (int nu : {1, 2, 3, 7, 16})
            for (float z : {2.0f, 5.5f}) {
                TestGrid g = sheet(nu, nu == 3 ? 2 : nu, z, 0.25f * float(nu));
                vm.run(surface, g.grid, lights.refs);
                expectSameBits(vm, g, fresh(surface, g, lights.refs));
                ++grids;
            }
        // The ambient and the distant light ran for the first grid only; the point light's
        // results are its points' own: run for every grid.
        EXPECT_EQ(vm.stats().lightReuses, uint64_t(2 * (grids - 1)));
        EXPECT_EQ(vm.stats().lightRuns, uint64_t(2 + grids));
    }
}

// Results given again are kept uniform (one value for all points, LightResult::uniform) through
// every function that reads a light: illuminance loops with categories and cones (a uniform and a
// varying axis), lightsource() outputs, ambient, diffuse, specular, phong and specularbrdf, a
// light that reaches no point, beside a point light whose results are per point. Each grid's Ci
// must be a fresh VM's (whose lights run, their results per point) bit for bit.
TEST(VmPointFreeLights, UniformResultsReadByEveryLightingFunctionAreTheRunsBitForBit) {
    ForestLights lights;
    ShaderInstance key(test::compile(R"(
        light key(float intensity = 0.8; color lightcolor = color(1, 0.9, 0.7);
                  point from = point "shader" (0, 0, 0); point to = point "shader" (0.3, -0.2, 1);
                  string __category = "key,rim"; output float tag = 0) {
            tag = intensity * 2;
            solar(to - from, 0) Cl = intensity * lightcolor;
        })"));
    ShaderInstance dark(test::compile(
        "light dark(float on = 0) { if (on > 0.5) { solar(vector(0, 0, 1), 0) Cl = 1; } }"));
    std::vector<LightRef> refs = lights.refs;
    refs.push_back({&key, Matrix4::rotate(-20, {1, 0, 0})});
    refs.push_back({&dark, Matrix4()});
    ShaderInstance surface(test::compile(R"(
        surface s(float Ks = 0.5; float roughness = 0.1) {
            normal Nf = faceforward(normalize(N), I);
            vector V = -normalize(I);
            color c = ambient();
            illuminance("key", P, Nf, PI / 2) {
                float t = 0;
                lightsource("tag", t);
                c += Cl * (normalize(L) . Nf) * (1 + t) + specularbrdf(normalize(L), Nf, V, roughness);
            }
            illuminance(P, vector(0, 0, -1), PI / 4) { c += 0.5 * Cl; }
            illuminance("-key", P) { c += 0.25 * Cl * (1 + xcomp(L)); }
            Ci = Cs * (c + diffuse(Nf)) + Ks * specular(Nf, V, roughness) + phong(Nf, V, 20);
        })"));
    ShadingVM vm;
    int grids = 0;
    for (int nu : {1, 2, 5, 16})  // 4 to 289 points: SIMD bodies and tails
        for (float tilt : {0.0f, 0.7f}) {
            TestGrid g = sheet(nu, nu == 5 ? 3 : nu, 3.0f + tilt, tilt);
            vm.run(surface, g.grid, refs);
            expectSameBits(vm, g, fresh(surface, g, refs));
            ++grids;
        }
    // The ambient, distant, key and dark lights ran for the first grid only (then uniform); the
    // point light for every grid.
    EXPECT_EQ(vm.stats().lightReuses, uint64_t(4 * (grids - 1)));
    EXPECT_EQ(vm.stats().lightRuns, uint64_t(4 + grids));
}

TEST(VmPointFreeLights, ALightReadingThePointIsRunForEveryGrid) {
    // Cl from Ps (varying) inside a uniform branch, and L from a varying axis.
    ShaderInstance depth(test::compile("light depth() { solar(vector(0, 0, -1), 0) Cl = zcomp(Ps); }"));
    ShaderInstance axis(test::compile("light axis() { solar(Ps - point(0, 0, 0), 0) Cl = 1; }"));
    ShaderInstance surface(test::compile("surface s() { Ci = diffuse(normalize(N)) + ambient(); }"));
    for (ShaderInstance* light : {&depth, &axis}) {
        std::vector<LightRef> refs{{light, Matrix4()}};
        ShadingVM vm;
        // Flat sheets at other depths: Cl is the same at every point of a grid, and not from
        // grid to grid (only the operations it ran tell that it reads the point).
        for (float z : {2.0f, 3.0f, 7.0f}) {
            TestGrid g = sheet(4, 4, z, 0);
            vm.run(surface, g.grid, refs);
            expectSameBits(vm, g, fresh(surface, g, refs));
        }
        EXPECT_EQ(vm.stats().lightReuses, 0u);
        EXPECT_EQ(vm.stats().lightRuns, 3u);
    }
}

TEST(VmPointFreeLights, AChangeOfWhatTheLightReadsRunsItAgain) {
    ShaderInstance surface(test::compile("surface s() { Ci = diffuse(normalize(N)) + ambient(); }"));
    TestGrid g = sheet(3, 3, 4, 0.5f);
    ShadingVM vm;
    auto check = [&](const std::vector<LightRef>& refs, uint64_t reuses) {
        vm.run(surface, g.grid, refs);
        expectSameBits(vm, g, fresh(surface, g, refs));
        EXPECT_EQ(vm.stats().lightReuses, reuses);
    };
    // A parameter set again on the same instance (the same address, another value).
    ShaderInstance sun(compileShaderFile(test::shaderPath("distantlight")));
    sun.set("from", BaseType::Point, {0, 0, -1});
    std::vector<LightRef> refs{{&sun, Matrix4()}};
    check(refs, 0);
    check(refs, 1);
    sun.set("from", BaseType::Point, {1, 0, -1});
    check(refs, 1);
    check(refs, 2);
    // Another "shader" space for the light.
    refs[0].toCurrent = Matrix4::rotate(40, {1, 0, 0});
    check(refs, 2);
    check(refs, 3);
    // A light reading "world" space and the time: a grid with another of either runs it again.
    ShaderInstance clock(test::compile(
        "light clock() { solar(vector \"world\" (0, 0, -1), 0) Cl = color(time, 1, 2); }"));
    std::vector<LightRef> clocks{{&clock, Matrix4()}};
    g.setFloat(Global::time, 0.25f);
    check(clocks, 3);
    check(clocks, 4);
    g.grid.setSpace(Space::World, Matrix4::rotate(90, {0, 1, 0}));
    check(clocks, 4);
    g.setFloat(Global::time, 0.5f);
    check(clocks, 4);
    check(clocks, 5);
}

}  // namespace
}  // namespace streyes::sl
