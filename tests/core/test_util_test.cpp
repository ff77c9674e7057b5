// The tests' own comparison helpers (tests/test_util.h): a helper that cannot see a NaN passes a
// broken render, so each is checked here on NaN, infinities and signed zeros.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "test_util.h"

namespace streyes {
namespace {

using test::RenderResult;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// One 2x1 frame whose first red value is `v` (everything else 0.5).
RenderResult oneValue(float v) {
    RenderResult r;
    r.frames.emplace_back();
    r.frames[0].resize(2, 1);
    for (float& c : r.frames[0].rgba) c = 0.5f;
    r.frames[0].rgba[0] = v;
    return r;
}

TEST(TestUtil, AbsDifferenceSeesNaNAndInfinities) {
    EXPECT_EQ(test::absDifference(0.25f, 1.0f), 0.75f);
    EXPECT_EQ(test::absDifference(0.0f, -0.0f), 0.0f);
    EXPECT_EQ(test::absDifference(kInf, kInf), 0.0f);
    EXPECT_EQ(test::absDifference(-kInf, -kInf), 0.0f);
    EXPECT_EQ(test::absDifference(kInf, -kInf), kInf);
    EXPECT_EQ(test::absDifference(kInf, 1.0f), kInf);
    EXPECT_EQ(test::absDifference(1.0f, kNaN), kInf);
    EXPECT_EQ(test::absDifference(kNaN, 1.0f), kInf);
    EXPECT_EQ(test::absDifference(kNaN, kNaN), kInf);
    EXPECT_EQ(test::absDifference(3e38f, -3e38f), kInf);  // overflows to +inf, stays large
}

TEST(TestUtil, MaxAndMeanDifferenceSeeNaNWhereverItIs) {
    const RenderResult half = oneValue(0.5f), nan = oneValue(kNaN);
    for (const auto& [a, b] : {std::pair{&half, &nan}, std::pair{&nan, &half}, std::pair{&nan, &nan}}) {
        EXPECT_EQ(test::maxAbsDifference(*a, *b), kInf);
        EXPECT_EQ(test::meanAbsDifference(*a, *b), kInf);
    }
    // A NaN after a real difference (std::max(m, NaN) returns m: the old helper's blind spot).
    RenderResult late = oneValue(0.0f);
    late.frames[0].rgba[5] = kNaN;
    EXPECT_EQ(test::maxAbsDifference(half, late), kInf);
    // Infinities: the same one in both is no difference; different ones are.
    EXPECT_EQ(test::maxAbsDifference(oneValue(kInf), oneValue(kInf)), 0.0f);
    EXPECT_EQ(test::maxAbsDifference(oneValue(kInf), oneValue(-kInf)), kInf);
    EXPECT_EQ(test::maxAbsDifference(oneValue(kInf), half), kInf);
    // Signed zeros are equal values; ordinary differences are measured.
    EXPECT_EQ(test::maxAbsDifference(oneValue(0.0f), oneValue(-0.0f)), 0.0f);
    EXPECT_EQ(test::maxAbsDifference(oneValue(0.0f), half), 0.5f);
    EXPECT_FLOAT_EQ(test::meanAbsDifference(oneValue(0.0f), half), 0.5f / 8);  // 8 values
    EXPECT_EQ(test::maxAbsDifference(half, half), 0.0f);
}

TEST(TestUtil, DifferingPixelsCountsPixelsNotChannels) {
    RenderResult a = oneValue(0.5f), b = oneValue(0.5f);
    EXPECT_EQ(test::differingPixels(a.frames[0], b.frames[0], 0.1f), 0u);
    b.frames[0].rgba[0] = 0.7f;  // pixel 0: red and alpha
    b.frames[0].rgba[3] = 0.0f;
    EXPECT_EQ(test::differingPixels(a.frames[0], b.frames[0], 0.1f), 1u);
    EXPECT_EQ(test::differingPixels(a.frames[0], b.frames[0], 0.25f), 1u);  // alpha's 0.5
    EXPECT_EQ(test::differingPixels(a.frames[0], b.frames[0], 0.5f), 0u);   // more than, not as much as
    b.frames[0].rgba[6] = kNaN;  // pixel 1: blue
    EXPECT_EQ(test::differingPixels(a.frames[0], b.frames[0], 0.1f), 2u);
    EXPECT_EQ(test::differingPixels(b.frames[0], b.frames[0], 1e30f), 1u);  // NaN against itself
}

TEST(TestUtil, IdenticalPixelsMeansTheSameBits) {
    EXPECT_TRUE(test::identicalPixels(oneValue(0.5f), oneValue(0.5f)));
    EXPECT_TRUE(test::identicalPixels(oneValue(kNaN), oneValue(kNaN)));  // the same NaN, the same bits
    EXPECT_TRUE(test::identicalPixels(oneValue(kInf), oneValue(kInf)));
    EXPECT_FALSE(test::identicalPixels(oneValue(kNaN), oneValue(0.5f)));
    EXPECT_FALSE(test::identicalPixels(oneValue(0.5f), oneValue(kNaN)));
    EXPECT_FALSE(test::identicalPixels(oneValue(0.0f), oneValue(-0.0f)));
    EXPECT_FALSE(test::identicalPixels(oneValue(kInf), oneValue(-kInf)));
    EXPECT_FALSE(test::identicalPixels(oneValue(0.5f), oneValue(std::nextafter(0.5f, 1.0f))));
    // Depth counts too, and a missing depth buffer is a difference, not a short comparison.
    RenderResult z = oneValue(0.5f);
    z.frames[0].z[1] = kNaN;
    EXPECT_FALSE(test::identicalPixels(oneValue(0.5f), z));
    RenderResult noZ = oneValue(0.5f);
    noZ.frames[0].z.clear();
    EXPECT_FALSE(test::identicalPixels(oneValue(0.5f), noZ));
    EXPECT_FALSE(test::identicalPixels(noZ, oneValue(0.5f)));
}

TEST(TestUtil, DifferingCountsNamesEveryCountButNotTheSeconds) {
    const RenderCounters zero;
    EXPECT_TRUE(test::differingCounts(zero, zero).empty());
    size_t counts = 0;
#define STREYES_ONE(member, key)                                                   \
    {                                                                              \
        RenderCounters c;                                                          \
        c.member = {1};                                                            \
        EXPECT_EQ(test::differingCounts(zero, c), std::vector<std::string>{key});  \
        ++counts;                                                                  \
    }
#define STREYES_SECONDS(member, key)                                               \
    {                                                                              \
        RenderCounters c;                                                          \
        c.member = 1.5;                                                            \
        EXPECT_TRUE(test::differingCounts(zero, c).empty()) << key;                \
    }
#define STREYES_SKIP(key, expression)
    STREYES_RENDER_COUNTERS(STREYES_ONE, STREYES_ONE, STREYES_SECONDS, STREYES_SKIP)
    EXPECT_GE(counts, 26u);  // the counts and lists there were when this was written
}

// Two records of one sample each, hits as given.
test::SampleAgreement agreement(const SampleHit& x, const SampleHit& y) {
    test::SampleRecord a, b;
    a.positions = b.positions = {SamplePosition{0.5f, 0.5f, 0.25f}};
    a.hits = {x};
    b.hits = {y};
    return test::compareSamples(a, b);
}

TEST(TestUtil, CompareSamplesSeesNaN) {
    const SampleHit hit{2.0f, {0.5f, 0.5f, 0.5f}, 7};
    EXPECT_EQ(agreement(hit, hit).sameSurface, 1u);
    for (int channel = 0; channel < 3; ++channel) {  // NaN in any channel, in either record
        SampleHit bad = hit;
        (channel == 0 ? bad.c.x : channel == 1 ? bad.c.y : bad.c.z) = kNaN;
        EXPECT_EQ(agreement(hit, bad).sameSurface, 0u) << channel;
        EXPECT_EQ(agreement(bad, hit).sameSurface, 0u) << channel;
    }
    SampleHit badZ = hit;
    badZ.z = kNaN;
    EXPECT_EQ(agreement(hit, badZ).sameSurface, 0u);
    EXPECT_EQ(agreement(badZ, hit).sameSurface, 0u);
    EXPECT_EQ(agreement(badZ, hit).hitOrMiss, 0u);
    const SampleHit miss{kInf, {0, 0, 0}, UINT32_MAX};
    EXPECT_EQ(agreement(miss, badZ).hitOrMiss, 0u);  // a NaN depth is not a miss either
    EXPECT_EQ(agreement(miss, miss).sameSurface, 1u);
}

}  // namespace
}  // namespace streyes
