// Cutting polygons: the faces cover the polygon exactly once (their areas add up to its area and
// each lies inside it), keep its winding, and convex quads stay whole.
#include "geom/triangulate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace streyes {
namespace {

// Signed area of a face in the z = const plane (triangles repeat their last corner).
double faceArea(const std::vector<Vec3d>& p, const std::array<int, 4>& f) {
    // Patch order 0 1 3 2 goes around the quad.
    const int ring[4] = {f[0], f[1], f[3], f[2]};
    double a = 0;
    for (int i = 0; i < 4; ++i) {
        const Vec3d &u = p[size_t(ring[i])], &v = p[size_t(ring[(i + 1) % 4])];
        a += u.x * v.y - v.x * u.y;
    }
    return 0.5 * a;
}

double loopArea(const std::vector<Vec3d>& p, const std::vector<int>& loop) {
    double a = 0;
    for (size_t i = 0; i < loop.size(); ++i) {
        const Vec3d &u = p[size_t(loop[i])], &v = p[size_t(loop[(i + 1) % loop.size()])];
        a += u.x * v.y - v.x * u.y;
    }
    return 0.5 * a;
}

// Even-odd inside test over all loops.
bool inside(const std::vector<Vec3d>& p, const std::vector<std::vector<int>>& loops, double x, double y) {
    bool in = false;
    for (const std::vector<int>& l : loops)
        for (size_t i = 0, j = l.size() - 1; i < l.size(); j = i++) {
            const Vec3d &a = p[size_t(l[i])], &b = p[size_t(l[j])];
            if ((a.y > y) != (b.y > y) && x < (b.x - a.x) * (y - a.y) / (b.y - a.y) + a.x) in = !in;
        }
    return in;
}

void expectCut(const std::vector<Vec3d>& p, const std::vector<std::vector<int>>& loops) {
    std::vector<std::array<int, 4>> faces;
    ASSERT_TRUE(cutPolygon(p, loops, &faces));
    double want = std::fabs(loopArea(p, loops[0]));
    for (size_t h = 1; h < loops.size(); ++h) want -= std::fabs(loopArea(p, loops[h]));
    const double sign = loopArea(p, loops[0]) > 0 ? 1 : -1;
    double got = 0;
    for (const auto& f : faces) {
        const double a = faceArea(p, f);
        EXPECT_GE(a * sign, 0) << "a face runs against the polygon's winding";
        got += std::fabs(a);
        // The face's centroid lies inside the polygon (outside every hole).
        const Vec3d c = (p[size_t(f[0])] + p[size_t(f[1])] + p[size_t(f[2])] + p[size_t(f[3])]) * 0.25;
        EXPECT_TRUE(inside(p, loops, c.x, c.y)) << "face centroid " << c.x << "," << c.y << " outside";
    }
    EXPECT_NEAR(got, want, 1e-9 * want);
}

TEST(CutPolygon, StarsWithAndWithoutHolesAreCoveredOnce) {
    std::mt19937 rng(41);
    for (int trial = 0; trial < 40; ++trial) {
        // A star-shaped (usually concave) polygon of n points, either winding.
        const int n = 5 + int(rng() % 12);
        std::vector<Vec3d> p;
        std::vector<int> outer;
        for (int i = 0; i < n; ++i) {
            const double a = 2 * M_PI * i / n, r = 4 + std::uniform_real_distribution<>(0, 6)(rng);
            p.push_back({r * std::cos(a), r * std::sin(a), 2});
            outer.push_back(i);
        }
        if (trial % 2) std::reverse(outer.begin(), outer.end());
        expectCut(p, {outer});
        // With two small square holes near the middle.
        std::vector<std::vector<int>> loops{outer};
        for (double cx : {-1.5, 1.5}) {
            std::vector<int> hole;
            for (const auto& q : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
                hole.push_back(int(p.size()));
                p.push_back({cx + 0.8 * q.first, 0.8 * q.second, 2});
            }
            loops.push_back(hole);
        }
        expectCut(p, loops);
    }
}

TEST(CutPolygon, ConvexQuadsStayWholeAndDegenerateOnesAreRefused) {
    std::vector<std::array<int, 4>> faces;
    std::vector<Vec3d> quad{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
    ASSERT_TRUE(cutPolygon(quad, {{0, 1, 2, 3}}, &faces));
    EXPECT_EQ(faces, (std::vector<std::array<int, 4>>{{0, 1, 3, 2}}));
    faces.clear();
    std::vector<Vec3d> dart{{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.5, 1, 0}};  // concave: two triangles
    ASSERT_TRUE(cutPolygon(dart, {{0, 1, 2, 3}}, &faces));
    EXPECT_EQ(faces.size(), 2u);
    expectCut(dart, {{0, 1, 2, 3}});
    // A polygon in another plane works the same.
    std::vector<Vec3d> wall{{0, 0, 0}, {0, 3, 0}, {0, 3, 3}, {0, 1, 1}, {0, 0, 3}};
    faces.clear();
    EXPECT_TRUE(cutPolygon(wall, {{0, 1, 2, 3, 4}}, &faces));
    EXPECT_EQ(faces.size(), 3u);
    std::vector<Vec3d> line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
    EXPECT_FALSE(cutPolygon(line, {{0, 1, 2, 3}}, &faces));
}

}  // namespace
}  // namespace streyes
