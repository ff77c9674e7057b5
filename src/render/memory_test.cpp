#include "streyes/memory.h"

#include <gtest/gtest.h>

#include "raster/image_block.h"
#include "streyes/error.h"

namespace streyes {
namespace {

TEST(Memory, ByteSizes) {
    uint64_t b = 0;
    EXPECT_TRUE(parseByteSize("4096", &b));
    EXPECT_EQ(b, 4096u);
    EXPECT_TRUE(parseByteSize("512M", &b));
    EXPECT_EQ(b, uint64_t(512) << 20);
    EXPECT_TRUE(parseByteSize("8g", &b));
    EXPECT_EQ(b, uint64_t(8) << 30);
    EXPECT_TRUE(parseByteSize("1.5GiB", &b));
    EXPECT_EQ(b, uint64_t(3) << 29);
    EXPECT_TRUE(parseByteSize("2KB", &b));
    EXPECT_EQ(b, 2048u);
    for (const char* bad : {"", "0", "-1G", "G", "8X", "8 G", "1e3", "8GG", "99999999999T"})
        EXPECT_FALSE(parseByteSize(bad, &b)) << bad;
    EXPECT_EQ(formatBytes(512), "512 bytes");
    EXPECT_EQ(formatBytes(uint64_t(3) << 29), "1.50 GiB");
    EXPECT_EQ(formatBytes(uint64_t(640) << 20), "640 MiB");
}

const MemoryShape kHd{1920, 1080, 16, 32, 1, 1, true, 1000 * 256};

TEST(Memory, EstimateCountsImagesAndSamplesPerWorker) {
    const MemoryEstimate e = estimateMemory(kHd, 10, 3);
    // RGBA + Z float: the 10 frames, the tiles' still pixels, the frame being written.
    EXPECT_EQ(e.frameImages, uint64_t(12) * 1920 * 1080 * 20);
    // A bucket of 34 x 34 pixels (tile and guard band): an 8-byte permutation key and its flag, and 16 samples
    // (position, still-layer hit, the moving sampler's slot of 6 floats and an index, A R G B of
    // the still layer and of a frame to resolve), for each of 10 frames a slot, a permutation, a
    // depth bound and at most a record of every sample, and what resolving keeps (32 x 32 pixels x
    // 6 floats).
    const uint64_t perPixel = 9 + 16 * (8 + 24 + 26 + 2 * 16) + 10 * (9 + 16 * 24);
    EXPECT_EQ(e.perWorker, uint64_t(34 * 34) * perPixel + uint64_t(32 * 32) * 24);
    // With occlusion culling, a coverage byte and a 32-bit table entry per pixel and frame more.
    MemoryShape culled = kHd;
    culled.occlusion = true;
    EXPECT_EQ(estimateMemory(culled, 10, 3).perWorker, e.perWorker + uint64_t(34 * 34) * 10 * 5);
    EXPECT_EQ(e.total(), e.baseline + e.scene + e.frameImages + 3 * e.perWorker + e.writer);
    // Per-frame buckets (Algorithm C) hold one frame whatever the block.
    MemoryShape frames = kHd;
    frames.spacetime = false;
    EXPECT_EQ(estimateMemory(frames, 10, 1).perWorker, estimateMemory(frames, 1, 1).perWorker);
    EXPECT_EQ(estimateMemory(frames, 10, 1).frameImages, uint64_t(11) * 1920 * 1080 * 20);  // no still pixels
    EXPECT_EQ(estimateMemory(kHd, 1, 1).frameImages, uint64_t(2) * 1920 * 1080 * 20);
}

TEST(Memory, OutputVariablesAddTheirFloatsPerSampleAndPixel) {
    // N and P: 6 floats beside every still-layer sample, every record sample and every frame pixel.
    MemoryShape aov = kHd;
    aov.aovFloats = 6;
    const MemoryEstimate e = estimateMemory(kHd, 10, 3), a = estimateMemory(aov, 10, 3);
    EXPECT_EQ(a.frameImages - e.frameImages, uint64_t(12) * 1920 * 1080 * 24);
    EXPECT_EQ(a.perWorker - e.perWorker, uint64_t(34 * 34) * (16 * 24 + 10 * 16 * 24));
    EXPECT_GT(a.writer, e.writer);
}

TEST(Memory, PlanShrinksTheBlockThenTheWorkers) {
    // Plenty: the block and the threads asked for.
    MemoryEstimate roomy = planMemory(kHd, 64, 8, uint64_t(64) << 30);
    EXPECT_EQ(roomy.frameBlock, 64);
    EXPECT_EQ(roomy.workers, 8);
    // A budget that fits 20 frames with one worker, not 21: the block is 20, whatever the threads,
    // and the workers are as many as fit beside it.
    const uint64_t budget = estimateMemory(kHd, 20, 1).total() + 1000;
    ASSERT_LT(budget, estimateMemory(kHd, 21, 1).total());
    for (int threads : {1, 2, 8}) {
        MemoryEstimate e = planMemory(kHd, 64, threads, budget);
        EXPECT_EQ(e.frameBlock, 20) << threads;
        EXPECT_EQ(e.workers, 1);
        EXPECT_LE(e.total(), budget);
    }
    const uint64_t twoWorkers = estimateMemory(kHd, 20, 2).total();
    EXPECT_EQ(planMemory(kHd, 20, 8, twoWorkers).workers, 2);
    EXPECT_EQ(planMemory(kHd, 20, 8, twoWorkers - 1).workers, 1);
}

TEST(Memory, RefusesWhatDoesNotFitOneFrameAtATime) {
    MemoryShape huge{65536, 65536, 16, 32, 1, 1, true, 10 * 256};
    const uint64_t need = estimateMemory(huge, 1, 1).total();
    try {
        planMemory(huge, 64, 8, uint64_t(16) << 30);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("needs about " + formatBytes(need)), std::string::npos) << m;
        EXPECT_NE(m.find("frame images 160 GiB (1 frame of 65536x65536 and one being written)"), std::string::npos) << m;
        EXPECT_NE(m.find("budget of 16.0 GiB"), std::string::npos) << m;
        EXPECT_NE(m.find("lower --res or --samples"), std::string::npos) << m;
    }
    EXPECT_EQ(planMemory(huge, 64, 8, need).frameBlock, 1);  // exactly enough is enough
}

TEST(Memory, DefaultBudgetIsAShareOfTheMachine) {
    const uint64_t budget = defaultMemoryBudget();
    EXPECT_GT(budget, uint64_t(64) << 20);
    EXPECT_LE(budget, physicalMemoryBytes() / 4 * 3);
}

}  // namespace
}  // namespace streyes
