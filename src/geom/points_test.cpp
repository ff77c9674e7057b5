// Point clouds: groups split into their halves down to single discs, every point reached; bounds
// hold what the discs dice to, at both ends of every piece's time span; disc sectors share their
// radii bit for bit.
#include "geom/points.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <random>

#include "geom/grid.h"

namespace streyes {
namespace {

std::unique_ptr<PointCloud> randomCloud(size_t n, bool moving, std::mt19937& rng) {
    std::uniform_real_distribution<float> pos(-50, 50), depth(10, 60), rad(0.1f, 3);
    std::vector<Vec3f> c0, c1;
    std::vector<float> r0, r1;
    std::vector<Color> cs;
    for (size_t i = 0; i < n; ++i) {
        c0.push_back({pos(rng), pos(rng), depth(rng)});
        r0.push_back(rad(rng));
        c1.push_back(c0.back() + Vec3f{pos(rng) * 0.1f, pos(rng) * 0.1f, 1});
        r1.push_back(r0.back() * 1.5f);
        cs.push_back({float(i), 0, 0});
    }
    if (!moving) c1.clear(), r1.clear();
    return std::make_unique<PointCloud>(TimeSpan{0, 2}, c0, c1, r0, r1, cs);
}

bool contains(const Bounds3f& b, Vec3f p) { return b.contains(p); }

TEST(PointCloud, GroupsSplitDownToEveryPointAndBoundsHoldTheDiscs) {
    std::mt19937 rng(7);
    for (bool moving : {false, true}) {
        SCOPED_TRACE(moving);
        auto cloud = randomCloud(333, moving, rng);
        std::unique_ptr<Body> root = cloud->root(nullptr);
        std::vector<float> seen(cloud->size(), 0);
        Grid grid;
        std::uniform_int_distribution<int> coin(0, 3), rate(1, 9);
        std::function<void(const Body&, int)> visit = [&](const Body& b, int depth) {
            const LBBox3f bound = b.bound();
            // Groups split to their halves (or in time); discs are diced, or split in angle or time.
            const bool disc = dynamic_cast<const DiscBody*>(&b) != nullptr;
            if (!disc || (depth < 40 && coin(rng) == 0)) {
                std::unique_ptr<Body> halves[2];
                b.split(coin(rng) == 0 && b.moving() ? SplitAxis::T : SplitAxis::U, halves);
                for (auto& h : halves) {
                    // A piece lies in its parent's bound over its own span (to the rounding of
                    // lerping boxes twice: 1e-6 of the coordinates).
                    Bounds3f parent = b.boundDuring(h->time().t0, h->time().t1);
                    const Vec3f slack = Vec3f(1, 1, 1) * (1e-6f * std::max(length(parent.lo), length(parent.hi)));
                    parent = {parent.lo - slack, parent.hi + slack};
                    const Bounds3f piece = h->bound().swept();
                    EXPECT_TRUE(contains(parent, piece.lo) && contains(parent, piece.hi));
                    visit(*h, depth + 1);
                }
                return;
            }
            b.dice(rate(rng), rate(rng), grid);
            for (int k = 0; k < (grid.moving ? 2 : 1); ++k)
                for (const Vec3f& p : grid.P[k]) EXPECT_TRUE(contains(k == 0 ? bound.b0 : bound.b1, p));
            seen[size_t(grid.Cs[0].x)] = 1;  // each disc's colour is its index
        };
        visit(*root, 0);
        for (size_t i = 0; i < seen.size(); ++i) EXPECT_GT(seen[i], 0.0f) << "point " << i << " never diced";
    }
}

TEST(PointCloud, SectorsShareTheirRadiiExactly) {
    std::mt19937 rng(3);
    auto cloud = randomCloud(1, true, rng);
    std::unique_ptr<Body> disc = cloud->root(nullptr);
    std::unique_ptr<Body> halves[2], quarters[2];
    disc->split(SplitAxis::U, halves);
    halves[0]->split(SplitAxis::V, quarters);  // any axis but time splits the angle
    Grid a, b, c;
    quarters[1]->dice(3, 5, a);  // [1/4, 1/2]
    halves[1]->dice(7, 2, b);    // [1/2, 1]
    quarters[0]->dice(4, 4, c);  // [0, 1/4]
    for (int k = 0; k < 2; ++k) {
        // The radius at 1/2 (a's last column, b's first), and at 0 (c's first column, b's last).
        EXPECT_EQ(a.P[k][size_t(a.index(a.nu, a.nv))], b.P[k][size_t(b.index(0, b.nv))]);
        EXPECT_EQ(c.P[k][size_t(c.index(0, c.nv))], b.P[k][size_t(b.index(b.nu, b.nv))]);
        EXPECT_EQ(a.P[k][size_t(a.index(0, 0))], b.P[k][size_t(b.index(0, 0))]);  // the centre
    }
}

}  // namespace
}  // namespace streyes
