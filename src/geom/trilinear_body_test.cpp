#include <gtest/gtest.h>

#include <random>

#include "geom/body.h"
#include "geom/grid.h"
#include "pixel_camera.h"

namespace streyes {
namespace {

using Corners = TrilinearBody::Corners;

Corners randomCorners(std::mt19937& rng) {
    std::uniform_real_distribution<float> d(-5, 5);
    Corners c;
    for (auto& p : c) p = {d(rng), d(rng), d(rng) + 20};
    return c;
}

Vec3f bilinear(const Corners& c, float u, float v) { return lerp(lerp(c[0], c[1], u), lerp(c[2], c[3], u), v); }

TEST(TrilinearBody, BoundContainsTheSurfaceAtEveryTime) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        Corners a = randomCorners(rng), b = randomCorners(rng);
        TrilinearBody body({2, 6}, a, b, {}, nullptr);
        LBBox3f lb = body.bound();
        for (float s : {0.0f, 0.3f, 0.5f, 1.0f}) {
            Bounds3f at = lb.at(s);
            // grow by a relative epsilon for float rounding of the interpolation
            Vec3f eps{1e-4f, 1e-4f, 1e-4f};
            at = {at.lo - eps, at.hi + eps};
            Corners c;
            for (int i = 0; i < 4; ++i) c[size_t(i)] = lerp(a[size_t(i)], b[size_t(i)], s);
            for (float u : {0.0f, 0.25f, 0.7f, 1.0f})
                for (float v : {0.0f, 0.5f, 1.0f}) EXPECT_TRUE(at.contains(bilinear(c, u, v)));
        }
    }
}

TEST(TrilinearBody, SplitHalvesReproduceTheParent) {
    std::mt19937 rng(11);
    Corners a = randomCorners(rng), b = randomCorners(rng);
    TrilinearBody body({0, 4}, a, b, {}, nullptr);
    BodyPtr h[2];
    body.split(SplitAxis::U, h);
    Grid g0, g1, gp;
    body.dice(4, 2, gp);
    h[0]->dice(2, 2, g0);
    h[1]->dice(2, 2, g1);
    // Child vertex (i, j) is parent vertex (i, j) for the first half and (i + 2, j) for the second.
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j <= 2; ++j)
            for (int i = 0; i <= 2; ++i) {
                Vec3f p0 = gp.P[k][size_t(gp.index(i, j))], c0 = g0.P[k][size_t(g0.index(i, j))];
                Vec3f p1 = gp.P[k][size_t(gp.index(i + 2, j))], c1 = g1.P[k][size_t(g1.index(i, j))];
                EXPECT_NEAR(length(p0 - c0), 0.0f, 1e-5f);
                EXPECT_NEAR(length(p1 - c1), 0.0f, 1e-5f);
            }
    // The shared edge is bit-identical.
    for (int j = 0; j <= 2; ++j) EXPECT_EQ(g0.P[0][size_t(g0.index(2, j))], g1.P[0][size_t(g1.index(0, j))]);

    body.split(SplitAxis::T, h);
    EXPECT_EQ(h[0]->time().t1, 2.0);
    EXPECT_EQ(h[1]->time().t0, 2.0);
    const auto& first = static_cast<const TrilinearBody&>(*h[0]);
    const auto& second = static_cast<const TrilinearBody&>(*h[1]);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(first.corners(1)[size_t(i)], second.corners(0)[size_t(i)]);
        EXPECT_NEAR(length(first.corners(1)[size_t(i)] - (a[size_t(i)] + b[size_t(i)]) * 0.5f), 0, 1e-5f);
    }
}

TEST(TrilinearBody, StillBodyStaysStillAndMeasuresNoMotion) {
    Corners a{{{0, 0, 5}, {1, 0, 5}, {0, 1, 5}, {1, 1, 5}}};
    TrilinearBody body({0, 10}, a, a, {}, nullptr);
    EXPECT_FALSE(body.moving());
    BodyPtr h[2];
    body.split(SplitAxis::V, h);
    EXPECT_FALSE(h[0]->moving());
    RasterMeasure m = body.measure(test::pixelCamera(10));
    EXPECT_EQ(m.motion, 0.0f);
    EXPECT_FLOAT_EQ(m.extentU, 1.0f);
    EXPECT_FLOAT_EQ(m.extentV, 1.0f);
    EXPECT_FLOAT_EQ(m.bound.b0.lo.x, 0.0f);
    EXPECT_FLOAT_EQ(m.bound.b0.hi.y, 10.0f);  // raster y = 10 - y
}

TEST(TrilinearBody, RestrictedToKeepsTheMotionLine) {
    Corners a{{{0, 0, 5}, {1, 0, 5}, {0, 1, 5}, {1, 1, 5}}}, b = a;
    for (auto& p : b) p.x += 8;
    TrilinearBody body({0, 8}, a, b, {}, nullptr);
    BodyPtr r = body.restrictedTo(2, 4);
    const auto& t = static_cast<const TrilinearBody&>(*r);
    EXPECT_EQ(r->time().t0, 2.0);
    EXPECT_FLOAT_EQ(t.corners(0)[0].x, 2.0f);
    EXPECT_FLOAT_EQ(t.corners(1)[0].x, 4.0f);
    BodyPtr whole = body.restrictedTo(0, 8);
    EXPECT_EQ(static_cast<const TrilinearBody&>(*whole).corners(1)[3], b[3]);  // exact at the ends
}

// Pieces of one surface that meet in time share no instant: the earlier is half-open.
TEST(TrilinearBody, TimePiecesShareNoInstant) {
    Corners a{{{0, 0, 5}, {1, 0, 5}, {0, 1, 5}, {1, 1, 5}}}, b = a;
    for (auto& p : b) p.x += 8;
    for (bool open : {false, true}) {
        TrilinearBody body({0, 8, open}, a, b, {}, nullptr);
        BodyPtr h[2];
        body.split(SplitAxis::T, h);
        EXPECT_TRUE(h[0]->time().openEnd);
        EXPECT_EQ(h[1]->time().openEnd, open);  // the second half ends where the body does
        EXPECT_FALSE(h[0]->time().contains(4));
        EXPECT_TRUE(h[1]->time().contains(4));
        EXPECT_EQ(h[1]->time().contains(8), !open);
        BodyPtr u[2];
        h[0]->split(SplitAxis::U, u);
        EXPECT_TRUE(u[0]->time().openEnd);  // splits in space keep the span
        // Cut short by a bucket's window, a piece is closed at the cut: nothing else covers it there.
        EXPECT_FALSE(body.restrictedTo(2, 4)->time().openEnd);
        EXPECT_EQ(body.restrictedTo(2, 8)->time().openEnd, open);
        Grid g;
        h[0]->dice(1, 1, g);
        EXPECT_TRUE(g.openEnd);
    }
    // A span that ends half-open at a window's start does not reach into it.
    EXPECT_FALSE((TimeSpan{0, 2, true}.overlaps(2, 3)));
    EXPECT_TRUE((TimeSpan{0, 2, false}.overlaps(2, 3)));
}

TEST(TrilinearBody, DegenerateCornersGiveFiniteNormals) {
    // A triangle as a patch with a collapsed edge, and a zero-area patch.
    Corners tri{{{0, 0, 5}, {1, 0, 5}, {0, 1, 5}, {0, 1, 5}}};
    Corners point{{{1, 1, 5}, {1, 1, 5}, {1, 1, 5}, {1, 1, 5}}};
    for (const Corners& c : {tri, point}) {
        TrilinearBody body({0, 0}, c, c, {}, nullptr);
        Grid g;
        body.dice(3, 3, g);
        for (const Vec3f& n : g.N[0]) {
            EXPECT_TRUE(isFinite(n));
            EXPECT_GT(length(n), 0.0f);
        }
    }
}

}  // namespace
}  // namespace streyes
