#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "streyes/image_block.h"

namespace streyes {
namespace {

TEST(SampleGen, StratifiedInSpaceAndTime) {
    SamplePattern p{4, 3, 42};
    std::vector<Sample> s(12);
    generatePixelSamples(10, 20, 5, p, s.data());
    std::set<std::pair<int, int>> strata;
    for (int k = 0; k < 12; ++k) {
        EXPECT_GE(s[size_t(k)].tf, float(k) / 12);  // slice k holds time stratum k
        EXPECT_LT(s[size_t(k)].tf, float(k + 1) / 12);
        EXPECT_GE(s[size_t(k)].x, 10.0f);
        EXPECT_LT(s[size_t(k)].x, 11.0f);
        EXPECT_GE(s[size_t(k)].y, 20.0f);
        EXPECT_LT(s[size_t(k)].y, 21.0f);
        EXPECT_TRUE(std::isinf(s[size_t(k)].z));
        strata.insert({int((s[size_t(k)].x - 10) * 4), int((s[size_t(k)].y - 20) * 3)});
    }
    EXPECT_EQ(strata.size(), 12u);  // one sample per (x, y) stratum
}

TEST(SampleGen, PureFunctionOfPixelFrameAndSeed) {
    SamplePattern p{2, 2, 1};
    std::vector<Sample> a(4), b(4), c(4), d(4);
    generatePixelSamples(3, 4, 7, p, a.data());
    generatePixelSamples(3, 4, 7, p, b.data());
    generatePixelSamples(3, 4, 8, p, c.data());
    p.seed = 2;
    generatePixelSamples(3, 4, 7, p, d.data());
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(a[size_t(k)].x, b[size_t(k)].x);
        EXPECT_EQ(a[size_t(k)].tf, b[size_t(k)].tf);
    }
    EXPECT_NE(a[0].x, c[0].x);
    EXPECT_NE(a[0].x, d[0].x);
}

TEST(SampleGen, TimeIsDecorrelatedFromPosition) {
    // Correlation between a sample's x within the pixel and its time, over many pixels.
    SamplePattern p{4, 4, 0};
    std::vector<Sample> s(16);
    double sx = 0, st = 0, sxx = 0, stt = 0, sxt = 0;
    int n = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            generatePixelSamples(x, y, 0, p, s.data());
            for (const Sample& q : s) {
                double u = q.x - x, t = q.tf;
                sx += u, st += t, sxx += u * u, stt += t * t, sxt += u * t;
                ++n;
            }
        }
    double cov = sxt / n - (sx / n) * (st / n);
    double corr = cov / std::sqrt((sxx / n - (sx / n) * (sx / n)) * (stt / n - (st / n) * (st / n)));
    EXPECT_LT(std::fabs(corr), 0.02);
}

TEST(ImageBlock, SlicesHoldOneSamplePerPixel) {
    ImageBlock block;
    block.reset({4, 6, 9, 8}, 10, 3, SamplePattern{2, 2, 0});
    EXPECT_EQ(block.sampleCount(), size_t(6 * 3 * 3 * 4));
    for (int fi = 0; fi < 3; ++fi)
        for (int k = 0; k < 4; ++k)
            for (int y = 6; y <= 8; ++y)
                for (int x = 4; x <= 9; ++x) {
                    const Sample& s = block.row(fi, k, y)[x - 4];
                    EXPECT_EQ(int(std::floor(s.x)), x);
                    EXPECT_EQ(int(std::floor(s.y)), y);
                    EXPECT_EQ(int(s.tf * 4), k);
                }
}

}  // namespace
}  // namespace streyes
