// Weber–Penn trees against the paper's formulas: for every preset, each stem's count of children,
// its length and radius are recomputed here from the paper's equations and the parent's grown data
// (never from numbers of a run), the axes are as long as the stems, children sit on their parents,
// and the lazily expanded procedural makes exactly the tree grown at once.
#include "procedural/weber_penn.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace streyes {
namespace {

// The paper's ShapeRatio, written out again from its table.
double paperShapeRatio(int shape, double r) {
    switch (shape) {
    case 0: return 0.2 + 0.8 * r;
    case 1: return 0.2 + 0.8 * std::sin(M_PI * r);
    case 2: return 0.2 + 0.8 * std::sin(M_PI / 2 * r);
    case 3: return 1;
    case 4: return 0.5 + 0.5 * r;
    case 5: return r <= 0.7 ? r / 0.7 : (1 - r) / 0.3;
    case 6: return 1 - 0.8 * r;
    default: return r <= 0.7 ? 0.5 + 0.5 * r / 0.7 : 0.5 + 0.5 * (1 - r) / 0.3;
    }
}

int roundedCount(double x) { return x > 0 ? int(std::lround(x)) : 0; }

// The paper's radius along a stem of nTaper 1 (every preset's), with the trunk's flare.
double paperRadius(const WeberPennParams& p, const WeberPennStem& s, double z) {
    double r = s.radius * (1 - z);
    if (s.level == 0) r *= p.flare * (std::pow(100.0, std::max(0.0, 1 - 8 * z)) - 1) / 100 + 1;
    return r;
}

double pathLength(const std::vector<Vec3d>& pts) {
    double l = 0;
    for (size_t i = 1; i < pts.size(); ++i) l += length(pts[i] - pts[i - 1]);
    return l;
}

// Distance from q to the polyline of the stem's paths.
double distanceToStem(const WeberPennStem& s, Vec3d q) {
    double best = 1e300;
    for (const auto& path : s.paths)
        for (size_t i = 1; i < path.points.size(); ++i) {
            const Vec3d a = path.points[i - 1], d = path.points[i] - a;
            const double t = std::clamp(dot(q - a, d) / std::max(1e-300, dot(d, d)), 0.0, 1.0);
            best = std::min(best, length(a + d * t - q));
        }
    return best;
}

const WeberPennParams& preset(const std::string& name) {
    const WeberPennParams* p = weberPennPreset(name);
    EXPECT_NE(p, nullptr) << name;
    return *p;
}

class WeberPennPresets : public testing::TestWithParam<std::string> {};

TEST_P(WeberPennPresets, StemsFollowThePapersFormulas) {
    for (uint64_t seed : {1u, 7u, 1234u}) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        WeberPennParams p = preset(GetParam());
        p.seed = seed;
        const WeberPennTree t = growWeberPenn(p);
        ASSERT_FALSE(t.stems.empty());
        const WeberPennStem& trunk = t.stems[0];
        const WeberPennLevel* c = p.level.data();
        // The trunk: length_trunk = (0Length ± 0LengthV) scale_tree, scale_tree = Scale ± ScaleV,
        // radius_trunk = length_trunk Ratio 0Scale, length_base = BaseSize scale_tree.
        EXPECT_GE(t.scaleTree, p.scale - p.scaleV);
        EXPECT_LE(t.scaleTree, p.scale + p.scaleV);
        EXPECT_GE(trunk.lengthChildMax, c[0].length - c[0].lengthV);
        EXPECT_LE(trunk.lengthChildMax, c[0].length + c[0].lengthV);
        EXPECT_DOUBLE_EQ(trunk.length, trunk.lengthChildMax * t.scaleTree);
        EXPECT_DOUBLE_EQ(trunk.radius, trunk.length * p.ratio * p.scale0);
        EXPECT_DOUBLE_EQ(trunk.baseLength, p.baseSize * t.scaleTree);
        EXPECT_EQ(trunk.children, roundedCount(c[1].branches));

        std::vector<int> counted(t.stems.size(), 0), leaves(t.stems.size(), 0);
        std::vector<int> perLevel(4, 0);
        for (const WeberPennLeaf& l : t.leaves) ++leaves[size_t(l.stem)];
        for (size_t i = 0; i < t.stems.size(); ++i) {
            const WeberPennStem& s = t.stems[i];
            ++perLevel[size_t(s.level)];
            SCOPED_TRACE("stem " + std::to_string(i) + " level " + std::to_string(s.level));
            // The axis is the stem's length (each path from the base), and every point lies within
            // it of the base (the bound the procedural declares relies on it).
            const Vec3d base = s.paths[0].points[0];
            EXPECT_NEAR(pathLength(s.paths[0].points), s.length, 1e-9 * (1 + s.length));
            for (const auto& path : s.paths) {
                EXPECT_LE(path.firstSegment + int(path.points.size()) - 1, c[std::min(s.level, 3)].curveRes);
                for (Vec3d q : path.points) EXPECT_LE(length(q - base), s.length * (1 + 1e-9) + 1e-12);
            }
            // Leaves on the last level: Leaves ShapeRatio(4, offset_child / length_parent).
            if (s.level == p.levels - 1) {
                const int want = s.level == 0 ? roundedCount(p.leaves)
                                              : roundedCount(p.leaves * paperShapeRatio(4, s.offset / s.parentLength));
                EXPECT_EQ(s.leaves, want);
                EXPECT_EQ(leaves[i], want);
                EXPECT_EQ(s.children, 0);
            }
            if (s.parent < 0) continue;
            ++counted[size_t(s.parent)];
            const WeberPennStem& parent = t.stems[size_t(s.parent)];
            const WeberPennLevel& cl = c[std::min(s.level, 3)];
            EXPECT_EQ(s.level, parent.level + 1);
            EXPECT_DOUBLE_EQ(s.parentLength, parent.length);
            EXPECT_GE(s.lengthChildMax, cl.length - cl.lengthV);
            EXPECT_LE(s.lengthChildMax, cl.length + cl.lengthV);
            // Children evenly along the parent, beyond the trunk's base length.
            const int j = counted[size_t(s.parent)] - 1;
            const double offset = parent.baseLength + (parent.length - parent.baseLength) * (j + 0.5) / parent.children;
            EXPECT_NEAR(s.offset, offset, 1e-12 * parent.length);
            EXPECT_LT(distanceToStem(parent, base), 1e-9 * (1 + parent.length));
            // length_child: the trunk's children length_trunk nLength ShapeRatio(Shape, (length_trunk
            // - offset) / (length_trunk - length_base)); deeper ones nLength (length_parent - 0.6 offset).
            const double length =
                s.level == 1 ? parent.length * s.lengthChildMax *
                                   paperShapeRatio(p.shape, (parent.length - s.offset) / (parent.length - parent.baseLength))
                             : s.lengthChildMax * (parent.length - 0.6 * s.offset);
            EXPECT_NEAR(s.length, std::max(0.0, length), 1e-12 * (1 + parent.length));
            // radius_child = radius_parent (length_child / length_parent)^RatioPower, no more than
            // the parent's radius where it grows.
            const double radius = std::min(parent.radius * std::pow(s.length / parent.length, p.ratioPower),
                                           paperRadius(p, parent, s.offset / parent.length));
            EXPECT_NEAR(s.radius, radius, 1e-12 * (1 + parent.radius));
            // Its children: level 1 nBranches (0.2 + 0.8 (length_child / length_parent) /
            // length_child_max), deeper nBranches (1 - 0.5 offset_child / length_parent).
            if (s.level < p.levels - 1) {
                const double most = c[s.level + 1].branches;
                const int want = s.level == 1
                                     ? roundedCount(most * (0.2 + 0.8 * (s.length / parent.length) / s.lengthChildMax))
                                     : roundedCount(most * (1 - 0.5 * s.offset / parent.length));
                EXPECT_EQ(s.children, want);
            }
        }
        for (size_t i = 0; i < t.stems.size(); ++i) EXPECT_EQ(counted[i], t.stems[i].children) << "stem " << i;
        // Every level the preset has is grown, and stems of level n are the children of level n - 1.
        for (int level = 0; level < p.levels; ++level) EXPECT_GT(perLevel[size_t(level)], 0) << "level " << level;
        EXPECT_GT(t.leaves.size(), 0u);
    }
}

TEST_P(WeberPennPresets, TheSameSeedGrowsTheSameTree) {
    WeberPennParams p = preset(GetParam());
    const WeberPennTree a = growWeberPenn(p), b = growWeberPenn(p);
    p.seed = 99;
    const WeberPennTree c = growWeberPenn(p);
    auto points = [](const WeberPennTree& t) {
        std::vector<double> v;
        for (const auto& s : t.stems)
            for (const auto& path : s.paths)
                for (Vec3d q : path.points) v.insert(v.end(), {q.x, q.y, q.z});
        for (const auto& l : t.leaves) v.insert(v.end(), {l.position.x, l.position.y, l.position.z, l.direction.x});
        return v;
    };
    const std::vector<double> pa = points(a), pb = points(b), pc = points(c);
    ASSERT_EQ(pa.size(), pb.size());
    EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(double)), 0);
    EXPECT_TRUE(pa.size() != pc.size() || std::memcmp(pa.data(), pc.data(), pa.size() * sizeof(double)) != 0)
        << "another seed grows the same tree";
}

// The procedural expands lazily (the trunk, then one procedural per first-level branch): at full
// detail it makes every stem (a patch mesh per path) and every leaf of the tree grown at once, as
// outline polygons (not squares), all inside the bound it declares.
TEST_P(WeberPennPresets, TheProceduralMakesTheTreeGrownAtOnce) {
    const WeberPennParams& p = preset(GetParam());
    const WeberPennTree t = growWeberPenn(p);
    const std::string datablock = "model=weberpenn preset=" + GetParam() + " seed=1";
    auto generator = makeWeberPennGenerator(datablock, {});
    ExpandContext ctx;
    ctx.detail = 1e12;  // full quality, every stem
    ProceduralOutput out;
    generator->expand(ctx, out);
    std::vector<ProceduralOutput> subtrees(out.procedurals.size());
    for (size_t i = 0; i < out.procedurals.size(); ++i) out.procedurals[i].generator->expand(ctx, subtrees[i]);
    size_t meshes = out.scene.patchMeshes.size(), polygons = 0, vertices = 0;
    Bounds3d made;
    auto take = [&](const ProceduralOutput& o) {
        for (const auto& m : o.scene.patchMeshes)
            for (Vec3d q : m.P[0]) made.extend(q);
        for (const auto& m : o.scene.polygonMeshes) {
            polygons += m.polygons.size();
            for (const auto& poly : m.polygons) vertices += poly[0].size();
            for (Vec3d q : m.P[0]) made.extend(q);
        }
    };
    take(out);
    for (const auto& o : subtrees) meshes += o.scene.patchMeshes.size(), take(o);
    size_t paths = 0;
    for (const auto& s : t.stems)
        if (s.length > 0 && s.radius > 0) paths += s.paths.size();
    EXPECT_EQ(meshes, paths);
    EXPECT_EQ(polygons, t.leaves.size());
    EXPECT_GE(vertices, 10 * polygons);  // leaf outlines of 10 or 12 points
    const Bounds3d bound = weberPennBound(p);
    EXPECT_TRUE(bound.lo.x <= made.lo.x && bound.lo.y <= made.lo.y && bound.lo.z <= made.lo.z);
    EXPECT_TRUE(bound.hi.x >= made.hi.x && bound.hi.y >= made.hi.y && bound.hi.z >= made.hi.z);
    // Each branch's procedural holds what it makes.
    for (size_t i = 0; i < subtrees.size(); ++i) {
        const Bounds3d& b = out.procedurals[i].desc.bound;
        for (const auto& m : subtrees[i].scene.polygonMeshes)
            for (Vec3d q : m.P[0])
                ASSERT_TRUE(q.x >= b.lo.x && q.y >= b.lo.y && q.z >= b.lo.z && q.x <= b.hi.x && q.y <= b.hi.y && q.z <= b.hi.z);
    }
}

INSTANTIATE_TEST_SUITE_P(Paper, WeberPennPresets, testing::ValuesIn(weberPennPresetNames()));

TEST(WeberPenn, PresetsAreThePapersFourSpecies) {
    EXPECT_EQ(weberPennPresetNames(),
              (std::vector<std::string>{"quaking_aspen", "black_tupelo", "weeping_willow", "ca_black_oak"}));
}

TEST(WeberPenn, ShapeRatioIsThePapersTable) {
    for (int shape = 0; shape <= 7; ++shape)
        for (double r = 0; r <= 1; r += 0.05) EXPECT_DOUBLE_EQ(weberPennShapeRatio(shape, r), paperShapeRatio(shape, r));
    EXPECT_DOUBLE_EQ(weberPennShapeRatio(1, 0.5), 1.0);  // spherical: widest in the middle
    EXPECT_DOUBLE_EQ(weberPennShapeRatio(7, 0.7), 1.0);  // tend flame: widest at 0.7
}

TEST(WeberPenn, ParametersOverrideThePresetByThePapersNames) {
    const WeberPennParams p = parseWeberPennParams("model=weberpenn 1Branches=10 preset=quaking_aspen Levels=2 "
                                                   "LeafShape=2 seed=5", {});
    EXPECT_EQ(p.levels, 2);
    EXPECT_EQ(p.level[1].branches, 10);
    EXPECT_EQ(p.level[2].branches, 30);  // the preset's
    EXPECT_EQ(p.leafShape, 2);
    EXPECT_EQ(p.seed, 5u);
    const WeberPennTree t = growWeberPenn(p);
    EXPECT_EQ(t.stems.size(), 11u);  // the trunk and its 10 branches, which carry the leaves
    for (const char* bad : {"model=weberpenn preset=oak", "model=weberpenn 1Branch=3", "model=weberpenn Levels=7",
                            "model=weberpenn Ratio=x", "model=weberpenn 5Length=1"}) {
        EXPECT_THROW(parseWeberPennParams(bad, {}), InputError) << bad;
    }
    try {
        parseWeberPennParams("model=weberpenn preset=oak", {});
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("quaking_aspen, black_tupelo, weeping_willow, ca_black_oak"), std::string::npos)
            << e.what();
    }
}

// Splitting: 0BaseSplits clones the trunk at its first segment; nSegSplits = 1 doubles a stem at
// every segment (until the cap of 32 paths), the clones starting where they split.
TEST(WeberPenn, SplitsMakeClonesWhereTheStemSplits) {
    WeberPennParams p = *weberPennPreset("ca_black_oak");
    p.levels = 1;
    p.level[0].segSplits = 0;
    const WeberPennTree t = growWeberPenn(p);
    ASSERT_EQ(t.stems[0].paths.size(), size_t(1 + p.baseSplits));
    for (size_t i = 1; i < t.stems[0].paths.size(); ++i) {
        const auto& clone = t.stems[0].paths[i];
        EXPECT_EQ(clone.firstSegment, 1);
        EXPECT_EQ(clone.points.front().x, t.stems[0].paths[0].points[1].x);
        EXPECT_NEAR(pathLength(clone.points), t.stems[0].length * (p.level[0].curveRes - 1) / p.level[0].curveRes, 1e-9);
    }
    p.baseSplits = 0;
    p.level[0].segSplits = 1;
    p.level[0].curveRes = 4;
    EXPECT_EQ(growWeberPenn(p).stems[0].paths.size(), 8u);  // 1 -> 2 -> 4 -> 8 at the 3 inner joints
}

}  // namespace
}  // namespace streyes
