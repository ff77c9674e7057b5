// Weber–Penn wind sway against the paper's formulas: a straight trunk's tip at a key time worked out
// by hand (its sway angles from WindSpeed, WindGust, its radius and length, turned segment by
// segment), the foot that never moves, a still tree that stays as it was (no motion keys), and a
// windy tree's keys inside the bounds its procedurals declare.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "procedural/weber_penn_wind.h"

namespace streyes {
namespace {

struct Expanded {
    ProceduralOutput top;
    std::vector<ProceduralOutput> subtrees;
};

Expanded expand(const std::string& datablock, double windowStart, double windowEnd) {
    Expanded e;
    ExpandContext ctx;
    ctx.detail = 1e12;
    ctx.windowStart = windowStart, ctx.windowEnd = windowEnd;
    makeWeberPennGenerator(datablock, {})->expand(ctx, e.top);
    e.subtrees.resize(e.top.procedurals.size());
    for (size_t i = 0; i < e.subtrees.size(); ++i) e.top.procedurals[i].generator->expand(ctx, e.subtrees[i]);
    return e;
}

std::vector<double> flatten(const Expanded& e) {
    std::vector<double> v;
    auto take = [&](const ProceduralOutput& o) {
        for (const auto& m : o.scene.patchMeshes) {
            v.insert(v.end(), m.times.begin(), m.times.end());
            for (const auto& key : m.P)
                for (Vec3d q : key) v.insert(v.end(), {q.x, q.y, q.z});
        }
        for (const auto& m : o.scene.polygonMeshes) {
            v.insert(v.end(), m.times.begin(), m.times.end());
            for (const auto& key : m.P)
                for (Vec3d q : key) v.insert(v.end(), {q.x, q.y, q.z});
        }
        for (const auto& g : o.procedurals)
            v.insert(v.end(), {g.desc.bound.lo.x, g.desc.bound.lo.y, g.desc.bound.hi.x, g.desc.bound.hi.z});
    };
    take(e.top);
    for (const auto& o : e.subtrees) take(o);
    return v;
}

// 3x3 rotations written out: about the unit axis a by angle t (radians).
using M3 = std::array<Vec3d, 3>;  // rows
M3 rotation(Vec3d a, double t) {
    const double c = std::cos(t), s = std::sin(t), k = 1 - c;
    return {Vec3d{c + a.x * a.x * k, a.x * a.y * k - a.z * s, a.x * a.z * k + a.y * s},
            Vec3d{a.y * a.x * k + a.z * s, c + a.y * a.y * k, a.y * a.z * k - a.x * s},
            Vec3d{a.z * a.x * k - a.y * s, a.z * a.y * k + a.x * s, c + a.z * a.z * k}};
}
Vec3d mul(const M3& m, Vec3d v) { return {dot(m[0], v), dot(m[1], v), dot(m[2], v)}; }

// A straight trunk of 4 segments (no curve, flare or lobes, taper 1): radius_z = radius (1 - z), so
// a0 = 4 length (1 - z) / radius_z = 4 length / radius on every segment, and each segment turns by
// the same angles about the trunk's x = (1, 0, 0) and y = z x x = (0, 0, -1). Segment j (0..3)
// then points along Q^(j+1) (0, length / 4, 0), Q = R_y(a_y) R_x(a_x); the tip is their sum.
TEST(WeberPennWind, ATrunksTipIsWhereThePapersAnglesTurnIt) {
    const std::string block =
        "model=weberpenn Levels=1 Leaves=0 Scale=10 ScaleV=0 0Length=1 0CurveRes=4 0Curve=0 0CurveV=0 Flare=0 Lobes=0 "
        "Ratio=0.02 WindSpeed=5 WindGust=3 windtime=40 keystep=4";
    const WeberPennParams p = parseWeberPennParams(block, {});
    const WeberPennStem trunk = weberPennTrunk(p, nullptr);
    ASSERT_DOUBLE_EQ(trunk.length, 10);
    const double L = trunk.length, R = trunk.radius;
    ASSERT_DOUBLE_EQ(R, 10 * 0.02);
    double offX, offY;
    weberPennSwayOffsets(trunk, &offX, &offY);
    for (double frame : {0.0, 8.0, 36.0}) {
        SCOPED_TRACE("frame " + std::to_string(frame));
        const double a0 = 4 * L / R, a1 = 5.0 / 50 * a0, a2 = 3.0 / 50 * a0 + a1 / 2;
        const double b = R / L * (frame * 40) / 15;
        const double ax = (a1 * std::sin(offX + b) + a2 * std::sin(0.7 * (offX + b))) / 4;
        const double ay = (a1 * std::sin(offY + b) + a2 * std::sin(0.7 * (offY + b))) / 4;
        for (int j = 0; j < 4; ++j) {
            const WeberPennSwayAngles a = weberPennSwayAngles(p, trunk, j, frame);
            EXPECT_NEAR(a.x, ax, 1e-9);
            EXPECT_NEAR(a.y, ay, 1e-9);
        }
        EXPECT_GT(std::fabs(ax) + std::fabs(ay), 1) << "degrees: the test must move the tip";
        const double deg = M_PI / 180;
        const M3 rx = rotation({1, 0, 0}, ax * deg), ry = rotation({0, 0, -1}, ay * deg);
        Vec3d segment{0, L / 4, 0}, tip{0, 0, 0};
        for (int j = 0; j < 4; ++j) {
            segment = mul(ry, mul(rx, segment));
            tip = tip + segment;
        }
        // The procedural's trunk, keyed at this frame (a multiple of keystep): its last control ring's
        // centre is the tip, its first the foot.
        const Expanded e = expand(block, frame, frame);
        ASSERT_EQ(e.top.scene.patchMeshes.size(), 1u);
        const PatchMeshDesc& m = e.top.scene.patchMeshes[0];
        ASSERT_EQ(m.times, (std::vector<double>{frame, frame + 4}));
        ASSERT_EQ(m.P.size(), 2u);
        auto centre = [&](const std::vector<Vec3d>& P, size_t ring) {
            Vec3d c{0, 0, 0};
            for (int i = 0; i < m.nu; ++i) c = c + P[ring * size_t(m.nu) + size_t(i)];
            return c * (1.0 / m.nu);
        };
        const Vec3d got = centre(m.P[0], size_t(m.nv - 1));
        EXPECT_NEAR(got.x, tip.x, 1e-9 * L);
        EXPECT_NEAR(got.y, tip.y, 1e-9 * L);
        EXPECT_NEAR(got.z, tip.z, 1e-9 * L);
        EXPECT_GT(length(got - Vec3d{0, L, 0}), 0.01 * L) << "the tip moved";
        for (const auto& key : m.P) EXPECT_LT(length(centre(key, 0)), 1e-12) << "the foot never moves";
    }
}

// WindSpeed and WindGust 0: what the procedural makes is what it made before the wind existed
// (one key each, the same numbers), whatever windtime and keystep say.
TEST(WeberPennWind, AStillTreeHasNoKeys) {
    for (const char* preset : {"quaking_aspen", "weeping_willow"}) {
        const std::string block = std::string("model=weberpenn seed=3 preset=") + preset;
        const Expanded plain = expand(block, 0, 8), set = expand(block + " windtime=7 keystep=2", 0, 8);
        const std::vector<double> a = flatten(plain), b = flatten(set);
        ASSERT_EQ(a.size(), b.size());
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
        for (const auto& o : plain.subtrees) {
            for (const auto& m : o.scene.patchMeshes) ASSERT_EQ(m.P.size(), 1u);
            for (const auto& m : o.scene.polygonMeshes) ASSERT_EQ(m.P.size(), 1u);
        }
    }
}

// A windy tree: every part keyed at the multiples of keystep covering the window, each branch's
// keys inside the bound of its procedural and the whole inside weberPennBound; the branches move
// relative to the trunk (not only with it).
TEST(WeberPennWind, AWindyTreeIsKeyedInsideItsBounds) {
    for (const char* preset : {"quaking_aspen", "black_tupelo", "ca_black_oak"}) {
        SCOPED_TRACE(preset);
        const std::string block = std::string("model=weberpenn seed=5 WindSpeed=4 WindGust=2 keystep=3 preset=") + preset;
        const WeberPennParams p = parseWeberPennParams(block, {});
        const Expanded e = expand(block, 1, 8);
        const std::vector<double> times{0, 3, 6, 9};
        const Bounds3d all = weberPennBound(p);
        auto inside = [](const Bounds3d& b, Vec3d q) {
            return q.x >= b.lo.x && q.y >= b.lo.y && q.z >= b.lo.z && q.x <= b.hi.x && q.y <= b.hi.y && q.z <= b.hi.z;
        };
        size_t moved = 0, points = 0;
        for (size_t i = 0; i < e.subtrees.size(); ++i) {
            const Bounds3d& b = e.top.procedurals[i].desc.bound;
            for (const auto& m : e.subtrees[i].scene.patchMeshes) {
                ASSERT_EQ(m.times, times);
                ASSERT_EQ(m.P.size(), times.size());
                for (const auto& key : m.P)
                    for (Vec3d q : key) ASSERT_TRUE(inside(b, q) && inside(all, q));
                for (size_t k = 0; k < m.P[0].size(); ++k, ++points) moved += length(m.P[0][k] - m.P[3][k]) > 1e-6;
            }
            for (const auto& m : e.subtrees[i].scene.polygonMeshes) {
                ASSERT_EQ(m.times, times);
                for (const auto& key : m.P)
                    for (Vec3d q : key) ASSERT_TRUE(inside(b, q) && inside(all, q));
            }
        }
        EXPECT_GT(moved, points / 2) << "most of the crown moves between keys";
    }
}

TEST(WeberPennWind, KeyTimesAreMultiplesOfKeyStep) {
    WeberPennParams p;
    p.windSpeed = 1, p.keyStep = 4;
    EXPECT_EQ(weberPennKeyTimes(p, 5, 13), (std::vector<double>{4, 8, 12, 16}));
    EXPECT_EQ(weberPennKeyTimes(p, 8, 8), (std::vector<double>{8, 12}));
    EXPECT_EQ(weberPennKeyTimes(p, 7.5, 8), (std::vector<double>{4, 8}));
    p.windSpeed = 0;
    EXPECT_EQ(weberPennKeyTimes(p, 5, 13), (std::vector<double>{5}));
    EXPECT_THROW(parseWeberPennParams("model=weberpenn WindSpeed=-1", {}), InputError);
    EXPECT_THROW(parseWeberPennParams("model=weberpenn keystep=0", {}), InputError);
}

}  // namespace
}  // namespace streyes
