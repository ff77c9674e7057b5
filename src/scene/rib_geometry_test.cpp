// Parsing the curved and polygon-mesh requests: Basis, Patch "bicubic", PatchMesh,
// SubdivisionMesh and its tags, the quadrics, polygons; their motion blocks;
// and the errors bad input gets (file:line and what is wrong).
#include <gtest/gtest.h>

#include <string>

#include "streyes/rib.h"

#include "test_util.h"

namespace streyes {
namespace {

Scene parse(const std::string& world, Log& log) {
    return parseRibString("WorldBegin\n" + world + "WorldEnd\n", "test.rib", log);
}
Scene parse(const std::string& world) {
    Log log;
    return parse(world, log);
}
std::string errorOf(const std::string& world) { return test::ribError("WorldBegin\n" + world + "WorldEnd\n"); }
std::string numbers(int n, double start = 0) {
    std::string s;
    for (int i = 0; i < n; ++i) s += std::to_string(start + i) + " ";
    return s;
}

TEST(RibCurved, BasisIsAnAttributeWithNamesMatricesAndSteps) {
    Scene s = parse("AttributeBegin\nBasis \"b-spline\" 1 [" + numbers(16) + "] 2\nPatch \"bicubic\" \"P\" [" +
                    numbers(48) + "]\nAttributeEnd\nPatch \"bicubic\" \"P\" [" + numbers(48) + "]\n");
    ASSERT_EQ(s.patchMeshes.size(), 2u);
    BasisDesc bspline;
    basisFromName("b-spline", &bspline);
    EXPECT_EQ(s.patchMeshes[0].uBasis.m, bspline.m);
    EXPECT_EQ(s.patchMeshes[0].uBasis.step, 1);
    EXPECT_EQ(s.patchMeshes[0].vBasis.m[5], 5.0);
    EXPECT_EQ(s.patchMeshes[0].vBasis.step, 2);
    EXPECT_EQ(s.patchMeshes[1].uBasis.m, BasisDesc{}.m);  // AttributeEnd restores Bezier
    EXPECT_EQ(s.patchMeshes[1].uBasis.step, 3);
    EXPECT_NE(errorOf("Basis \"nurbs\" 1 \"bezier\" 3\n").find("bad.rib:2: Basis: unknown basis \"nurbs\""),
              std::string::npos);
    EXPECT_NE(errorOf("Basis \"bezier\" 0 \"bezier\" 3\n").find("the step must be at least 1"), std::string::npos);
}

TEST(RibCurved, PatchMeshesCountTheirPatchesAndPrimvars) {
    Scene s = parse("Basis \"b-spline\" 1 \"bezier\" 3\n"
                    "PatchMesh \"bicubic\" 5 \"nonperiodic\" 7 \"nonperiodic\" \"P\" [" + numbers(105) +
                    "] \"Cs\" [" + numbers(3 * 3 * 3) + "]\n"
                    "PatchMesh \"bicubic\" 6 \"periodic\" 4 \"nonperiodic\" \"P\" [" + numbers(72) +
                    "] \"uniform color Cs\" [" + numbers(18) + "]\n"
                    "PatchMesh \"bilinear\" 3 \"nonperiodic\" 2 \"periodic\" \"Pw\" [" + numbers(24, 1) + "]\n");
    ASSERT_EQ(s.patchMeshes.size(), 3u);
    const PatchMeshDesc &a = s.patchMeshes[0], &b = s.patchMeshes[1], &c = s.patchMeshes[2];
    EXPECT_EQ(a.uPatches(), 2);  // b-spline, step 1: 5 points make 2 patches along u
    EXPECT_EQ(a.vPatches(), 2);  // bezier, step 3: 7 points make 2 patches along v
    EXPECT_EQ(a.Cs.cls, ParamClass::Varying);
    EXPECT_EQ(a.Cs.values.size(), 9u);  // (2 + 1) x (2 + 1) corners
    EXPECT_EQ(b.uPatches(), 6);  // periodic: one patch per point
    EXPECT_EQ(b.Cs.values.size(), 6u);
    EXPECT_FALSE(c.bicubic);
    EXPECT_EQ(c.uPatches(), 2);
    EXPECT_EQ(c.vPatches(), 2);
    EXPECT_NEAR(c.P[0][1].x, 5.0 / 8, 1e-12);  // Pw divided by w
    // A nonperiodic bezier mesh needs 4 + 3k points.
    EXPECT_NE(errorOf("PatchMesh \"bicubic\" 5 \"nonperiodic\" 4 \"nonperiodic\" \"P\" [" + numbers(60) + "]\n")
                  .find("bad.rib:2: PatchMesh: 5 points along u do not make whole nonperiodic patches with a basis "
                        "step of 3"),
              std::string::npos);
    EXPECT_NE(errorOf("Patch \"bicubic\" \"P\" [" + numbers(45) + "]\n")
                  .find("parameter 'P' has 45 numbers, expected 48 (16 vertex points of 3 numbers each)"),
              std::string::npos);
    EXPECT_NE(errorOf("PatchMesh \"bicubic\" 4 \"sometimes\" 4 \"periodic\" \"P\" [" + numbers(48) + "]\n")
                  .find("uwrap must be \"periodic\" or \"nonperiodic\""),
              std::string::npos);
    EXPECT_NE(errorOf("PatchMesh \"bicubic\" 4 \"nonperiodic\" 4 \"nonperiodic\" \"P\" [" + numbers(48) +
                      "] \"Cs\" [1 0 0]\n")
                  .find("parameter 'Cs' has 3 numbers, expected 12 (4 varying colors of 3 numbers each)"),
              std::string::npos);
}

const char* kCubeTopology = "[4 4 4 4 4 4] [0 1 3 2 2 3 5 4 4 5 7 6 6 7 1 0 1 7 5 3 6 0 2 4]";
const char* kCubePoints = "\"P\" [-1 -1 1 1 -1 1 -1 1 1 1 1 1 -1 1 -1 1 1 -1 -1 -1 -1 1 -1 -1]";

TEST(RibCurved, SubdivisionMeshReadsItsTopologyAndTags) {
    Log log;
    Scene s = parse(std::string("SubdivisionMesh \"catmull-clark\" ") + kCubeTopology +
                        " [\"crease\" \"corner\" \"hole\" \"interpolateboundary\" \"smoothtriangles\"]"
                        " [3 1 2 2 1 0 0 0 1 0] [0 1 3 6 4 3 1] [2.5 10 3] " + kCubePoints + "\n",
                    log);
    ASSERT_EQ(s.subdivisionMeshes.size(), 1u);
    const SubdivisionMeshDesc& d = s.subdivisionMeshes[0];
    EXPECT_EQ(d.vertexCount, 8);
    EXPECT_EQ(d.faceSizes.size(), 6u);
    EXPECT_EQ(d.creaseEdges, (std::vector<int>{0, 1, 1, 3}));  // the chain 0 1 3 is two edges
    EXPECT_EQ(d.creaseSharpness, (std::vector<float>{2.5f, 2.5f}));
    EXPECT_EQ(d.corners, (std::vector<int>{6, 4}));
    EXPECT_EQ(d.cornerSharpness, (std::vector<float>{10, 3}));
    EXPECT_EQ(d.holes, (std::vector<int>{3}));
    EXPECT_EQ(d.interpolateBoundary, 1);
    ASSERT_EQ(log.warnings().size(), 1u);
    EXPECT_NE(log.warnings()[0].find("tag \"smoothtriangles\" is not supported"), std::string::npos);
    // No tags at all is fine too.
    EXPECT_EQ(parse(std::string("SubdivisionMesh \"catmull-clark\" ") + kCubeTopology + " " + kCubePoints + "\n")
                  .subdivisionMeshes.size(),
              1u);

    auto mesh = [](const std::string& tags) {
        return std::string("SubdivisionMesh \"catmull-clark\" ") + kCubeTopology + " " + tags + " " + kCubePoints + "\n";
    };
    EXPECT_NE(errorOf(mesh("[\"crease\"] [2 1] [0 7] [1]")).find("vertices 0 and 7 are not joined by an edge"),
              std::string::npos);
    EXPECT_NE(errorOf(mesh("[\"corner\"] [1 1] [9] [1]")).find("vertex 9 is not in the mesh"), std::string::npos);
    EXPECT_NE(errorOf(mesh("[\"crease\"] [2 1] [0 1] [-1]")).find("sharpness must not be negative"),
              std::string::npos);
    EXPECT_NE(errorOf(mesh("[\"hole\"] [1 0] [6] []")).find("face 6 is not in the mesh"), std::string::npos);
    EXPECT_NE(errorOf(mesh("[\"crease\"] [2] [0 1] [1]")).find("nargs must hold 2 (or 3) counts per tag"),
              std::string::npos);
    EXPECT_NE(errorOf("SubdivisionMesh \"catmull-clark\" [4] [0 1 1 2] \"P\" [0 0 0 1 0 0 1 1 0]\n")
                  .find("face 0 uses vertex 1 twice"),
              std::string::npos);
    EXPECT_NE(errorOf("SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] \"P\" [0 0 0 1 0 0 1 1 0]\n")
                  .find("parameter 'P' has 9 numbers, expected 12"),
              std::string::npos);
    EXPECT_NE(errorOf("SubdivisionMesh \"butterfly\" [3] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0]\n")
                  .find("bad.rib:2: SubdivisionMesh: unknown subdivision scheme \"butterfly\""),
              std::string::npos);
    Log loopLog;
    EXPECT_TRUE(parse("SubdivisionMesh \"loop\" [3] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0]\n", loopLog)
                    .subdivisionMeshes.empty());
    EXPECT_EQ(loopLog.warnings().size(), 1u);
}

TEST(RibCurved, QuadricsKeepTheirArguments) {
    Scene s = parse(
        "Sphere 2 -1 1.5 270\nCylinder [1 -1 1 360]\nCone 2 1 400\nDisk 0.5 2 90\nParaboloid 1 0 2 360\n"
        "Hyperboloid 1 0 -1 0 1 1 360\nTorus 3 1 0 360 180 \"varying color Cs\" [1 0 0 0 1 0 0 0 1 1 1 1]\n");
    ASSERT_EQ(s.quadrics.size(), 7u);
    EXPECT_EQ(s.quadrics[0].kind, QuadricKind::Sphere);
    EXPECT_EQ(s.quadrics[0].params[0][1], -1.0);
    EXPECT_EQ(s.quadrics[0].params[0][3], 270.0);
    EXPECT_EQ(s.quadrics[1].kind, QuadricKind::Cylinder);
    EXPECT_EQ(s.quadrics[2].params[0][2], 360.0);  // thetamax clamped to a full turn
    EXPECT_EQ(s.quadrics[5].kind, QuadricKind::Hyperboloid);
    EXPECT_EQ(s.quadrics[5].params[0][6], 360.0);
    EXPECT_EQ(s.quadrics[6].Cs.values.size(), 4u);
    EXPECT_NE(errorOf("Paraboloid 1 0 -2 360\n").find("bad.rib:2: Paraboloid: needs 0 <= zmin <= zmax and zmax > 0"),
              std::string::npos);
    EXPECT_NE(errorOf("Sphere 1 -1 1\n").find("Sphere: expected 4 numbers (radius zmin zmax thetamax), got 3"),
              std::string::npos);
    EXPECT_NE(errorOf("Torus 3 1 0 360 180 \"Cs\" [1 0 0 0 1 0]\n").find("expected 12 (4 varying colors"),
              std::string::npos);
}

// Polygons are kept as loops of points; the bodies stage cuts them (bodies/polygons_test.cpp).
TEST(RibCurved, PolygonsAreKeptAsLoops) {
    Scene s = parse(
        "Polygon \"P\" [0 0 0 2 0 0 3 1 0 1 2 0 -1 1 0]\n"  // a convex pentagon
        "PointsPolygons [4 4] [0 1 2 3 1 4 5 2] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0 3 0 0 1.5 0.5 0]"
        " \"facevarying color Cs\" [" + numbers(24) + "]\n"
        "GeneralPolygon [4 3] \"P\" [0 0 0 4 0 0 4 4 0 0 4 0 1 1 0 1 2 0 2 1 0]\n");
    using Polygons = std::vector<std::vector<std::vector<int>>>;
    ASSERT_EQ(s.polygonMeshes.size(), 3u);
    EXPECT_EQ(s.polygonMeshes[0].request, "Polygon");
    EXPECT_EQ(s.polygonMeshes[0].polygons, (Polygons{{{0, 1, 2, 3, 4}}}));
    const PolygonMeshDesc& pp = s.polygonMeshes[1];
    EXPECT_EQ(pp.request, "PointsPolygons");
    EXPECT_EQ(pp.polygons, (Polygons{{{0, 1, 2, 3}}, {{1, 4, 5, 2}}}));
    ASSERT_EQ(pp.P.size(), 1u);
    EXPECT_EQ(pp.P[0].size(), 6u);
    EXPECT_EQ(pp.Cs.cls, ParamClass::FaceVarying);
    ASSERT_EQ(pp.Cs.values.size(), 8u);
    EXPECT_EQ(pp.Cs.values[4], (Color{12, 13, 14}));  // the second polygon's first corner
    EXPECT_EQ(s.polygonMeshes[2].request, "GeneralPolygon");
    EXPECT_EQ(s.polygonMeshes[2].polygons, (Polygons{{{0, 1, 2, 3}, {4, 5, 6}}}));  // a square with a hole
    // A polygon without area is kept too: the bodies stage warns about it.
    Log log;
    EXPECT_EQ(parse("Polygon \"P\" [0 0 0 1 1 1 2 2 2 3 3 3 4 4 4]\n", log).polygonMeshes.size(), 1u);
    EXPECT_TRUE(log.warnings().empty());
    EXPECT_NE(errorOf("PointsPolygons [3 3] [0 1 2 2 1] \"P\" [0 0 0 1 0 0 1 1 0]\n")
                  .find("vertices has 5 indices but nvertices asks for 6"),
              std::string::npos);
    EXPECT_NE(errorOf("PointsGeneralPolygons [2] [3] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0]\n")
                  .find("nvertices has 1 loop but nloops asks for 2"),
              std::string::npos);
}

TEST(RibCurved, MotionBlocksMoveCurvedGeometry) {
    Scene s = parse(std::string("MotionBegin [0 2]\nSphere 1 -1 1 360\nSphere 2 -2 2 360\nMotionEnd\n") +
                    "MotionBegin [0 1]\nSubdivisionMesh \"catmull-clark\" " + kCubeTopology + " " + kCubePoints +
                    "\nSubdivisionMesh \"catmull-clark\" " + kCubeTopology + " " + kCubePoints + "\nMotionEnd\n" +
                    "MotionBegin [0 1]\nPatch \"bicubic\" \"P\" [" + numbers(48) + "]\nPatch \"bicubic\" \"P\" [" +
                    numbers(48, 1) + "]\nMotionEnd\n" +
                    "MotionBegin [0 1]\nPolygon \"P\" [0 0 0 1 0 0 1 1 0 .5 2 0 0 1 0]\n"
                    "Polygon \"P\" [0 0 1 1 0 1 1 1 1 .5 2 1 0 1 1]\nMotionEnd\n");
    ASSERT_EQ(s.quadrics.size(), 1u);
    EXPECT_EQ(s.quadrics[0].times, (std::vector<double>{0, 2}));
    EXPECT_EQ(s.quadrics[0].params[1][0], 2.0);
    ASSERT_EQ(s.subdivisionMeshes.size(), 1u);
    EXPECT_EQ(s.subdivisionMeshes[0].times.size(), 1u);  // equal keys: static
    ASSERT_EQ(s.patchMeshes.size(), 1u);
    EXPECT_EQ(s.patchMeshes[0].P.size(), 2u);
    EXPECT_EQ(s.patchMeshes[0].P[1][0].x, 1.0);
    ASSERT_EQ(s.polygonMeshes.size(), 1u);
    EXPECT_EQ(s.polygonMeshes[0].P.size(), 2u);
    EXPECT_EQ(s.polygonMeshes[0].P[1][0].z, 1.0);

    EXPECT_NE(errorOf(std::string("MotionBegin [0 1]\nSubdivisionMesh \"catmull-clark\" ") + kCubeTopology + " " +
                      kCubePoints + "\nSubdivisionMesh \"catmull-clark\" " + kCubeTopology +
                      " [\"hole\"] [1 0] [0] [] " + kCubePoints + "\nMotionEnd\n")
                  .find("bad.rib:3: the SubdivisionMesh requests of a motion block must have the same topology"),
              std::string::npos);
    EXPECT_NE(errorOf("MotionBegin [0 1]\nPolygon \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]\n"
                      "Polygon \"P\" [0 0 0 1 0 0 1 1 0 .5 2 0 0 1 0]\nMotionEnd\n")
                  .find("must have the same number of vertices (4 and 5)"),
              std::string::npos);
}

}  // namespace
}  // namespace streyes
