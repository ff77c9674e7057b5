#include "bodies/body_factory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "procedural/procedural.h"
#include "streyes/error.h"

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

// A factory over frames [0, windowEnd] seen by a 64-pixel camera, as a render's is.
struct FactoryUnderCamera {
    Log log;
    const Camera camera = test::pixelCamera(64);
    BodyFactory factory;
    explicit FactoryUnderCamera(double windowEnd) : factory(MotionTransform(), 0, windowEnd, log) {
        factory.setCamera(&camera);
    }
};

// Subdivision meshes of one topology and tags share one shape (OpenSubdiv's refined topology,
// the costly part): the instances of an object, or a mesh written out many times. Different
// positions keep their own surfaces; a crease makes another shape.
TEST(BodyFactory, MeshesOfOneTopologyShareTheirSubdivisionShape) {
    FactoryUnderCamera made(0);
    BodyFactory& factory = made.factory;
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

// A swaying leaf over a shot: a patch through `keys` motion keys, one a frame from 0.
BilinearPatchDesc swayingPatch(int keys) {
    BilinearPatchDesc p;
    p.attributes = std::make_shared<Attributes>();
    for (int k = 0; k < keys; ++k) {
        p.times.push_back(double(k));
        const double x = 0.1 * k * k;  // keys off a straight line: a keyed body keeps every one
        p.P.push_back({Vec3d{x, 0, 10}, Vec3d{x + 1, 0, 10}, Vec3d{x, 1, 10}, Vec3d{x + 1, 1, 10}});
    }
    return p;
}

// The factory adds up what the bodies it makes hold (the memory budget counts it): a body with
// 17 motion keys holds them, a still one only itself, and the sum is the bodies' own figures.
// The ray tracer's expansion stops at the budget by that sum, not by a count of bodies.
TEST(BodyFactory, BodiesCountTheMemoryTheyHold) {
    FactoryUnderCamera made(16);
    BodyFactory& factory = made.factory;
    Scene scene;
    scene.patches = {swayingPatch(17), swayingPatch(1)};
    std::vector<BodyPtr> roots;
    uint64_t id = 0;
    factory.addPrimitives(scene, {}, 0, [&id] { return ++id; }, roots);
    ASSERT_EQ(roots.size(), 2u);
    ASSERT_NE(dynamic_cast<const KeyedPatchBody*>(roots[0].get()), nullptr);
    const size_t keyed = roots[0]->memoryBytes(), still = roots[1]->memoryBytes();
    EXPECT_GE(keyed, sizeof(KeyedPatchBody) + 17 * (sizeof(TrilinearBody::Corners) + sizeof(double)));
    EXPECT_GE(still, sizeof(TrilinearBody));
    EXPECT_LT(still, keyed / 4);
    EXPECT_EQ(factory.bodyBytes(), uint64_t(keyed + still));

    // A procedural's output of 100 such leaves: about 100 x 1 KiB. Within a budget of 64 KiB
    // for bodies the first expansion goes through (the check comes before it), the next is refused.
    ProceduralOutput leaves;
    for (int i = 0; i < 100; ++i) leaves.scene.patches.push_back(swayingPatch(17));
    factory.setBodyBudget(uint64_t(1) << 20, uint64_t(64) << 10);
    std::vector<BodyPtr> children;
    factory.addChildren(leaves, 1, 1, children);
    EXPECT_EQ(children.size(), 100u);
    EXPECT_GT(factory.bodyBytes(), uint64_t(100 * keyed));
    try {
        factory.addChildren(leaves, 2, 1, children);
        FAIL() << "expanding past the budget for bodies was not refused";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("memory budget of 1 MiB"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("raise --max-memory"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace streyes
