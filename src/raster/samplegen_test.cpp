#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "raster/image_block.h"

namespace streyes {
namespace {

TEST(SampleGen, StratifiedInSpaceAndTime) {
    SamplePattern p{4, 3, 42};
    std::vector<SamplePosition> s(12);
    std::vector<uint16_t> slice(12);
    generatePixelSamples(10, 20, 5, p, s.data(), slice.data());
    std::set<int> strataOfSlices;
    for (int j = 0; j < 12; ++j) {
        // Sample j lies in (x, y) stratum (j % 4, j / 4) of pixel (10, 20).
        EXPECT_EQ(int((s[size_t(j)].x - 10) * 4), j % 4);
        EXPECT_EQ(int((s[size_t(j)].y - 20) * 3), j / 4);
    }
    for (int k = 0; k < 12; ++k) {
        const SamplePosition& q = s[slice[size_t(k)]];
        EXPECT_GE(q.tf, float(k) / 12);  // slice k's sample lies in time stratum k
        EXPECT_LT(q.tf, float(k + 1) / 12);
        strataOfSlices.insert(slice[size_t(k)]);
    }
    EXPECT_EQ(strataOfSlices.size(), 12u);  // a permutation: one sample per slice
}

TEST(SampleGen, PureFunctionOfPixelFrameAndSeed) {
    SamplePattern p{2, 2, 1};
    std::vector<SamplePosition> a(4), b(4), c(4), d(4);
    std::vector<uint16_t> k(4);
    generatePixelSamples(3, 4, 7, p, a.data(), k.data());
    generatePixelSamples(3, 4, 7, p, b.data(), k.data());
    generatePixelSamples(3, 4, 8, p, c.data(), k.data());
    p.seed = 2;
    generatePixelSamples(3, 4, 7, p, d.data(), k.data());
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(a[size_t(i)].x, b[size_t(i)].x);
        EXPECT_EQ(a[size_t(i)].tf, b[size_t(i)].tf);
    }
    EXPECT_NE(a[0].x, c[0].x);
    EXPECT_NE(a[0].x, d[0].x);
}

TEST(SampleGen, TimeIsDecorrelatedFromPosition) {
    // Correlation between a sample's x within the pixel and its time, over many pixels.
    SamplePattern p{4, 4, 0};
    std::vector<SamplePosition> s(16);
    std::vector<uint16_t> k(16);
    double sx = 0, st = 0, sxx = 0, stt = 0, sxt = 0;
    int n = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            generatePixelSamples(x, y, 0, p, s.data(), k.data());
            for (const SamplePosition& q : s) {
                double u = q.x - x, t = q.tf;
                sx += u, st += t, sxx += u * u, stt += t * t, sxt += u * t;
                ++n;
            }
        }
    double cov = sxt / n - (sx / n) * (st / n);
    double corr = cov / std::sqrt((sxx / n - (sx / n) * (sx / n)) * (stt / n - (st / n) * (st / n)));
    EXPECT_LT(std::fabs(corr), 0.02);
}

TEST(ImageBlock, EachSliceHoldsOneSamplePerPixel) {
    ImageBlock block;
    block.reset({4, 6, 9, 8}, 10, 3, SamplePattern{2, 2, 0});
    EXPECT_EQ(block.sampleCount(), size_t(6 * 3 * 3 * 4));
    for (int fi = 0; fi < 3; ++fi)
        for (int y = 6; y <= 8; ++y)
            for (int x = 4; x <= 9; ++x) {
                std::set<size_t> seen;
                for (int k = 0; k < 4; ++k) {
                    size_t i = block.sliceIndex(fi, k, x, y);
                    seen.insert(i);
                    const SamplePosition& s = block.positions()[i];
                    EXPECT_EQ(int(std::floor(s.x)), x);
                    EXPECT_EQ(int(std::floor(s.y)), y);
                    EXPECT_EQ(int(s.tf * 4), k);
                    EXPECT_TRUE(std::isinf(block.hits()[i].z));
                }
                EXPECT_EQ(seen.size(), 4u);
                EXPECT_EQ(*seen.begin(), block.pixelOffset(x, y) + size_t(fi) * 4);
            }
}

}  // namespace
}  // namespace streyes
