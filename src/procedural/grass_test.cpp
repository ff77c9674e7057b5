// The grass procedural: blade counts against density x area (stratified: the whole rectangle holds
// floor(density x area), each tile within one blade of density x its area), roots on the ground
// rectangle, lengths within [min, max], every key inside its tile's declared bound, the same seed
// giving the same numbers, and a frame's wind keys the same whether it is expanded alone or in a
// block of frames.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "procedural/grass.h"

namespace streyes {
namespace {

struct GrassExpansion {
    ProceduralOutput top;
    std::vector<ProceduralOutput> tiles;
};

GrassExpansion expandGrass(const std::string& block, double detail = 1e12, double start = 0, double end = 0) {
    GrassExpansion e;
    ExpandContext ctx;
    ctx.detail = detail;
    ctx.windowStart = start, ctx.windowEnd = end;
    makeGrassGenerator(block, {})->expand(ctx, e.top);
    e.tiles.resize(e.top.procedurals.size());
    for (size_t i = 0; i < e.tiles.size(); ++i) e.top.procedurals[i].generator->expand(ctx, e.tiles[i]);
    return e;
}

size_t bladesOf(const ProceduralOutput& o) {
    size_t n = 0;
    for (const CurvesDesc& c : o.scene.curves) n += c.nvertices.size();
    return n;
}

size_t bladesOf(const GrassExpansion& e) {
    size_t n = 0;
    for (const ProceduralOutput& o : e.tiles) n += bladesOf(o);
    return n;
}

// Every number the expansion made, in order (times, points, widths, colours, bounds).
std::vector<double> flatten(const GrassExpansion& e) {
    std::vector<double> v;
    for (const GeneratedProcedural& p : e.top.procedurals)
        v.insert(v.end(), {p.desc.bound.lo.x, p.desc.bound.lo.y, p.desc.bound.lo.z, p.desc.bound.hi.x,
                           p.desc.bound.hi.y, p.desc.bound.hi.z});
    for (const ProceduralOutput& o : e.tiles)
        for (const CurvesDesc& c : o.scene.curves) {
            v.insert(v.end(), c.times.begin(), c.times.end());
            for (const auto& key : c.P)
                for (Vec3d q : key) v.insert(v.end(), {q.x, q.y, q.z});
            v.insert(v.end(), c.width.begin(), c.width.end());
            for (Color k : c.Cs.values) v.insert(v.end(), {double(k.x), double(k.y), double(k.z)});
        }
    return v;
}

bool bitIdentical(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

TEST(Grass, BladeCountIsDensityTimesArea) {
    // A rectangle that is not a whole number of tiles, and a density that is not an integer.
    const std::string block = "seed=3 rect=-1.3,0.2,2.45,3.1 tile=0.7 density=123.4";
    const GrassExpansion e = expandGrass(block);
    const GrassParams g = parseGrassParams(block, {});
    const double area = (2.45 + 1.3) * (3.1 - 0.2);
    EXPECT_EQ(double(bladesOf(e)), std::floor(123.4 * area));
    // 6 x 5 tiles (the last column and row cut short); each within one blade of density x its area.
    ASSERT_EQ(e.top.procedurals.size(), 30u);
    for (size_t k = 0; k < e.tiles.size(); ++k) {
        SCOPED_TRACE(k);
        const int i = int(k % 6), j = int(k / 6);
        const double w = std::min(2.45, -1.3 + 0.7 * (i + 1)) - (-1.3 + 0.7 * i);
        const double d = std::min(3.1, 0.2 + 0.7 * (j + 1)) - (0.2 + 0.7 * j);
        EXPECT_LE(std::fabs(double(bladesOf(e.tiles[k])) - 123.4 * w * d), 1.0);
        EXPECT_EQ(int64_t(bladesOf(e.tiles[k])), grassBladesBefore(g, int64_t(k) + 1) - grassBladesBefore(g, int64_t(k)));
    }
    EXPECT_EQ(bladesOf(expandGrass("rect=0,0,2,2 density=0")), 0u);
}

TEST(Grass, RootsOnTheRectangleAndLengthsWithinTheirRange) {
    const std::string block = "seed=9 rect=-2,-1,1,1.5 density=300 height=0.2,0.5 lean=30 bend=40 width=0.01";
    const GrassExpansion e = expandGrass(block);
    ASSERT_GT(bladesOf(e), 2000u);
    for (size_t k = 0; k < e.tiles.size(); ++k) {
        const Bounds3d& bound = e.top.procedurals[k].desc.bound;
        for (const CurvesDesc& c : e.tiles[k].scene.curves) {
            ASSERT_TRUE(c.cubic);
            ASSERT_EQ(c.P.size(), 1u);  // still: one key
            ASSERT_EQ(c.width.size(), 2 * c.nvertices.size());
            const std::vector<Vec3d>& P = c.P[0];
            for (size_t b = 0; b < c.nvertices.size(); ++b) {
                ASSERT_EQ(c.nvertices[b], 4);
                const Vec3d* q = &P[4 * b];
                EXPECT_EQ(q[0].y, 0.0);
                EXPECT_TRUE(q[0].x >= -2 && q[0].x <= 1 && q[0].z >= -1 && q[0].z <= 1.5) << q[0].x << " " << q[0].z;
                double len = 0;
                for (int i = 1; i < 4; ++i) {
                    len += length(q[i] - q[i - 1]);
                    EXPECT_GT(q[i].y, q[i - 1].y);  // lean + bend under 90 degrees: every leg climbs
                    EXPECT_TRUE(bound.contains(q[i]));
                }
                EXPECT_GE(len, 0.2 - 1e-12);
                EXPECT_LE(len, 0.5 + 1e-12);
                EXPECT_GE(c.width[2 * b], 0.007 - 1e-12);  // the root: width +-30%
                EXPECT_LE(c.width[2 * b], 0.013 + 1e-12);
                EXPECT_NEAR(c.width[2 * b + 1], 0.1 * c.width[2 * b], 1e-15);  // tapering to a tenth
            }
        }
    }
}

TEST(Grass, TheSameSeedGivesTheSameGrass) {
    const std::string block = "rect=0,0,3,2 density=200 wind=0.8 winddir=1,1 keystep=2";
    const std::vector<double> a = flatten(expandGrass("seed=5 " + block, 1e12, 0, 10));
    const std::vector<double> b = flatten(expandGrass("seed=5 " + block, 1e12, 0, 10));
    const std::vector<double> c = flatten(expandGrass("seed=6 " + block, 1e12, 0, 10));
    ASSERT_GT(a.size(), 10000u);
    for (double x : a) ASSERT_TRUE(std::isfinite(x));
    EXPECT_TRUE(bitIdentical(a, b));
    EXPECT_FALSE(bitIdentical(a, c));
}

// A frame's keys are the multiples of keystep around it, whatever the block: the frame's pixels
// interpolate the same two keys alone and in a block. The wind moves the blades (keys differ), but
// never their roots, and keeps every key within the tile's bound.
TEST(Grass, AFramesWindKeysDoNotDependOnTheBlock) {
    const std::string block = "seed=2 rect=-1,-1,1,1 density=150 wind=1.5 winddir=1,0.3 period=20 keystep=3";
    const GrassExpansion alone = expandGrass(block, 1e12, 7, 7.5), inBlock = expandGrass(block, 1e12, 0, 24);
    ASSERT_EQ(alone.tiles.size(), inBlock.tiles.size());
    size_t compared = 0;
    for (size_t k = 0; k < alone.tiles.size(); ++k) {
        ASSERT_EQ(alone.tiles[k].scene.curves.size(), 1u);
        const CurvesDesc& a = alone.tiles[k].scene.curves[0];
        const CurvesDesc& b = inBlock.tiles[k].scene.curves[0];
        ASSERT_EQ(a.times, (std::vector<double>{6, 9}));
        ASSERT_EQ(b.times.front(), 0);
        ASSERT_GE(b.times.back(), 24);
        const Bounds3d& bound = alone.top.procedurals[k].desc.bound;
        for (size_t i = 0; i < a.times.size(); ++i) {
            const size_t j = size_t(std::find(b.times.begin(), b.times.end(), a.times[i]) - b.times.begin());
            ASSERT_LT(j, b.times.size());
            ASSERT_EQ(a.P[i].size(), b.P[j].size());
            EXPECT_EQ(std::memcmp(a.P[i].data(), b.P[j].data(), a.P[i].size() * sizeof(Vec3d)), 0);
            for (const Vec3d& q : a.P[i]) EXPECT_TRUE(bound.contains(q));
            ++compared;
        }
        size_t moved = 0;
        for (size_t p = 0; p < a.P[0].size(); ++p) {
            if (p % 4 == 0) {
                EXPECT_EQ(std::memcmp(&a.P[0][p], &a.P[1][p], sizeof(Vec3d)), 0);  // roots stay
            }
            moved += length(a.P[0][p] - a.P[1][p]) > 1e-4;
        }
        EXPECT_GT(moved, a.P[0].size() / 2);
    }
    EXPECT_GT(compared, 0u);
}

// Far away a tile keeps 4 x detail blades a pixel of its bound's area (at least 5%), the first of
// its sequence, as straight segments, each wider by count / kept.
TEST(Grass, DistantTilesKeepFewerWiderStraightBlades) {
    const std::string block = "seed=4 rect=0,0,1,1 density=1000";
    const GrassExpansion near = expandGrass(block), far = expandGrass(block, 100), farther = expandGrass(block, 1);
    ASSERT_EQ(bladesOf(near), 1000u);
    EXPECT_EQ(bladesOf(far), 400u);       // 4 x 100 pixels
    EXPECT_EQ(bladesOf(farther), 50u);    // 5% at least
    const CurvesDesc& n = near.tiles[0].scene.curves[0];
    const CurvesDesc& f = far.tiles[0].scene.curves[0];
    EXPECT_FALSE(f.cubic);
    for (size_t b = 0; b < 400; ++b) {
        EXPECT_EQ(f.nvertices[b], 2);
        EXPECT_EQ(std::memcmp(&f.P[0][2 * b], &n.P[0][4 * b], sizeof(Vec3d)), 0);          // the root
        EXPECT_EQ(std::memcmp(&f.P[0][2 * b + 1], &n.P[0][4 * b + 3], sizeof(Vec3d)), 0);  // the tip
        EXPECT_NEAR(f.width[2 * b], n.width[2 * b] * 2.5, 1e-15);
    }
}

TEST(Grass, BadParametersAreErrors) {
    for (const char* bad : {"rect=1,0,0,1", "height=0.5,0.2", "density=-1", "lean=70", "winddir=0,0", "tile=0",
                            "colour=1,1,1", "seed", "rect=0,0,1", "rect=0,0,1e5,1e5 tile=1", "rect=0,0,1000,1000 tile=10 density=2000"})
        EXPECT_THROW(parseGrassParams(bad, {}), InputError) << bad;
}

}  // namespace
}  // namespace streyes
