#include "raster/coverage.h"

#include <gtest/gtest.h>

namespace streyes {
namespace {

TEST(Occlusion, CoverageNeedsEverySampleHitNearerThanTheBoundary) {
    ImageBlock block;
    block.reset({0, 0, 2, 0}, 0, 2, SamplePattern{2, 1, 0});  // 3 pixels, 2 frames, 2 samples
    auto hit = [&](int x, int fi, int k, float z) {
        SampleHit& s = block.hits()[block.pixelOffset(x, 0) + size_t(fi) * 2 + size_t(k)];
        s.z = z;
        s.a = 1;
    };
    hit(0, 0, 0, 5), hit(0, 0, 1, 6);  // pixel 0 frame 0: both samples hit
    hit(1, 0, 0, 5);                   // pixel 1 frame 0: one sample only
    hit(2, 1, 0, 5), hit(2, 1, 1, 7);  // pixel 2 frame 1: one sample exactly at the boundary
    std::vector<uint8_t> coverage;
    EXPECT_EQ(updateCoverage(block, 7.0f, coverage), 1u);
    EXPECT_EQ(coverage, (std::vector<uint8_t>{1, 0, 0, 0, 0, 0}));
    EXPECT_EQ(updateCoverage(block, 7.5f, coverage), 1u);  // the boundary moved past z = 7
    EXPECT_EQ(coverage, (std::vector<uint8_t>{1, 0, 0, 0, 0, 1}));
    EXPECT_EQ(updateCoverage(block, 8.0f, coverage), 0u);  // nothing new
}

}  // namespace
}  // namespace streyes
