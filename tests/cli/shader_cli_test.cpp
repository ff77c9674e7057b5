// `streyes shader` and shaders in `streyes render` from the command line: parameters printed,
// bad shaders and bindings exit 2 naming the shader's file:line:column or the RIB's file:line,
// and no frame is written.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_run.h"
#include "test_util.h"

namespace streyes::test {
namespace {

TEST(ShaderCli, PrintsTheParametersOfAShippedShader) {
    CliRun r = runStreyes("shader " + sourcePath("shaders/spotlight.sl"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("light \"spotlight\""), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("coneangle"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("beamdistribution"), std::string::npos) << r.output;
}

TEST(ShaderCli, ABadShaderExitsTwoAtItsLineAndColumn) {
    const TempDir dir("shader-cli");
    const std::string sl = writeFile(dir.path(), "bad.sl", "surface bad() {\n  Ci = 1 +;\n}\n");
    CliRun check = runStreyes("shader " + sl);
    EXPECT_EQ(check.exitCode, 2);
    EXPECT_NE(check.output.find("bad.sl:2:"), std::string::npos) << check.output;

    // The same shader named by a scene: the render stops before writing anything.
    const std::string rib = writeFile(dir.path(), "scene.rib",
                                      "Format 16 16 1\nProjection \"orthographic\"\nWorldBegin\nSurface \"bad\"\n"
                                      "Patch \"bilinear\" \"P\" [-1 -1 5 1 -1 5 -1 1 5 1 1 5]\nWorldEnd\n");
    CliRun render = runStreyes("render " + rib + " -o " + dir.path() + "/out.####.exr");
    EXPECT_EQ(render.exitCode, 2) << render.output;
    EXPECT_NE(render.output.find("bad.sl:2:"), std::string::npos) << render.output;
    EXPECT_FALSE(std::filesystem::exists(dir.path() + "/out.0000.exr"));

    // A parameter the shader declares otherwise: the RIB line.
    writeFile(dir.path(), "good.sl", "surface good(float k = 1) { Ci = k; }\n");
    const std::string rib2 = writeFile(dir.path(), "scene2.rib",
                                       "Format 16 16 1\nProjection \"orthographic\"\nWorldBegin\n"
                                       "Surface \"good\" \"string k\" \"no\"\n"
                                       "Patch \"bilinear\" \"P\" [-1 -1 5 1 -1 5 -1 1 5 1 1 5]\nWorldEnd\n");
    CliRun wrong = runStreyes("render " + rib2 + " -o " + dir.path() + "/out2.####.exr");
    EXPECT_EQ(wrong.exitCode, 2) << wrong.output;
    EXPECT_NE(wrong.output.find("scene2.rib:4:"), std::string::npos) << wrong.output;
    EXPECT_FALSE(std::filesystem::exists(dir.path() + "/out2.0000.exr"));
}

}  // namespace
}  // namespace streyes::test

namespace streyes::test {
namespace {

// -I DIR: where #include files are looked for after the shader's own folder; errors through
// includes and macros exit 2 at the original file:line:column.
TEST(ShaderCli, IncludePathsAndPreprocessorErrors) {
    const TempDir dir("shader-cli-pp");
    std::filesystem::create_directories(dir.path() + "/lib");
    writeFile(dir.path() + "/lib", "pattern.h", "#define STRIPE(x, n) mod(floor((x) * (n)), 2)\n");
    const std::string sl = writeFile(dir.path(), "striped.sl",
                                     "#include \"pattern.h\"\n#if defined(STREYES)\n"
                                     "surface striped(float n = 4) { Ci = STRIPE(s, n); }\n#endif\n");
    CliRun without = runStreyes("shader " + sl);
    EXPECT_EQ(without.exitCode, 2);
    EXPECT_NE(without.output.find(sl + ":1:1: error: #include \"pattern.h\": no such file"), std::string::npos) << without.output;
    CliRun with = runStreyes("shader -I " + dir.path() + "/lib " + sl);
    EXPECT_EQ(with.exitCode, 0) << with.output;
    EXPECT_NE(with.output.find("surface \"striped\""), std::string::npos) << with.output;
    CliRun joined = runStreyes("shader -I" + dir.path() + "/lib " + sl);
    EXPECT_EQ(joined.exitCode, 0) << joined.output;

    const std::string bad = writeFile(dir.path(), "bad.sl",
                                      "#include \"pattern.h\"\nsurface bad() {\n  Ci = STRIPE(s);\n}\n");
    CliRun wrong = runStreyes("shader -I " + dir.path() + "/lib " + bad);
    EXPECT_EQ(wrong.exitCode, 2);
    EXPECT_NE(wrong.output.find(bad + ":3:8: error: too few arguments for macro 'STRIPE'"), std::string::npos) << wrong.output;
    CliRun noDir = runStreyes("shader -I");
    EXPECT_EQ(noDir.exitCode, 2);

    // An #if without its #endif, and headers that include each other.
    const std::string open = writeFile(dir.path(), "open.sl", "surface open() {\n  #if defined(STREYES)\n  Ci = 1;\n}\n");
    CliRun unterminated = runStreyes("shader " + open);
    EXPECT_EQ(unterminated.exitCode, 2);
    EXPECT_NE(unterminated.output.find(open + ":2:3: error: this #if has no #endif"), std::string::npos) << unterminated.output;
    writeFile(dir.path(), "ping.h", "#include \"pong.h\"\n");
    writeFile(dir.path(), "pong.h", "#include \"ping.h\"\n");
    const std::string loop = writeFile(dir.path(), "loop.sl", "#include \"ping.h\"\nsurface loop() {}\n");
    CliRun recursion = runStreyes("shader " + loop);
    EXPECT_EQ(recursion.exitCode, 2);
    EXPECT_NE(recursion.output.find(dir.path() + "/pong.h:1:1: error: recursion through #include"), std::string::npos)
        << recursion.output;
}

}  // namespace
}  // namespace streyes::test
