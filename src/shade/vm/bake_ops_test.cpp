// bake3d(), texture3d() and bake() as the interpreter runs them, through the render's store
// (shade/point_clouds.h): the round trip of baked values, the radius each point stands for, the
// warnings for a missing cloud or channel, and the compiler's refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "shade/point_clouds.h"
#include "shade/vm/vm_test_util.h"
#include "test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

// A 3 x 3 micropolygon grid (16 points) one unit apart in z = 0, facing +z.
TestGrid square() {
    TestGrid g(3, 3);
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{float(i % 4), float(i / 4), 0}; });
    g.setVarying(Global::N, 3, [](int) { return Vec3f{0, 0, 1}; });
    return g;
}

const char* kBake =
    "surface b(string f = \"\") {\n"
    "  float ok = bake3d(f, \"\", P, N, \"v\", xcomp(P) + 10 * ycomp(P), \"c\", color(ycomp(P), 1, 2));\n"
    "  Ci = ok;\n}\n";
const char* kRead =
    "surface r(string f = \"\") {\n"
    "  float v = -1; color c = -1;\n"
    "  float ok = texture3d(f, P, N, \"v\", v, \"c\", c);\n"
    "  Ci = color(v, comp(c, 0), ok);\n}\n";

TEST(VmBake3d, ValuesReadBackExactlyAtTheBakedPoints) {
    streyes::test::TempDir dir("bake3d");
    const std::string file = dir.path() + "/sq.ptc";
    TestGrid g = square();
    Log log;
    {
        PointClouds clouds(log);
        ShaderInstance s(test::compile(kBake));
        s.setStrings("f", {file});
        ShadingVM vm;
        vm.setPointClouds(&clouds);
        vm.run(s, g.grid);
        for (int i = 0; i < 16; ++i) EXPECT_EQ(vm.result(Global::Ci).at(0, i), 1.0f);
        const BakedPointCloud c = clouds.gathered(file);
        ASSERT_EQ(c.size(), 16u);
        // Half the micropolygon's diagonal: sqrt(2) / 2.
        for (size_t i = 0; i < c.size(); ++i) EXPECT_FLOAT_EQ(c.point(i)[6], std::sqrt(2.0f) / 2);
        clouds.write();
    }
    PointClouds clouds(log);
    ShaderInstance s(test::compile(kRead));
    s.setStrings("f", {file});
    ShadingVM vm;
    vm.setPointClouds(&clouds);
    vm.setLog(&log);
    vm.run(s, g.grid);
    const ValueRef ci = vm.result(Global::Ci);
    for (int i = 0; i < 16; ++i) {
        EXPECT_EQ(ci.at(0, i), float(i % 4) + 10 * float(i / 4)) << i;
        EXPECT_EQ(ci.at(1, i), float(i / 4)) << i;
        EXPECT_EQ(ci.at(2, i), 1.0f);
    }
    EXPECT_TRUE(log.warnings().empty());
}

TEST(VmBake3d, InterpolateBakesMicropolygonCentresWithTheirCornersMeanAndReach) {
    TestGrid g = square();
    Log log;
    PointClouds clouds(log);
    ShaderInstance s(test::compile(
        "surface b() {\n  bake3d(\"m\", \"\", P, N, \"v\", xcomp(P), \"interpolate\", 1);\n}\n"));
    ShadingVM vm;
    vm.setPointClouds(&clouds);
    vm.run(s, g.grid);
    const BakedPointCloud c = clouds.gathered("m");
    ASSERT_EQ(c.size(), 9u);  // 3 x 3 micropolygons
    for (size_t i = 0; i < 9; ++i) {
        const float* p = c.point(i);
        EXPECT_EQ(p[0] - std::floor(p[0]), 0.5f);
        EXPECT_EQ(p[1] - std::floor(p[1]), 0.5f);
        EXPECT_FLOAT_EQ(p[6], std::sqrt(0.5f));
        EXPECT_EQ(p[7], p[0]);  // the mean of the corners' x
    }
}

TEST(VmBake3d, MissingCloudAndUnknownChannelWarnOnceAtTheCallAndLeaveTheVariables) {
    streyes::test::TempDir dir("bake3d");
    TestGrid g = square();
    Log log;
    PointClouds clouds(log);
    ShaderInstance s(test::compile(kRead));
    s.setStrings("f", {dir.path() + "/absent.ptc"});
    ShadingVM vm;
    vm.setPointClouds(&clouds);
    vm.setLog(&log);
    vm.run(s, g.grid);
    vm.run(s, g.grid);
    ValueRef ci = vm.result(Global::Ci);
    EXPECT_EQ(ci.at(0, 5), -1.0f);
    EXPECT_EQ(ci.at(2, 5), 0.0f);
    ASSERT_EQ(log.warnings().size(), 1u);
    EXPECT_NE(log.warnings()[0].find("test.sl:3:"), std::string::npos) << log.warnings()[0];
    EXPECT_NE(log.warnings()[0].find("absent.ptc"), std::string::npos) << log.warnings()[0];

    // A cloud with "v" only: "c" is warned about and left; "v" is read.
    const std::string file = dir.path() + "/v.ptc";
    const float rec[] = {1, 1, 0, 0, 0, 1, 1, 42};
    ASSERT_TRUE(BakedPointCloud({{"v", 1}}, {std::begin(rec), std::end(rec)}).write(file, nullptr));
    Log log2;
    PointClouds clouds2(log2);
    s.setStrings("f", {file});
    vm.setPointClouds(&clouds2);
    vm.setLog(&log2);
    vm.run(s, g.grid);
    ci = vm.result(Global::Ci);
    EXPECT_EQ(ci.at(0, 5), 42.0f);  // point 5 is (1, 1): the baked point itself
    EXPECT_EQ(ci.at(1, 5), -1.0f);
    ASSERT_EQ(log2.warnings().size(), 1u);
    EXPECT_NE(log2.warnings()[0].find("no channel \"c\""), std::string::npos) << log2.warnings()[0];
}

TEST(VmBake, WritesSTAndValueOfEveryPointThatRuns) {
    TestGrid g = square();
    g.setVarying(Global::s, 1, [](int i) { return Vec3f{float(i % 4) / 4, 0, 0}; });
    g.setVarying(Global::t, 1, [](int i) { return Vec3f{float(i / 4) / 4, 0, 0}; });
    streyes::test::TempDir dir("bake");
    const std::string file = dir.path() + "/s.bake";
    Log log;
    PointClouds clouds(log);
    ShaderInstance s(test::compile(
        "surface b(string f = \"\") {\n  if (s < 0.5) bake(f, s, t, color(s + t, 0, 1));\n}\n"));
    s.setStrings("f", {file});
    ShadingVM vm;
    vm.setPointClouds(&clouds);
    vm.run(s, g.grid);
    clouds.write();
    std::ifstream in(file);
    std::string header;
    int comps = 0;
    std::getline(in, header);
    in >> comps;
    EXPECT_EQ(header, "Aqsis bake file");
    EXPECT_EQ(comps, 3);
    int lines = 0;
    float ss, tt, r, gg, b;
    while (in >> ss >> tt >> r >> gg >> b) {
        ++lines;
        EXPECT_LT(ss, 0.5f);
        EXPECT_EQ(r, ss + tt);
        EXPECT_EQ(b, 1.0f);
    }
    EXPECT_EQ(lines, 8);  // s = 0 and 0.25 of 4 rows
}

TEST(VmBake3d, CompilerRefusesMalformedCallsAtTheirLine) {
    EXPECT_NE(test::compileError("surface t() {\n  bake3d(\"f\", P, N);\n}\n").find("test.sl:2:"), std::string::npos);
    EXPECT_NE(test::compileError("surface t() {\n  texture3d(\"f\", P, N, \"v\", 1 + 2);\n}\n").find("must be a variable"),
              std::string::npos);
    EXPECT_NE(test::compileError("surface t() {\n  float v;\n  texture3d(\"f\", P, N, \"v\");\n}\n").find("test.sl:3:"),
              std::string::npos);
    EXPECT_NE(test::compileError("surface t() {\n  bake(\"f\", s, t);\n}\n").find("bake takes"), std::string::npos);
    EXPECT_EQ(test::compileError("surface t() {\n  float o = occlusion(P, N, 0, \"pointbased\", 1, \"filename\", \"x.ptc\", "
                                 "\"microbufres\", 10, \"maxsolidangle\", 0.03);\n}\n"),
              "");
}

}  // namespace
}  // namespace streyes::sl
