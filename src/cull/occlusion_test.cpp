#include "cull/occlusion.h"

#include <gtest/gtest.h>

#include <random>

namespace streyes {
namespace {

uint64_t bruteSum(const std::vector<uint8_t>& c, int w, int h, const CellBlock& b) {
    uint64_t s = 0;
    for (int f = b.f0; f <= b.f1; ++f)
        for (int y = b.y0; y <= b.y1; ++y)
            for (int x = b.x0; x <= b.x1; ++x) s += c[(size_t(f) * size_t(h) + size_t(y)) * size_t(w) + size_t(x)];
    return s;
}

template <typename Count>
void checkAgainstBruteForce(int w, int h, int d, double density, uint32_t seed) {
    std::mt19937 rng(seed);
    std::bernoulli_distribution cell(density);
    std::vector<uint8_t> c(size_t(w) * size_t(h) * size_t(d));
    for (auto& v : c) v = cell(rng) ? 1 : 0;
    SummedVolumeTable<Count> t;
    t.build(c.data(), w, h, d);
    std::uniform_int_distribution<int> X(0, w - 1), Y(0, h - 1), F(0, d - 1);
    for (int q = 0; q < 300; ++q) {
        CellBlock b;
        b.x0 = X(rng), b.x1 = X(rng), b.y0 = Y(rng), b.y1 = Y(rng), b.f0 = F(rng), b.f1 = F(rng);
        if (b.x0 > b.x1) std::swap(b.x0, b.x1);
        if (b.y0 > b.y1) std::swap(b.y0, b.y1);
        if (b.f0 > b.f1) std::swap(b.f0, b.f1);
        ASSERT_EQ(uint64_t(t.sum(b)), bruteSum(c, w, h, b)) << w << "x" << h << "x" << d;
    }
    EXPECT_EQ(uint64_t(t.sum({0, w - 1, 0, h - 1, 0, d - 1})), bruteSum(c, w, h, {0, w - 1, 0, h - 1, 0, d - 1}));
}

TEST(SummedVolumeTable, ExactAgainstBruteForceOnRandomVolumes) {
    checkAgainstBruteForce<uint32_t>(1, 1, 1, 0.5, 1);
    checkAgainstBruteForce<uint32_t>(7, 5, 3, 0.5, 2);
    checkAgainstBruteForce<uint32_t>(33, 17, 9, 0.9, 3);
    checkAgainstBruteForce<uint32_t>(64, 1, 1, 0.3, 4);
    checkAgainstBruteForce<uint32_t>(1, 1, 50, 0.7, 5);
    checkAgainstBruteForce<uint64_t>(20, 12, 6, 0.5, 6);
}

TEST(SummedVolumeTable, OneFrameIsASummedAreaTable) {
    std::vector<uint8_t> c = {1, 0, 1,  //
                              1, 1, 1};
    SummedVolumeTable<uint32_t> sat;
    sat.build(c.data(), 3, 2, 1);
    EXPECT_EQ(sat.sum({0, 2, 0, 1, 0, 0}), 5u);
    EXPECT_EQ(sat.sum({1, 1, 0, 0, 0, 0}), 0u);
    EXPECT_EQ(sat.sum({1, 2, 0, 1, 0, 0}), 3u);
}

TEST(SummedVolumeTable, AllCovered4KVolumeOf64FramesIsExact) {
    const int w = 3840, h = 2160, d = 64;  // 530,841,600 cells: fits 32-bit counts
    std::vector<uint8_t> c(size_t(w) * size_t(h) * size_t(d), 1);
    SummedVolumeTable<uint32_t> t;
    t.build(c.data(), w, h, d);
    EXPECT_EQ(t.sum({w - 1, w - 1, h - 1, h - 1, d - 1, d - 1}), 1u);  // the far corner cell
    EXPECT_EQ(uint64_t(t.sum({0, w - 1, 0, h - 1, 0, d - 1})), uint64_t(w) * h * d);
    CellBlock mid{1000, 1999, 500, 1499, 10, 29};
    EXPECT_EQ(uint64_t(t.sum(mid)), mid.volume());
}

TEST(Occlusion, TheThresholdIsExact) {
    // Dropped when B - A <= epsilon * B, also where epsilon * B has no exact binary form.
    EXPECT_TRUE(occludedWithin(100, 71, 0.29));   // 29 uncovered, 0.29 * 100 = 28.999999999999996 in double
    EXPECT_FALSE(occludedWithin(100, 70, 0.29));  // 30 uncovered
    EXPECT_TRUE(occludedWithin(100, 95, 0.05));
    EXPECT_FALSE(occludedWithin(100, 94, 0.05));
    EXPECT_TRUE(occludedWithin(3, 2, 1.0 / 3.0));
    EXPECT_TRUE(occludedWithin(1000, 1000, 0));   // epsilon 0: only full coverage
    EXPECT_FALSE(occludedWithin(1000, 999, 0));
    EXPECT_FALSE(occludedWithin(uint64_t(1) << 40, (uint64_t(1) << 40) - 1, 0));
}

}  // namespace
}  // namespace streyes
