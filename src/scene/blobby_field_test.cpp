// The Blobby polygonizer: closed, consistently wound meshes whose vertices lie on the level.
#include "scene/blobby_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>

namespace streyes {
namespace {

BlobbyOp sphere(double R, Vec3d c) {
    BlobbyOp op;
    op.kind = BlobbyOp::Kind::Ellipsoid;
    op.toObject = Matrix4::scale({R, R, R}) * Matrix4::translate(c);
    EXPECT_TRUE(invert(op.toObject, &op.toBlob));
    return op;
}

BlobbyOp combine(BlobbyOp::Kind kind, std::vector<int> operands) {
    BlobbyOp op;
    op.kind = kind;
    op.operands = std::move(operands);
    return op;
}

// Every directed edge once, and its reverse once: closed, no cracks, one orientation throughout.
void expectClosedAndConsistent(const BlobbyMesh& m) {
    std::map<std::pair<int, int>, int> edges;
    for (const auto& t : m.triangles)
        for (int k = 0; k < 3; ++k) ++edges[{t[size_t(k)], t[size_t((k + 1) % 3)]}];
    for (const auto& [e, count] : edges) {
        EXPECT_EQ(count, 1) << e.first << "-" << e.second;
        auto back = edges.find({e.second, e.first});
        ASSERT_NE(back, edges.end()) << "open edge " << e.first << "-" << e.second;
        EXPECT_EQ(back->second, 1);
    }
}

TEST(BlobbyField, FalloffIsOneAtTheCentreAndAtTheLevelAtHalfItsReach) {
    EXPECT_EQ(blobFalloff(0), 1);
    EXPECT_EQ(blobFalloff(1), 0);
    EXPECT_EQ(blobFalloff(4), 0);
    EXPECT_EQ(blobFalloff(0.25), kBlobbyLevel);  // r = 1/2: (1 - 1/4)^3 = 27/64, exactly
}

TEST(BlobbyField, OneBlobIsAClosedSphereOfTheLevelRadius) {
    BlobbyField f;
    f.ops = {sphere(2, {1, 2, 3})};
    const BlobbyMesh m = polygonizeBlobby(f, 32);
    ASSERT_GT(m.triangles.size(), 500u);
    EXPECT_FALSE(m.openAtBound);
    expectClosedAndConsistent(m);
    const double r = 2 * 0.5;  // half the reach
    std::vector<double> scratch;
    for (const Vec3d& p : m.P) {
        EXPECT_NEAR(length(p - Vec3d{1, 2, 3}), r, 1e-6);
        EXPECT_NEAR(f.value(p, scratch), kBlobbyLevel, 1e-6);
    }
    // Outward: the signed volume of the mesh (divergence theorem) is positive, near the ball's.
    double volume = 0;
    for (const auto& t : m.triangles)
        volume += dot(m.P[size_t(t[0])], cross(m.P[size_t(t[1])], m.P[size_t(t[2])])) / 6;
    EXPECT_NEAR(volume, 4.0 / 3.0 * M_PI * r * r * r, 0.01 * 4.0 / 3.0 * M_PI * r * r * r);
    // A sphere: V - E + F = 2.
    const size_t E = m.triangles.size() * 3 / 2;
    EXPECT_EQ(long(m.P.size()) - long(E) + long(m.triangles.size()), 2);
}

TEST(BlobbyField, MergedAndCarvedBlobsStayClosed) {
    BlobbyField merged;
    merged.ops = {sphere(1, {0, 0, 0}), sphere(1, {0.9, 0.2, 0}), combine(BlobbyOp::Kind::Add, {0, 1})};
    SCOPED_TRACE("merged");
    expectClosedAndConsistent(polygonizeBlobby(merged, 40));
    BlobbyField carved;
    SCOPED_TRACE("carved");
    carved.ops = {sphere(2, {0, 0, 0}), sphere(1, {0.6, 0, -0.5}), combine(BlobbyOp::Kind::Subtract, {0, 1})};
    expectClosedAndConsistent(polygonizeBlobby(carved, 40));
}

TEST(BlobbyField, ConstantsAboveTheLevelAreCutOpenAtTheBound) {
    BlobbyField f;
    BlobbyOp c;
    c.kind = BlobbyOp::Kind::Constant;
    c.value = 0.6;
    f.ops = {sphere(1, {0, 0, 0}), c, combine(BlobbyOp::Kind::Add, {0, 1})};
    EXPECT_TRUE(polygonizeBlobby(f, 16).openAtBound);
}

}  // namespace
}  // namespace streyes
