// Blobby repelling planes (opcode 1003): the repulsion's closed form, a blob pushed off its ground
// to where field + repulsion = 27/64, and no repulsion (A = 0, a map that saw nothing) changing
// nothing.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>

#include "scene/blobby_field.h"

namespace streyes {
namespace {

constexpr double kA = 0.4, kB = 0.01, kC = 0.3, kD = 0.08;  // Aqsis's repel.rib

BlobbyOp sphereAt(double R, Vec3d c) {
    BlobbyOp op;
    op.kind = BlobbyOp::Kind::Ellipsoid;
    op.toObject = Matrix4::scale({R, R, R}) * Matrix4::translate(c);
    EXPECT_TRUE(invert(op.toObject, &op.toBlob));
    return op;
}

BlobbyOp plane(double A, std::shared_ptr<const BlobbyGround> ground = nullptr) {
    BlobbyOp op;
    op.kind = BlobbyOp::Kind::Plane;
    op.repel[0] = A, op.repel[1] = kB, op.repel[2] = kC, op.repel[3] = kD;
    op.ground = std::move(ground);
    return op;
}

BlobbyOp add(std::vector<int> operands) {
    BlobbyOp op;
    op.kind = BlobbyOp::Kind::Add;
    op.operands = std::move(operands);
    return op;
}

// The formula, written out: bump and ease as polynomials in their expanded form.
double repulsionByHand(double z, double A, double B, double C, double D) {
    if (z >= A) return 0;
    z = std::max(z, 1e-6);
    const double r = z / C, e = z / A;
    const double bump = r >= 2 ? 0 : 8 * r * r * r - 12 * std::pow(r, 4) + 6 * std::pow(r, 5) - std::pow(r, 6);
    const double ease = 3 * e * e - 2 * e * e * e;
    return (D * bump - B / z) * (1 - ease);
}

TEST(BlobbyRepel, RepulsionIsTheClosedForm) {
    // z = 0.2: bump(2/3) = 512/729, ease(1/2) = 1/2.
    EXPECT_NEAR(blobbyRepulsion(0.2, kA, kB, kC, kD), (kD * 512.0 / 729.0 - kB / 0.2) * 0.5, 1e-15);
    for (double z : {0.001, 0.05, 0.1, 0.29, 0.3, 0.35, 0.399})
        EXPECT_NEAR(blobbyRepulsion(z, kA, kB, kC, kD), repulsionByHand(z, kA, kB, kC, kD), 1e-12) << z;
    EXPECT_EQ(blobbyRepulsion(0.4, kA, kB, kC, kD), 0);  // from A up: nothing
    EXPECT_EQ(blobbyRepulsion(7, kA, kB, kC, kD), 0);
    EXPECT_EQ(blobbyRepulsion(INFINITY, kA, kB, kC, kD), 0);
    // At and under the ground: z is taken as 1e-6, so the field is about -B 10^6.
    EXPECT_NEAR(blobbyRepulsion(-3, kA, kB, kC, kD), -kB * 1e6, 1e-6);
    EXPECT_EQ(blobbyRepulsion(-3, kA, kB, kC, kD), blobbyRepulsion(0, kA, kB, kC, kD));
    for (double z : {-1.0, 0.0, 0.1, 0.3}) EXPECT_EQ(blobbyRepulsion(z, 0, kB, kC, kD), 0);  // A = 0: none
}

// A blob of radius R centred at height h above the plane z = 0 (object space, heights as -z, as
// Aqsis takes a plane with no map): on its axis the surface's lowest point is at height h - r, r
// the root of (1 - (r/R)^2)^3 + repulsion(h - r) = 27/64, found here by bisection on the formula.
constexpr double kR = 1.5, kH = 0.85;

double lowestHeightByHand(double centre = kH) {
    auto f = [&](double r) {
        const double s = 1 - (r / kR) * (r / kR);
        return s * s * s + repulsionByHand(centre - r, kA, kB, kC, kD) - 27.0 / 64.0;
    };
    double in = 0, out = centre;  // f(0) > 0: inside; at r = h (the ground) far below 0
    for (int i = 0; i < 200; ++i) {
        const double m = (in + out) / 2;
        (f(m) > 0 ? in : out) = m;
    }
    return centre - (in + out) / 2;
}

// The mesh's lowest vertex (nearest the ground: largest z).
double lowestHeight(const BlobbyMesh& m) {
    double zmax = -INFINITY;
    for (const Vec3d& p : m.P) zmax = std::max(zmax, p.z);
    return -zmax;
}

TEST(BlobbyRepel, APlaneWithNoMapPushesTheBlobOffZEqualsZero) {
    BlobbyField alone;
    alone.ops = {sphereAt(kR, {0, 0, -kH})};
    BlobbyField repelled;
    repelled.ops = {sphereAt(kR, {0, 0, -kH}), plane(kA), add({0, 1})};
    const double gapAlone = kH - kR * 0.5;  // 0.1: the blob's own bottom
    const double gap = lowestHeightByHand();
    ASSERT_GT(gap, gapAlone + 0.02);  // the push is large against the tolerances below
    const int cells = 96;
    const BlobbyMesh m = polygonizeBlobby(repelled, cells);
    ASSERT_GT(m.triangles.size(), 1000u);
    // Vertices lie on the surface; the lowest is within a cell's sagitta of the axis's point, and
    // never below it.
    const double h = 2 * kR / cells;
    EXPECT_GE(lowestHeight(m), gap - 1e-9);
    EXPECT_LE(lowestHeight(m), gap + h * h / kR);
    EXPECT_NEAR(lowestHeight(polygonizeBlobby(alone, cells)), gapAlone, h * h / kR);
    // The sampler that skips far leaves gives the field's own value, bit for bit.
    BlobbyEvaluator eval(repelled);
    std::vector<double> scratch;
    for (double z : {-3.0, -1.0, -0.2, -0.05, 0.0, 0.5})
        for (double x : {0.0, 0.7, 2.5}) {
            const Vec3d p{x, 0.3, z};
            EXPECT_EQ(eval.value(p), repelled.value(p, scratch)) << x << " " << z;
        }
}

bool sameMesh(const BlobbyMesh& a, const BlobbyMesh& b) {
    if (a.P.size() != b.P.size() || a.triangles != b.triangles) return false;
    for (size_t i = 0; i < a.P.size(); ++i)
        if (a.P[i].x != b.P[i].x || a.P[i].y != b.P[i].y || a.P[i].z != b.P[i].z) return false;
    return true;
}

TEST(BlobbyRepel, NoRepulsionLeavesTheSurfaceBitForBit) {
    BlobbyField alone;
    alone.ops = {sphereAt(kR, {0, 0, -kH})};
    const BlobbyMesh want = polygonizeBlobby(alone, 48);
    BlobbyField zeroA;
    zeroA.ops = {sphereAt(kR, {0, 0, -kH}), plane(0), add({0, 1})};
    EXPECT_TRUE(sameMesh(polygonizeBlobby(zeroA, 48), want));
    // A map that saw nothing anywhere: no ground, no repulsion.
    auto empty = std::make_shared<BlobbyGround>();
    empty->map.width = empty->map.height = 4;
    empty->map.z.assign(16, FLT_MAX);
    empty->objectToScreen = Matrix4::scale({0.2, 0.2, 1});
    empty->objectToCamera = Matrix4::translate({0, 0, 10});
    BlobbyField unseen;
    unseen.ops = {sphereAt(kR, {0, 0, -kH}), plane(kA, empty), add({0, 1})};
    EXPECT_TRUE(sameMesh(polygonizeBlobby(unseen, 48), want));
    // And the repelled one is not the same (the comparison can fail).
    BlobbyField repelled;
    repelled.ops = {sphereAt(kR, {0, 0, -kH}), plane(kA), add({0, 1})};
    EXPECT_FALSE(sameMesh(polygonizeBlobby(repelled, 48), want));
}

// A map of constant depth 10 from an orthographic camera 10 above the plane z = 0 (looking down +z,
// as object z grows toward the ground) is the same ground: the same lowest point.
TEST(BlobbyRepel, AMapOfConstantDepthIsTheGroundItSaw) {
    auto flat = std::make_shared<BlobbyGround>();
    flat->map.width = flat->map.height = 8;
    flat->map.z.assign(64, 10.0f);
    flat->objectToCamera = Matrix4::translate({0, 0, 10});
    flat->objectToScreen = Matrix4::scale({0.2, 0.2, 1}) * Matrix4::translate({0, 0, 10});  // [-5, 5] across
    EXPECT_NEAR(flat->height({1, 2, -0.3}), 0.3, 1e-12);
    EXPECT_NEAR(flat->height({-4.9, 4.9, 0.2}), -0.2, 1e-12);
    EXPECT_EQ(flat->height({6, 0, -0.3}), INFINITY);  // off the map
    EXPECT_EQ(flat->height({0, 0, -11}), INFINITY);   // behind its camera
    BlobbyField repelled;
    repelled.ops = {sphereAt(kR, {0, 0, -kH}), plane(kA, flat), add({0, 1})};
    const int cells = 96;
    const double h = 2 * kR / cells;
    const BlobbyMesh m = polygonizeBlobby(repelled, cells);
    EXPECT_GE(lowestHeight(m), lowestHeightByHand() - 1e-9);
    EXPECT_LE(lowestHeight(m), lowestHeightByHand() + h * h / kR);
    // A ground 0.2 lower (depth 10.2): the blob is 0.95 above it, and less pushed.
    auto lower = std::make_shared<BlobbyGround>(*flat);
    lower->map.z.assign(64, 10.2f);
    BlobbyField down;
    down.ops = {sphereAt(kR, {0, 0, -kH}), plane(kA, lower), add({0, 1})};
    const double above = lowestHeight(polygonizeBlobby(down, cells)) + 0.2;
    EXPECT_GE(above, lowestHeightByHand(kH + 0.2) - 1e-6);
    EXPECT_LE(above, lowestHeightByHand(kH + 0.2) + h * h / kR);
    EXPECT_GT(lowestHeightByHand(kH + 0.2) - lowestHeightByHand(kH), 0.1);  // the two differ: less pushed
}

}  // namespace
}  // namespace streyes
