// option(), attribute(), rendererinfo(), textureinfo(): 1 and the variable written when the
// value exists and fits it, else 0 and the variable left alone (RI Spec 3.2, section 15.8).
#include <gtest/gtest.h>

#include <map>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

struct FakeState final : StateQueries {
    std::map<std::string, QueryValue> options, attributes;
    bool option(const std::string& name, QueryValue& out) const override { return find(options, name, out); }
    bool attribute(const std::string& name, QueryValue& out) const override { return find(attributes, name, out); }
    static bool find(const std::map<std::string, QueryValue>& m, const std::string& name, QueryValue& out) {
        auto it = m.find(name);
        if (it == m.end()) return false;
        out = it->second;
        return true;
    }
};

struct FakeTextures final : TextureSource {
    bool texture(const std::string&, const TextureOptions&, const TextureQuery&, float* const*) override { return false; }
    bool environment(const std::string&, const TextureOptions&, const DirectionQuery&, float* const*) override { return false; }
    bool shadow(const std::string&, const TextureOptions&, const DirectionQuery&, float* const*) override { return false; }
    bool textureInfo(const std::string& name, const std::string& field, QueryValue& out) override {
        if (name != "grid.tex") return false;
        if (field == "resolution") out = QueryValue::numbers({256, 128});
        else if (field == "type") out = QueryValue::string("texture");
        else return false;
        return true;
    }
};

struct QueryRun {
    FakeState state;
    FakeTextures textures;
    TestGrid g{3, 3};
    ShadingVM vm;
    QueryRun() {
        state.options["Format"] = QueryValue::numbers({640, 480, 1});
        state.options["user:pass"] = QueryValue::string("beauty");
        QueryValue c;
        c.type = BaseType::Color;
        c.floats = {0.25f, 0.5f, 0.75f};
        state.options["user:tint"] = c;
        state.attributes["ShadingRate"] = QueryValue::numbers({0.5f});
        state.attributes["identifier:name"] = QueryValue::string("ball");
        g.grid.state = &state;
        g.setVarying(Global::s, 1, [](int i) { return Vec3f{float(i) / 15.0f, 0, 0}; });
        vm.setTextureSource(&textures);
    }
    void run(const std::string& src) {
        ShaderInstance inst(test::compile(src));
        vm.run(inst, g.grid);
    }
    float out(const std::string& name, int element = 0, int i = 0) { return vm.param(name, element).at(0, i); }
};

TEST(VmInfo, OptionFillsVariablesThatFit) {
    QueryRun r;
    r.run("surface s(output uniform float fmt[3] = {0, 0, 0}; output uniform float ok[6] = {9, 9, 9, 9, 9, 9};\n"
          "          output uniform float small = -1; output uniform color tint = 0; output uniform float pass = 0) {\n"
          "  ok[0] = option(\"Format\", fmt);\n"
          "  ok[1] = option(\"Format\", small);\n"       // a float[3] does not fit a float: 0, left alone
          "  string p = \"\";\n"
          "  ok[2] = option(\"user:pass\", p);\n"
          "  pass = p == \"beauty\" ? 1 : 0;\n"
          "  ok[3] = option(\"user:tint\", tint);\n"
          "  ok[4] = option(\"user:nosuch\", small);\n"
          "  float f[2] = {7, 7};\n"
          "  ok[5] = option(\"Format\", f);\n"          // two elements cannot hold three
          "}\n");
    EXPECT_EQ(r.out("fmt", 0), 640.0f);
    EXPECT_EQ(r.out("fmt", 1), 480.0f);
    EXPECT_EQ(r.out("fmt", 2), 1.0f);
    const float expected[6] = {1, 0, 1, 1, 0, 0};
    for (int k = 0; k < 6; ++k) EXPECT_EQ(r.out("ok", k), expected[k]) << k;
    EXPECT_EQ(r.out("small"), -1.0f);
    EXPECT_EQ(r.out("pass"), 1.0f);
    EXPECT_EQ(test::at3(r.vm.param("tint"), 0).y, 0.5f);
}

// Without a renderer state (a shader checked alone) every query gives 0.
TEST(VmInfo, WithoutStateQueriesGiveZero) {
    QueryRun r;
    r.g.grid.state = nullptr;
    r.run("surface s(output uniform float ok = 9; output uniform float fmt[3] = {5, 5, 5}) {\n"
          "  ok = option(\"Format\", fmt) + attribute(\"ShadingRate\", fmt[0]);\n}\n");
    EXPECT_EQ(r.out("ok"), 0.0f);
    EXPECT_EQ(r.out("fmt", 0), 5.0f);
}

// attribute() into a varying variable under a varying condition: only the points that run.
TEST(VmInfo, AttributeUnderAVaryingCondition) {
    QueryRun r;
    r.run("surface s(output varying float rate = 0; output uniform float named = 0) {\n"
          "  rate = -s;\n"
          "  if (s > 0.5) attribute(\"ShadingRate\", rate);\n"
          "  string n = \"\";\n"
          "  named = attribute(\"identifier:name\", n) + (n == \"ball\" ? 10 : 0);\n"
          "}\n");
    for (int i = 0; i < r.g.n(); ++i) {
        const float s = float(i) / 15.0f;
        EXPECT_EQ(r.out("rate", 0, i), s > 0.5f ? 0.5f : -s) << i;
    }
    EXPECT_EQ(r.out("named"), 11.0f);
}

// rendererinfo() names streyes and its version, and the two agree.
TEST(VmInfo, RendererInfo) {
    QueryRun r;
    r.run("surface s(output uniform float ok[4] = {0, 0, 0, 0}; output uniform float v[4] = {-1, -1, -1, -1}) {\n"
          "  string name = \"\", vs = \"\";\n"
          "  ok[0] = rendererinfo(\"renderer\", name) * (name == \"streyes\" ? 1 : 0);\n"
          "  ok[1] = rendererinfo(\"version\", v);\n"
          "  ok[2] = rendererinfo(\"versionstring\", vs) * (format(\"%d.%d.%d\", v[0], v[1], v[2]) == vs ? 1 : 0);\n"
          "  ok[3] = rendererinfo(\"nosuch\", name);\n"
          "}\n");
    EXPECT_EQ(r.out("ok", 0), 1.0f);
    EXPECT_EQ(r.out("ok", 1), 1.0f);
    EXPECT_EQ(r.out("ok", 2), 1.0f);
    EXPECT_EQ(r.out("ok", 3), 0.0f);
    EXPECT_GE(r.out("v", 0), 0.0f);
    EXPECT_EQ(r.out("v", 3), 0.0f);
}

TEST(VmInfo, TextureInfoAsksTheTextureSource) {
    QueryRun r;
    r.run("surface s(output uniform float res[2] = {0, 0}; output uniform float ok[3] = {9, 9, 9}) {\n"
          "  ok[0] = textureinfo(\"grid.tex\", \"resolution\", res);\n"
          "  string t = \"\";\n"
          "  ok[1] = textureinfo(\"grid.tex\", \"type\", t) * (t == \"texture\" ? 1 : 0);\n"
          "  ok[2] = textureinfo(\"nosuch.tex\", \"resolution\", res);\n"
          "}\n");
    EXPECT_EQ(r.out("res", 0), 256.0f);
    EXPECT_EQ(r.out("res", 1), 128.0f);
    EXPECT_EQ(r.out("ok", 0), 1.0f);
    EXPECT_EQ(r.out("ok", 1), 1.0f);
    EXPECT_EQ(r.out("ok", 2), 0.0f);
}

TEST(VmInfo, ShaderName) {
    QueryRun r;
    r.run("surface glossy(output uniform float ok = 0) { ok = shadername() == \"glossy\" ? 1 : 0; }\n");
    EXPECT_EQ(r.out("ok"), 1.0f);
}

TEST(VmInfo, BadCallsAreCompileErrors) {
    EXPECT_NE(test::compileError("surface s() { float f; option(1, f); }").find("option takes (string name, output variable)"),
              std::string::npos);
    EXPECT_NE(test::compileError("surface s() { option(\"Format\", 1); }").find("must be a variable"), std::string::npos);
    EXPECT_NE(test::compileError("surface s() { float f; textureinfo(\"a\", f); }").find("textureinfo takes (string map"),
              std::string::npos);
}

}  // namespace
}  // namespace streyes::sl
