// Weber–Penn pruning against the envelope's formula: the profile at points worked out by hand, every
// stem point inside the envelope at PruneRatio 1, PruneRatio 0 leaving the tree as it grows unpruned
// (whatever the envelope), and PruneRatio blending a stem's length between the two.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>

#include "procedural/weber_penn.h"

namespace streyes {
namespace {

std::vector<double> pointsOf(const WeberPennTree& t) {
    std::vector<double> v;
    for (const auto& s : t.stems) {
        v.insert(v.end(), {s.length, s.radius, double(s.children), double(s.leaves)});
        for (const auto& path : s.paths)
            for (Vec3d q : path.points) v.insert(v.end(), {q.x, q.y, q.z});
    }
    for (const auto& l : t.leaves)
        v.insert(v.end(), {l.position.x, l.position.y, l.position.z, l.direction.x, l.direction.y, l.normal.z});
    return v;
}

// An envelope that cuts most presets' crowns: narrow, its widest point low.
WeberPennParams pruned(const std::string& preset, double ratio) {
    WeberPennParams p = *weberPennPreset(preset);
    p.pruneRatio = ratio;
    p.pruneWidth = 0.3;
    p.pruneWidthPeak = 0.4;
    p.prunePowerLow = 0.3;
    p.prunePowerHigh = 1.5;
    return p;
}

TEST(WeberPennPrune, TheEnvelopesProfileIsThePapersFormula) {
    WeberPennParams p;
    p.pruneWidth = 0.5, p.pruneWidthPeak = 0.3, p.prunePowerLow = 0.5, p.prunePowerHigh = 2, p.baseSize = 0.2;
    // Above the peak (ratio < 1 - 0.3): (0.35 / 0.7)^2 = 0.25; below: ((1 - 0.85) / 0.3)^0.5 = sqrt(0.5).
    EXPECT_DOUBLE_EQ(weberPennEnvelope(p, 0.35), 0.25);
    EXPECT_DOUBLE_EQ(weberPennEnvelope(p, 0.85), std::sqrt(0.5));
    EXPECT_DOUBLE_EQ(weberPennEnvelope(p, 0.7), 1.0);  // the peak, from both sides
    EXPECT_NEAR(weberPennEnvelope(p, 0.7 - 1e-12), 1.0, 1e-9);
    EXPECT_EQ(weberPennEnvelope(p, 0), 0.0);  // the tree's top
    EXPECT_EQ(weberPennEnvelope(p, -0.1), 0.0);
    EXPECT_EQ(weberPennEnvelope(p, 1.2), 0.0);  // below the crown's base
    EXPECT_EQ(weberPennEnvelope(p, std::nan("")), 0.0);
    // scale_tree 10, BaseSize 0.2: the crown spans y 2..10; ratio 0.35 is y = 10 - 0.35 * 8 = 7.2,
    // where the envelope's radius is PruneWidth 0.5 * 0.25 * 10 = 1.25.
    EXPECT_TRUE(weberPennInsideEnvelope(p, 10, {1.2, 7.2, 0}));
    EXPECT_TRUE(weberPennInsideEnvelope(p, 10, {0.7, 7.2, -1.0}));  // radius 1.22
    EXPECT_FALSE(weberPennInsideEnvelope(p, 10, {0, 7.2, 1.3}));
    EXPECT_FALSE(weberPennInsideEnvelope(p, 10, {0.9, 7.2, 0.9}));  // radius 1.27
    // ratio 0.85 is y = 3.2: radius 0.5 sqrt(0.5) 10 = 3.5355.
    EXPECT_TRUE(weberPennInsideEnvelope(p, 10, {3.53, 3.2, 0}));
    EXPECT_FALSE(weberPennInsideEnvelope(p, 10, {3.54, 3.2, 0}));
    EXPECT_FALSE(weberPennInsideEnvelope(p, 10, {0, 1.9, 0}));   // below the crown
    EXPECT_FALSE(weberPennInsideEnvelope(p, 10, {0, 10.1, 0}));  // above the tree
}

TEST(WeberPennPrune, ScaleTreeIsTheTrunksDraw) {
    for (const std::string& name : weberPennPresetNames()) {
        WeberPennParams p = *weberPennPreset(name);
        p.seed = 17;
        EXPECT_EQ(weberPennScaleTree(p), growWeberPenn(p).scaleTree) << name;
    }
}

class WeberPennPrunePresets : public testing::TestWithParam<std::string> {};

TEST_P(WeberPennPrunePresets, AtPruneRatioOneEveryStemPointIsInsideTheEnvelope) {
    for (uint64_t seed : {1u, 5u}) {
        WeberPennParams p = pruned(GetParam(), 1);
        p.seed = seed;
        WeberPennParams none = p;
        none.pruneRatio = 0;
        const WeberPennTree t = growWeberPenn(p), unpruned = growWeberPenn(none);
        size_t tested = 0;
        for (const WeberPennStem& s : t.stems) {
            if (s.level == 0 || s.length <= 0) continue;
            for (const auto& path : s.paths)
                for (Vec3d q : path.points) {
                    ++tested;
                    ASSERT_TRUE(weberPennInsideEnvelope(p, t.scaleTree, q))
                        << "level " << s.level << " stem point (" << q.x << ", " << q.y << ", " << q.z << ")";
                }
        }
        EXPECT_GT(tested, 50u);
        // The trunk is never pruned; the envelope did cut the crown (the unpruned tree leaves it).
        EXPECT_EQ(t.stems[0].length, unpruned.stems[0].length);
        size_t outside = 0;
        for (const WeberPennStem& s : unpruned.stems)
            if (s.level > 0)
                for (const auto& path : s.paths)
                    for (Vec3d q : path.points) outside += !weberPennInsideEnvelope(p, unpruned.scaleTree, q);
        EXPECT_GT(outside, 0u) << "the test's envelope does not cut this tree";
    }
}

TEST_P(WeberPennPrunePresets, AtPruneRatioZeroTheEnvelopeChangesNothing) {
    const WeberPennParams plain = *weberPennPreset(GetParam());
    const std::vector<double> a = pointsOf(growWeberPenn(plain)), b = pointsOf(growWeberPenn(pruned(GetParam(), 0)));
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
    // ... while a ratio above zero does change it.
    EXPECT_NE(pointsOf(growWeberPenn(pruned(GetParam(), 0.5))), a);
}

// A first-level branch grows on the (unpruned) trunk at the same place whatever PruneRatio: its
// length at ratio 0.5 lies halfway between its lengths at 0 and 1, and its radius follows that length.
TEST_P(WeberPennPrunePresets, PruneRatioBlendsTheLength) {
    std::map<uint64_t, const WeberPennStem*> none, full, half;
    const WeberPennTree t0 = growWeberPenn(pruned(GetParam(), 0)), t1 = growWeberPenn(pruned(GetParam(), 1)),
                        th = growWeberPenn(pruned(GetParam(), 0.5));
    for (const auto& s : t0.stems) if (s.level == 1) none[s.key] = &s;
    for (const auto& s : t1.stems) if (s.level == 1) full[s.key] = &s;
    for (const auto& s : th.stems) if (s.level == 1) half[s.key] = &s;
    ASSERT_EQ(none.size(), half.size());
    size_t shortened = 0;
    for (const auto& [key, first] : none) {
        const WeberPennStem& s0 = *first;
        const WeberPennStem& s1 = *full.at(key);
        const WeberPennStem& sh = *half.at(key);
        EXPECT_LE(s1.length, s0.length);
        EXPECT_NEAR(sh.length, 0.5 * (s0.length + s1.length), 1e-7 * s0.length + 1e-12);
        shortened += s1.length < s0.length;
        const WeberPennStem& trunk = th.stems[0];
        EXPECT_DOUBLE_EQ(sh.radius, std::min(trunk.radius * std::pow(sh.length / trunk.length, pruned(GetParam(), 0.5).ratioPower),
                                             weberPennRadiusAt(th.params, trunk, sh.offset / trunk.length)));
    }
    EXPECT_GT(shortened, 0u);
}

INSTANTIATE_TEST_SUITE_P(Paper, WeberPennPrunePresets, testing::ValuesIn(weberPennPresetNames()));

TEST(WeberPennPrune, ParsesThePapersNames) {
    const WeberPennParams p = parseWeberPennParams(
        "model=weberpenn PruneRatio=0.8 PruneWidth=0.4 PruneWidthPeak=0.6 PrunePowerLow=0.001 PrunePowerHigh=0.5", {});
    EXPECT_EQ(p.pruneRatio, 0.8);
    EXPECT_EQ(p.pruneWidth, 0.4);
    EXPECT_EQ(p.pruneWidthPeak, 0.6);
    EXPECT_EQ(p.prunePowerLow, 0.001);
    EXPECT_EQ(p.prunePowerHigh, 0.5);
    EXPECT_THROW(parseWeberPennParams("model=weberpenn PruneRatio=1.5", {}), InputError);
    EXPECT_THROW(parseWeberPennParams("model=weberpenn PruneWidthPeak=-1", {}), InputError);
}

}  // namespace
}  // namespace streyes
