// Polygons as bilinear patches: small Polygons become one patch (corner order, Cs), other polygons
// are cut into triangles and convex quads (facevarying colours follow), and the primitive ids
// they take are the ones they always had.
#include "bodies/polygons.h"

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "bodies/render_scene.h"
#include "streyes/rib.h"

namespace streyes {
namespace {

Scene parse(const std::string& world, Log& log) {
    return parseRibString("WorldBegin\n" + world + "WorldEnd\n", "test.rib", log);
}
Scene parse(const std::string& world) {
    Log log;
    return parse(world, log);
}
std::string numbers(int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += std::to_string(i) + " ";
    return s;
}

void expectNear(Vec3d a, Vec3d b) {
    EXPECT_NEAR(a.x, b.x, 1e-12);
    EXPECT_NEAR(a.y, b.y, 1e-12);
    EXPECT_NEAR(a.z, b.z, 1e-12);
}

TEST(Polygons, QuadAndTriangleCornerOrder) {
    Scene scene = parse(
        "Polygon \"P\" [0 0 0  1 0 0  1 1 0  0 1 0] \"Cs\" [1 0 0  0 1 0  0 0 1  1 1 1]\n"
        "Polygon \"P\" [0 0 0  2 0 0  0 2 0] \"vertex color Cs\" [1 0 0  0 1 0  0 0 1]\n");
    ASSERT_EQ(scene.polygonMeshes.size(), 2u);
    // Quad v0 v1 v2 v3 -> corners v0 v1 v3 v2.
    const std::optional<BilinearPatchDesc> quad = polygonAsPatch(scene.polygonMeshes[0]);
    ASSERT_TRUE(quad);
    expectNear(quad->P[0][0], {0, 0, 0});
    expectNear(quad->P[0][1], {1, 0, 0});
    expectNear(quad->P[0][2], {0, 1, 0});
    expectNear(quad->P[0][3], {1, 1, 0});
    ASSERT_TRUE(quad->hasCs);
    EXPECT_EQ(quad->Cs[0], Color(1, 0, 0));
    EXPECT_EQ(quad->Cs[1], Color(0, 1, 0));
    EXPECT_EQ(quad->Cs[2], Color(1, 1, 1));
    EXPECT_EQ(quad->Cs[3], Color(0, 0, 1));
    EXPECT_EQ(quad->loc.line, 2);
    // Triangle v0 v1 v2 -> corners v0 v1 v2 v2.
    const std::optional<BilinearPatchDesc> tri = polygonAsPatch(scene.polygonMeshes[1]);
    ASSERT_TRUE(tri);
    expectNear(tri->P[0][0], {0, 0, 0});
    expectNear(tri->P[0][1], {2, 0, 0});
    expectNear(tri->P[0][2], {0, 2, 0});
    expectNear(tri->P[0][3], {0, 2, 0});
    EXPECT_EQ(tri->Cs[2], Color(0, 0, 1));
    EXPECT_EQ(tri->Cs[3], Color(0, 0, 1));
    // A uniform colour is every corner's.
    Scene uniform = parse("Polygon \"P\" [0 0 0  1 0 0  1 1 0] \"uniform color Cs\" [0.25 0.5 0.75]\n");
    const std::optional<BilinearPatchDesc> flat = polygonAsPatch(uniform.polygonMeshes[0]);
    ASSERT_TRUE(flat);
    for (const Color& c : flat->Cs) EXPECT_EQ(c, Color(0.25f, 0.5f, 0.75f));
}

TEST(Polygons, ConcaveQuadsAndLargerPolygonsAreCut) {
    Log log;
    Scene s = parse(
        "Polygon \"P\" [0 0 0 2 0 0 3 1 0 1 2 0 -1 1 0]\n"  // a convex pentagon: 3 triangles
        "PointsPolygons [4 4] [0 1 2 3 1 4 5 2] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0 3 0 0 1.5 0.5 0]"
        " \"facevarying color Cs\" [" + numbers(24) + "]\n"
        "GeneralPolygon [4 3] \"P\" [0 0 0 4 0 0 4 4 0 0 4 0 1 1 0 1 2 0 2 1 0]\n",
        log);
    ASSERT_EQ(s.polygonMeshes.size(), 3u);
    for (const PolygonMeshDesc& mesh : s.polygonMeshes) EXPECT_FALSE(polygonAsPatch(mesh));
    EXPECT_EQ(cutPolygons(s.polygonMeshes[0], log).faces.size(), 3u);
    // A convex quad stays one bilinear face (corners in patch order); the concave one is cut in two.
    const PolygonFaces pp = cutPolygons(s.polygonMeshes[1], log);
    ASSERT_EQ(pp.faces.size(), 3u);
    EXPECT_EQ(pp.faces[0], (std::array<int, 4>{0, 1, 3, 2}));
    ASSERT_EQ(pp.faceCs.size(), 3u);
    // Facevarying colours follow each polygon's own corners: the second polygon's point 1 is its
    // first corner, face-vertex 4.
    bool found = false;
    for (size_t f = 1; f < 3; ++f)
        for (size_t k = 0; k < 4; ++k)
            if (pp.faces[f][k] == 1) found = found || pp.faceCs[f][k] == Color{12, 13, 14};
    EXPECT_TRUE(found);
    EXPECT_EQ(cutPolygons(s.polygonMeshes[2], log).faces.size(), 7u);  // a square with a triangular hole
    EXPECT_TRUE(log.warnings().empty());

    // A concave quad is cut too; a convex one stays a bilinear patch.
    Scene quads = parse("Polygon \"P\" [0 0 0 2 0 0 0.5 0.5 0 0 2 0]\nPolygon \"P\" [0 0 0 2 0 0 2 2 0 0 2 0]\n");
    ASSERT_EQ(quads.polygonMeshes.size(), 2u);
    EXPECT_FALSE(polygonAsPatch(quads.polygonMeshes[0]));
    EXPECT_EQ(cutPolygons(quads.polygonMeshes[0], log).faces.size(), 2u);
    EXPECT_TRUE(polygonAsPatch(quads.polygonMeshes[1]));
    // Concave at any key: cut, at the first key (convex here: one face).
    Scene turning = parse(
        "MotionBegin [0 1]\nPolygon \"P\" [0 0 0 2 0 0 2 2 0 0 2 0]\nPolygon \"P\" [0 0 0 2 0 0 0.5 0.5 0 0 2 0]\n"
        "MotionEnd\n");
    ASSERT_EQ(turning.polygonMeshes.size(), 1u);
    EXPECT_FALSE(polygonAsPatch(turning.polygonMeshes[0]));
    EXPECT_EQ(cutPolygons(turning.polygonMeshes[0], log).faces.size(), 1u);

    // A polygon without area warns and has no faces.
    Scene line = parse("Polygon \"P\" [0 0 0 1 1 1 2 2 2 3 3 3 4 4 4]\n");
    EXPECT_TRUE(cutPolygons(line.polygonMeshes[0], log).faces.empty());
    ASSERT_EQ(log.warnings().size(), 1u);
    EXPECT_NE(log.warnings()[0].find("test.rib:2: warning: Polygon: a polygon has no area"), std::string::npos)
        << log.warnings()[0];
}

// Ids decide exact depth ties, so they are what they were when the reader made patches of small
// Polygons and cut the rest: patches and Polygons that are one patch in the order read, then
// procedurals and curved primitives, then cut polygons; a polygon without area takes no id.
TEST(Polygons, PrimitiveIdsByGroupInTheOrderRead) {
    Log log;
    Scene scene = parse(
        "Translate 0 0 5\n"
        "Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n"         // line 3: id 1
        "Polygon \"P\" [0 0 0 1 0 0 0 1 0]\n"                          // line 4: id 2
        "Polygon \"P\" [0 0 0 2 0 0 0.5 0.5 0 0 2 0]\n"                // line 5: concave, id 6
        "Sphere 1 -1 1 360\n"                                          // line 6: id 5
        "Polygon \"P\" [0 0 0 1 1 1 2 2 2]\n"                          // line 7: a line, but a patch: id 3
        "Polygon \"P\" [0 0 0 1 1 1 2 2 2 3 3 3 4 4 4]\n"              // line 8: no area, no id
        "Polygon \"P\" [0 0 0 2 0 0 3 1 0 1 2 0 -1 1 0]\n"             // line 9: id 7
        "Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n",        // line 10: id 4
        log);
    std::unique_ptr<RenderScene> rs = buildRenderScene(scene, 0, 0, 64, 48, log);
    std::map<int, std::set<uint32_t>> idsOfLine;
    for (const BodyPtr& b : rs->roots) idsOfLine[b->source()->line].insert(b->primitiveId());
    const std::map<int, std::set<uint32_t>> expected = {{3, {1}}, {4, {2}}, {5, {6}}, {6, {5}},
                                                         {7, {3}}, {9, {7}}, {10, {4}}};
    EXPECT_EQ(idsOfLine, expected);
}

}  // namespace
}  // namespace streyes
