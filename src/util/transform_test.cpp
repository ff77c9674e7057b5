#include <gtest/gtest.h>

#include <cmath>

#include "streyes/transform.h"

namespace streyes {
namespace {

void expectNear(Vec3d a, Vec3d b, double eps = 1e-12) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

TEST(Transform, RowVectorConventionAppliesTheLeftMatrixFirst) {
    Matrix4 t = Matrix4::translate({1, 0, 0}), s = Matrix4::scale({2, 2, 2});
    expectNear((t * s).point({0, 0, 0}), {2, 0, 0});  // translate, then scale
    expectNear((s * t).point({0, 0, 0}), {1, 0, 0});
    expectNear(Matrix4::rotate(90, {0, 0, 1}).point({1, 0, 0}), {0, 1, 0});
}

TEST(Transform, InverseUndoes) {
    Matrix4 m = Matrix4::rotate(33, {1, 2, 3}) * Matrix4::translate({4, -5, 6}) * Matrix4::scale({2, 3, 4});
    Matrix4 inv;
    ASSERT_TRUE(invert(m, &inv));
    expectNear((m * inv).point({7, 8, 9}), {7, 8, 9}, 1e-9);
    Matrix4 singular = Matrix4::scale({1, 0, 1});
    EXPECT_FALSE(invert(singular, &inv));
}

TEST(Transform, BoxHoldsEveryCornerTransformed) {
    // A quarter turn about z, then a move: x [1, 2] y [0, 3] z [0, 1] goes to x [-3, 0] y [1, 2],
    // then x [7, 10] y [1, 2] z [0, 1]; a 45-degree turn widens a unit square to its diagonal.
    const Bounds3d b({1, 0, 0}, {2, 3, 1});
    const Bounds3d r = (Matrix4::rotate(90, {0, 0, 1}) * Matrix4::translate({10, 0, 0})).box(b);
    expectNear(r.lo, {7, 1, 0});
    expectNear(r.hi, {10, 2, 1});
    const Vec3d d = Matrix4::rotate(45, {0, 0, 1}).box(Bounds3d({0, 0, 0}, {1, 1, 1})).diagonal();
    expectNear(d, {std::sqrt(2.0), std::sqrt(2.0), 1});
    EXPECT_TRUE(Matrix4().box(Bounds3d()).empty());  // an empty box stays empty
}

TEST(MotionTransform, LinearBetweenKeysHeldOutside) {
    MotionTransform m({0, 10}, {Matrix4::translate({0, 0, 0}), Matrix4::translate({10, 0, 0})});
    expectNear(m.at(-5).point({}), {0, 0, 0});
    expectNear(m.at(2.5).point({}), {2.5, 0, 0});
    expectNear(m.at(20).point({}), {10, 0, 0});
    MotionTransform still({0, 1}, {Matrix4::scale({2, 2, 2}), Matrix4::scale({2, 2, 2})});
    EXPECT_TRUE(still.isStatic());
}

TEST(MotionTransform, ThenUsesTheUnionOfKeys) {
    MotionTransform a({0, 4}, {Matrix4::translate({0, 0, 0}), Matrix4::translate({4, 0, 0})});
    MotionTransform b({2, 6}, {Matrix4::translate({0, 0, 0}), Matrix4::translate({0, 4, 0})});
    MotionTransform c = a.then(b);
    ASSERT_EQ(c.times(), (std::vector<double>{0, 2, 4, 6}));
    expectNear(c.at(4).point({}), {4, 2, 0});
    expectNear(c.at(3).point({}), {3, 1, 0});
}

}  // namespace
}  // namespace streyes
