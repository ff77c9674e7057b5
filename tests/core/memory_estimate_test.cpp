// The memory estimate (memory.h) against what a render really holds, and the budget's effect.
#include <gtest/gtest.h>

#include <fstream>

#include "streyes/memory.h"
#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

uint64_t residentBytes() {
    std::ifstream f("/proc/self/statm");
    uint64_t size = 0, resident = 0;
    f >> size >> resident;
    return resident * uint64_t(sysconf(_SC_PAGE_SIZE));
}

// One bucket (a 32 x 32 tile, box filter: no guard band) over 24 frames with 64 samples per pixel:
// a sample block of 1.6 M samples, about 50 MiB.
const char* kScene = R"(Format 32 32 1
PixelSamples 8 8
PixelFilter "box" 1 1
Option "streyes" "int frames" [1 24]
WorldBegin
Surface "constant"
Patch "bilinear" "P" [-0.5 -0.5 1  0.5 -0.5 1  -0.5 0.5 1  0.5 0.5 1]
WorldEnd
)";

// The images and sample blocks the estimate counts are what the render's resident memory grows
// by, to within 10% (the estimate's program baseline is for the executable's libraries, which
// this test process does not load).
TEST(MemoryEstimate, MatchesWhatTheRenderHolds) {
    Log log;
    Scene scene = parseRibString(kScene, "memory.rib", log);
    RenderOptions o;
    o.threads = 1;
    const uint64_t before = residentBytes();
    Renderer renderer(scene, o, log);
    RenderStats stats = renderer.render([](const FrameImage&) {});
    ASSERT_EQ(stats.frameBlock, 24);
    const MemoryShape shape{32, 32, 64, 32, 0, 0, true, 1, usesOcclusion(RenderOptions{}.algorithm)};
    const MemoryEstimate e = estimateMemory(shape, 24, 1);
    EXPECT_EQ(stats.memoryEstimateBytes, e.total());
    const double counted = double(e.frameImages + e.perWorker), grown = double(stats.peakMemoryBytes - before);
    EXPECT_GT(grown, 0.9 * counted);
    EXPECT_LT(grown, 1.1 * counted);
    RecordProperty("estimated_bytes", std::to_string(uint64_t(counted)));
    RecordProperty("resident_growth_bytes", std::to_string(uint64_t(grown)));
}

// A budget that fits only a few frames at a time shrinks the frame block; the pixels stay the
// same whatever the thread count, and close to the unconstrained render's.
TEST(MemoryEstimate, BudgetShrinksTheFrameBlock) {
    const MemoryShape shape{32, 32, 64, 32, 0, 0, true, 1, usesOcclusion(RenderOptions{}.algorithm)};
    RenderOptions tight;
    tight.maxMemoryBytes = estimateMemory(shape, 6, 1).total();
    RenderOptions tightTwo = tight;
    tight.threads = 1;
    tightTwo.threads = 2;
    test::RenderResult a = test::renderRib(kScene, tight), b = test::renderRib(kScene, tightTwo),
                       roomy = test::renderRib(kScene);
    EXPECT_EQ(a.stats.frameBlock, 6);
    EXPECT_EQ(b.stats.frameBlock, 6);
    EXPECT_LE(a.stats.memoryEstimateBytes, tight.maxMemoryBytes);
    EXPECT_EQ(b.stats.threads, 1);  // the second worker does not fit
    EXPECT_EQ(roomy.stats.frameBlock, 24);
    EXPECT_TRUE(test::identicalPixels(a, b));
    EXPECT_LT(test::meanAbsDifference(a, roomy), 1e-4f);
}

}  // namespace
}  // namespace streyes
