// The paper's degradation at range for Weber–Penn trees: at quality q a subtree keeps
// ceil(n / stemStep) of each stem's n last-level stems and ceil(L / leafStep) of each kept stem's
// L leaves, each the full tree's own (the same key, axis and place), the leaves grown so that
// their area is the full tree's; stems under a pixel are lines and under a quarter of one gone;
// a tree under 40 pixels is its crown's volume; and at every range what the procedural makes
// lies inside the bounds it declares.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "procedural/weber_penn.h"
#include "util/sampling.h"

namespace streyes {
namespace {

// The reduction written out from its definition: stemStep = floor(1 / sqrt(q)) on a last stem
// level of 2 or deeper, leafStep = round(1 / (q stemStep)).
TEST(WeberPennRange, TheStepsFollowTheQuality) {
    const WeberPennParams& aspen = *weberPennPreset("quaking_aspen");  // Levels 3: its last stem level is 2
    WeberPennParams two = aspen;
    two.levels = 2;  // the last stem level is the first: only leaves thin out
    struct Case {
        double q;
        int stemStep, leafStep;
    };
    for (const Case& c : {Case{1, 1, 1}, Case{0.5, 1, 2}, Case{0.25, 2, 2}, Case{0.1, 3, 3}, Case{0.05, 4, 5},
                          Case{0.01, 4, 5} /* taken at 0.05 */}) {
        const WeberPennReduction r = weberPennReduction(aspen, c.q);
        EXPECT_EQ(r.stemStep, c.stemStep) << c.q;
        EXPECT_EQ(r.leafStep, c.leafStep) << c.q;
        const WeberPennReduction r2 = weberPennReduction(two, c.q);
        EXPECT_EQ(r2.stemStep, 1) << c.q;
        EXPECT_EQ(r2.leafStep, int(std::lround(1 / std::max(c.q, 0.05)))) << c.q;
    }
}

bool sameStem(const WeberPennStem& a, const WeberPennStem& b) {
    if (a.key != b.key || a.length != b.length || a.radius != b.radius || a.paths.size() != b.paths.size()) return false;
    for (size_t i = 0; i < a.paths.size(); ++i)
        if (a.paths[i].points.size() != b.paths[i].points.size()) return false;
        else
            for (size_t j = 0; j < a.paths[i].points.size(); ++j)
                if (!(a.paths[i].points[j] == b.paths[i].points[j])) return false;
    return true;
}

class WeberPennRangePresets : public testing::TestWithParam<std::string> {};

// Counts against the formulas, on the tree grown at once at several qualities: the stems above the
// last stem level are all there; of each stem's n children on the last stem level, ceil(n /
// stemStep), each the full tree's child j (j % stemStep == 0); of each kept stem's L leaves,
// ceil(L / leafStep), at the full tree's leaf j, grown by sqrt(n / kept stems * L / kept leaves).
// The leaf area (count times grow squared) stays within a few percent of the full tree's.
TEST_P(WeberPennRangePresets, StemAndLeafCountsFollowThePapersReduction) {
    WeberPennParams p = *weberPennPreset(GetParam());
    p.seed = 3;
    const WeberPennTree full = growWeberPenn(p);
    const int lastStemLevel = p.levels - 1;
    std::map<uint64_t, size_t> fullByKey;
    for (size_t i = 0; i < full.stems.size(); ++i) fullByKey[full.stems[i].key] = i;
    std::map<uint64_t, std::vector<const WeberPennLeaf*>> fullLeaves;  // by their stem's key
    for (const WeberPennLeaf& l : full.leaves) fullLeaves[full.stems[size_t(l.stem)].key].push_back(&l);

    for (double q : {0.5, 0.25, 0.1, 0.05}) {
        SCOPED_TRACE(q);
        const WeberPennReduction r = weberPennReduction(p, q);
        const WeberPennTree t = growWeberPenn(p, r);
        const int stemStep = lastStemLevel >= 2 ? r.stemStep : 1;
        // Every stem is the full tree's; the levels above the last stem level all there.
        std::map<int, size_t> perLevel, perLevelFull;
        for (const auto& s : full.stems) ++perLevelFull[s.level];
        for (const auto& s : t.stems) {
            ++perLevel[s.level];
            ASSERT_TRUE(fullByKey.count(s.key));
            ASSERT_TRUE(sameStem(s, full.stems[fullByKey[s.key]]));
        }
        for (int level = 0; level < lastStemLevel; ++level) EXPECT_EQ(perLevel[level], perLevelFull[level]) << level;
        // Children kept per parent on the last stem level: ceil(n / stemStep), those with j % stemStep == 0.
        size_t keptStems = 0, expectedStems = 0;
        for (size_t i = 0; i < t.stems.size(); ++i) {
            const WeberPennStem& s = t.stems[i];
            if (s.level != lastStemLevel - 1) continue;
            const int n = s.children;
            expectedStems += size_t((n + stemStep - 1) / stemStep);
            for (const auto& c : t.stems)
                if (c.parent == int(i)) {
                    ++keptStems;
                    bool found = false;
                    for (int j = 0; j < n; j += stemStep) found = found || c.key == hashCombine(s.key, uint64_t(j) + 1);
                    EXPECT_TRUE(found) << "a kept stem that is not child j % stemStep == 0";
                }
        }
        EXPECT_EQ(keptStems, expectedStems);
        if (lastStemLevel >= 1) {
            EXPECT_EQ(keptStems, perLevel[lastStemLevel]);
        }
        // Leaves: ceil(L / leafStep) per kept stem, at the full tree's places, grown by the formula.
        std::map<int, int> leavesOn;
        for (const WeberPennLeaf& l : t.leaves) ++leavesOn[l.stem];
        size_t expectedLeaves = 0;
        double area = 0, fullArea = double(full.leaves.size());
        for (size_t i = 0; i < t.stems.size(); ++i) {
            const WeberPennStem& s = t.stems[i];
            if (s.level != lastStemLevel) continue;
            const int kept = (s.leaves + r.leafStep - 1) / r.leafStep;
            expectedLeaves += size_t(kept);
            EXPECT_EQ(leavesOn[int(i)], kept);
        }
        EXPECT_EQ(t.leaves.size(), expectedLeaves);
        for (const WeberPennLeaf& l : t.leaves) {
            const WeberPennStem& s = t.stems[size_t(l.stem)];
            double stemShare = 1;
            if (stemStep > 1 && s.parent >= 0) {
                const int n = t.stems[size_t(s.parent)].children;
                stemShare = double(n) / double((n + stemStep - 1) / stemStep);
            }
            const double leafShare = double(s.leaves) / double((s.leaves + r.leafStep - 1) / r.leafStep);
            EXPECT_NEAR(l.grow, std::sqrt(stemShare * leafShare), 1e-12);
            area += l.grow * l.grow;
            // At a place of the full tree's.
            bool found = false;
            for (const WeberPennLeaf* f : fullLeaves[s.key]) found = found || f->position == l.position;
            EXPECT_TRUE(found);
        }
        // About q of the leaves, and the leaf area of the full tree (stems left out carry their own
        // counts, which their kept siblings stand for: a few percent).
        EXPECT_GT(double(t.leaves.size()), 0.4 * q * double(full.leaves.size()));
        EXPECT_LT(double(t.leaves.size()), 2.5 * q * double(full.leaves.size()));
        EXPECT_NEAR(area / fullArea, 1.0, 0.15);
    }
}

bool inside(const Bounds3d& b, Vec3d q) {
    return q.x >= b.lo.x && q.y >= b.lo.y && q.z >= b.lo.z && q.x <= b.hi.x && q.y <= b.hi.y && q.z <= b.hi.z;
}

struct Made {
    size_t meshes = 0, curves = 0, leafPolygons = 0, procedurals = 0;
    bool allInside = true;
};

void check(const ProceduralOutput& o, const Bounds3d& bound, Made& m) {
    for (const auto& mesh : o.scene.patchMeshes) {
        ++m.meshes;
        for (const auto& key : mesh.P)
            for (Vec3d q : key) m.allInside = m.allInside && inside(bound, q);
    }
    for (const auto& c : o.scene.curves) {
        m.curves += c.nvertices.size();
        for (const auto& key : c.P)
            for (Vec3d q : key) m.allInside = m.allInside && inside(bound, q);
    }
    for (const auto& mesh : o.scene.polygonMeshes) {
        m.leafPolygons += mesh.polygons.size();
        for (const auto& key : mesh.P)
            for (Vec3d q : key) m.allInside = m.allInside && inside(bound, q);
    }
    m.procedurals += o.procedurals.size();
}

// The tree seen at `ppu` pixels a unit: expanded as the renderer expands it (detail: the bound's
// raster area), and each branch's procedural at its own size.
struct Expanded {
    Made tree;  // the tree's own expansion
    Made branches;
    std::vector<ProceduralOutput> subtrees;
};

Expanded expandAt(const WeberPennParams& p, double ppu) {
    const Bounds3d bound = weberPennBound(p);
    auto side = [](const Bounds3d& b) {
        const Vec3d d = b.diagonal();
        return std::max({d.x, d.y, d.z});
    };
    ExpandContext ctx;
    ctx.read.pixelsPerUnit = ppu;
    ctx.detail = std::pow(ppu * side(bound), 2);
    ctx.windowStart = 1, ctx.windowEnd = 3.5;
    ProceduralOutput out;
    makeWeberPennGenerator(p)->expand(ctx, out);
    Expanded e;
    check(out, bound, e.tree);
    for (const auto& g : out.procedurals) {
        EXPECT_TRUE(inside(bound, g.desc.bound.lo) && inside(bound, g.desc.bound.hi));
        ExpandContext c = ctx;
        c.detail = std::pow(ppu * side(g.desc.bound), 2);
        ProceduralOutput o;
        g.generator->expand(c, o);
        check(o, g.desc.bound, e.branches);
        e.subtrees.push_back(std::move(o));
    }
    return e;
}

// At every range, still and in the wind, what the tree makes lies inside the bounds it declares.
TEST_P(WeberPennRangePresets, BoundsHoldAtEveryRange) {
    for (const char* wind : {"", " WindSpeed=2 WindGust=1"}) {
        const WeberPennParams p =
            parseWeberPennParams("model=weberpenn preset=" + GetParam() + " seed=4" + wind, {});
        for (double ppu : {0.5, 2.0, 8.0, 30.0, 200.0}) {
            SCOPED_TRACE(std::string(wind) + " ppu " + std::to_string(ppu));
            const Expanded e = expandAt(p, ppu);
            EXPECT_TRUE(e.tree.allInside);
            EXPECT_TRUE(e.branches.allInside);
        }
    }
}

// A tree under 40 pixels (its still bound's longest side on screen, times detail=) is a trunk and
// a crown volume of 8 x 7 faces and makes no branch procedurals; above, its first-level branches'
// procedurals; detail=2 halves the range.
TEST_P(WeberPennRangePresets, AFarTreeIsASimpleVolume) {
    WeberPennParams p = *weberPennPreset(GetParam());
    p.seed = 4;
    std::vector<WeberPennStem> stems{weberPennTrunk(p, nullptr)};
    weberPennGrowBelow(p, stems, 0, 1, nullptr);
    const Bounds3d still = weberPennBound(p);  // still: the tree's own bound
    const Vec3d d = still.diagonal();
    const double side = std::max({d.x, d.y, d.z});
    for (double detail : {1.0, 2.0}) {
        p.detail = detail;
        const Expanded farTree = expandAt(p, 39 / detail / side);
        EXPECT_EQ(farTree.tree.procedurals, 0u);
        EXPECT_EQ(farTree.tree.leafPolygons, 8u * 7u);  // the volume: 8 around, 6 rings, closed
        EXPECT_EQ(farTree.tree.meshes + farTree.tree.curves, stems[0].paths.size());  // the trunk
        const Expanded nearer = expandAt(p, 41 / detail / side);
        size_t branches = 0;
        for (size_t i = 1; i < stems.size(); ++i) branches += stems[i].length > 0;
        EXPECT_EQ(nearer.tree.procedurals, branches);
        EXPECT_EQ(nearer.tree.leafPolygons, 0u);
    }
}

// Each stem by its width on screen (times detail=): a patch mesh per path from a pixel across,
// lines (a curve per path) from a quarter of a pixel, nothing under (but for the first level).
TEST_P(WeberPennRangePresets, ThinStemsAreLinesAndThinnerOnesGone) {
    WeberPennParams p = *weberPennPreset(GetParam());
    p.seed = 4;
    for (double ppu : {4.0, 30.0}) {
        SCOPED_TRACE(ppu);
        const Expanded e = expandAt(p, ppu);
        ASSERT_GT(e.subtrees.size(), 0u);
        // Recount from the stems the subtrees grow (at their own quality).
        std::vector<WeberPennStem> stems{weberPennTrunk(p, nullptr)};
        weberPennGrowBelow(p, stems, 0, 1, nullptr);
        const Bounds3d bound = weberPennBound(p);
        size_t meshes = 0, curves = 0, gone = 0, subtree = 0;
        ProceduralOutput out;
        ExpandContext ctx;
        ctx.read.pixelsPerUnit = ppu;
        const Vec3d d = bound.diagonal();
        ctx.detail = std::pow(ppu * std::max({d.x, d.y, d.z}), 2);
        makeWeberPennGenerator(p)->expand(ctx, out);
        for (const auto& g : out.procedurals) {
            const Vec3d gd = g.desc.bound.diagonal();
            const double size = ppu * std::max({gd.x, gd.y, gd.z});
            const double q = std::clamp(std::pow(size * p.detail / 300, 2), 0.05, 1.0);
            // The branch this procedural grows: the first-level stems in order, those of positive length.
            while (stems[1 + subtree].length <= 0) ++subtree;
            std::vector<WeberPennStem> below{stems[1 + subtree]};
            ++subtree;
            std::vector<WeberPennLeaf> leaves;
            weberPennGrowBelow(p, below, 0, p.levels, &leaves, weberPennReduction(p, q));
            for (const auto& s : below) {
                if (s.length <= 0 || s.radius <= 0) continue;
                const double across = 2 * s.radius * ppu * p.detail;
                if (across >= 1) meshes += s.paths.size();
                else if (s.level <= 1 || across >= 0.25) curves += s.paths.size();
                else ++gone;
            }
        }
        EXPECT_EQ(e.branches.meshes, meshes);
        EXPECT_EQ(e.branches.curves, curves);
        if (ppu == 4.0) {
            EXPECT_GT(curves + gone, 0u);  // the range does thin them
        }
    }
}

// Leaves as made: at full detail outlines of 10 or 12 points; thinned, diamonds (one bilinear
// patch each) whose total area is the full tree's leaf area (within the 15% the counts allow).
TEST_P(WeberPennRangePresets, ThinnedLeavesAreDiamondsWithTheFullArea) {
    WeberPennParams p = *weberPennPreset(GetParam());
    p.seed = 4;
    auto leafArea = [](const std::vector<ProceduralOutput>& outs, size_t* points4, size_t* polygons) {
        double area = 0;
        for (const auto& o : outs)
            for (const auto& m : o.scene.polygonMeshes)
                for (const auto& poly : m.polygons) {
                    const auto& loop = poly[0];
                    ++*polygons;
                    *points4 += loop.size() == 4;
                    Vec3d sum{0, 0, 0};
                    for (size_t k = 1; k + 1 < loop.size(); ++k)
                        sum = sum + cross(m.P[0][size_t(loop[k])] - m.P[0][size_t(loop[0])],
                                          m.P[0][size_t(loop[k + 1])] - m.P[0][size_t(loop[0])]);
                    area += 0.5 * length(sum);
                }
        return area;
    };
    size_t fullDiamonds = 0, fullLeaves = 0, farDiamonds = 0, farLeaves = 0;
    const double full = leafArea(expandAt(p, 1e4).subtrees, &fullDiamonds, &fullLeaves);
    const double far = leafArea(expandAt(p, 3).subtrees, &farDiamonds, &farLeaves);
    EXPECT_EQ(fullDiamonds, 0u);
    ASSERT_GT(farLeaves, 0u);
    EXPECT_EQ(farDiamonds, farLeaves);
    EXPECT_LT(farLeaves * 5, fullLeaves);
    EXPECT_NEAR(far / full, 1.0, 0.15);
}

INSTANTIATE_TEST_SUITE_P(Paper, WeberPennRangePresets, testing::ValuesIn(weberPennPresetNames()));

}  // namespace
}  // namespace streyes
