// Creases as RenderMan files give them, read by the RIB reader and evaluated through streyes's
// subdivision surfaces, against OpenSubdiv evaluated directly (Pixar's definition of RenderMan's
// subdivision: a "crease" tag's intargs are a chain of vertices, each consecutive pair an edge
// with the chain's sharpness, or its own) and against closed forms for infinitely sharp creases
// and for vertices where creases meet. The mesh is Aqsis's features/subdivision/creases.rib.
#include <gtest/gtest.h>

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <memory>
#include <string>
#include <vector>

#include "bodies/material.h"
#include "geom/subdivision.h"
#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// creases.rib's octahedron of 8 triangles, with its two chains: the equator 1-2-3-4-1 at sharpness
// 4 and the meridian 0-1-5-3-0 at 2; they cross at vertices 1 and 3.
const char* kFaces = "[3 3 3 3 3 3 3 3] [0 1 2  0 2 3  0 3 4  0 4 1  5 2 1  5 3 2  5 4 3  5 1 4]";
const char* kPoints = "\"P\" [0 1.414 0  1 0 1  -1 0 1  -1 0 -1  1 0 -1  0 -1.414 0]";

SubdivisionMeshDesc readMesh(const std::string& tags) {
    Log log;
    const Scene scene = parseRibString(std::string("WorldBegin\nSubdivisionMesh \"catmull-clark\" ") + kFaces + "\n" +
                                           tags + "\n" + kPoints + "\nWorldEnd\n",
                                       "creases.rib", log);
    EXPECT_TRUE(log.warnings().empty());
    return scene.subdivisionMeshes.at(0);
}

// The limit positions at every face corner of streyes's surface (its faces are the level-1 faces).
std::vector<Vec3f> cornerLimits(const SubdivisionMeshDesc& d) {
    auto shape = std::make_shared<SubdivisionShape>(d);
    auto key = shape->key(d.P[0]);
    Material material;
    Camera camera = test::pixelCamera(256);
    SubdivisionMesh mesh(shape, key, key, TimeSpan{0, 0}, &material, &camera, shape->colors({}, Color{1, 1, 1}));
    std::vector<Vec3f> out;
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int c = 0; c < 4; ++c) {
            Vec3f P, N;
            mesh.evaluatePoint(f, c & 1, c >> 1, 0, &P, &N);
            out.push_back(P);
        }
    return out;
}

bool near(const std::vector<Vec3f>& points, Vec3d p, double eps) {
    for (const Vec3f& q : points)
        if (length(Vec3d(q) - p) < eps) return true;
    return false;
}

struct Point3 {
    double p[3];
    void Clear() { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const Point3& s, double w) {
        for (int i = 0; i < 3; ++i) p[i] += w * s.p[i];
    }
};

// OpenSubdiv by itself: the mesh with the chains' edges creased as pairs, and the limit positions
// of the level-1 vertices. Far's Limit is exact only where no edge is semi-sharp any more (it
// applies each vertex's rule at the level it is given), so the mesh is refined past the largest
// sharpness (each level takes 1 off) and each level-1 vertex's limit is read at its descendant
// there.
std::vector<Vec3d> openSubdivLimits(const std::vector<int>& creasePairs, const std::vector<float>& sharpness,
                                    const std::vector<Vec3d>& P) {
    constexpr int kLevels = 6;  // creases.rib's sharpest edges (4) are smooth from level 4 on
    const std::vector<int> sizes(8, 3);
    const std::vector<int> verts = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1, 5, 2, 1, 5, 3, 2, 5, 4, 3, 5, 1, 4};
    Far::TopologyDescriptor d;
    d.numVertices = 6;
    d.numFaces = 8;
    d.numVertsPerFace = sizes.data();
    d.vertIndicesPerFace = verts.data();
    d.numCreases = int(sharpness.size());
    d.creaseVertexIndexPairs = creasePairs.data();
    d.creaseWeights = sharpness.data();
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    std::unique_ptr<Far::TopologyRefiner> refiner(
        Factory::Create(d, Factory::Options(Sdc::SCHEME_CATMARK, Sdc::Options())));
    Far::TopologyRefiner::UniformOptions uniform(kLevels);
    uniform.fullTopologyInLastLevel = true;  // Limit needs the last level's full topology
    refiner->RefineUniform(uniform);
    std::vector<std::vector<Point3>> levels(kLevels + 1);
    levels[0].resize(P.size());
    for (size_t i = 0; i < P.size(); ++i) levels[0][i] = {{P[i].x, P[i].y, P[i].z}};
    Far::PrimvarRefinerReal<double> primvar(*refiner);
    for (int l = 1; l <= kLevels; ++l) {
        levels[size_t(l)].resize(size_t(refiner->GetLevel(l).GetNumVertices()));
        Point3 *src = levels[size_t(l - 1)].data(), *dst = levels[size_t(l)].data();
        primvar.Interpolate(l, src, dst);
    }
    std::vector<Point3> limit(levels[kLevels].size());
    Point3 *last = levels[kLevels].data(), *dst = limit.data();
    primvar.Limit(last, dst);
    std::vector<Vec3d> out;
    for (int v = 0; v < refiner->GetLevel(1).GetNumVertices(); ++v) {
        int at = v;
        for (int l = 1; l < kLevels; ++l) at = refiner->GetLevel(l).GetVertexChildVertex(at);
        const Point3& q = limit[size_t(at)];
        out.push_back({q.p[0], q.p[1], q.p[2]});
    }
    return out;
}

// creases.rib as PRMan reads it: every level-1 vertex's limit where OpenSubdiv puts it. (Aqsis
// maps a sharpness s to a blend of min(s, 5) / 5, bent by a power of 0.2, at every level of its own
// subdivision: an approximation it names as such, and why its outline differs from streyes's.)
TEST(SubdivisionCreases, ChainsAreReadAsOpenSubdivDefinesThem) {
    const SubdivisionMeshDesc d = readMesh("[\"crease\" \"crease\"] [5 1 5 1] [1 2 3 4 1 0 1 5 3 0] [4 2]");
    const std::vector<int> pairs = {1, 2, 2, 3, 3, 4, 4, 1, 0, 1, 1, 5, 5, 3, 3, 0};
    EXPECT_EQ(d.creaseEdges, pairs);
    EXPECT_EQ(d.creaseSharpness, (std::vector<float>{4, 4, 4, 4, 2, 2, 2, 2}));
    const std::vector<Vec3f> ours = cornerLimits(d);
    const std::vector<Vec3d> reference = openSubdivLimits(pairs, d.creaseSharpness, d.P[0]);
    ASSERT_EQ(reference.size(), 6u + 12u + 8u);  // vertices, edges and faces of the octahedron
    for (const Vec3d& p : reference) EXPECT_TRUE(near(ours, p, 1e-5)) << p.x << " " << p.y << " " << p.z;
    for (const Vec3f& p : ours) {
        bool found = false;
        for (const Vec3d& q : reference) found = found || length(Vec3d(p) - q) < 1e-5;
        EXPECT_TRUE(found) << p.x << " " << p.y << " " << p.z;
    }
    // Without the creases the surface is another: the tags reached OpenSubdiv.
    const std::vector<Vec3d> smooth = openSubdivLimits({}, {}, d.P[0]);
    EXPECT_FALSE(near(ours, smooth[0], 1e-3));
}

// Infinitely sharp chains: a vertex on one chain (two creased edges) follows the chain's uniform
// cubic B-spline, its limit (P_prev + 4 P + P_next) / 6; a vertex where the chains cross (four
// creased edges) is a corner and stays where it is. One sharpness per edge reads as one per chain.
TEST(SubdivisionCreases, InfinitelySharpChainsAndWhereTheyMeet) {
    const std::vector<std::pair<std::string, std::string>> given = {{"[5 1 5 1]", "[10 10]"},
                                                                    {"[5 4 5 4]", "[10 10 10 10  10 10 10 10]"}};
    for (const auto& [nargs, floats] : given) {
        const SubdivisionMeshDesc d = readMesh("[\"crease\" \"crease\"] " + nargs + " [1 2 3 4 1 0 1 5 3 0] " + floats);
        EXPECT_EQ(d.creaseSharpness, std::vector<float>(8, 10.0f)) << floats;
        const std::vector<Vec3f> ours = cornerLimits(d);
        const std::vector<Vec3d>& P = d.P[0];
        EXPECT_TRUE(near(ours, P[1], 1e-5)) << floats;  // where the chains cross: a corner
        EXPECT_TRUE(near(ours, P[3], 1e-5)) << floats;
        EXPECT_TRUE(near(ours, (P[1] + P[2] * 4.0 + P[3]) * (1.0 / 6), 1e-5)) << floats;  // on the equator
        EXPECT_TRUE(near(ours, (P[3] + P[4] * 4.0 + P[1]) * (1.0 / 6), 1e-5)) << floats;
        EXPECT_TRUE(near(ours, (P[1] + P[0] * 4.0 + P[3]) * (1.0 / 6), 1e-5)) << floats;  // on the meridian
        EXPECT_TRUE(near(ours, (P[1] + P[5] * 4.0 + P[3]) * (1.0 / 6), 1e-5)) << floats;
    }
    // Per-edge values as given: the equator sharp, the meridian smooth but for one edge.
    const SubdivisionMeshDesc d =
        readMesh("[\"crease\" \"crease\"] [5 4 5 4] [1 2 3 4 1 0 1 5 3 0] [10 10 10 10  0 0 3 0]");
    EXPECT_EQ(d.creaseSharpness, (std::vector<float>{10, 10, 10, 10, 0, 0, 3, 0}));
}

TEST(SubdivisionCreases, AChainWithTheWrongNumberOfSharpnessesIsAnError) {
    const std::string e = test::ribError(std::string("WorldBegin\n\nSubdivisionMesh \"catmull-clark\" ") + kFaces +
                                         " [\"crease\"] [5 2] [1 2 3 4 1] [1 2] " + kPoints + "\nWorldEnd\n");
    EXPECT_NE(e.find("bad.rib:3: "), std::string::npos) << e;
    EXPECT_NE(e.find("one sharpness (or one per edge)"), std::string::npos) << e;
}

}  // namespace
}  // namespace streyes
