// The memory estimate (memory.h) against what a render really holds, and the budget's effect.
#include <gtest/gtest.h>

#include <unistd.h>

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

// The process's peak resident set (what RenderStats::peakMemoryBytes reads) starts again from
// what it holds now, so that a render is measured alone, whatever ran in this process before.
bool resetPeakResident() {
    std::ofstream f("/proc/self/clear_refs");
    return bool(f << "5" << std::flush);
}

// One bucket (a 32 x 32 tile, box filter: no guard band) over 24 frames with 64 samples per pixel:
// a sample block of 1.6 M samples, about 70 MiB.
const char* kHeader = R"(Format 32 32 1
PixelSamples 8 8
PixelFilter "box" 1 1
Option "streyes" "int frames" [1 24]
WorldBegin
Surface "constant"
)";
const char* kSquare = "Patch \"bilinear\" \"P\" [-0.5 -0.5 1  0.5 -0.5 1  -0.5 0.5 1  0.5 0.5 1]\nWorldEnd\n";
// The same square moving across the image: its pieces are cut wherever the frame block ends.
const char* kMovingSquare = "MotionBegin [1 24]\nTranslate -0.4 0 0\nTranslate 0.4 0 0\nMotionEnd\n"
                            "Patch \"bilinear\" \"P\" [-0.3 -0.3 1  0.3 -0.3 1  -0.3 0.3 1  0.3 0.3 1]\nWorldEnd\n";

// What a render's resident memory grows by, against what its estimate counts (all but the
// program's libraries, which this test process does not load): within 10% where every frame
// keeps its own samples (`exact`: dense blocks, as with shadows); otherwise the estimate counts a
// record of every sample of every frame, made only where something moves, and is a bound.
void expectEstimateMatchesGrowth(const std::string& rib, bool exact) {
    // The address sanitizer pads every allocation and keeps freed memory in quarantine (hundreds
    // of MiB): resident growth under it says nothing about the renderer's. The release suite checks.
    if (test::kAddressSanitizer) GTEST_SKIP() << "resident memory is not the renderer's under the address sanitizer";
    Log log;
    Scene scene = parseRibString(rib, "memory.rib", log);
    RenderOptions o;
    o.threads = 1;
    o.bucketSize = 32;  // the block sizes below are for 32-pixel buckets
    o.gridCacheBytes = 0;  // counted at its capacity, a bound (grid_cache_test.cpp holds it)
    ASSERT_TRUE(resetPeakResident()) << "cannot reset the peak resident set (/proc/self/clear_refs)";
    const uint64_t before = residentBytes();
    Renderer renderer(scene, o, log);
    RenderStats stats = renderer.render([](const FrameImage&) {});
    ASSERT_EQ(stats.frameBlock, 24);
    const double counted = double(stats.memoryEstimateBytes - stats.memoryProgramBytes);
    const double grown = double(stats.peakMemoryBytes) - double(before);
    if (exact) {
        EXPECT_GT(grown, 0.9 * counted) << "estimated " << counted << " bytes";
    }
    EXPECT_LT(grown, 1.1 * counted) << "estimated " << counted << " bytes";
    testing::Test::RecordProperty("estimated_bytes", std::to_string(uint64_t(counted)));
    testing::Test::RecordProperty("resident_growth_bytes", std::to_string(uint64_t(grown)));
}

TEST(MemoryEstimate, BoundsWhatTheRenderHolds) {
    expectEstimateMatchesGrowth(std::string(kHeader) + kSquare, false);
    expectEstimateMatchesGrowth(std::string(kHeader) + kMovingSquare, false);
}

// With a light that casts shadows, every sample keeps that light's contribution for its shadow
// ray (12 bytes a sample: a fifth of the sample block here), and the ray tracer holds its bodies
// and hierarchy (a 60 x 60 mesh of quads: 3,600 bodies).
TEST(MemoryEstimate, MatchesWhatARenderWithShadowsHolds) {
    std::string mesh = "PointsPolygons [";
    for (int i = 0; i < 3600; ++i) mesh += "4 ";
    mesh += "] [";
    for (int j = 0; j < 60; ++j)
        for (int i = 0; i < 60; ++i) {
            const int a = j * 61 + i;
            mesh += std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 62) + " " +
                    std::to_string(a + 61) + " ";
        }
    mesh += "] \"P\" [";
    for (int j = 0; j <= 60; ++j)
        for (int i = 0; i <= 60; ++i)
            mesh += std::to_string(-0.6 + 0.02 * i) + " " + std::to_string(-0.6 + 0.02 * j) + " 2 ";
    mesh += "]\n";
    // Shadows tested per sample keep every frame's samples (dense): the estimate is exact. At the
    // shading rate (the default) still grids whose shadows fold into their colour share the still
    // layer (docs/ARCHITECTURE.md, "Shadows"): the estimate is a bound.
    const std::string world = "Attribute \"light\" \"shadows\" \"on\"\nLightSource \"distantlight\" 1\n"
                              "Surface \"matte\"\n" + mesh + kSquare;
    std::string header = kHeader;
    header.insert(header.find("WorldBegin"), "Option \"trace\" \"string shadowtest\" [\"sample\"]\n");
    expectEstimateMatchesGrowth(header + world, true);
    expectEstimateMatchesGrowth(std::string(kHeader) + world, false);
}

// A budget that fits only a few frames at a time shrinks the frame block, as a smaller machine's
// default budget does: the pixels stay the same, bit for bit, whatever the thread count and
// whatever the machine's memory (they depended on it in their last bits when moving bodies were
// cut at block boundaries).
TEST(MemoryEstimate, BudgetShrinksTheFrameBlock) {
    const std::string rib = std::string(kHeader) + kMovingSquare;
    test::RenderResult roomy = test::renderRib(rib, [] {
        RenderOptions o;
        o.bucketSize = 32;
        return o;
    }());
    // The square's body holds what the roomy render says its bodies hold.
    MemoryShape shape{32, 32, 64, 32, 0, 0, true, roomy.stats.memoryBodiesBytes, usesOcclusion(RenderOptions{}.algorithm)};
    RenderOptions tight;
    tight.bucketSize = 32;  // as the shape says
    tight.maxMemoryBytes = estimateMemory(shape, 6, 1).total();
    RenderOptions tightTwo = tight;
    tight.threads = 1;
    tightTwo.threads = 2;
    test::RenderResult a = test::renderRib(rib, tight), b = test::renderRib(rib, tightTwo);
    EXPECT_EQ(a.stats.frameBlock, 6);
    EXPECT_EQ(b.stats.frameBlock, 6);
    EXPECT_LE(a.stats.memoryEstimateBytes, tight.maxMemoryBytes);
    EXPECT_EQ(b.stats.threads, 1);  // the second worker does not fit
    EXPECT_EQ(roomy.stats.frameBlock, 24);
    EXPECT_TRUE(test::identicalPixels(a, b));
    EXPECT_TRUE(test::identicalPixels(a, roomy));
}

// Ray tracing (here for shadows) expands every procedural before anything renders; a forest
// expanded whole that would not fit the budget is refused while it expands, naming the budget,
// not left to run the machine out of memory.
TEST(MemoryEstimate, ExpandingProceduralsForRayTracingStaysInTheBudget) {
    Log log;
    Scene scene = parseRibFile(test::sourcePath("scenes/forest-small.rib"), log);
    scene.lights[1].castsShadows = true;  // the sun
    RenderOptions o;
    o.xres = 64;
    o.yres = 36;
    o.hasFrames = true;
    o.firstFrame = o.lastFrame = 1;
    o.maxMemoryBytes = uint64_t(52) << 20;  // the program's 40 MiB, and 12 MiB for everything else
    try {
        test::renderScene(scene, o);
        FAIL() << "the forest's bodies do not fit 12 MiB";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("memory budget of 52 MiB"), std::string::npos) << e.report();
    }
    // That the whole forest does expand within a roomy budget (and makes more bodies than 12 MiB
    // holds): the release suite checks; under the address sanitizer it takes three minutes.
    if (test::kAddressSanitizer) return;
    o.maxMemoryBytes = uint64_t(4) << 30;
    EXPECT_GT(test::renderScene(scene, o).stats.memoryBodiesBytes, uint64_t(12) << 20);
}

}  // namespace
}  // namespace streyes
