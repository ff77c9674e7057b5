// Map-based occlusion (occlusion_maps.h): closed forms on depth maps made by casting rays at a
// known scene from known directions.
#include "shade/occlusion_maps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace streyes {
namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3d unit(Vec3d v) { return v * (1 / std::sqrt(dot(v, v))); }

// The scene: the ground z = 0 and a wall 0.5 <= x <= 0.6, |y| <= 20, 0 <= z <= 20 (a box).
// The nearest hit along o + s dir, s > 0 (infinity: none).
double castAtScene(const Vec3d& o, const Vec3d& dir, bool wall) {
    double best = std::numeric_limits<double>::infinity();
    if (dir.z != 0) {
        const double s = -o.z / dir.z;
        const Vec3d h = o + dir * s;
        if (s > 0 && std::fabs(h.x) <= 40 && std::fabs(h.y) <= 40) best = s;
    }
    if (wall) {
        const double lo[3] = {0.5, -20, 0}, hi[3] = {0.6, 20, 20};
        const double org[3] = {o.x, o.y, o.z}, d[3] = {dir.x, dir.y, dir.z};
        double t0 = 0, t1 = std::numeric_limits<double>::infinity();
        bool hit = true;
        for (int a = 0; a < 3 && hit; ++a) {
            if (d[a] == 0) {
                hit = org[a] >= lo[a] && org[a] <= hi[a];
                continue;
            }
            double ta = (lo[a] - org[a]) / d[a], tb = (hi[a] - org[a]) / d[a];
            if (ta > tb) std::swap(ta, tb);
            t0 = std::max(t0, ta), t1 = std::min(t1, tb);
            hit = t0 <= t1;
        }
        if (hit && t0 > 0) best = std::min(best, t0);
    }
    return best;
}

// An orthographic depth map of the scene from 10 units along `sky` (so that it sees the sky in
// direction `sky`), 8 x 8 units across, res x res texels.
DepthMap mapFrom(const Vec3d& sky, int res, bool wall) {
    const Vec3d z = unit(sky * -1.0);  // the camera looks along -sky
    const Vec3d up = std::fabs(z.y) < 0.9 ? Vec3d{0, 1, 0} : Vec3d{1, 0, 0};
    const Vec3d x = unit(cross(up, z)), y = cross(z, x);
    const Vec3d c = unit(sky) * 10.0;
    DepthMap m;
    m.width = m.height = res;
    const Vec3d axes[3] = {x, y, z};
    for (int i = 0; i < 3; ++i) {
        m.worldToCamera(0, i) = axes[i].x, m.worldToCamera(1, i) = axes[i].y, m.worldToCamera(2, i) = axes[i].z;
        m.worldToCamera(3, i) = -dot(c, axes[i]);
    }
    Matrix4 screen;  // orthographic, the screen window [-4, 4]^2
    screen(0, 0) = screen(1, 1) = 0.25;
    m.worldToScreen = m.worldToCamera * screen;
    m.z.resize(size_t(res) * size_t(res));
    for (int j = 0; j < res; ++j)
        for (int i = 0; i < res; ++i) {
            const double sx = (i + 0.5) / res * 2 - 1, sy = 1 - (j + 0.5) / res * 2;
            const double s = castAtScene(c + x * (4 * sx) + y * (4 * sy), z, wall);
            m.z[size_t(j) * size_t(res) + size_t(i)] = std::isfinite(s) ? float(s) : DepthMap::kNoDepth;
        }
    return m;
}

// Chains maps as Display "append" does: the last given is the file's last.
std::shared_ptr<const DepthMap> chainOf(std::vector<DepthMap> maps) {
    std::shared_ptr<const DepthMap> chain;
    for (DepthMap& m : maps) {
        m.previous = chain;
        chain = std::make_shared<const DepthMap>(std::move(m));
    }
    return chain;
}

Vec3d polar(double thetaDeg, double phiDeg) {
    const double t = thetaDeg * kPi / 180, p = phiDeg * kPi / 180;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

TEST(OcclusionMaps, OneMapFacingTheNormalGivesZeroOpenAndOneCovered) {
    for (bool covered : {false, true}) {
        DepthMap m = mapFrom({0, 0, 1}, 32, false);
        if (covered)  // a roof at height 1 over everything the map sees
            for (float& z : m.z) z = 9;
        auto file = chainOf({m});
        OcclusionViews v;
        std::string error;
        ASSERT_TRUE(v.set(*file, Matrix4(), &error)) << error;
        ASSERT_EQ(v.size(), 1u);
        EXPECT_NEAR(v.skyward(0).z, 1, 1e-12);
        for (const Vec3d p : {Vec3d{0, 0, 0}, Vec3d{-1.3, 2.1, 0}, Vec3d{0.2, -3, 0}})
            EXPECT_EQ(v.occlusion(p, {0, 0, 1}, 0.05f, 0.01f, 16), covered ? 1.0f : 0.0f) << p.x << " " << p.y;
        // A normal facing away from the only map: nothing to weigh, open sky.
        EXPECT_EQ(v.occlusion({0, 0, 0}, {0, 0, -1}, 0, 0.01f, 16), 0.0f);
    }
}

// Maps from directions at known angles to N = +z, with a wall at x = 0.5 beside the point at the
// origin: the maps whose sky direction points at the wall (x > 0) see it in front of the point.
// The occlusion is the sum of their cosines over the sum of every facing map's cosine.
TEST(OcclusionMaps, AWallBesideThePointBlocksTheCosineWeightedShareOfTheMapsThatSeeIt) {
    const std::vector<Vec3d> dirs = {polar(0, 0),   polar(30, 0),   polar(30, 180), polar(60, 90),
                                     polar(60, 0),  polar(60, 200), polar(135, 0),  polar(180, 0)};
    std::vector<DepthMap> maps;
    for (const Vec3d& d : dirs) maps.push_back(mapFrom(d, 128, true));
    auto file = chainOf(maps);
    OcclusionViews v;
    std::string error;
    ASSERT_TRUE(v.set(*file, Matrix4(), &error)) << error;
    ASSERT_EQ(v.size(), dirs.size());
    double blocked = 0, total = 0;
    for (size_t i = 0; i < dirs.size(); ++i) {
        EXPECT_NEAR(dot(v.skyward(i), unit(dirs[i])), 1, 1e-9) << "map " << i << " in file order";
        const double w = dirs[i].z;  // cos to N = +z
        if (w <= 0) continue;        // below the ground: not a direction of the hemisphere
        total += w;
        if (dirs[i].x > 1e-9) blocked += w;  // the ray from the origin meets the wall
    }
    // cos 30 + cos 60 over 1 + 2 cos 30 + 3 cos 60.
    EXPECT_NEAR(blocked / total, (std::cos(kPi / 6) + 0.5) / (1 + 2 * std::cos(kPi / 6) + 1.5), 1e-12);
    // (A bias of 0.2 clears the ground's own slope across a texel in the tilted maps: P's depth is
    // compared as one constant, as Aqsis does.)
    EXPECT_NEAR(v.occlusion({0, 0, 0}, {0, 0, 1}, 0, 0.2f, 16), blocked / total, 1e-6);
    // The normal's length does not matter.
    EXPECT_NEAR(v.occlusion({0, 0, 0}, {0, 0, 7}, 0, 0.2f, 16), blocked / total, 1e-6);
    // N = -x: the facing maps are the two whose sky lies at x < 0, away from the wall: open.
    EXPECT_EQ(v.occlusion({0, 0, 0}, {-1, 0, 0}, 0, 0.2f, 16), 0.0f);
    // 3 units from the wall every ray toward +x at these angles still meets it below its top.
    EXPECT_NEAR(v.occlusion({-3, 0, 0}, {0, 0, 1}, 0, 0.2f, 16), blocked / total, 1e-6);
}

// "blur" averages over a box of that share of the map: across the wall's shadow edge in one map
// it gives the covered fraction of the box.
TEST(OcclusionMaps, BlurAveragesTheCoveredShareOfTheBox) {
    DepthMap m = mapFrom({0, 0, 1}, 64, false);
    for (int j = 0; j < 64; ++j)
        for (int i = 32; i < 64; ++i) m.z[size_t(j) * 64 + size_t(i)] = 9;  // the right half covered
    auto file = chainOf({m});
    OcclusionViews v;
    std::string error;
    ASSERT_TRUE(v.set(*file, Matrix4(), &error)) << error;
    // The point over the edge (x = 0: texel boundary 32): a box of 0.25 x 64 = 16 texels, half covered.
    EXPECT_NEAR(v.occlusion({0, 0, 0}, {0, 0, 1}, 0.25f, 0.01f, 16), 0.5, 1e-6);
    // (The map's raster x runs along world -x.) Half a unit, 4 texels, to the open side: 4 of
    // the box's 16 texels covered; unblurred, open.
    EXPECT_NEAR(v.occlusion({0.5, 0, 0}, {0, 0, 1}, 0.25f, 0.01f, 16), 4.0 / 16.0, 1e-6);
    EXPECT_EQ(v.occlusion({0.5, 0, 0}, {0, 0, 1}, 0.0f, 0.01f, 16), 0.0f);
    EXPECT_EQ(v.occlusion({-0.5, 0, 0}, {0, 0, 1}, 0.0f, 0.01f, 16), 1.0f);
}

TEST(OcclusionMaps, BiasKeepsTheGroundFromCoveringItself) {
    // A map 40 degrees off the normal sees the ground sloping across its texels: P's depth taken as
    // one constant over the box (Aqsis's), the nearer half of the box covers P at bias 0; a bias
    // above the slope across the box clears it.
    auto file = chainOf({mapFrom(polar(40, 30), 64, false)});
    OcclusionViews v;
    std::string error;
    ASSERT_TRUE(v.set(*file, Matrix4(), &error)) << error;
    EXPECT_GT(v.occlusion({0.3, 0.2, 0}, {0, 0, 1}, 0.02f, 0.0f, 16), 0.2f);
    EXPECT_EQ(v.occlusion({0.3, 0.2, 0}, {0, 0, 1}, 0.02f, 0.2f, 16), 0.0f);
    // A bias larger than the roof's height above the point lets the roof through.
    DepthMap m = mapFrom({0, 0, 1}, 16, false);
    for (float& z : m.z) z = 9.5f;  // 0.5 above the ground
    auto roofed = chainOf({m});
    ASSERT_TRUE(v.set(*roofed, Matrix4(), &error)) << error;
    EXPECT_EQ(v.occlusion({0, 0, 0}, {0, 0, 1}, 0, 0.4f, 16), 1.0f);
    EXPECT_EQ(v.occlusion({0, 0, 0}, {0, 0, 1}, 0, 0.6f, 16), 0.0f);
}

}  // namespace
}  // namespace streyes
