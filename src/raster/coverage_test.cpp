#include "raster/coverage.h"

#include <gtest/gtest.h>

#include <limits>

namespace streyes {
namespace {

TEST(Occlusion, CoverageNeedsEverySampleHitNearerThanTheBoundary) {
    const PatternTable patterns(SamplePattern{2, 1, 0});
    ImageBlock block;
    block.reset({0, 0, 2, 0}, 0, 2, patterns, false);  // 3 pixels, 2 frames, 2 samples
    auto hit = [&](int x, int fi, int k, float z) {
        SampleHit* r = block.record(fi, block.pixelIndex(x, 0));
        if (!r) r = block.makeRecord(fi, block.pixelIndex(x, 0));
        r[k].z = z;
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

// The still layer covers a pixel in every frame that has no record of it; a frame's record
// decides for that frame alone.
TEST(Occlusion, StillLayerCoversEveryFrameWithoutARecord) {
    const PatternTable patterns(SamplePattern{2, 1, 0});
    ImageBlock block;
    block.reset({0, 0, 0, 0}, 0, 3, patterns, false);  // 1 pixel, 3 frames
    for (int k = 0; k < 2; ++k) block.still(0)[k] = {4.0f, {1, 1, 1}, 1};
    SampleHit* r = block.makeRecord(1, 0);  // frame 1: something nearer, then something missing
    r[1] = kNoHit;
    std::vector<uint8_t> coverage;
    EXPECT_EQ(updateCoverage(block, 5.0f, coverage), 2u);
    EXPECT_EQ(coverage, (std::vector<uint8_t>{1, 0, 1}));
}

// The farthest hit of each cell scanned: +inf while a sample has no opaque hit; cells covered
// before keep what they had (stale is conservative: depths only decrease). Writes are touched
// and the marks cleared after each measure, as the samplers and the bucket do.
TEST(Occlusion, FarthestHitPerCell) {
    const PatternTable patterns(SamplePattern{2, 1, 0});
    ImageBlock block;
    block.reset({0, 0, 1, 0}, 0, 2, patterns, false);  // 2 pixels, 2 frames
    for (int k = 0; k < 2; ++k) block.still(0)[k] = {4.0f + float(k), {1, 1, 1}, 1};
    block.still(1)[0] = {3.0f, {1, 1, 1}, 1};  // pixel 1: one sample only
    SampleHit* r = block.makeRecord(1, 0);          // frame 1 of pixel 0: nearer
    r[1].z = 2.0f;
    block.touch(0), block.touch(1);  // what the samplers mark as they write
    std::vector<uint8_t> coverage;
    std::vector<float> farthest;
    const float inf = std::numeric_limits<float>::infinity();
    auto measure = [&](float boundary) {
        const uint64_t added = updateCoverage(block, boundary, coverage, -1, &farthest);
        block.untouchAll();
        return added;
    };
    EXPECT_EQ(measure(4.5f), 1u);
    EXPECT_EQ(farthest, (std::vector<float>{5.0f, inf, 4.0f, inf}));
    block.still(1)[1].z = std::numeric_limits<float>::quiet_NaN();  // never taken for a depth
    block.touch(1);
    measure(4.5f);
    EXPECT_EQ(farthest[1], inf);
    block.still(1)[1].z = 3.5f;
    block.touch(1);
    EXPECT_EQ(measure(4.5f), 2u);
    EXPECT_EQ(farthest, (std::vector<float>{5.0f, 3.5f, 4.0f, 3.5f}));
}

// A pixel nothing was written to since it was measured keeps that measure: it is not read again,
// and it is covered once the boundary passes it. A write left untouched leaves the measure a
// looser bound (the cell is not covered), never a tighter one.
TEST(Occlusion, UntouchedPixelsKeepTheirMeasure) {
    const PatternTable patterns(SamplePattern{2, 1, 0});
    ImageBlock block;
    block.reset({0, 0, 1, 0}, 0, 1, patterns, false);  // 2 pixels, 1 frame
    for (int k = 0; k < 2; ++k) block.still(0)[k] = {4.0f, {1, 1, 1}, 1};
    block.still(1)[0] = {3.0f, {1, 1, 1}, 1};
    block.touch(0), block.touch(1);  // what the samplers mark as they write
    std::vector<uint8_t> coverage;
    std::vector<float> farthest;
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(updateCoverage(block, 3.5f, coverage, -1, &farthest), 0u);
    EXPECT_EQ(farthest, (std::vector<float>{4.0f, inf}));
    block.untouchAll();
    EXPECT_EQ(updateCoverage(block, 4.5f, coverage, -1, &farthest), 1u);  // pixel 0 from its measure
    EXPECT_EQ(coverage, (std::vector<uint8_t>{1, 0}));
    block.still(1)[1] = {3.0f, {1, 1, 1}, 1};  // written but not touched: not seen
    EXPECT_EQ(updateCoverage(block, 4.5f, coverage, -1, &farthest), 0u);
    EXPECT_EQ(farthest[1], inf);
    block.touch(1);
    EXPECT_EQ(updateCoverage(block, 4.5f, coverage, -1, &farthest), 1u);
    EXPECT_EQ(farthest[1], 3.0f);
    EXPECT_EQ(coverage, (std::vector<uint8_t>{1, 1}));
}

}  // namespace
}  // namespace streyes
