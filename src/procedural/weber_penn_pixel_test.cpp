// The cap on detail per pixel of Weber–Penn trees: a leaf whose length on screen (at the
// procedural's pixels a unit, times detail=) is under a pixel keeps the share (that length)², the
// paper's range reduction at that quality, so that a near branch whose leaves are far under a
// pixel grows about a pixel's worth of them with the full tree's leaf area; leaves over a pixel
// are all kept while the branch is near.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "procedural/weber_penn.h"

namespace streyes {
namespace {

double pixelCapSide(const Bounds3d& b) {
    const Vec3d d = b.diagonal();
    return std::max({d.x, d.y, d.z});
}

struct PixelCapLeaves {
    size_t leaves = 0, expected = 0, capped = 0;  // made, grown by the formula, branches the cap thinned
    double area = 0;
};

// The tree at `ppu` pixels a unit, each branch's procedural expanded at its own size; the leaves
// each grows, against weberPennGrowBelow at the quality the formula gives it.
PixelCapLeaves pixelCapExpand(const WeberPennParams& p, double ppu) {
    PixelCapLeaves r;
    std::vector<WeberPennStem> stems{weberPennTrunk(p, nullptr)};
    weberPennGrowBelow(p, stems, 0, 1, nullptr);
    ExpandContext ctx;
    ctx.read.pixelsPerUnit = ppu;
    ctx.detail = std::pow(ppu * pixelCapSide(weberPennBound(p)), 2);
    ProceduralOutput top;
    makeWeberPennGenerator(p)->expand(ctx, top);
    size_t branch = 1;
    for (const auto& g : top.procedurals) {
        ExpandContext c = ctx;
        c.detail = std::pow(ppu * pixelCapSide(g.desc.bound), 2);
        ProceduralOutput o;
        g.generator->expand(c, o);
        for (const auto& m : o.scene.polygonMeshes)
            for (const auto& poly : m.polygons) {
                ++r.leaves;
                const auto& loop = poly[0];
                Vec3d sum{0, 0, 0};
                for (size_t k = 1; k + 1 < loop.size(); ++k)
                    sum = sum + cross(m.P[0][size_t(loop[k])] - m.P[0][size_t(loop[0])],
                                      m.P[0][size_t(loop[k + 1])] - m.P[0][size_t(loop[0])]);
                r.area += 0.5 * length(sum);
            }
        // The formula: the range's quality, capped by the leaf's length in pixels, squared.
        const double range = std::pow(std::sqrt(c.detail) * p.detail / 300, 2);
        const double leafPixels = p.leafScale * std::max(1.0, p.leafScaleX) * ppu * p.detail;
        const double q = std::clamp(std::min(range, leafPixels * leafPixels), 0.05, 1.0);
        r.capped += leafPixels * leafPixels < range;
        while (stems[branch].length <= 0) ++branch;
        std::vector<WeberPennStem> below{stems[branch++]};
        std::vector<WeberPennLeaf> leaves;
        weberPennGrowBelow(p, below, 0, p.levels, &leaves, weberPennReduction(p, q));
        r.expected += leaves.size();
    }
    return r;
}

TEST(WeberPennPixelCap, LeavesFarUnderAPixelAreThinnedWithTheirAreaKept) {
    WeberPennParams p = *weberPennPreset("quaking_aspen");
    p.seed = 4;
    p.leafScale = 0.008;  // 0.48 pixels at 60 pixels a metre, where its branches are 300 or more
    const PixelCapLeaves near = pixelCapExpand(p, 60);
    const PixelCapLeaves full = pixelCapExpand(p, 1e4);  // every leaf (80 pixels long)
    ASSERT_GT(full.leaves, 1000u);
    EXPECT_EQ(full.leaves, full.expected);
    EXPECT_EQ(near.leaves, near.expected);
    EXPECT_GT(near.capped, 0u) << "the cap, not the range, decides some branches";
    EXPECT_LT(near.leaves * 3, full.leaves);  // (0.48)^2: about a quarter kept
    EXPECT_NEAR(near.area / full.area, 1.0, 0.15);
    // detail=2 doubles the leaf's length in pixels: 0.96, so about all kept.
    p.detail = 2;
    const PixelCapLeaves sharper = pixelCapExpand(p, 60);
    EXPECT_EQ(sharper.leaves, sharper.expected);
    EXPECT_GT(sharper.leaves * 10, full.leaves * 8);
}

TEST(WeberPennPixelCap, LeavesOverAPixelAreAllKept) {
    WeberPennParams p = *weberPennPreset("quaking_aspen");
    p.seed = 4;
    p.leafScale = 0.05;  // 3 pixels at 60 pixels a metre
    const PixelCapLeaves near = pixelCapExpand(p, 60), full = pixelCapExpand(p, 1e4);
    EXPECT_EQ(near.capped, 0u);
    EXPECT_EQ(near.leaves, near.expected);
    EXPECT_GT(near.leaves * 10, full.leaves * 9);  // only branches under 300 pixels thin
}

// What a tree at `ppu` makes: leaves (and those of 4 points), their area, stem meshes and curves.
struct PixelCapMade {
    size_t leaves = 0, diamonds = 0, meshes = 0, curves = 0;
    double area = 0;
};

PixelCapMade pixelCapMade(const WeberPennParams& p, double ppu) {
    PixelCapMade r;
    ExpandContext ctx;
    ctx.read.pixelsPerUnit = ppu;
    ctx.detail = std::pow(ppu * pixelCapSide(weberPennBound(p)), 2);
    ctx.windowStart = 1, ctx.windowEnd = 3.5;
    ProceduralOutput top;
    makeWeberPennGenerator(p)->expand(ctx, top);
    for (const auto& g : top.procedurals) {
        ExpandContext c = ctx;
        c.detail = std::pow(ppu * pixelCapSide(g.desc.bound), 2);
        ProceduralOutput o;
        g.generator->expand(c, o);
        r.meshes += o.scene.patchMeshes.size();
        for (const auto& cv : o.scene.curves) r.curves += cv.nvertices.size();
        for (const auto& m : o.scene.polygonMeshes)
            for (const auto& poly : m.polygons) {
                const auto& loop = poly[0];
                ++r.leaves;
                r.diamonds += loop.size() == 4;
                Vec3d sum{0, 0, 0};
                for (size_t k = 1; k + 1 < loop.size(); ++k)
                    sum = sum + cross(m.P[0][size_t(loop[k])] - m.P[0][size_t(loop[0])],
                                      m.P[0][size_t(loop[k + 1])] - m.P[0][size_t(loop[0])]);
                r.area += 0.5 * length(sum);
            }
    }
    return r;
}

// A leaf under 6 pixels long (times detail=) is a diamond of its outline's area (one bilinear
// patch, 4 keyed points) even where every leaf is kept; from 6 pixels, its outline.
TEST(WeberPennPixelCap, LeavesUnderSixPixelsAreDiamondsOfTheirArea) {
    WeberPennParams p = *weberPennPreset("quaking_aspen");  // LeafScale 0.17
    p.seed = 4;
    const PixelCapMade small = pixelCapMade(p, 34);  // 5.8 pixels
    const PixelCapMade large = pixelCapMade(p, 36);  // 6.1 pixels
    const PixelCapMade full = pixelCapMade(p, 1e4);
    ASSERT_GT(small.leaves, 1000u);
    EXPECT_EQ(small.diamonds, small.leaves);
    EXPECT_LT(large.diamonds * 2, large.leaves) << "the leaves every branch keeps are outlines";
    EXPECT_EQ(full.diamonds, 0u);
    EXPECT_NEAR(small.area / full.area, 1.0, 0.15);
}

// The wind widens a branch's bound, not its detail: its size on screen is its still subtree's,
// so a windy tree grows the leaves and stems the still tree does.
TEST(WeberPennPixelCap, TheWindDoesNotChangeTheDetail) {
    const WeberPennParams still = parseWeberPennParams("model=weberpenn preset=black_tupelo seed=4", {});
    const WeberPennParams windy = parseWeberPennParams("model=weberpenn preset=black_tupelo seed=4 WindSpeed=2 WindGust=1", {});
    for (double ppu : {9.0, 18.0}) {
        SCOPED_TRACE(ppu);
        const PixelCapMade a = pixelCapMade(still, ppu), b = pixelCapMade(windy, ppu);
        ASSERT_GT(a.leaves, 0u);
        EXPECT_EQ(a.leaves, b.leaves);
        EXPECT_EQ(a.meshes, b.meshes);
        EXPECT_EQ(a.curves, b.curves);
    }
}

}  // namespace
}  // namespace streyes
