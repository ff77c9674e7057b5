// Bezier form of bicubic patches: every RenderMan basis converts exactly, fitting recovers a
// bicubic, and de Casteljau's halves and sub-patches are the same surface.
#include "geom/bezier.h"

#include <gtest/gtest.h>

#include <random>

namespace streyes {
namespace {

// [t^3 t^2 t 1] * M * g: a cubic in a RenderMan basis, evaluated directly.
double basisCurve(const BasisDesc& b, const double g[4], double t) {
    const double T[4] = {t * t * t, t * t, t, 1};
    double s = 0;
    for (int k = 0; k < 4; ++k)
        for (int i = 0; i < 4; ++i) s += T[k] * b.m[size_t(k * 4 + i)] * g[i];
    return s;
}

Vec3d basisPatch(const BasisDesc& bu, const BasisDesc& bv, const Vec3d g[16], double u, double v) {
    Vec3d p;
    for (int c = 0; c < 3; ++c) {
        double rows[4];
        for (int j = 0; j < 4; ++j) {
            double row[4];
            for (int i = 0; i < 4; ++i) row[i] = g[j * 4 + i][c];
            rows[j] = basisCurve(bu, row, u);
        }
        p[c] = basisCurve(bv, rows, v);
    }
    return p;
}

Vec3d evalAt(const BezierPatch& cp, double u, double v) {
    Vec3d p;
    evalBezier(cp, u, v, &p, nullptr, nullptr);
    return p;
}

TEST(Bezier, EveryNamedBasisConvertsToTheSameSurface) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> d(-2, 2);
    for (const char* name : {"bezier", "b-spline", "catmull-rom", "hermite", "power"}) {
        BasisDesc b;
        ASSERT_TRUE(basisFromName(name, &b)) << name;
        Vec3d g[16];
        for (Vec3d& p : g) p = {d(rng), d(rng), d(rng)};
        const Matrix4x4 c = basisToBezier(b);
        const BezierPatch cp = patchToBezier(c, c, g);
        for (double u : {0.0, 0.13, 0.5, 0.77, 1.0})
            for (double v : {0.0, 0.31, 0.62, 1.0}) {
                const Vec3d want = basisPatch(b, b, g, u, v), got = evalAt(cp, u, v);
                EXPECT_NEAR(length(want - got), 0.0, 1e-5) << name << " at " << u << "," << v;
            }
    }
    BasisDesc unknown;
    EXPECT_FALSE(basisFromName("nurbs", &unknown));
}

TEST(Bezier, BSplinePatchLimitPointsMatchTheBSplineFormula) {
    // A uniform cubic B-spline patch: at its corner the surface is the mask
    // (1 4 1) x (1 4 1) / 36 of the 3x3 control points around it.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> d(-1, 1);
    Vec3d g[16];
    for (Vec3d& p : g) p = {d(rng), d(rng), d(rng)};
    BasisDesc bs;
    basisFromName("b-spline", &bs);
    const Matrix4x4 c = basisToBezier(bs);
    const BezierPatch cp = patchToBezier(c, c, g);
    const double w[3] = {1, 4, 1};
    Vec3d corner;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) corner += g[j * 4 + i] * (w[i] * w[j] / 36);
    EXPECT_NEAR(length(evalAt(cp, 0, 0) - corner), 0.0, 1e-6);
    // The middle of the patch: mask (1 23 23 1) / 48 in both directions.
    const double m[4] = {1, 23, 23, 1};
    Vec3d centre;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) centre += g[j * 4 + i] * (m[i] * m[j] / 2304);
    EXPECT_NEAR(length(evalAt(cp, 0.5, 0.5) - centre), 0.0, 1e-6);
}

TEST(Bezier, FitRecoversABicubicAndEdgesAreExact) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> d(-3, 3);
    BezierPatch cp;
    for (Vec3f& p : cp) p = {d(rng), d(rng), d(rng)};
    Vec3d samples[16];
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) samples[j * 4 + i] = evalAt(cp, i / 3.0, j / 3.0);
    const BezierPatch fit = fitBezier(samples);
    for (size_t i = 0; i < 16; ++i) EXPECT_NEAR(length(fit[i] - cp[i]), 0.0f, 2e-5f);
    // On the edge v = 0 the surface is exactly the first row's curve, whatever the other rows.
    BezierPatch other = cp;
    for (size_t i = 4; i < 16; ++i) other[i] = other[i] * 2.0f;
    for (double u : {0.1, 0.25, 0.9}) EXPECT_EQ(evalAt(cp, u, 0), evalAt(other, u, 0));
}

TEST(Bezier, HalvesAndSubPatchesAreTheSameSurface) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> d(-3, 3);
    BezierPatch cp;
    for (Vec3f& p : cp) p = {d(rng), d(rng), d(rng)};
    for (int axis = 0; axis < 2; ++axis) {
        BezierPatch lo, hi;
        splitBezier(cp, axis, lo, hi);
        for (double s : {0.0, 0.3, 1.0})
            for (double t : {0.0, 0.6, 1.0}) {
                const double u = axis == 0 ? s : t, v = axis == 0 ? t : s;
                const double pu = axis == 0 ? s / 2 : t, pv = axis == 0 ? t : s / 2;
                const double qu = axis == 0 ? 0.5 + s / 2 : t, qv = axis == 0 ? t : 0.5 + s / 2;
                EXPECT_NEAR(length(evalAt(lo, u, v) - evalAt(cp, pu, pv)), 0.0, 2e-5);
                EXPECT_NEAR(length(evalAt(hi, u, v) - evalAt(cp, qu, qv)), 0.0, 2e-5);
            }
        // The halves meet at bit-identical control points.
        for (int k = 0; k < 4; ++k) {
            const size_t a = size_t(axis == 0 ? k * 4 + 3 : 12 + k), b = size_t(axis == 0 ? k * 4 : k);
            EXPECT_EQ(lo[a], hi[b]);
        }
    }
    const BezierPatch sub = bezierSubPatch(cp, 0.25, 0.75, 0.1, 0.35);
    const Bounds3f box = bezierBound(sub);
    for (double s : {0.0, 0.4, 1.0})
        for (double t : {0.0, 0.7, 1.0}) {
            const Vec3d want = evalAt(cp, 0.25 + 0.5 * s, 0.1 + 0.25 * t);
            EXPECT_NEAR(length(evalAt(sub, s, t) - want), 0.0, 2e-5);
            const Vec3f w(want);
            EXPECT_TRUE(box.contains(w) || length(vmin(vmax(w, box.lo), box.hi) - w) < 1e-5f);
        }
}

}  // namespace
}  // namespace streyes
