#include "bodies/body_factory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "pixel_camera.h"
#include "raster/image_block.h"

namespace streyes {
namespace {

// Ids decide exact depth ties, so two primitives must never share one. A forest makes about a
// million bodies; 32-bit hashed ids collided by the thousand at four million (about n^2 / 2^33).
TEST(BodyFactory, ChildIdsOfFourMillionChildrenAreDistinct) {
    std::vector<uint64_t> ids;
    const uint64_t parents[] = {1, 2, 77, childPrimitiveId(3, 5)};
    for (uint64_t parent : parents)
        for (uint64_t i = 0; i < 1000000; ++i) ids.push_back(childPrimitiveId(parent, i));
    for (uint64_t id : ids) ASSERT_TRUE(id != 0 && id != kNoPrimitive);
    std::sort(ids.begin(), ids.end());
    EXPECT_EQ(std::adjacent_find(ids.begin(), ids.end()), ids.end()) << "two children share an id";
}

TEST(BodyFactory, ChildIdsArePureFunctionsOfParentAndIndex) {
    EXPECT_EQ(childPrimitiveId(12, 7), childPrimitiveId(12, 7));
    EXPECT_NE(childPrimitiveId(12, 7), childPrimitiveId(12, 8));
    EXPECT_NE(childPrimitiveId(12, 7), childPrimitiveId(13, 7));
}

// Subdivision meshes of one topology and tags share one shape (OpenSubdiv's refined topology,
// the costly part): the instances of an object, or a mesh written out many times. Different
// positions keep their own surfaces; a crease makes another shape.
TEST(BodyFactory, MeshesOfOneTopologyShareTheirSubdivisionShape) {
    Log log;
    const Camera camera = test::pixelCamera(64);
    BodyFactory factory(MotionTransform(), 0, 0, log);
    factory.setCamera(&camera);
    SubdivisionMeshDesc cube;
    cube.faceSizes = {4, 4, 4, 4, 4, 4};
    cube.faceVertices = {0, 1, 3, 2, 2, 3, 5, 4, 4, 5, 7, 6, 6, 7, 1, 0, 1, 7, 5, 3, 6, 0, 2, 4};
    cube.vertexCount = 8;
    cube.times = {0};
    cube.attributes = std::make_shared<Attributes>();
    auto at = [](double x) {
        std::vector<Vec3d> P;
        for (int i = 0; i < 8; ++i) P.push_back({x + ((i & 1) ? 8.0 : 0.0), (i & 2) ? 8.0 : 0.0, (i & 4) ? 18.0 : 10.0});
        return P;
    };
    std::vector<BodyPtr> a, b, c;
    cube.P = {at(4)};
    factory.addSubdivisionMesh(cube, 1, a);
    cube.P = {at(30)};
    factory.addSubdivisionMesh(cube, 2, b);
    EXPECT_EQ(factory.subdivisionShapes(), 1u);
    ASSERT_EQ(a.size(), b.size());
    ASSERT_FALSE(a.empty());
    EXPECT_NEAR(b[0]->bound().b0.lo.x - a[0]->bound().b0.lo.x, 26.0f, 1e-3f);  // each its own positions
    cube.creaseEdges = {0, 1};
    cube.creaseSharpness = {2.0f};
    factory.addSubdivisionMesh(cube, 3, c);
    EXPECT_EQ(factory.subdivisionShapes(), 2u);
}

}  // namespace
}  // namespace streyes
