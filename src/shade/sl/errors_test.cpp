// Bad shaders: every error names file:line:column and says what is wrong.
#include <gtest/gtest.h>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::compileError;

// The error starts with "test.sl:line:column: " and contains `what`.
void expectError(const std::string& src, int line, int column, const std::string& what) {
    std::string msg = compileError(src);
    SCOPED_TRACE(src);
    const std::string where = "test.sl:" + std::to_string(line) + ":" + std::to_string(column) + ": ";
    EXPECT_EQ(msg.rfind(where, 0), 0u) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
}

TEST(SlLexer, Errors) {
    expectError("surface s() {\n  Ci = 1 @ 2;\n}\n", 2, 10, "unexpected character '@'");
    expectError("surface s() {\n  string a = \"abc\n}\n", 2, 14, "unterminated string");
    expectError("surface s() { /* never closed\n}\n", 1, 15, "unterminated comment");
    expectError("#include \"x.h\"\nsurface s() {}\n", 1, 1, "#include \"x.h\": no such file");
    expectError("surface s() {\n  float a = 1.5x;\n}\n", 2, 16, "after the number 1.5");
}

TEST(SlLexer, CommentsStringsAndNumbers) {
    ProgramPtr p = test::compile(
        "// line comment\n/* block\n comment */\n#pragma once\n"
        "surface s(string n = \"a\" \"b\\tc\"; float x = 1e-2; float y = .5; float z = 2.;) { Ci = x + y + z; }");
    EXPECT_EQ(p->params[0].defaultStrings[0], "ab\tc");
    EXPECT_FLOAT_EQ(p->params[1].defaultFloats[0], 0.01f);
    EXPECT_FLOAT_EQ(p->params[2].defaultFloats[0], 0.5f);
    EXPECT_FLOAT_EQ(p->params[3].defaultFloats[0], 2.0f);
}

TEST(SlParser, Errors) {
    expectError("surface s() {\n  Ci = (1 + ;\n}\n", 2, 13, "expected an expression, found ';'");
    expectError("surface s() {\n  Ci = 1\n}\n", 3, 1, "expected ';' after the expression, found '}'");
    expectError("surface s(float Kd) { Ci = Kd; }", 1, 17, "parameter 'Kd' needs a default value");
    expectError("surface s() {\n  if (1) { Ci = 0; \n", 3, 1, "expected '}'");
    expectError("surface s() { } surface t() { }", 1, 17, "a second shader in one file");
    expectError("float f(float x) { return x; }", 1, 31, "no shader defined");
    expectError("surface s() {\n  else Ci = 1;\n}", 2, 3, "'else' without 'if'");
    expectError("surface s() {\n  Ci = (1, 2);\n}", 2, 8, "a tuple has 3 values");
    expectError("surface s() {\n  float a[0];\n}", 2, 11, "positive whole array length");
    expectError("surface s() {\n  float f(float x) { return x; }\n}", 2, 3, "functions cannot be defined inside");
    expectError("transformation t() {}", 1, 1, "transformation shaders are not supported");
}

TEST(SlChecker, UndefinedNamesAndFunctions) {
    expectError("surface s() {\n  Ci = Kd;\n}", 2, 8, "undefined variable 'Kd'");
    expectError("surface s() {\n  Ci = frobnicate(P);\n}", 2, 8, "unknown function 'frobnicate'");
    expectError("surface s() {\n  float a = 1;\n  float a = 2;\n}", 3, 9, "'a' is already declared in this scope");
    // A function sees the shader's parameters only through extern.
    expectError("float f() { return Kd; }\nsurface s(float Kd = 1) { Ci = f(); }", 1, 20, "undefined variable 'Kd'");
    expectError("float f() { extern float Kx; return Kx; }\nsurface s(float Kd = 1) { Ci = f(); }", 1, 26,
                "extern 'Kx' names no shader parameter");
}

TEST(SlChecker, TypeErrors) {
    expectError("surface s() {\n  float a = P;\n}", 2, 13, "cannot use a point as 'a' (float)");
    expectError("surface s() {\n  Ci = P;\n}", 2, 8, "cannot use a point as the value of 'Ci' (color)");
    expectError("surface s() {\n  Ci = Cs + P;\n}", 2, 11, "'+' cannot take a color and a point");
    expectError("surface s() {\n  float d = Cs . Cs;\n}", 2, 16, "'.' cannot take a color and a color");
    expectError("surface s() {\n  if (P) Ci = 1;\n}", 2, 7, "a condition must be a float");
    expectError("surface s() {\n  string x = \"a\";\n  Ci = x * 2;\n}", 3, 10, "'*' cannot take a string and a float");
    expectError("surface s() {\n  float a = 1;\n  float b = a[0];\n}", 3, 14, "only arrays can be indexed");
    expectError("surface s() {\n  E = P;\n}", 2, 3, "'E' is read-only");
    expectError("surface s() {\n  float a[2] = {1, 2, 3};\n}", 2, 16, "has 2 elements, the initialiser 3");
    EXPECT_EQ(compileError("surface s() {\n  Ci = color \"hsv\" P;\n}"), "");  // a point is a triple: allowed
    expectError("surface s() {\n  float x = float \"world\" 1;\n}", 2, 13, "only colors, points, vectors, normals and matrices take a space");
}

TEST(SlChecker, ArgumentCounts) {
    expectError("surface s() {\n  float a = sqrt(1, 2);\n}", 2, 13, "no form of 'sqrt' takes (float, float)");
    expectError("float f(float x) { return x; }\nsurface s() {\n  Ci = f(1, 2);\n}", 3, 8, "'f' takes 1 argument, not 2");
    expectError("surface s() {\n  Ci = mix(Cs, Cs);\n}", 2, 8, "no form of 'mix' takes (color, color)");
    expectError("surface s() {\n  float t = texture(\"a\", s);\n}", 2, 13, "texture takes (name), (name, s, t)");
    expectError("surface s() {\n  float t = texture(\"a\", s, t, \"blurr\", 1);\n}", 2, 32, "unknown texture option \"blurr\"");
    expectError("surface s() {\n  illuminance(P, N) { Ci += Cl; }\n}", 2, 3, "illuminance takes");
    expectError("surface s() {\n  illuminate(P) { Cl = 1; }\n}", 2, 3, "illuminate is only for light shaders");
    expectError("light l() {\n  illuminance(P) { Cl = 1; }\n}", 2, 3, "illuminance is only for surface and volume");
    expectError("float f(float x) { x = 2; return x; }\nsurface s() { Ci = f(1); }", 1, 20,
                "'x' is a parameter of 'f' not declared output");
    expectError("void f(output float x) { x = 2; }\nsurface s() {\n  f(1);\n}", 3, 5, "must be a variable");
}

TEST(SlChecker, StatementsInTheirPlace) {
    expectError("surface s() {\n  break;\n}", 2, 3, "break outside a loop");
    expectError("surface s() {\n  while (1) { continue 2; }\n}", 2, 15, "continue out of more loops");
    expectError("surface s() {\n  return 1;\n}", 2, 10, "a shader returns no value");
    expectError("float f() { return; }\nsurface s() { Ci = f(); }", 1, 13, "'f' must return a float");
    expectError("void f() { return 1; }\nsurface s() { f(); }", 1, 19, "'f' returns no value");
}

TEST(SlChecker, VaryingToUniform) {
    expectError("surface s() {\n  uniform float a = s;\n}", 2, 17, "cannot assign a varying value to uniform variable 'a'");
    expectError("surface s(float Kd = 1) {\n  Kd = t;\n}", 2, 6, "cannot assign a varying value to uniform variable 'Kd'");
    expectError("surface s() {\n  uniform float a = 0;\n  if (s > .5) a = 1;\n}", 3, 17,
                "cannot assign to uniform variable 'a' under a varying condition");
    expectError("surface s(float Kd = s) { Ci = Kd; }", 1, 22, "cannot assign a varying value to uniform variable 'Kd'");
    expectError("float f(uniform float x) { return x; }\nsurface s() {\n  Ci = f(u);\n}", 3, 10,
                "parameter 'x' of f is uniform; the value passed is varying");
    // Not errors: a variable without a storage class becomes varying; so does a varying one.
    EXPECT_EQ(compileError("surface s() { float a = 0; if (s > .5) a = 1; Ci = a; }"), "");
    EXPECT_EQ(compileError("surface s() { varying float a = 1; Ci = a; }"), "");
}

TEST(SlChecker, RecursionIsRefused) {
    expectError("float f(float x) { return f(x); }\nsurface s() { Ci = f(1); }", 1, 27, "'f' calls itself");
}

}  // namespace
}  // namespace streyes::sl
