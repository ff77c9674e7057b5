// Literals and storage classes as RenderMan's compilers have them: C's float suffix, random()
// giving one number a grid where a uniform value is wanted, and variables declared without a
// storage class inside a function taking what they are given.
#include <gtest/gtest.h>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

TEST(SlRules, FloatSuffix) {
    ProgramPtr p = test::compile("surface s(float a = 0.0f; float b = 1.5F; float c = 2.f; float d = 1e-3f) { Ci = a; }");
    EXPECT_EQ(p->params[0].defaultFloats[0], 0.0f);
    EXPECT_EQ(p->params[1].defaultFloats[0], 1.5f);
    EXPECT_EQ(p->params[2].defaultFloats[0], 2.0f);
    EXPECT_EQ(p->params[3].defaultFloats[0], 1e-3f);
    // Anything else after a number is still an error.
    EXPECT_NE(test::compileError("surface s(float a = 1.5fx) { Ci = a; }").find("after the number 1.5"), std::string::npos);
}

TestGrid grid(unsigned seed) {
    TestGrid g(7, 7);
    g.setVarying(Global::s, 1, [](int i) { return Vec3f{float(i) / 63.0f, 0, 0}; });
    g.setVec(Global::Os, {1, 1, 1});
    g.grid.seed = seed;
    return g;
}

// debug.sl and randgrid.sl: `uniform color c = color(random(), random(), random())` is one
// colour for the whole grid (a different one on another grid); a varying variable gets one a point.
TEST(SlRules, RandomInAUniformContextIsOneNumberAGrid) {
    ProgramPtr p = test::compile(
        "surface s(output uniform float u = 0; output varying float v = 0) {\n"
        "  uniform color c = color(random(), random(), random());\n"
        "  uniform float r;\n"
        "  r = random();\n"
        "  u = r;\n"
        "  v = random();\n"
        "  Oi = Os;\n"
        "  Ci = Os * c;\n"
        "}\n");
    ShaderInstance inst(p);
    ShadingVM vm;
    TestGrid a = grid(1);
    vm.run(inst, a.grid);
    ValueRef ci = vm.result(Global::Ci), v = vm.output("v");
    const Vec3f first = test::at3(ci, 0);
    float vmin = 1, vmax = 0;
    for (int i = 0; i < a.n(); ++i) {
        EXPECT_EQ(test::at3(ci, i).x, first.x);
        EXPECT_EQ(test::at3(ci, i).z, first.z);
        vmin = std::min(vmin, v.at(0, i));
        vmax = std::max(vmax, v.at(0, i));
    }
    EXPECT_FALSE(vm.output("u").varying());
    EXPECT_GT(vmax - vmin, 0.5f);  // varying: a number a point
    EXPECT_NE(first.x, first.y);   // three calls, three numbers
    for (float c : {first.x, first.y, first.z}) {
        EXPECT_GE(c, 0.0f);
        EXPECT_LT(c, 1.0f);
    }
    TestGrid b = grid(2);
    vm.run(inst, b.grid);
    EXPECT_NE(test::at3(vm.result(Global::Ci), 0).x, first.x);  // another grid, another colour
    // A varying value into a variable declared uniform is still an error.
    EXPECT_NE(test::compileError("surface s() {\n  uniform float r = s;\n  Ci = r;\n}").find("test.sl:2:"), std::string::npos);
}

// A variable declared without uniform or varying inside a function is what the call gives it.
TEST(SlRules, FunctionLocalsTakeTheirStorageClassFromTheCall) {
    ProgramPtr p = test::compile(
        "float twice(float x) {\n"
        "  float y;\n"
        "  y = x * 2;\n"
        "  float z = y;\n"
        "  return z;\n"
        "}\n"
        "surface s(output uniform float u = 0) {\n"
        "  uniform float k = twice(3);\n"
        "  u = k;\n"
        "  Ci = twice(s);\n"
        "}\n");
    ShaderInstance inst(p);
    ShadingVM vm;
    TestGrid g = grid(1);
    vm.run(inst, g.grid);
    EXPECT_EQ(vm.output("u").at(0, 0), 6.0f);
    for (int i = 0; i < g.n(); ++i) EXPECT_FLOAT_EQ(vm.result(Global::Ci).at(0, i), 2 * float(i) / 63.0f);
}

}  // namespace
}  // namespace streyes::sl
