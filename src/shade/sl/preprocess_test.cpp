// The C preprocessor in front of the compiler, used the way shader libraries use it: headers in a
// folder of their own, macros with arguments, #if on the renderer's name. Errors name the
// original file:line:column through includes and macros.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

namespace fs = std::filesystem;
using test::TestGrid;

struct ScratchDir {
    fs::path path;
    ScratchDir() {
        path = fs::temp_directory_path() / ("streyes-pp-" + std::to_string(::getpid()) + "-" +
                                            std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
        fs::create_directories(path);
    }
    ~ScratchDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    std::string write(const std::string& name, const std::string& text) const {
        const fs::path p = path / name;
        fs::create_directories(p.parent_path());
        std::ofstream(p) << text;
        return p.string();
    }
    std::string dir(const std::string& name) const { return (path / name).string(); }
};

// The message of the InputError compiling `file` throws ("" when it compiles).
std::string errorOf(const std::string& file, const PreprocessOptions& options = {}) {
    try {
        compileShaderFile(file, options);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// A 16 x 16 grid with s, t and P varying: what the shaders below read.
TestGrid stGrid() {
    TestGrid g(15, 15);
    g.setVarying(Global::s, 1, [](int i) { return Vec3f{float(i % 16) / 15.0f, 0, 0}; });
    g.setVarying(Global::t, 1, [](int i) { return Vec3f{float(i / 16) / 15.0f, 0, 0}; });
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{float(i % 16) * 0.1f, float(i / 16) * 0.1f, 1}; });
    return g;
}

// Ci of `program` over stGrid(), every component of every point.
std::vector<float> shade(const ProgramPtr& program) {
    TestGrid g = stGrid();
    ShaderInstance inst(program);
    ShadingVM vm;
    vm.run(inst, g.grid);
    std::vector<float> out;
    ValueRef ci = vm.result(Global::Ci);
    for (int i = 0; i < g.n(); ++i)
        for (int c = 0; c < 3; ++c) out.push_back(ci.at(c, i));
    return out;
}

const char* kLibrary =
    "#ifndef STRIPES_H\n"
    "#define STRIPES_H\n"
    "/* What rmannotes.sl and patterns.sl are made of: functions and macros with arguments. */\n"
    "#define PULSE(a, b, fuzz, x) (smoothstep((a) - (fuzz), (a), (x)) - smoothstep((b) - (fuzz), (b), (x)))\n"
    "#define REPEAT(x, freq) (mod((x) * (freq), 1.0))\n"
    "float bands(float x; float n) {\n"
    "    float f = REPEAT(x, n);\n"
    "    return PULSE(0.25, 0.75, 0.1, f);\n"
    "}\n"
    "#endif\n";

// Shaded through the header (found along -I, included twice: the guard holds) and the
// renderer's name; and the same code written out by hand: the same grid, bit for bit.
TEST(SlPreprocess, AnIncludedFunctionAndAMacroGiveTheGridOfTheCodeWrittenOut) {
    ScratchDir dir;
    dir.write("include/stripes.h", kLibrary);
    const std::string viaHeader = dir.write("shaders/stripes.sl",
                                            "#include \"stripes.h\"\n"
                                            "#include <stripes.h>\n"
                                            "#define MIXC(a, b, x) ((a) + ((b) - (a)) * (x))\n"
                                            "surface stripes(float freq = 4) {\n"
                                            "#if defined(STREYES) && !defined(AQSIS)\n"
                                            "    float m = bands(s, freq) * REPEAT(t, 2);\n"
                                            "#elif defined(AQSIS)\n"
                                            "    float m = 0;\n"
                                            "#else\n"
                                            "    float m = 1;\n"
                                            "#endif\n"
                                            "    Ci = MIXC(color(1, 0, 0), color(0, 0.5, 1), m);\n"
                                            "}\n");
    const std::string writtenOut = dir.write("shaders/plain.sl",
                                             "float bands(float x; float n) {\n"
                                             "    float f = (mod((x) * (n), 1.0));\n"
                                             "    return (smoothstep((0.25) - (0.1), (0.25), (f)) - smoothstep((0.75) - (0.1), (0.75), (f)));\n"
                                             "}\n"
                                             "surface stripes(float freq = 4) {\n"
                                             "    float m = bands(s, freq) * (mod((t) * (2), 1.0));\n"
                                             "    Ci = ((color(1, 0, 0)) + ((color(0, 0.5, 1)) - (color(1, 0, 0))) * (m));\n"
                                             "}\n");
    PreprocessOptions options;
    options.includePath = {dir.dir("include")};
    ProgramPtr a = compileShaderFile(viaHeader, options);
    ProgramPtr b = compileShaderFile(writtenOut);
    const std::vector<float> ga = shade(a), gb = shade(b);
    ASSERT_EQ(ga.size(), gb.size());
    EXPECT_EQ(std::memcmp(ga.data(), gb.data(), ga.size() * sizeof(float)), 0);
    // Not a trivial grid: red where the bands are off, blends towards blue where they are on.
    float lo = 1, hi = 0;
    for (size_t i = 0; i < ga.size(); i += 3) {
        lo = std::min(lo, ga[i]);
        hi = std::max(hi, ga[i]);
    }
    EXPECT_LT(lo, 0.25f);
    EXPECT_EQ(hi, 1.0f);
    // The header is among the program's sources (what the shader cache keys on).
    ASSERT_EQ(a->sources.size(), 2u);
    EXPECT_EQ(a->sources[0], viaHeader);
    EXPECT_EQ(fs::path(a->sources[1]).filename(), "stripes.h");
}

// #include "x" looks in the including file's folder, then along the path in order;
// #include <x> along the path only. A header's own includes start from its folder.
TEST(SlPreprocess, IncludeSearchOrder) {
    ScratchDir dir;
    dir.write("shaders/which.h", "#define WHICH 1\n");
    dir.write("first/which.h", "#define WHICH 2\n");
    dir.write("second/which.h", "#define WHICH 3\n");
    dir.write("second/nested/inner.h", "#include \"../which.h\"\n#define INNER WHICH\n");
    PreprocessOptions options;
    options.includePath = {dir.dir("first"), dir.dir("second")};
    auto value = [&](const std::string& name, const std::string& text) {
        ProgramPtr p = compileShaderFile(dir.write("shaders/" + name, text), options);
        return p->params[0].defaultFloats[0];
    };
    EXPECT_EQ(value("q.sl", "#include \"which.h\"\nsurface q(float w = WHICH) { Ci = w; }\n"), 1.0f);
    EXPECT_EQ(value("a.sl", "#include <which.h>\nsurface a(float w = WHICH) { Ci = w; }\n"), 2.0f);
    EXPECT_EQ(value("n.sl", "#include \"nested/inner.h\"\nsurface n(float w = INNER) { Ci = w; }\n"), 3.0f);
    fs::remove(dir.path / "shaders/which.h");
    EXPECT_EQ(value("q2.sl", "#include \"which.h\"\nsurface q2(float w = WHICH) { Ci = w; }\n"), 2.0f);
}

TEST(SlPreprocess, DefineUndefConditionalsAndLine) {
    ProgramPtr p = test::compile(
        "#define K 3\n"
        "#define TWICE(x) (2 * (x))\n"
        "#ifdef K\n#define A TWICE(K)\n#else\n#define A 0\n#endif\n"
        "#define Z 1\n#undef Z\n"
        "#ifndef Z\n#define B 5\n#endif\n"
        "#if B > 4 && defined(TWICE)\n#define C 1\n#elif 1\n#define C 2\n#endif\n"
        "#if STREYES\n#define D 7\n#endif\n"
        "surface s(float a = A; float b = B; float c = C; float d = D; float f = 0.25f) { Ci = a; }\n");
    ASSERT_EQ(p->params.size(), 5u);
    EXPECT_EQ(p->params[0].defaultFloats[0], 6.0f);
    EXPECT_EQ(p->params[1].defaultFloats[0], 5.0f);
    EXPECT_EQ(p->params[2].defaultFloats[0], 1.0f);
    EXPECT_EQ(p->params[3].defaultFloats[0], 7.0f);
    EXPECT_EQ(p->params[4].defaultFloats[0], 0.25f);  // C's float suffix, as RenderMan's compilers accept it

    // #line renames and renumbers what follows: errors say so.
    const std::string msg = test::compileError("#line 100 \"original.sl\"\nsurface s() {\n  Ci = nope;\n}\n");
    EXPECT_EQ(msg.rfind("original.sl:101:8: ", 0), 0u) << msg;
}

// Strings come through the C preprocessor as they were written: "\%" (an escape C lacks, which
// format strings use), runs of spaces, what would be a comment or a character constant in C.
TEST(SlPreprocess, StringsKeepWhatTheySay) {
    ProgramPtr p = test::compile(
        "#define NAME \"k\"\n"
        "surface s(string a = \"x  \\% y\"; string b = \"it's # fine // not /* a comment */\";\n"
        "          string c = NAME; float after = 2) {\n"
        "  Ci = after;\n"
        "}\n");
    EXPECT_EQ(p->params[0].defaultStrings[0], "x  \\% y");
    EXPECT_EQ(p->params[1].defaultStrings[0], "it's # fine // not /* a comment */");
    EXPECT_EQ(p->params[2].defaultStrings[0], "k");
    EXPECT_EQ(p->params[3].defaultFloats[0], 2.0f);
    // Columns after such a string are where they were written.
    const std::string msg = test::compileError("surface s(string a = \"\\%\") {\n  Ci = \"\\%\" + nope;\n}\n");
    EXPECT_EQ(msg.rfind("test.sl:2:15: undefined variable 'nope'", 0), 0u) << msg;
}

// The error starts with `where` ("file:line:column: ") and contains `what`.
void expectAt(const std::string& msg, const std::string& where, const std::string& what) {
    EXPECT_EQ(msg.rfind(where, 0), 0u) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
}

TEST(SlPreprocess, ErrorsNameTheOriginalFileLineAndColumn) {
    ScratchDir dir;
    // An #include that is not found: the directive's '#'.
    const std::string missing = dir.write("missing.sl", "surface s() {\n   #include \"nothere.h\"\n}\n");
    expectAt(errorOf(missing), missing + ":2:4: ", "#include \"nothere.h\": no such file");
    // A macro with the wrong number of arguments: the call.
    const std::string args = dir.write("args.sl", "#define SQ(x) ((x) * (x))\nsurface s() {\n  Ci = SQ(1, 2);\n}\n");
    expectAt(errorOf(args), args + ":3:8: ", "too many arguments for macro 'SQ': it takes 1 (x), defined at " + args + ":1:");
    const std::string few = dir.write("few.sl", "#define MIX3(a, b, c) ((a) + (b) + (c))\nsurface s() {\n  Ci = MIX3(1, 2);\n}\n");
    expectAt(errorOf(few), few + ":3:8: ", "too few arguments for macro 'MIX3'");
    // An #if without its #endif: the #if, in the file where it is.
    dir.write("open.h", "float f() { return 1; }\n#ifdef NEVER\nfloat g() { return 2; }\n");
    const std::string open = dir.write("open.sl", "#include \"open.h\"\nsurface s() { Ci = f(); }\n");
    expectAt(errorOf(open), dir.dir("open.h") + ":2:1: ", "this #if has no #endif");
    const std::string open2 = dir.write("open2.sl", "surface s() {\n#if 1\n  Ci = 1;\n#if 0\n#endif\n}\n");
    expectAt(errorOf(open2), open2 + ":2:1: ", "this #if has no #endif");
    // Recursion through includes: the #include that goes round again.
    dir.write("a.h", "#include \"b.h\"\n");
    dir.write("b.h", "float q = 1;\n#include \"a.h\"\n");
    const std::string loop = dir.write("loop.sl", "#include \"a.h\"\nsurface s() {}\n");
    expectAt(errorOf(loop), dir.dir("b.h") + ":2:1: ", "recursion through #include");
    // #error says what the library says.
    const std::string stop = dir.write("stop.sl", "#ifndef STREYES\n#endif\n#if !defined(AQSIS)\n#error needs Aqsis\n#endif\n");
    expectAt(errorOf(stop), stop + ":4:1: ", "needs Aqsis");
}

TEST(SlPreprocess, ErrorsInHeadersAndMacrosPointThere) {
    ScratchDir dir;
    // A type error in an included function: the header's line and column.
    dir.write("lib/bad.h", "float f(float x) {\n    return x + nope;\n}\n");
    const std::string uses = dir.write("uses.sl", "#include \"lib/bad.h\"\nsurface s() { Ci = f(s); }\n");
    expectAt(errorOf(uses), dir.dir("lib/bad.h") + ":2:16: ", "undefined variable 'nope'");
    // An error a macro's body makes: the #define, and which call it is.
    const std::string macro = dir.write("macro.sl",
                                        "#define HALF(x) ((x) / 2 + missing)\n"
                                        "surface s() {\n  float a = 1;\n  Ci = HALF(a);\n}\n");
    expectAt(errorOf(macro), macro + ":1:28: ", "undefined variable 'missing' (in the expansion of the macro at " + macro + ":4:8)");
    // A macro naming the header makes no text: the error after it is no expansion's.
    dir.write("lib/empty.h", "\n");
    const std::string named = dir.write("named.sl", "#define HDR \"lib/empty.h\"\n#include HDR\nnope s() {}\n");
    const std::string namedMsg = errorOf(named);
    expectAt(namedMsg, named + ":3:1: ", "found 'nope'");
    EXPECT_EQ(namedMsg.find("in the expansion"), std::string::npos) << namedMsg;
    // An argument's own error: where the argument is written.
    const std::string arg = dir.write("arg.sl", "#define HALF(x) ((x) / 2)\nsurface s() {\n  Ci = HALF(1 + nope);\n}\n");
    expectAt(errorOf(arg), arg + ":3:17: ", "undefined variable 'nope'");
}

TEST(SlPreprocess, WarningsGoWithTheProgram) {
    ProgramPtr p = test::compile("#define A 1\n#define A 2\n#warning check this\nsurface s(float a = A) { Ci = a; }\n");
    ASSERT_EQ(p->warnings.size(), 2u);
    EXPECT_EQ(p->warnings[0].str(), "test.sl:2:1: warning: macro 'A' is defined again differently: the first definition is kept");
    EXPECT_EQ(p->warnings[1].str(), "test.sl:3:1: warning: #warning check this");
    EXPECT_EQ(p->params[0].defaultFloats[0], 1.0f);  // as Aqsis (Boost.Wave) keeps it
}

// The cache compiles a shader again when a header it included changes.
TEST(SlPreprocess, TheCacheKeysOnIncludedFiles) {
    ScratchDir dir;
    dir.write("lib/k.h", "#define K 1\n");
    dir.write("shaders/glow.sl", "#include <k.h>\nsurface glow(float k = K) { Ci = k; }\n");
    ShaderCache cache({dir.dir("shaders"), dir.dir("lib")});
    EXPECT_EQ(cache.get("glow")->params[0].defaultFloats[0], 1.0f);
    EXPECT_EQ(cache.get("glow")->params[0].defaultFloats[0], 1.0f);
    EXPECT_EQ(cache.compiledCount(), 1u);
    dir.write("lib/k.h", "#define K 2\n");
    fs::last_write_time(dir.path / "lib/k.h", fs::last_write_time(dir.path / "lib/k.h") + std::chrono::seconds(5));
    EXPECT_EQ(cache.get("glow")->params[0].defaultFloats[0], 2.0f);
    EXPECT_EQ(cache.compiledCount(), 2u);
    // Another search path may find other headers: compiled again.
    dir.write("other/k.h", "#define K 3\n");
    cache.setSearchPath(dir.dir("shaders") + ":" + dir.dir("other"));
    EXPECT_EQ(cache.get("glow")->params[0].defaultFloats[0], 3.0f);
    EXPECT_EQ(cache.compiledCount(), 3u);
}

}  // namespace
}  // namespace streyes::sl
