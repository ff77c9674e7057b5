// Ribbons: a straight camera-facing ribbon is exactly its rectangle; an N-oriented one has N as
// its normal; segments meeting at a joint share its cross-section bit for bit; vertex widths
// follow the basis.
#include "geom/curves.h"

#include <cmath>

#include <gtest/gtest.h>

namespace streyes {
namespace {

CurvesDesc curves(bool cubic, std::vector<int> n, std::vector<Vec3d> P) {
    CurvesDesc d;
    d.cubic = cubic;
    d.nvertices = std::move(n);
    d.P = {std::move(P)};
    return d;
}

TEST(CurveRibbons, StraightCameraFacingRibbonIsItsRectangle) {
    CurvesDesc d = curves(false, {3}, {{0, 0, 5}, {4, 0, 5}, {10, 0, 5}});
    d.widthClass = ParamClass::Varying;
    d.width = {2, 2, 4};
    const CurveRibbons r(d);
    ASSERT_EQ(r.faceCount(), 2);
    const std::vector<BezierPatch> p = r.patches(d.P[0], Matrix4{}, false);
    // Corners: (0,0) (1,0) (0,1) (1,1) are control points 0, 3, 12, 15; the width lies along y.
    EXPECT_FLOAT_EQ(std::fabs(p[0][0].y - p[0][12].y), 2.0f);
    EXPECT_FLOAT_EQ(std::fabs(p[1][3].y - p[1][15].y), 4.0f);
    EXPECT_EQ(p[0][3], p[1][0]);  // the joint, shared
    EXPECT_EQ(p[0][15], p[1][12]);
    for (const BezierPatch& b : p)
        for (const Vec3f& c : b) EXPECT_EQ(c.z, 5.0f);  // facing the camera (orthographic)
    // Scaled by 3: widths scale with the transform.
    const std::vector<BezierPatch> s = r.patches(d.P[0], Matrix4::scale({3, 3, 3}), false);
    EXPECT_FLOAT_EQ(std::fabs(s[0][0].y - s[0][12].y), 6.0f);
}

TEST(CurveRibbons, NormalsOrientTheRibbon) {
    CurvesDesc d = curves(false, {2}, {{0, 0, 5}, {0, 10, 5}});
    d.N = {{1, 0, 0}, {1, 0, 0}};  // the ribbon lies in the plane x = 0: its width along z
    const CurveRibbons r(d);
    const BezierPatch p = r.patches(d.P[0], Matrix4{}, true)[0];
    EXPECT_FLOAT_EQ(p[0].x, 0.0f);
    EXPECT_FLOAT_EQ(p[12].x, 0.0f);
    EXPECT_FLOAT_EQ(std::fabs(p[12].z - p[0].z), 1.0f);
}

TEST(CurveRibbons, PeriodicCubicCurvesCloseAndVertexWidthsFollowTheBasis) {
    BasisDesc bspline;
    ASSERT_TRUE(basisFromName("b-spline", &bspline));
    CurvesDesc d = curves(true, {4}, {{0, 0, 5}, {10, 0, 5}, {10, 10, 5}, {0, 10, 5}});
    d.basis = bspline;
    d.periodic = true;
    d.widthClass = ParamClass::Vertex;
    d.width = {6, 0, 0, 0};
    const CurveRibbons r(d);
    ASSERT_EQ(r.faceCount(), 4);
    const std::vector<BezierPatch> p = r.patches(d.P[0], Matrix4{}, false);
    for (int f = 0; f < 4; ++f) {
        EXPECT_EQ(p[size_t(f)][3], p[size_t((f + 1) % 4)][0]);  // closed: the last joint is the first
        EXPECT_EQ(p[size_t(f)][15], p[size_t((f + 1) % 4)][12]);
    }
    // A uniform B-spline's segment s starts at (P[s] + 4 P[s+1] + P[s+2]) / 6: with vertex widths
    // 6, 0, 0, 0 segment 0 starts 1 wide, segment 3 (points 3, 0, 1) 4 wide.
    EXPECT_NEAR(length(Vec3d(p[0][12] - p[0][0])), 1.0, 1e-5);
    EXPECT_NEAR(length(Vec3d(p[3][12] - p[3][0])), 4.0, 1e-5);
}

TEST(CurveRibbons, BentSegmentsKeepTheirWidth) {
    // A quarter circle of radius 10 as one Bezier segment (k = 0.5523), 2 wide, facing the camera.
    const double k = 0.5523 * 10;
    CurvesDesc d = curves(true, {4}, {{10, 0, 5}, {10, k, 5}, {k, 10, 5}, {0, 10, 5}});
    d.width = {2};
    const CurveRibbons r(d);
    const BezierPatch p = r.patches(d.P[0], Matrix4{}, false)[0];
    for (double u : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        Vec3d a, b, du, dv;
        evalBezier(p, u, 0, &a, &du, &dv);
        evalBezier(p, u, 1, &b, &du, &dv);
        EXPECT_NEAR(length(b - a), 2.0, 0.02) << u;  // blending the ends' directions gave 1.41 at 0.5
    }
}

}  // namespace
}  // namespace streyes
