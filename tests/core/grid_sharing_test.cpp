// Grids shared between buckets (src/render/grid_cache.h): a piece whose bound reaches several
// buckets is diced and shaded once. The pixels are those of every bucket dicing its own, bit for
// bit, whatever the cache's room, the threads or the bucket size; and a moving surface costs at
// most twice the micropolygons of the same surface still (issue 12; it was 3 to 3.5 times).
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "test_util.h"

namespace streyes {
namespace {

RenderOptions sharing(uint64_t bytes, int threads = 0, int bucket = 0, Algorithm a = Algorithm::SpacetimeOcclusion) {
    RenderOptions o = test::optionsFor(a);
    o.gridCacheBytes = bytes;
    o.threads = threads;
    o.bucketSize = bucket;
    return o;
}

// The dicing benchmark's scenes (bench/dicestats/scenes), at one sample a pixel: micropolygons do
// not depend on the samples.
std::string dicestats(const std::string& name) { return "bench/dicestats/scenes/" + name + ".rib"; }

TEST(GridSharing, PixelsAreThoseOfEveryBucketDicingItsOwn) {
    // Scenes, two of their frames (one for a single-frame scene), and whether their grids reach
    // several buckets (cube_spin_fast and time_keys_blur: bodies with many motion keys, diced key
    // by key, are not shared; they are 64 and 40 pixels wide). The scenes' Format, halved under the
    // sanitizers where it is more than 64 pixels wide (0: the scene's own).
    struct Case {
        const char* scene;
        int first, last;
        bool shares;
        int width, height;
    };
    const Case cases[] = {{"bench/dicestats/scenes/sphere_camera_moving.rib", 0, 0, true, 480, 360},
                          {"bench/dicestats/scenes/subd_cube_moving.rib", 0, 0, true, 480, 360},
                          {"scenes/hard/cube_spin_fast.rib", 1, 2, false, 0, 0},
                          {"scenes/hard/time_keys_blur.rib", 2, 3, false, 0, 0},
                          {"scenes/dof.rib", 18, 19, true, 240, 160},
                          {"scenes/transparency.rib", 1, 2, true, 480, 270},
                          {"scenes/quadrics.rib", 1, 2, true, 640, 360}};
    for (const auto& [scene, first, last, shares, width, height] : cases) {
        SCOPED_TRACE(scene);
        if (test::slowUnderSanitizers(scene)) continue;
        auto framed = [&, first = first, last = last, width = width, height = height](RenderOptions o) {
            o.hasFrames = true;
            o.firstFrame = first;
            o.lastFrame = last;
            o.samples = 4;
            test::halfResolutionUnderSanitizers(o, width, height);
            return o;
        };
        const test::RenderResult ref = test::renderFile(test::sourcePath(scene), framed(sharing(0)));
        ASSERT_FALSE(ref.frames.empty());
        EXPECT_EQ(ref.stats.counters.gridsShared, 0u);
        for (int bucket : {0, 32}) {
            for (const RenderOptions& o : {sharing(128 << 20, 1, bucket), sharing(128 << 20, 2, bucket), sharing(4 << 10, 2, bucket)}) {
                const test::RenderResult r = test::renderFile(test::sourcePath(scene), framed(o));
                if (shares && o.gridCacheBytes > (1 << 20)) {
                    EXPECT_GT(r.stats.counters.gridsShared, 0u);
                }
                EXPECT_TRUE(test::identicalPixels(ref, r)) << "threads " << o.threads << ", bucket " << o.bucketSize
                                                             << ", cache " << o.gridCacheBytes;
            }
        }
    }
}

// Every bucket either dices a grid or takes it from the one that did: with room to spare the
// grids diced and taken add up to what the buckets dice on their own, fewer are diced (grids
// reaching three buckets or more are diced once; those on the border of two, twice, against once
// by one bucket spanning the image), and the counts do not depend on threads.
TEST(GridSharing, EachGridIsDicedOnceAndTakenByTheOtherBuckets) {
    const std::string scene = test::sourcePath(dicestats("sphere_camera_moving"));
    auto run = [&](uint64_t bytes, int threads, int bucket) {
        RenderOptions o = sharing(bytes, threads, bucket, Algorithm::Spacetime);
        o.samples = 1;
        return test::renderFile(scene, o).stats.counters;
    };
    const RenderCounters own = run(0, 1, 0), shared1 = run(128 << 20, 1, 0), shared2 = run(128 << 20, 2, 0),
                         whole = run(0, 1, 512);
    ASSERT_GT(shared1.gridsShared, 0u);
    EXPECT_EQ(shared1.gridsEvicted, 0u);
    EXPECT_EQ(shared1.gridsDiced + shared1.gridsShared, own.gridsDiced);
    EXPECT_EQ(shared1.micropolygons + shared1.micropolygonsShared, own.micropolygons);
    EXPECT_LT(shared1.gridsDiced, own.gridsDiced);
    EXPECT_GE(shared1.gridsDiced, whole.gridsDiced);
    EXPECT_LT(shared1.micropolygons, 2 * whole.micropolygons);
    EXPECT_EQ(test::differingCounts(shared1, shared2), std::vector<std::string>{});

    // A cache too small for one grid: every bucket dices its own again, and counts the evictions.
    const RenderCounters cramped = run(1024, 1, 0);
    EXPECT_EQ(cramped.gridsDiced, own.gridsDiced);
    EXPECT_GT(cramped.gridsEvicted, 0u);
}

// An instance is expanded by each bucket for itself (InstanceGenerator keeps no children), the
// same children every time: they are keyed by the instance and their place, so their grids are
// shared too. A sphere instanced twice, both copies moving across the frame.
TEST(GridSharing, InstancesExpandedByEachBucketShareTheirGrids) {
    const std::string rib = R"(Format 320 240 1
PixelSamples 2 2
Shutter 0 1
Projection "perspective" "fov" [40]
Translate 0 0 6
WorldBegin
LightSource "distantlight" 1 "from" [0 0 -1] "to" [0 0 0]
Surface "matte"
ObjectBegin 1
Sphere 1 -1 1 360
ObjectEnd
AttributeBegin
MotionBegin [0 1]
Translate -1.5 0.5 0
Translate 0.5 0.5 0
MotionEnd
ObjectInstance 1
AttributeEnd
AttributeBegin
Translate 0 -1 1
Scale 0.7 0.7 0.7
ObjectInstance 1
AttributeEnd
WorldEnd
)";
    RenderOptions own;
    own.gridCacheBytes = 0;
    const test::RenderResult ref = test::renderRib(rib, own);
    ASSERT_GT(ref.stats.counters.proceduralsExpanded, 2u);  // expanded in several buckets
    for (int threads : {1, 2}) {
        RenderOptions o;
        o.threads = threads;
        const test::RenderResult r = test::renderRib(rib, o);
        // (Seen to fail once in about fifteen full runs on 2026-11-27, not reproduced in 450 runs
        // of this test alone or under load: the messages say which part, and by how much.)
        EXPECT_TRUE(test::identicalPixels(ref, r))
            << threads << " threads: largest difference " << test::maxAbsDifference(ref, r);
        EXPECT_GT(r.stats.counters.gridsShared, 0u) << threads << " threads";
        EXPECT_EQ(r.stats.counters.gridsDiced + r.stats.counters.gridsShared, ref.stats.counters.gridsDiced)
            << threads << " threads: " << r.stats.counters.gridsDiced << " diced, " << r.stats.counters.gridsShared
            << " shared, " << r.stats.counters.gridsEvicted << " evicted";
    }
}

// Issue 12's measure: the sphere under a camera moving 80 pixels in an exposure, and a
// subdivision cube moving as far, against the same surfaces still (480 x 360, ShadingRate 1).
TEST(GridSharing, AMovingSurfaceCostsAtMostTwiceTheMicropolygonsOfItStill) {
    auto micropolygons = [](const std::string& name) {
        RenderOptions o;
        o.samples = 1;
        return double(test::renderFile(test::sourcePath(dicestats(name)), o).stats.counters.micropolygons);
    };
    const double sphere = micropolygons("sphere_camera_moving") / micropolygons("sphere");
    const double cube = micropolygons("subd_cube_moving") / micropolygons("subd_cube");
    EXPECT_GT(sphere, 1.0);
    EXPECT_LE(sphere, 2.0);
    EXPECT_GT(cube, 1.0);
    EXPECT_LE(cube, 2.0);
    testing::Test::RecordProperty("sphere_ratio", std::to_string(sphere));
    testing::Test::RecordProperty("cube_ratio", std::to_string(cube));
}

}  // namespace
}  // namespace streyes
