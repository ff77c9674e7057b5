// Run-time safety: an array index outside the array is clamped into it and warned once at its
// place in the shader; loops that never end stop at the per-grid iteration budget, warned once.
#include <gtest/gtest.h>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

TestGrid grid() {
    TestGrid g(7, 7);
    g.setVarying(Global::s, 1, [](int i) { return Vec3f{float(i) / 63.0f, 0, 0}; });
    return g;
}

size_t countWith(const std::vector<std::string>& lines, const std::string& what) {
    size_t n = 0;
    for (const std::string& l : lines) n += l.find(what) != std::string::npos;
    return n;
}

TEST(VmSafety, AnIndexOutsideTheArrayIsClampedAndWarnedOnceAtItsPlace) {
    ProgramPtr p = compileShader(
        "surface s(output varying float lo = 0; output varying float hi = 0; output uniform float w = 0) {\n"
        "  float a[3] = {10, 20, 30};\n"
        "  hi = a[1e9];\n"
        "  lo = a[s * 0 - 2];\n"
        "  if (s > 2) hi = a[-5];\n"  // never runs: no warning
        "  a[7] = 40;\n"
        "  w = a[2];\n"
        "  string names[2] = {\"x\", \"y\"};\n"
        "  Ci = names[3] == \"y\" ? 1 : 0;\n"
        "}\n",
        "safe.sl");
    ShaderInstance inst(p);
    Log log;
    log.setQuiet(true);
    ShadingVM vm;
    vm.setLog(&log);
    TestGrid g = grid();
    for (int run = 0; run < 2; ++run) vm.run(inst, g.grid);
    for (int i = 0; i < g.n(); ++i) {
        EXPECT_EQ(vm.output("hi").at(0, i), 30.0f);
        EXPECT_EQ(vm.output("lo").at(0, i), 10.0f);
        EXPECT_EQ(vm.result(Global::Ci).at(0, i), 1.0f);
    }
    EXPECT_EQ(vm.output("w").at(0, 0), 40.0f);
    const std::vector<std::string> w = log.warnings();
    EXPECT_EQ(w.size(), 4u);  // four places, each once over two grids
    EXPECT_EQ(countWith(w, "safe.sl:3:"), 1u);
    EXPECT_EQ(countWith(w, "safe.sl:4:"), 1u);
    EXPECT_EQ(countWith(w, "safe.sl:6:"), 1u);
    EXPECT_EQ(countWith(w, "safe.sl:9:"), 1u);
    EXPECT_EQ(countWith(w, "safe.sl:5:"), 0u);
    EXPECT_EQ(countWith(w, "array index 1e+09 is outside 'a' of 3 (0 to 2): clamped"), 1u);
    EXPECT_EQ(vm.stats().indicesClamped, 8u);  // four places, two grids
}

TEST(VmSafety, ARunawayLoopStopsAtTheBudgetAndWarnsOnce) {
    ProgramPtr p = compileShader(
        "surface s(output uniform float k = 0; output varying float j = 0; output uniform float m = 0) {\n"
        "  while (1) { k += 1; }\n"
        "  while (s >= 0) { j += 1; }\n"
        "  float i;\n"
        "  for (i = 0; i < 5; i += 1) m += 1;\n"
        "  Ci = 1;\n"
        "}\n",
        "spin.sl");
    ShaderInstance inst(p);
    Log log;
    log.setQuiet(true);
    ShadingVM vm;
    vm.setLog(&log);
    vm.setLoopBudget(1000);
    TestGrid g = grid();
    for (int run = 0; run < 2; ++run) vm.run(inst, g.grid);
    // The first loop takes the whole budget (its body runs once more than it turns); after it,
    // each loop ends at its next turn, so the body of each later loop runs once.
    EXPECT_EQ(vm.output("k").at(0, 0), 1001.0f);
    EXPECT_EQ(vm.output("j").at(0, 5), 1.0f);
    EXPECT_EQ(vm.output("m").at(0, 0), 1.0f);
    EXPECT_EQ(vm.result(Global::Ci).at(0, 0), 1.0f);  // the rest of the shader ran
    EXPECT_EQ(vm.stats().loopsStopped, 2u);
    const std::vector<std::string> w = log.warnings();
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("spin.sl:2:"), std::string::npos) << w[0];
    EXPECT_NE(w[0].find("loops ran more than 1000 turns on one grid"), std::string::npos) << w[0];
}

// Within the budget nothing changes; the default budget ends a runaway loop too.
TEST(VmSafety, TheDefaultBudget) {
    ProgramPtr p = compileShader(
        "surface s(output uniform float k = 0; output uniform float m = 0) {\n"
        "  float i, j;\n"
        "  for (i = 0; i < 300; i += 1) for (j = 0; j < 300; j += 1) m += 1;\n"
        "  while (1) k += 1;\n"
        "}\n",
        "budget.sl");
    ShaderInstance inst(p);
    ShadingVM vm;
    TestGrid g = grid();
    vm.run(inst, g.grid);
    EXPECT_EQ(vm.output("m").at(0, 0), 90000.0f);
    EXPECT_EQ(vm.output("k").at(0, 0), float(ShadingVM::kDefaultLoopBudget - 90000 - 300 + 1));
    EXPECT_EQ(vm.stats().loopsStopped, 1u);
}

}  // namespace
}  // namespace streyes::sl
