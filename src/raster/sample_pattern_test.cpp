#include "raster/sample_pattern.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <utility>

#include "raster/image_block.h"

namespace streyes {
namespace {

// Correlated multi-jitter: sample j of an m x n pattern in stratum (j % m, j / m), and one sample
// in each of the m n columns and m n rows (N-rooks), for any m and n.
TEST(SamplePattern, CorrelatedMultiJitterIsStratifiedIn2DAndInEachAxis) {
    for (auto [m, n] : {std::pair<int, int>{4, 4}, {4, 3}, {1, 5}, {8, 8}, {7, 2}})
        for (uint32_t p : {0u, 1u, 12345u}) {
            const int N = m * n;
            std::set<int> columns, rows;
            for (int j = 0; j < N; ++j) {
                float x, y;
                correlatedMultiJitter(j, m, n, p, &x, &y);
                ASSERT_GE(x, 0.0f);
                ASSERT_LT(x, 1.0f);
                ASSERT_GE(y, 0.0f);
                ASSERT_LT(y, 1.0f);
                EXPECT_EQ(int(x * float(m)), j % m) << m << "x" << n << " sample " << j;
                EXPECT_EQ(int(y * float(n)), j / m) << m << "x" << n << " sample " << j;
                columns.insert(int(x * float(N)));
                rows.insert(int(y * float(N)));
            }
            EXPECT_EQ(int(columns.size()), N) << m << "x" << n;
            EXPECT_EQ(int(rows.size()), N) << m << "x" << n;
        }
}

TEST(SamplePattern, TimePermutationsAreStratifiedAndInverse) {
    const PatternTable t(SamplePattern{4, 3, 42});
    ASSERT_EQ(t.samples(), 12);
    for (int q = 0; q < t.permutationCount(); ++q) {
        std::set<int> strata;
        for (int j = 0; j < 12; ++j) {
            const int k = t.stratumOfSample(q)[j];
            strata.insert(k);
            EXPECT_EQ(t.sampleOfStratum(q)[k], j);
        }
        EXPECT_EQ(strata.size(), 12u);  // a permutation: one sample a slice
        for (int k = 0; k < 12; ++k) {
            EXPECT_GE(t.stratumTimes(q)[k], float(k) / 12);  // slice k's time lies in stratum k
            EXPECT_LT(t.stratumTimes(q)[k], float(k + 1) / 12);
        }
    }
}

TEST(SamplePattern, PureFunctionOfPixelFrameAndSeed) {
    const PatternTable a(SamplePattern{2, 2, 1}), b(SamplePattern{2, 2, 1}), c(SamplePattern{2, 2, 2});
    EXPECT_EQ(a.patternOf(3, 4), b.patternOf(3, 4));
    EXPECT_EQ(a.permutationOf(3, 4, 7), b.permutationOf(3, 4, 7));
    for (int i = 0; i < 8; ++i) EXPECT_EQ(a.offsets(a.patternOf(3, 4))[i], b.offsets(b.patternOf(3, 4))[i]);
    // Another seed, other patterns; other frames, other permutations (over many pixels).
    int samePattern = 0, samePermutation = 0;
    for (int x = 0; x < 64; ++x) {
        samePattern += a.offsets(a.patternOf(x, 0))[0] == c.offsets(c.patternOf(x, 0))[0];
        samePermutation += a.permutationOf(x, 0, 7) == a.permutationOf(x, 0, 8);
    }
    EXPECT_LT(samePattern, 8);
    EXPECT_LT(samePermutation, 8);
}

// FastMod32 is a % d exactly, at the ends of the range and in between.
TEST(SamplePattern, FastModIsTheRemainder) {
    std::mt19937 rng(3);
    for (uint32_t d : {1u, 2u, 3u, 7u, 63u, 64u, 65u, 1000003u, 0x7fffffffu, 0x80000001u, 0xffffffffu}) {
        const FastMod32 mod(d);
        for (uint32_t a : {0u, 1u, d - 1, d, d + 1, 0x7fffffffu, 0x80000000u, 0xfffffffeu, 0xffffffffu})
            ASSERT_EQ(mod(a), a % d) << a << " % " << d;
        for (int k = 0; k < 20000; ++k) {
            const uint32_t a = uint32_t(rng());
            ASSERT_EQ(mod(a), a % d) << a << " % " << d;
        }
    }
}

// A pixel's pattern and its permutation in a frame are the hashes of (seed, x, y[, frame]) the
// images were made with (the keys hashed once and the remainder by FastMod32 must not move them).
TEST(SamplePattern, PatternAndPermutationAreTheHashesOfPixelAndFrame) {
    for (uint64_t seed : {0ull, 7ull}) {
        const PatternTable table(SamplePattern{4, 4, seed});
        for (int y = -3; y < 40; y += 3)
            for (int x = -5; x < 70; x += 4) {
                const uint64_t hp = hashCombine(hashCombine(mix64(seed), uint64_t(uint32_t(x))), uint64_t(uint32_t(y)));
                ASSERT_EQ(table.patternOf(x, y), int((hp >> 32) % uint64_t(table.patternCount())));
                for (int f : {0, 1, 17, 1000}) {
                    const uint64_t hq = hashCombine(
                        hashCombine(hashCombine(mix64(seed ^ 0x2545f4914f6cdd1dull), uint64_t(uint32_t(x))), uint64_t(uint32_t(y))),
                        uint64_t(uint32_t(f)));
                    ASSERT_EQ(table.permutationOf(x, y, f), int((hq >> 32) % uint64_t(table.permutationCount())));
                }
            }
    }
}

TEST(SamplePattern, TimeIsDecorrelatedFromPosition) {
    // Correlation between a sample's x within the pixel and its time, over many pixels and frames.
    const PatternTable t(SamplePattern{4, 4, 0});
    double sx = 0, st = 0, sxx = 0, stt = 0, sxt = 0;
    int n = 0;
    for (int f = 0; f < 4; ++f)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                const float* o = t.offsets(t.patternOf(x, y));
                const int q = t.permutationOf(x, y, f);
                for (int j = 0; j < 16; ++j) {
                    const double u = o[2 * j], tf = t.stratumTimes(q)[t.stratumOfSample(q)[j]];
                    sx += u, st += tf, sxx += u * u, stt += tf * tf, sxt += u * tf;
                    ++n;
                }
            }
    const double cov = sxt / n - (sx / n) * (st / n);
    const double corr = cov / std::sqrt((sxx / n - (sx / n) * (sx / n)) * (stt / n - (st / n) * (st / n)));
    EXPECT_LT(std::fabs(corr), 0.02);
}

// A block's samples: the same positions in every frame, each slice of a frame holding one sample
// of every pixel, and no hits yet.
TEST(ImageBlock, PositionsAreSharedByTheFramesAndEachSliceHoldsOneSamplePerPixel) {
    const PatternTable t(SamplePattern{2, 2, 0});
    ImageBlock block;
    block.reset({4, 6, 9, 8}, 10, 3, t, false);
    EXPECT_EQ(block.pixelCount(), 18);
    for (int y = 6; y <= 8; ++y)
        for (int x = 4; x <= 9; ++x) {
            const size_t i = block.pixelIndex(x, y);
            for (int fi = 0; fi < 3; ++fi) {
                EXPECT_FALSE(block.hasRecord(fi, i));
                block.needTimes(fi);
                const int q = block.permutation(fi, i);
                std::set<int> seen;
                for (int k = 0; k < 4; ++k) {
                    const int j = t.sampleOfStratum(q)[k];
                    seen.insert(j);
                    const SamplePosition s = block.position(fi, i, j);
                    EXPECT_EQ(int(std::floor(s.x)), x);
                    EXPECT_EQ(int(std::floor(s.y)), y);
                    EXPECT_EQ(int(s.tf * 4), k);
                    EXPECT_EQ(s.x, block.position(0, i, j).x);  // the same position in every frame
                    EXPECT_EQ(block.permutation(fi, i), t.permutationOf(x, y, 10 + fi));
                }
                EXPECT_EQ(seen.size(), 4u);
            }
            for (int j = 0; j < 4; ++j) EXPECT_TRUE(std::isinf(block.still(i)[j].z));
        }
}

// A block's permutations are hashed a pixel at a time, when first asked for, from a key it makes
// per pixel: whatever order pixels and frames are asked in, each is the table's, and a block
// reused for another bucket (another rect, other frames) makes its keys again.
TEST(ImageBlock, AReusedBlockHashesItsOwnPixelsPermutations) {
    const PatternTable t(SamplePattern{4, 4, 0});
    ImageBlock block;
    block.reset({0, 0, 7, 7}, 0, 2, t, false);
    block.needTimes(1);
    for (size_t i = 0; i < 64; ++i) block.permutation(1, i);  // every key made
    int differs = 0, asked = 0;
    for (const auto& [rect, first] : {std::pair{PixelRect{0, 0, 7, 7}, 5}, std::pair{PixelRect{40, 8, 47, 15}, 0}}) {
        block.reset(rect, first, 2, t, false);
        // The later frame first, a third of its pixels, backwards; then every pixel of the other.
        for (int fi = 1; fi >= 0; --fi) {
            block.needTimes(fi);
            for (int y = rect.y1; y >= rect.y0; --y)
                for (int x = rect.x1; x >= rect.x0; --x) {
                    if (fi == 1 && (x + y) % 3 != 0) continue;
                    const int q = block.permutation(fi, block.pixelIndex(x, y));
                    ASSERT_EQ(q, t.permutationOf(x, y, first + fi)) << x << "," << y << " frame " << first + fi;
                    ASSERT_EQ(block.permutation(fi, block.pixelIndex(x, y)), q);  // kept
                    differs += q != t.permutationOf(x - rect.x0, y - rect.y0, fi);
                    ++asked;
                }
        }
    }
    EXPECT_GT(asked, 2 * 64);
    EXPECT_GT(differs, asked / 2);  // the buckets' pixels and frames are not the first block's
}

// A record starts as the still layer and then differs from it; a dense block has one for every
// pixel of every frame.
TEST(ImageBlock, RecordsCopyTheStillLayerAndDenseBlocksHaveThemAll) {
    const PatternTable t(SamplePattern{2, 1, 0});
    ImageBlock block;
    block.reset({0, 0, 1, 0}, 0, 2, t, false);
    block.still(1)[0] = {3.0f, {1, 0, 0}, 7};
    SampleHit* r = block.makeRecord(1, 1);
    EXPECT_EQ(r[0].z, 3.0f);
    r[1] = {2.0f, {0, 1, 0}, 8};
    EXPECT_EQ(block.hits(1, 1)[1].id, 8u);
    EXPECT_EQ(block.hits(0, 1)[1].id, kNoPrimitive);  // frame 0 still sees the still layer
    EXPECT_EQ(block.recordCount(), 1u);
    block.reset({0, 0, 1, 0}, 0, 2, t, true);
    EXPECT_EQ(block.recordCount(), 4u);
    for (int fi = 0; fi < 2; ++fi)
        for (size_t i = 0; i < 2; ++i) {
            ASSERT_TRUE(block.hasRecord(fi, i));
            EXPECT_TRUE(std::isinf(block.record(fi, i)[0].z));
        }
}

// A block is reused from bucket to bucket: a new bucket has none of the last one's records or
// farthest bounds, in any frame (each frame's row of them is written when the frame first needs
// it), and a frame given a record has it for that pixel only.
TEST(ImageBlock, ANewBucketForgetsTheLastOnesRecordsAndBounds) {
    const PatternTable t(SamplePattern{2, 1, 0});
    ImageBlock block;
    block.reset({0, 0, 1, 0}, 0, 3, t, true);  // dense: every frame has a record of every pixel
    block.record(2, 1)[0].z = 3.0f;
    block.reset({0, 0, 1, 0}, 0, 3, t, false);
    block.makeRecord(1, 0)[0].z = 2.0f;
    block.farthestBound(1, 0) = 5.0f;
    block.farthestBound(2, 1) = 4.0f;
    block.reset({0, 0, 1, 0}, 3, 3, t, false);
    EXPECT_EQ(block.recordCount(), 0u);
    for (int fi = 0; fi < 3; ++fi)
        for (size_t i = 0; i < 2; ++i) {
            EXPECT_FALSE(block.hasRecord(fi, i)) << fi << " " << i;
            EXPECT_EQ(block.record(fi, i), nullptr);
            EXPECT_TRUE(std::isinf(block.hits(fi, i)[0].z));
            EXPECT_EQ(block.farthestBound(fi, i), -std::numeric_limits<float>::infinity()) << fi << " " << i;
        }
    SampleHit* r = block.makeRecord(2, 1);
    EXPECT_TRUE(std::isinf(r[0].z));  // a copy of this bucket's still layer
    EXPECT_TRUE(block.hasRecord(2, 1));
    EXPECT_FALSE(block.hasRecord(2, 0));
    EXPECT_FALSE(block.hasRecord(1, 0));
    EXPECT_EQ(block.recordCount(), 1u);
}

}  // namespace
}  // namespace streyes
