// Resizable arrays (RSL 2): unsized parameters sized by their value, unsized formals taking any
// length, resize, push and pop on unsized locals, arraylength at run time; closed forms over
// grids, and the compile errors of their misuse at file:line:column.
#include <gtest/gtest.h>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::compileError;
using test::TestGrid;

size_t countWith(const std::vector<std::string>& lines, const std::string& what) {
    size_t n = 0;
    for (const std::string& l : lines) n += l.find(what) != std::string::npos;
    return n;
}

// A grid of 8 x 8 micropolygons (81 points) whose u is i / 80 at point i.
TestGrid uGrid() {
    TestGrid g(8, 8);
    g.setVarying(Global::u, 1, [](int i) { return Vec3f{float(i) / 80.0f, 0, 0}; });
    return g;
}

const char* const kSumShader =
    "float sumOf(float v[]) {\n"
    "  float s = 0;\n"
    "  uniform float i;\n"
    "  for (i = 0; i < arraylength(v); i += 1) s += v[i];\n"
    "  return s;\n"
    "}\n"
    "surface arrsum(float a[] = {1, 2}; output uniform float total = 0; output uniform float count = 0;\n"
    "               output uniform float fixedTotal = 0) {\n"
    "  total = sumOf(a);\n"
    "  count = arraylength(a);\n"
    "  float f[3] = {4, 5, 6};\n"
    "  fixedTotal = sumOf(f);\n"
    "}\n";

TEST(ResizableArrays, AnUnsizedParameterTakesTheLengthOfItsValue) {
    ProgramPtr p = compileShader(kSumShader, "arrsum.sl");
    EXPECT_EQ(p->params[0].type.name(), "float[]");
    EXPECT_EQ(p->params[0].defaultFloats, (std::vector<float>{1, 2}));
    ShaderInstance byDefault(p), given(p), empty(p);
    given.setDeclared("float a", {1, 2, 3, 4}, {});
    std::vector<float> hundred;
    for (int k = 1; k <= 100; ++k) hundred.push_back(float(k));
    ShaderInstance many(p);
    many.set("a", SlType(), hundred, {});
    empty.setDeclared("float a", {}, {});
    ShadingVM vm;
    TestGrid g = uGrid();
    // One VM, the instances in turn: each run has its own length, nothing left from the last.
    vm.run(given, g.grid);
    EXPECT_EQ(vm.output("total").at(0, 0), 10.0f);
    EXPECT_EQ(vm.output("count").at(0, 0), 4.0f);
    EXPECT_EQ(vm.output("fixedTotal").at(0, 0), 15.0f);  // an unsized formal given a float[3]
    vm.run(byDefault, g.grid);
    EXPECT_EQ(vm.output("total").at(0, 0), 3.0f);
    EXPECT_EQ(vm.output("count").at(0, 0), 2.0f);
    vm.run(many, g.grid);
    EXPECT_EQ(vm.output("total").at(0, 0), 5050.0f);
    EXPECT_EQ(vm.output("count").at(0, 0), 100.0f);
    vm.run(empty, g.grid);
    EXPECT_EQ(vm.output("total").at(0, 0), 0.0f);
    EXPECT_EQ(vm.output("count").at(0, 0), 0.0f);
}

TEST(ResizableArrays, AFixedParameterGivenTheWrongCountIsStillAnError) {
    ProgramPtr p = compileShader("surface s(float b[3] = {1, 2, 3}; color c[] = {1, 2}) { Ci = b[0] + c[1]; }", "s.sl");
    ShaderInstance inst(p);
    try {
        inst.setDeclared("float b", {1, 2, 3, 4}, {});
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("it takes 3 values, not 4"), std::string::npos) << e.what();
    }
    // A color[] takes whole colors.
    try {
        inst.setDeclared("color c", {1, 2, 3, 4}, {});
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("it takes 3 values an element, not 4 in all"), std::string::npos) << e.what();
    }
    inst.setDeclared("color c", {1, 2, 3, 4, 5, 6}, {});
    ShadingVM vm;
    TestGrid g = uGrid();
    vm.run(inst, g.grid);
    EXPECT_EQ(test::at3(vm.result(Global::Ci), 5), (Vec3f{5, 6, 7}));  // b[0] + c[1]
}

TEST(ResizableArrays, PushAppendsAndArraylengthCountsThem) {
    ProgramPtr p = compileShader(
        "surface pushes(uniform float n = 5; output uniform float len = 0; output uniform float total = 0;\n"
        "               output uniform float vals[6] = {0, 0, 0, 0, 0, 0}) {\n"
        "  float a[];\n"
        "  uniform float i;\n"
        "  for (i = 0; i < n; i += 1) push(a, 10 * i + 1);\n"
        "  len = arraylength(a);\n"
        "  for (i = 0; i < len; i += 1) { total += a[i]; if (i < 6) vals[i] = a[i]; }\n"
        "}\n",
        "pushes.sl");
    ShadingVM vm;
    TestGrid g = uGrid();
    for (int n : {5, 1000, 0, 3}) {
        SCOPED_TRACE(n);
        ShaderInstance inst(p);
        inst.set("n", SlType(), {float(n)}, {});
        vm.run(inst, g.grid);
        EXPECT_EQ(vm.output("len").at(0, 0), float(n));
        EXPECT_EQ(vm.output("total").at(0, 0), 10.0f * float(n) * float(n - 1) / 2 + float(n));
        for (int k = 0; k < 6; ++k) EXPECT_EQ(vm.param("vals", k).at(0, 0), k < n ? 10.0f * float(k) + 1 : 0.0f) << k;
    }
    EXPECT_EQ(vm.stats().indicesClamped, 0u);
}

TEST(ResizableArrays, PopReturnsTheLastInReverseOrderAndAnEmptyPopIsZeroWarnedOnce) {
    ProgramPtr p = compileShader(
        "surface pops(output uniform float p0 = 0; output uniform float p1 = 0; output uniform float p2 = 0;\n"
        "             output uniform float len = -1; output uniform float p3 = -1; output uniform float len2 = -1) {\n"
        "  float a[] = {3, 5, 7};\n"
        "  p0 = pop(a); p1 = pop(a); p2 = pop(a);\n"
        "  len = arraylength(a);\n"
        "  p3 = pop(a);\n"
        "  len2 = arraylength(a);\n"
        "}\n",
        "pops.sl");
    ShaderInstance inst(p);
    Log log;
    log.setQuiet(true);
    ShadingVM vm;
    vm.setLog(&log);
    TestGrid g = uGrid();
    for (int run = 0; run < 2; ++run) {
        vm.run(inst, g.grid);
        EXPECT_EQ(vm.output("p0").at(0, 0), 7.0f);
        EXPECT_EQ(vm.output("p1").at(0, 0), 5.0f);
        EXPECT_EQ(vm.output("p2").at(0, 0), 3.0f);
        EXPECT_EQ(vm.output("len").at(0, 0), 0.0f);
        EXPECT_EQ(vm.output("p3").at(0, 0), 0.0f);
        EXPECT_EQ(vm.output("len2").at(0, 0), 0.0f);
    }
    const std::vector<std::string> w = log.warnings();
    ASSERT_EQ(w.size(), 1u);  // one place, once over two grids
    EXPECT_EQ(countWith(w, "pops.sl:6:"), 1u) << w[0];
    EXPECT_EQ(countWith(w, "pop of 'a', which is empty: 0"), 1u) << w[0];
    EXPECT_EQ(vm.stats().indicesClamped, 2u);
}

TEST(ResizableArrays, ResizeKeepsTheFirstElementsAndGrowsWithZeros) {
    ProgramPtr p = compileShader(
        "surface sizes(output uniform float l1 = -1; output uniform float l2 = -1; output uniform float l3 = -1;\n"
        "              output uniform float e[4] = {-1, -1, -1, -1}) {\n"
        "  color c[] = {1, 2, 3, 4, 5};\n"
        "  resize(c, 2);\n"
        "  l1 = arraylength(c);\n"
        "  resize(c, 4);\n"  // grows: the 3, 4 dropped before do not come back
        "  l2 = arraylength(c);\n"
        "  uniform float i;\n"
        "  for (i = 0; i < 4; i += 1) e[i] = comp(c[i], 1);\n"
        "  resize(c, -3);\n"
        "  l3 = arraylength(c);\n"
        "}\n",
        "sizes.sl");
    ShaderInstance inst(p);
    ShadingVM vm;
    TestGrid g = uGrid();
    vm.run(inst, g.grid);
    EXPECT_EQ(vm.output("l1").at(0, 0), 2.0f);
    EXPECT_EQ(vm.output("l2").at(0, 0), 4.0f);
    EXPECT_EQ(vm.output("l3").at(0, 0), 0.0f);  // a negative length is 0
    const float want[4] = {1, 2, 0, 0};
    for (int k = 0; k < 4; ++k) EXPECT_EQ(vm.param("e", k).at(0, 0), want[k]) << k;
}

TEST(ResizableArrays, VaryingValuesPushedPerPoint) {
    ProgramPtr p = compileShader(
        "surface vpush(output varying float first = 0; output varying float last = 0; output varying float total = 0;\n"
        "              output varying float popped = 0; output uniform float len = 0) {\n"
        "  float a[];\n"
        "  uniform float i;\n"
        "  for (i = 0; i < 40; i += 1) push(a, u + i);\n"
        "  len = arraylength(a);\n"
        "  first = a[0];\n"
        "  last = a[39];\n"
        "  for (i = 0; i < len; i += 1) total += a[i];\n"
        "  popped = pop(a);\n"
        "}\n",
        "vpush.sl");
    ShaderInstance inst(p);
    ShadingVM vm;
    TestGrid big = uGrid(), small(3, 2);
    small.setVarying(Global::u, 1, [](int i) { return Vec3f{0.25f * float(i), 0, 0}; });
    for (TestGrid* grid : {&big, &small}) {  // the second run over a smaller grid: the storage re-laid for its n
        TestGrid& g = *grid;
        vm.run(inst, g.grid);
        EXPECT_EQ(vm.output("len").at(0, 0), 40.0f);
        for (int i = 0; i < g.n(); ++i) {
            const float u = g.grid.globals[size_t(Global::u)].at(0, i);
            EXPECT_EQ(vm.output("first").at(0, i), u) << i;
            EXPECT_EQ(vm.output("last").at(0, i), u + 39.0f) << i;
            EXPECT_EQ(vm.output("popped").at(0, i), u + 39.0f) << i;
            float want = 0;
            for (int k = 0; k < 40; ++k) want += u + float(k);
            EXPECT_EQ(vm.output("total").at(0, i), want) << i;
        }
    }
}

TEST(ResizableArrays, ADeclarationInALoopStartsAfreshAndWholeArraysAssign) {
    ProgramPtr p = compileShader(
        "surface fresh(output uniform float l = -1; output uniform float lb = -1; output uniform float lc = -1;\n"
        "              output uniform float cs = -1; output uniform float oob = -1) {\n"
        "  uniform float i;\n"
        "  for (i = 0; i < 3; i += 1) { float b[]; push(b, i); l = arraylength(b); }\n"
        "  float f[3] = {1, 2, 4};\n"
        "  float c[] = f;\n"
        "  push(c, 8);\n"
        "  float d[] = {9};\n"
        "  d = c;\n"
        "  lc = arraylength(d);\n"
        "  cs = d[0] + d[1] + d[2] + d[3];\n"
        "  oob = d[7];\n"
        "}\n",
        "fresh.sl");
    ShaderInstance inst(p);
    Log log;
    log.setQuiet(true);
    ShadingVM vm;
    vm.setLog(&log);
    TestGrid g = uGrid();
    vm.run(inst, g.grid);
    EXPECT_EQ(vm.output("l").at(0, 0), 1.0f);
    EXPECT_EQ(vm.output("lc").at(0, 0), 4.0f);
    EXPECT_EQ(vm.output("cs").at(0, 0), 15.0f);
    EXPECT_EQ(vm.output("oob").at(0, 0), 8.0f);  // clamped to the last, as a fixed array's index is
    ASSERT_EQ(log.warnings().size(), 1u);
    EXPECT_EQ(countWith(log.warnings(), "fresh.sl:12:"), 1u) << log.warnings()[0];
    EXPECT_EQ(countWith(log.warnings(), "array index 7 is outside 'd' of 4 (0 to 3): clamped"), 1u) << log.warnings()[0];
}

// The error starts with "test.sl:line:column: " and contains `what`.
void expectError(const std::string& src, int line, int column, const std::string& what) {
    const std::string msg = compileError(src);
    SCOPED_TRACE(src);
    const std::string where = "test.sl:" + std::to_string(line) + ":" + std::to_string(column) + ": ";
    EXPECT_EQ(msg.rfind(where, 0), 0u) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
}

TEST(ResizableArrays, MisuseIsACompileErrorAtItsPlace) {
    expectError("surface s() {\n  float f[3] = {1, 2, 3};\n  push(f, 4);\n}\n", 3, 8,
                "push of 'f', a float[3] of fixed length: only arrays declared without a length (float f[])");
    expectError("surface s() {\n  color f[2];\n  resize(f, 4);\n}\n", 3, 10, "resize of 'f', a color[2] of fixed length");
    expectError("surface s() {\n  float f[2];\n  Ci = pop( f);\n}\n", 3, 13, "pop of 'f', a float[2] of fixed length");
    expectError("surface s() {\n  float x = 1;\n  push(x, 4);\n}\n", 3, 8, "push needs an array, not the float 'x'");
    expectError("surface s() {\n  float a[];\n  push(a, color 1);\n}\n", 3, 11, "cannot use a color");
    expectError("surface s() {\n  float a[];\n  push(a);\n}\n", 3, 3, "push takes (array, value)");
    // Under a varying condition: the length is one value for the grid.
    expectError("surface s() {\n  float a[];\n  if (u > 0.5)\n    push(a, 1);\n}\n", 4, 5,
                "push of 'a' under a varying condition");
    expectError("surface s() {\n  float a[] = {1};\n  resize(a, u);\n}\n", 3, 13, "resize's length is one value for the whole grid");
    // An unsized output formal given a fixed array at the call: the error at the push.
    expectError("void add(output float v[]) {\n  push(v, 1);\n}\nsurface s() {\n  float f[2];\n  add(f);\n}\n", 2, 8,
                "push of 'v', here a float[2] of fixed length");
    // A formal not declared output cannot be changed.
    expectError("void add(float v[]) {\n  push(v, 1);\n}\nsurface s() {\n  float f[];\n  add(f);\n}\n", 2, 8,
                "not declared output");
    // A fixed array cannot take an array of another length.
    expectError("surface s() {\n  float a[] = {1, 2};\n  float f[2] = a;\n}\n", 3, 16, "cannot use a float[] as 'f' (float[2])");
}

TEST(ResizableArrays, AnOutputFormalPushesIntoTheCallersArray) {
    ProgramPtr p = compileShader(
        "void fill(output float v[]; float n) {\n"
        "  uniform float i;\n"
        "  for (i = 0; i < n; i += 1) push(v, i * i);\n"
        "}\n"
        "surface s(output uniform float len = 0; output uniform float lastv = 0) {\n"
        "  float a[] = {7};\n"
        "  fill(a, 4);\n"
        "  len = arraylength(a);\n"
        "  lastv = a[4];\n"
        "}\n",
        "fill.sl");
    ShaderInstance inst(p);
    ShadingVM vm;
    TestGrid g = uGrid();
    vm.run(inst, g.grid);
    EXPECT_EQ(vm.output("len").at(0, 0), 5.0f);
    EXPECT_EQ(vm.output("lastv").at(0, 0), 9.0f);
}

// String arrays resize, push and pop as the numeric ones (uniform: one list a grid); an empty
// one reads "" and pops "", warned once; a whole-array assignment takes the source's length.
TEST(ResizableArrays, StringArraysPushPopResizeAndCount) {
    ProgramPtr p = compileShader(
        "surface strs(uniform float n = 3; output uniform float len = -1; output uniform float len2 = -1;\n"
        "             output uniform float len3 = -1; output uniform float hits = 0; output uniform float copied = -1;\n"
        "             output uniform string last = \"x\"; output uniform string gone = \"x\"; output uniform string grown = \"x\";\n"
        "             output uniform string oob = \"x\") {\n"
        "  string a[];\n"
        "  uniform float i;\n"
        "  for (i = 0; i < n; i += 1) push(a, format(\"s%d\", i));\n"
        "  len = arraylength(a);\n"
        "  for (i = 0; i < len; i += 1) if (a[i] == format(\"s%d\", i)) hits += 1;\n"
        "  last = pop(a);\n"
        "  len2 = arraylength(a);\n"
        "  string b[] = a;\n"
        "  copied = arraylength(b);\n"
        "  resize(a, 0);\n"
        "  gone = pop(a);\n"
        "  resize(a, 2);\n"
        "  grown = concat(a[0], a[1], \"|\");\n"
        "  len3 = arraylength(a);\n"
        "  oob = b[len + 5];\n"
        "}\n",
        "strs.sl");
    Log log;
    log.setQuiet(true);
    ShadingVM vm;
    vm.setLog(&log);
    TestGrid g = uGrid();
    for (int n : {3, 1000, 1}) {
        SCOPED_TRACE(n);
        ShaderInstance inst(p);
        inst.set("n", SlType(), {float(n)}, {});
        vm.run(inst, g.grid);
        EXPECT_EQ(vm.output("len").at(0, 0), float(n));
        EXPECT_EQ(vm.output("hits").at(0, 0), float(n));
        EXPECT_EQ(vm.paramStrings("last"), std::vector<std::string>{"s" + std::to_string(n - 1)});
        EXPECT_EQ(vm.output("len2").at(0, 0), float(n - 1));
        EXPECT_EQ(vm.output("copied").at(0, 0), float(n - 1));
        EXPECT_EQ(vm.paramStrings("gone"), std::vector<std::string>{""});  // popped from an empty array
        EXPECT_EQ(vm.paramStrings("grown"), std::vector<std::string>{"|"});  // resize grows with ""
        EXPECT_EQ(vm.output("len3").at(0, 0), 2.0f);
        // b[len + 5]: clamped to the last, or "" from an empty b (n = 1).
        EXPECT_EQ(vm.paramStrings("oob"), std::vector<std::string>{n > 1 ? "s" + std::to_string(n - 2) : ""});
    }
    const std::vector<std::string> w = log.warnings();
    EXPECT_EQ(countWith(w, "strs.sl:15:"), 1u);  // the empty pop, once over three grids
    EXPECT_EQ(countWith(w, "pop of 'a', which is empty: \"\""), 1u);
    EXPECT_EQ(countWith(w, "strs.sl:19:"), 1u);  // b[len + 5], once
}

// An unsized string parameter takes as many strings as it is given (its default's otherwise).
TEST(ResizableArrays, AnUnsizedStringParameterTakesTheLengthOfItsValue) {
    ProgramPtr p = compileShader(
        "surface names(string s[] = {\"a\", \"b\"}; output uniform float count = -1; output uniform string first = \"\") {\n"
        "  count = arraylength(s);\n"
        "  push(s, \"z\");\n"
        "  first = s[0];\n"
        "}\n",
        "names.sl");
    EXPECT_EQ(p->params[0].type.name(), "string[]");
    EXPECT_EQ(p->params[0].defaultStrings, (std::vector<std::string>{"a", "b"}));
    ShaderInstance byDefault(p), given(p), none(p);
    given.setStrings("s", {"x", "y", "w", "v"}, {});
    none.setStrings("s", {}, {});
    ShadingVM vm;
    TestGrid g = uGrid();
    vm.run(given, g.grid);
    EXPECT_EQ(vm.output("count").at(0, 0), 4.0f);
    EXPECT_EQ(vm.paramStrings("s"), (std::vector<std::string>{"x", "y", "w", "v", "z"}));
    EXPECT_EQ(vm.paramStrings("first"), std::vector<std::string>{"x"});
    vm.run(byDefault, g.grid);
    EXPECT_EQ(vm.output("count").at(0, 0), 2.0f);
    EXPECT_EQ(vm.paramStrings("s"), (std::vector<std::string>{"a", "b", "z"}));
    vm.run(none, g.grid);
    EXPECT_EQ(vm.output("count").at(0, 0), 0.0f);
    EXPECT_EQ(vm.paramStrings("first"), std::vector<std::string>{"z"});
}

TEST(ResizableArrays, StringArrayMisuseIsACompileErrorAtItsPlace) {
    expectError("surface s() {\n  string f[2] = {\"a\", \"b\"};\n  push(f, \"c\");\n}\n", 3, 8,
                "push of 'f', a string[2] of fixed length: only arrays declared without a length (string f[])");
    expectError("surface s() {\n  string a[];\n  push(a, 1);\n}\n", 3, 11, "cannot use a float");
    expectError("surface s() {\n  string a[];\n  float x = pop(a);\n}\n", 3, 13, "cannot use a string");
    expectError("surface s() {\n  string a[];\n  if (u > 0.5)\n    push(a, \"x\");\n}\n", 4, 5,
                "push of 'a' under a varying condition");
    expectError("surface s() {\n  string a[];\n  resize(a, \"x\");\n}\n", 3, 13, "resize's length");
}

}  // namespace
}  // namespace streyes::sl
