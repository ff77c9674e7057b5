// Parsing Curves and Points: counts by class, widths, normals, the basis and its step, motion
// blocks, and the errors bad input gets (file:line and what is wrong).
#include <gtest/gtest.h>

#include <string>

#include "streyes/rib.h"

#include "test_util.h"

namespace streyes {
namespace {

Scene parse(const std::string& world) {
    Log log;
    return parseRibString("WorldBegin\n" + world + "WorldEnd\n", "test.rib", log);
}
std::string errorOf(const std::string& world) { return test::ribError("WorldBegin\n" + world + "WorldEnd\n"); }
bool says(const std::string& error, const std::string& what) { return error.find(what) != std::string::npos; }

TEST(RibCurves, LinearAndCubicCurvesWithTheirCountsWidthsAndBasis) {
    Scene s = parse(
        "Curves \"linear\" [2 3] \"nonperiodic\" \"P\" [0 0 0 1 0 0  0 1 0 1 1 0 2 1 0] \"width\" [1 2 3 4 5]\n"
        "Basis \"bezier\" 3 \"b-spline\" 1\n"
        "Curves \"cubic\" [5] \"periodic\" \"P\" [0 0 0 1 0 0 1 1 0 0 1 0 0 2 0] \"constantwidth\" [0.5]\n"
        "Curves \"cubic\" [6] \"nonperiodic\" \"P\" [0 0 0 1 0 0 2 0 0 3 0 0 4 0 0 5 0 0]"
        " \"N\" [0 0 -1 0 0 -1 0 0 -1 0 0 -1] \"uniform color Cs\" [1 0 0]\n");
    ASSERT_EQ(s.curves.size(), 3u);
    const CurvesDesc& lin = s.curves[0];
    EXPECT_FALSE(lin.cubic);
    EXPECT_EQ(lin.nvertices, (std::vector<int>{2, 3}));
    EXPECT_EQ(lin.segments(0), 1);
    EXPECT_EQ(lin.segments(1), 2);
    EXPECT_EQ(lin.widthClass, ParamClass::Varying);
    EXPECT_EQ(lin.width, (std::vector<double>{1, 2, 3, 4, 5}));
    const CurvesDesc& per = s.curves[1];
    EXPECT_TRUE(per.cubic && per.periodic);
    EXPECT_EQ(per.basis.step, 1);  // the v basis
    EXPECT_EQ(per.segments(0), 5);
    EXPECT_EQ(per.varying(0), 5);
    EXPECT_EQ(per.widthClass, ParamClass::Constant);
    EXPECT_EQ(per.width, (std::vector<double>{0.5}));
    const CurvesDesc& oriented = s.curves[2];
    EXPECT_EQ(oriented.segments(0), 3);
    EXPECT_EQ(oriented.N.size(), 4u);  // varying: one per segment end
    EXPECT_EQ(oriented.Cs.cls, ParamClass::Uniform);
    EXPECT_EQ(oriented.width, (std::vector<double>{1.0}));  // RenderMan's default width
}

TEST(RibCurves, PointsWithWidthsAndColours) {
    Scene s = parse("Points \"P\" [0 0 0 1 1 1 2 2 2] \"width\" [1 2 3] \"Cs\" [1 0 0 0 1 0 0 0 1]\n"
                    "Points \"P\" [0 0 0] \"constantwidth\" 0.25\n");
    ASSERT_EQ(s.points.size(), 2u);
    EXPECT_EQ(s.points[0].P[0].size(), 3u);
    EXPECT_EQ(s.points[0].width, (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(s.points[0].Cs.values.size(), 3u);
    EXPECT_EQ(s.points[1].width, (std::vector<double>{0.25}));
}

TEST(RibCurves, MotionBlocksMakeKeys) {
    Scene s = parse("MotionBegin [0 1]\n"
                    "Curves \"linear\" [2] \"nonperiodic\" \"P\" [0 0 0 1 0 0]\n"
                    "Curves \"linear\" [2] \"nonperiodic\" \"P\" [0 1 0 1 1 0]\n"
                    "MotionEnd\n"
                    "MotionBegin [0 2]\nPoints \"P\" [0 0 0]\nPoints \"P\" [3 0 0]\nMotionEnd\n");
    ASSERT_EQ(s.curves.size(), 1u);
    EXPECT_EQ(s.curves[0].times, (std::vector<double>{0, 1}));
    EXPECT_EQ(s.curves[0].P[1][0].y, 1.0);
    ASSERT_EQ(s.points.size(), 1u);
    EXPECT_EQ(s.points[0].times, (std::vector<double>{0, 2}));
    EXPECT_EQ(s.points[0].P[1][0].x, 3.0);
    EXPECT_TRUE(says(errorOf("MotionBegin [0 1]\nCurves \"linear\" [2] \"nonperiodic\" \"P\" [0 0 0 1 0 0]\n"
                             "Curves \"linear\" [3] \"nonperiodic\" \"P\" [0 0 0 1 0 0 2 0 0]\nMotionEnd\n"),
                     "type, nvertices and wrap"));
}

TEST(RibCurves, BadInputNamesFileAndLine) {
    const std::string P2 = " \"P\" [0 0 0 1 0 0]";
    // Missing P, wrong counts, negative widths, unknown type or wrap.
    EXPECT_TRUE(says(errorOf("Curves \"linear\" [2] \"nonperiodic\" \"width\" [1 1]\n"),
                     "bad.rib:2: Curves: missing \"P\""));
    EXPECT_TRUE(says(errorOf("Points \"width\" [1]\n"), "bad.rib:2: Points: missing \"P\""));
    EXPECT_TRUE(says(errorOf("Curves \"linear\" [3] \"nonperiodic\"" + P2 + "\n"),
                     "bad.rib:2: Curves: parameter 'P' has 6 numbers, expected 9"));
    EXPECT_TRUE(says(errorOf("Curves \"linear\" [2] \"nonperiodic\"" + P2 + " \"width\" [1 2 3]\n"),
                     "bad.rib:2: Curves: parameter 'width' has 3 numbers, expected 2"));
    EXPECT_TRUE(says(errorOf("Points \"P\" [0 0 0 1 1 1] \"width\" [1]\n"),
                     "bad.rib:2: Points: parameter 'width' has 1 number, expected 2"));
    EXPECT_TRUE(says(errorOf("Curves \"cubic\" [5] \"nonperiodic\" \"P\" [0 0 0 1 0 0 2 0 0 3 0 0 4 0 0]\n"),
                     "bad.rib:2: Curves: curve 0 has 5 vertices: a nonperiodic cubic curve needs 4 plus a multiple of "
                     "the basis step (3)"));
    EXPECT_TRUE(
        says(errorOf("Curves \"linear\" [1] \"nonperiodic\" \"P\" [0 0 0]\n"), "a linear curve needs at least 2"));
    EXPECT_TRUE(says(errorOf("Curves \"linear\" [2] \"nonperiodic\"" + P2 + " \"width\" [1 -1]\n"),
                     "bad.rib:2: Curves: \"width\" value 1 is -1: widths must be at least 0"));
    EXPECT_TRUE(says(errorOf("Points \"P\" [0 0 0] \"constantwidth\" [-2]\n"),
                     "bad.rib:2: Points: \"constantwidth\" value 0 is -2: widths must be at least 0"));
    EXPECT_TRUE(says(errorOf("Curves \"quadratic\" [2] \"nonperiodic\"" + P2 + "\n"),
                     "bad.rib:2: Curves: the curve type must be \"linear\" or \"cubic\", got \"quadratic\""));
    EXPECT_TRUE(says(errorOf("Curves \"linear\" [2] \"closed\"" + P2 + "\n"),
                     "bad.rib:2: Curves: the wrap must be \"periodic\" or \"nonperiodic\", got \"closed\""));
    EXPECT_TRUE(says(errorOf("Curves \"linear\" [2] \"nonperiodic\"" + P2 + " \"width\" [1 1] \"constantwidth\" 1\n"),
                     "either \"width\" or \"constantwidth\""));
    EXPECT_TRUE(says(errorOf("Curves \"linear\" [2] \"nonperiodic\"" + P2 + " \"N\" [0 0 1]\n"),
                     "parameter 'N' has 3 numbers, expected 6"));
    // The error is at the line of the value, where a request spans lines.
    EXPECT_TRUE(says(errorOf("Curves \"linear\" [2]\n \"nonperiodic\"" + P2 + "\n \"width\" [1 -1]\n"), "bad.rib:4:"));
}

}  // namespace
}  // namespace streyes
