// NURBS evaluation against exact answers: a rational quadratic circle lies on the circle, the
// derivatives agree with finite differences, the basis sums to one, a piece's Bezier-net bound
// holds the surface and shrinks with it; trim loops cut what they enclose.
#include "geom/nurbs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geom/nurbs_trim.h"

namespace streyes {
namespace {

const double kH = std::sqrt(0.5);

// The rational quadratic circle of radius 1 in z = 0: 9 points around a square, weights
// 1, sqrt(2)/2, 1, ... and knots at the quarters.
struct Circle {
    std::vector<double> knot{0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
    std::vector<Vec3d> P{{1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}, {-1, 0, 0},
                         {-1, -1, 0}, {0, -1, 0}, {1, -1, 0}, {1, 0, 0}};
    std::vector<double> w{1, kH, 1, kH, 1, kH, 1, kH, 1};
    std::vector<double> vknot{0, 1};
    // As a surface of one row (order 1 in v).
    NurbsSurface surface() const {
        NurbsSurface s;
        s.nu = 9, s.uorder = 3, s.nv = 1, s.vorder = 1;
        s.uknot = knot.data(), s.vknot = vknot.data(), s.w = w.data(), s.P = P.data();
        return s;
    }
};

TEST(Nurbs, RationalQuadraticCircleLiesOnTheCircle) {
    const Circle c;
    const NurbsSurface s = c.surface();
    double worst = 0;
    for (int i = 0; i <= 1000; ++i) {
        Vec3d p, du, dv;
        s.evaluate(i / 1000.0, 0.5, &p, &du, &dv);
        worst = std::max(worst, std::fabs(length(p) - 1));
        // In float, as the renderer keeps it: within float rounding of the circle.
        const Vec3f f(p);
        EXPECT_NEAR(std::hypot(double(f.x), double(f.y)), 1.0, 2e-7) << "u " << i / 1000.0;
        // The tangent is perpendicular to the radius.
        EXPECT_NEAR(dot(p, du) / length(du), 0.0, 1e-12);
    }
    EXPECT_LT(worst, 1e-14);
    // The quarters are the control points themselves, bit for bit.
    Vec3d p, du, dv;
    s.evaluate(0.25, 0, &p, &du, &dv);
    EXPECT_EQ(p, Vec3d(0, 1, 0));
    s.evaluate(1, 0, &p, &du, &dv);
    EXPECT_EQ(p, Vec3d(1, 0, 0));
}

// A rational bicubic-by-quadratic surface with non-uniform knots, a double knot and uneven
// weights, for derivative and bound checks.
struct Wavy {
    std::vector<double> uknot{0, 0, 0, 0, 0.3, 0.3, 0.7, 1.2, 1.2, 1.2, 1.2};  // 7 points, order 4
    std::vector<double> vknot{-1, -1, -1, 0, 0.5, 2, 2, 2};                  // 5 points, order 3
    std::vector<Vec3d> P;
    std::vector<double> w;
    Wavy() {
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> d(-1, 1), wd(0.3, 3);
        for (int j = 0; j < 5; ++j)
            for (int i = 0; i < 7; ++i) {
                P.push_back({i + 0.3 * d(rng), j + 0.3 * d(rng), d(rng)});
                w.push_back(wd(rng));
            }
    }
    NurbsSurface surface() const {
        NurbsSurface s;
        s.nu = 7, s.uorder = 4, s.nv = 5, s.vorder = 3;
        s.uknot = uknot.data(), s.vknot = vknot.data(), s.w = w.data(), s.P = P.data();
        return s;
    }
};

TEST(Nurbs, DerivativesAgreeWithFiniteDifferences) {
    const Wavy wavy;
    const NurbsSurface s = wavy.surface();
    const double h = 1e-6;
    for (double u : {0.01, 0.2, 0.31, 0.5, 0.69, 1.0, 1.19})
        for (double v : {-0.99, -0.4, 0.1, 0.49, 1.3, 1.99}) {
            Vec3d p, du, dv, a, b, unused;
            s.evaluate(u, v, &p, &du, &dv);
            s.evaluate(u + h, v, &a, &unused, &unused);
            s.evaluate(u - h, v, &b, &unused, &unused);
            const Vec3d fu = (a - b) / (2 * h);
            s.evaluate(u, v + h, &a, &unused, &unused);
            s.evaluate(u, v - h, &b, &unused, &unused);
            const Vec3d fv = (a - b) / (2 * h);
            EXPECT_LT(length(du - fu), 1e-6 * (1 + length(du))) << u << " " << v;
            EXPECT_LT(length(dv - fv), 1e-6 * (1 + length(dv))) << u << " " << v;
        }
}

TEST(Nurbs, BasisSumsToOneAndItsDerivativesToZero) {
    const Wavy wavy;
    for (double t : {0.0, 0.1, 0.3, 0.65, 1.2}) {
        const int s = nurbsSpan(wavy.uknot.data(), 7, 4, t);
        EXPECT_LE(wavy.uknot[size_t(s)], t);
        EXPECT_LT(wavy.uknot[size_t(s)], wavy.uknot[size_t(s) + 1]);
        double N[kMaxNurbsOrder], dN[kMaxNurbsOrder];
        nurbsBasis(wavy.uknot.data(), 4, s, t, N, dN);
        double sum = 0, dsum = 0;
        for (int r = 0; r < 4; ++r) {
            EXPECT_GE(N[r], 0);
            sum += N[r], dsum += dN[r];
        }
        EXPECT_NEAR(sum, 1, 1e-15);
        EXPECT_NEAR(dsum, 0, 1e-12);
    }
}

TEST(Nurbs, BezierNetBoundHoldsThePieceAndShrinksWithIt) {
    const Wavy wavy;
    const NurbsSurface s = wavy.surface();
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> ud(0, 1.2), vd(-1, 2);
    for (int trial = 0; trial < 200; ++trial) {
        double u0 = ud(rng), u1 = ud(rng), v0 = vd(rng), v1 = vd(rng);
        if (u0 > u1) std::swap(u0, u1);
        if (v0 > v1) std::swap(v0, v1);
        const Bounds3d b = s.bound(u0, u1, v0, v1);
        const Vec3d pad{1e-12, 1e-12, 1e-12};
        const Bounds3d grown(b.lo - pad, b.hi + pad);
        for (int j = 0; j <= 8; ++j)
            for (int i = 0; i <= 8; ++i) {
                Vec3d p, du, dv;
                s.evaluate(u0 + (u1 - u0) * i / 8, v0 + (v1 - v0) * j / 8, &p, &du, &dv);
                ASSERT_TRUE(grown.contains(p)) << "trial " << trial;
            }
    }
    // A small piece's bound is about the piece's size, not its spans' (the control hull's).
    const Bounds3d whole = s.bound(0, 1.2, -1, 2), piece = s.bound(0.5, 0.5 + 1e-3, 0.2, 0.2 + 1e-3);
    EXPECT_LT(length(piece.diagonal()), 1e-2);
    EXPECT_GT(length(whole.diagonal()), 5);
}

// A large patch (12 x 10 spans): rectangles over many spans are bounded by their spans' control
// points, smaller ones by Bezier nets; both hold the surface.
TEST(Nurbs, BoundOverManySpansHoldsTheSurface) {
    const int n = 15, m = 13;
    std::vector<double> uk{0, 0, 0}, vk{0, 0, 0};
    for (int i = 0; i <= n - 3; ++i) uk.push_back(i + 0.1 * (i % 3));
    for (int i = 0; i <= m - 3; ++i) vk.push_back(0.5 * i);
    for (int i = 0; i < 3; ++i) uk.push_back(uk.back()), vk.push_back(vk.back());
    std::vector<Vec3d> P;
    std::vector<double> w;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> d(-1, 1), wd(0.2, 4);
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i) P.push_back({i + d(rng), j + d(rng), 3 * d(rng)}), w.push_back(wd(rng));
    NurbsSurface s;
    s.nu = n, s.uorder = 4, s.nv = m, s.vorder = 4;
    s.uknot = uk.data(), s.vknot = vk.data(), s.w = w.data(), s.P = P.data();
    const double U = uk[size_t(n)], V = vk[size_t(m)];
    std::uniform_real_distribution<double> ud(0, U), vd(0, V);
    for (int trial = 0; trial < 100; ++trial) {
        double u0 = ud(rng), u1 = ud(rng), v0 = vd(rng), v1 = vd(rng);
        if (trial == 0) u0 = 0, u1 = U, v0 = 0, v1 = V;
        if (u0 > u1) std::swap(u0, u1);
        if (v0 > v1) std::swap(v0, v1);
        const Bounds3d b = s.bound(u0, u1, v0, v1);
        const Vec3d pad{1e-12, 1e-12, 1e-12};
        const Bounds3d grown(b.lo - pad, b.hi + pad);
        for (int j = 0; j <= 20; ++j)
            for (int i = 0; i <= 20; ++i) {
                Vec3d p, du, dv;
                s.evaluate(u0 + (u1 - u0) * i / 20, v0 + (v1 - v0) * j / 20, &p, &du, &dv);
                ASSERT_TRUE(grown.contains(p)) << "trial " << trial;
            }
    }
}

TEST(Nurbs, IsoCurveOfAnEndIsTheBoundaryRow) {
    const Wavy wavy;
    std::vector<HPoint> row;
    wavy.surface().isoCurve(false, -1, &row);  // v = vmin: the first row, clamped knots
    ASSERT_EQ(row.size(), 7u);
    for (size_t i = 0; i < 7; ++i) {
        EXPECT_NEAR(row[i].w, wavy.w[i], 1e-15);
        EXPECT_LT(length(row[i].p / row[i].w - wavy.P[i]), 1e-14);
    }
}

// A circle of radius r about (cu, cv) in (u, v): the rational quadratic above, homogeneous.
TrimCurveDesc trimCircle(double cu, double cv, double r) {
    const Circle c;
    TrimCurveDesc t;
    t.order = 3;
    t.knot = c.knot;
    t.tmin = 0, t.tmax = 1;
    for (size_t i = 0; i < 9; ++i) {
        t.u.push_back((cu + r * c.P[i].x) * c.w[i]);
        t.v.push_back((cv + r * c.P[i].y) * c.w[i]);
        t.w.push_back(c.w[i]);
    }
    return t;
}

TEST(NurbsTrim, CutsWhatTheLoopsEncloseByTheOddRule) {
    TrimLoops loops;
    loops.loops = {{trimCircle(0.5, 0.5, 0.3)}, {trimCircle(0.5, 0.5, 0.1)}};
    const NurbsTrim trim(loops);
    EXPECT_FALSE(trim.cut(0.5, 0.5));   // inside both loops: crossed twice
    EXPECT_TRUE(trim.cut(0.5, 0.75));   // between them
    EXPECT_TRUE(trim.cut(0.29, 0.5));
    EXPECT_FALSE(trim.cut(0.19, 0.5));  // outside the outer
    EXPECT_FALSE(trim.cut(0.9, 0.9));
    // On a grid: the cut micropolygons' area is the ring's, to the grid's resolution.
    std::vector<uint8_t> hole;
    ASSERT_TRUE(trim.mark(0, 1, 0, 1, 400, 400, hole));
    size_t cut = 0;
    for (uint8_t h : hole) cut += h;
    const double area = double(cut) / (400.0 * 400.0), ring = M_PI * (0.09 - 0.01);
    EXPECT_NEAR(area, ring, 2e-3 * ring);
    // A rectangle away from the loops is not touched.
    std::vector<uint8_t> none;
    EXPECT_FALSE(trim.mark(0.85, 1, 0.85, 1, 4, 4, none));
    EXPECT_TRUE(none.empty());
}

// A loop of several curves, head to tail: a square of four linear (order 2) sides, one with a
// knot inside, and a rational one whose weights leave its line straight.
TEST(NurbsTrim, LoopsOfSeveralCurvesCutTheirInside) {
    auto side = [](std::vector<double> u, std::vector<double> v, std::vector<double> w, std::vector<double> knot) {
        TrimCurveDesc t;
        t.order = 2, t.knot = std::move(knot), t.tmin = t.knot[1], t.tmax = t.knot[t.knot.size() - 2];
        t.u = std::move(u), t.v = std::move(v), t.w = std::move(w);
        return t;
    };
    TrimLoops loops;
    loops.loops = {{side({0.25, 0.75}, {0.25, 0.25}, {1, 1}, {0, 0, 1, 1}),
                    side({0.75, 0.75, 0.75}, {0.25, 0.5, 0.75}, {1, 1, 1}, {0, 0, 0.5, 1, 1}),
                    side({0.75 * 2, 0.25 * 2}, {0.75 * 2, 0.75 * 2}, {2, 2}, {0, 0, 1, 1}),  // homogeneous
                    side({0.25, 0.25}, {0.75, 0.25}, {1, 1}, {3, 3, 4, 4})}};
    const NurbsTrim trim(loops);
    EXPECT_TRUE(trim.cut(0.5, 0.5));
    EXPECT_TRUE(trim.cut(0.74, 0.26));
    EXPECT_FALSE(trim.cut(0.76, 0.5));
    EXPECT_FALSE(trim.cut(0.5, 0.8));
    std::vector<uint8_t> hole;
    ASSERT_TRUE(trim.mark(0, 1, 0, 1, 100, 100, hole));
    size_t cut = 0;
    for (uint8_t h : hole) cut += h;
    EXPECT_EQ(cut, 50u * 50u);  // centres (i + 0.5) / 100 inside [0.25, 0.75]: i = 25 .. 74
}

}  // namespace
}  // namespace streyes
