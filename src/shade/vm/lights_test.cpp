// Lights: illuminance loops with categories and cones, __nondiffuse and __nonspecular,
// lightsource(), break inside the loop, and each light run once per grid.
#include <gtest/gtest.h>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

const char* kLight = R"(
    light tagged(float intensity = 1; point from = point "shader" (0, 0, 0);
                 string __category = ""; float __nondiffuse = 0; float __nonspecular = 0;
                 output float tag = 0) {
        illuminate(from) Cl = intensity;
    })";

struct Rig {
    ProgramPtr lightProgram = test::compile(kLight);
    std::vector<std::unique_ptr<ShaderInstance>> insts;
    std::vector<LightRef> lights;
    // A light at the origin side of the surface with `intensity`, category and tag.
    void add(float intensity, const std::string& category, float tag, float nondiffuse = 0, float nonspecular = 0) {
        insts.push_back(std::make_unique<ShaderInstance>(lightProgram));
        ShaderInstance& l = *insts.back();
        l.set("intensity", BaseType::Float, {intensity});
        l.setStrings("__category", {category});
        l.set("tag", BaseType::Float, {tag});
        l.set("__nondiffuse", BaseType::Float, {nondiffuse});
        l.set("__nonspecular", BaseType::Float, {nonspecular});
        lights.push_back({&l, Matrix4()});
    }
};

TestGrid facingGrid(int n) {
    TestGrid g(n);
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{0, 0, float(i + 1)}; });
    g.setVec(Global::N, {0, 0, -1});
    return g;
}

float red(ShadingVM& vm, int i) { return vm.result(Global::Ci).at(0, i); }

TEST(VmLights, IlluminanceCategoriesAndLightsource) {
    Rig rig;
    rig.add(1, "key", 1);
    rig.add(10, "fill,back", 2);
    rig.add(100, "", 4);
    TestGrid g = facingGrid(3);
    ShadingVM vm;
    auto run = [&](const std::string& body) {
        ShaderInstance s(test::compile("surface s() { Ci = 0; " + body + " }"));
        vm.run(s, g.grid, rig.lights);
        return red(vm, 0);
    };
    EXPECT_FLOAT_EQ(run("illuminance(P) Ci += Cl;"), 111);
    EXPECT_FLOAT_EQ(run("illuminance(\"key\", P) Ci += Cl;"), 1);
    EXPECT_FLOAT_EQ(run("illuminance(\"back\", P) Ci += Cl;"), 10);
    EXPECT_FLOAT_EQ(run("illuminance(\"-key\", P) Ci += Cl;"), 110);
    EXPECT_FLOAT_EQ(run("illuminance(P) { float t = 0; if (lightsource(\"tag\", t) == 1) Ci += t; }"), 7);
    EXPECT_FLOAT_EQ(run("illuminance(P) { float t = 0; lightsource(\"nosuch\", t); Ci += t + 1; }"), 3);
    // A cone about -z: all three lights (at the origin) are within it from points on +z.
    EXPECT_FLOAT_EQ(run("illuminance(P, vector(0, 0, -1), PI / 4) Ci += Cl;"), 111);
    EXPECT_FLOAT_EQ(run("illuminance(P, vector(0, 0, 1), PI / 4) Ci += Cl;"), 0);
    // break leaves the loop over lights; continue goes to the next light.
    EXPECT_FLOAT_EQ(run("illuminance(P) { Ci += Cl; if (comp(Cl, 0) > 5) break; }"), 11);
}

TEST(VmLights, LightsRunOncePerGridAndRespectNonDiffuseNonSpecular) {
    Rig rig;
    rig.add(1, "", 0, /*nondiffuse*/ 1, 0);
    rig.add(2, "", 0, 0, /*nonspecular*/ 1);
    TestGrid g = facingGrid(4);
    ShaderInstance s(test::compile(R"(
        surface s(output varying color d = 0; output varying color sp = 0) {
            normal Nf = normalize(N);
            d = diffuse(Nf);
            sp = specular(Nf, -normalize(I), .1);
            illuminance(P, Nf, PI / 2) { Ci += 0; }
            Ci = d + sp + ambient();
        })"));
    ShadingVM vm;
    vm.run(s, g.grid, rig.lights);
    EXPECT_FLOAT_EQ(vm.output("d").at(0, 0), 2.0f);   // only the second light is diffuse
    EXPECT_FLOAT_EQ(vm.output("sp").at(0, 0), 1.0f);  // only the first is specular (N.H = 1)
    EXPECT_EQ(vm.stats().lightRuns, 2u);              // diffuse, specular and the loop share them
}

TEST(VmLights, AmbientLightsOnlyInAmbient) {
    ProgramPtr amb = test::compile("light a(float intensity = 1) { Cl = intensity; }");
    ShaderInstance l1(amb), l2(amb);
    l2.set("intensity", BaseType::Float, {2});
    std::vector<LightRef> lights{{&l1, Matrix4()}, {&l2, Matrix4()}};
    TestGrid g = facingGrid(2);
    ShaderInstance s(test::compile("surface s() { Ci = ambient(); illuminance(P) Ci += 100; }"));
    ShadingVM vm;
    vm.run(s, g.grid, lights);
    EXPECT_FLOAT_EQ(red(vm, 1), 3.0f);
}

TEST(VmLights, SolarWithoutAxisAndBroadCones) {
    ProgramPtr sky = test::compile("light skylight() { solar() Cl = 1; }");
    ShaderInstance l(sky);
    std::vector<LightRef> lights{{&l, Matrix4()}};
    TestGrid g = facingGrid(2);
    ShaderInstance s(test::compile("surface s() { Ci = diffuse(normalize(N)); }"));
    ShadingVM vm;
    vm.run(s, g.grid, lights);
    EXPECT_FLOAT_EQ(red(vm, 0), 1.0f);  // light from along the normal
}

}  // namespace
}  // namespace streyes::sl
