#include "render/grid_cache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <thread>
#include <vector>

#include "cull/view_cull.h"

namespace streyes {
namespace {

// The buckets a bound reaches, counted as the view cull tests them: every bucket of the
// renderer's layout, one by one.
int bruteForceReached(const TileLayout& t, const Bounds3f& r) {
    int n = 0;
    for (int ty = 0; ty * t.tileSize < t.height; ++ty)
        for (int tx = 0; tx * t.tileSize < t.width; ++tx) n += !rasterOutside(r, t.bucketRect(tx, ty));
    return n;
}

// A bucket samples its tile and the guard band around it, within the image.
TEST(GridCache, BucketsSampleTheirTileAndItsGuardBandInTheImage) {
    const TileLayout t{100, 37, 16, 3, 1};
    const PixelRect first = t.tile(0, 0), last = t.tile(6, 2);
    EXPECT_EQ(std::vector<int>({first.x0, first.y0, first.x1, first.y1}), std::vector<int>({0, 0, 15, 15}));
    EXPECT_EQ(std::vector<int>({last.x0, last.y0, last.x1, last.y1}), std::vector<int>({96, 32, 99, 36}));
    const PixelRect a = t.bucketRect(0, 0), b = t.bucketRect(3, 1), c = t.bucketRect(6, 2);
    EXPECT_EQ(std::vector<int>({a.x0, a.y0, a.x1, a.y1}), std::vector<int>({0, 0, 18, 16}));
    EXPECT_EQ(std::vector<int>({b.x0, b.y0, b.x1, b.y1}), std::vector<int>({45, 15, 66, 32}));
    EXPECT_EQ(std::vector<int>({c.x0, c.y0, c.x1, c.y1}), std::vector<int>({93, 31, 99, 36}));
}

TEST(GridCache, BucketsReachedAreThoseTheViewCullKeeps) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> pos(-80.0f, 400.0f), size(0.0f, 150.0f);
    for (const TileLayout t : {TileLayout{320, 200, 64, 1, 1}, TileLayout{100, 37, 16, 3, 0}, TileLayout{64, 64, 64, 2, 2}}) {
        for (int i = 0; i < 5000; ++i) {
            Bounds3f r;
            r.lo = {pos(rng), pos(rng), 1};
            r.hi = {r.lo.x + size(rng), r.lo.y + size(rng), 2};
            if (i % 7 == 0) r.hi.x = r.lo.x = std::floor(r.lo.x);  // on a tile's edge, zero width
            ASSERT_EQ(t.bucketsReached(r), bruteForceReached(t, r)) << r.lo.x << " " << r.lo.y << " " << r.hi.x << " " << r.hi.y;
        }
        // Bounds far outside, huge, or NaN.
        const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
        Bounds3f all;
        all.lo = {-inf, -1e30f, 0};
        all.hi = {inf, 1e30f, 1};
        EXPECT_EQ(t.bucketsReached(all), bruteForceReached(t, all));
        EXPECT_EQ(t.bucketsReached(all), ((t.width + t.tileSize - 1) / t.tileSize) * ((t.height + t.tileSize - 1) / t.tileSize));
        Bounds3f none;
        none.lo = {nan, 0, 0};
        none.hi = {nan, 10, 1};
        EXPECT_EQ(t.bucketsReached(none), 0);
        none.lo = {1e9f, 0, 0};
        none.hi = {2e9f, 10, 1};
        EXPECT_EQ(t.bucketsReached(none), 0);
    }
}

std::shared_ptr<const Grid> gridOf(int nu, int nv, float x) {
    Grid g;
    g.resize(nu, nv, true);
    for (Vec3f& p : g.P[0]) p = {x, 0, 1};
    return std::make_shared<const Grid>(g);
}

GridKey keyOf(uint64_t piece) {
    GridKey k;
    k.piece = piece;
    k.uv = {0, 1, 0, 1};
    k.nu = k.nv = 4;
    k.frameCount = 1;
    return k;
}

TEST(GridCache, AGridServesTheOtherBucketsItReachesThenGoes) {
    GridCache cache;
    cache.configure({256, 256, 64, 1, 1}, 1 << 20);
    const GridKey key = keyOf(1);
    GridCache::Lease first = cache.acquire(key);
    EXPECT_FALSE(first.grid);
    ASSERT_TRUE(first.make);
    const std::shared_ptr<const Grid> made = gridOf(4, 4, 3);
    cache.publish(key, made, 2);  // two more buckets
    for (int i = 0; i < 2; ++i) {
        GridCache::Lease l = cache.acquire(key);
        EXPECT_EQ(l.grid, made) << i;
        EXPECT_FALSE(l.make);
    }
    GridCache::Lease again = cache.acquire(key);  // every bucket took it: gone, made again
    EXPECT_FALSE(again.grid);
    EXPECT_TRUE(again.make);
    cache.abandon(key);
    // Another piece, or the same piece at another lattice or in other frames, is another grid.
    GridKey other = key;
    other.nu = 5;
    EXPECT_TRUE(cache.acquire(other).make);
    other = key;
    other.firstFrame = 1;
    EXPECT_TRUE(cache.acquire(other).make);
    EXPECT_TRUE(cache.acquire(keyOf(2)).make);
}

TEST(GridCache, TheLeastRecentlyUsedGoWhenFull) {
    const uint64_t one = gridBytes(*gridOf(8, 8, 0));
    GridCache cache;
    cache.configure({256, 256, 64, 1, 1}, 2 * one + one / 2);  // room for two
    for (uint64_t k = 1; k <= 3; ++k) {
        ASSERT_TRUE(cache.acquire(keyOf(k)).make);
        cache.publish(keyOf(k), gridOf(8, 8, float(k)), 5);
        if (k == 2) {
            EXPECT_TRUE(cache.acquire(keyOf(1)).grid);  // 1 is used again: 2 goes first
        }
    }
    EXPECT_EQ(cache.evictions(), 1u);
    EXPECT_LE(cache.peakBytes(), 2 * one + one / 2);
    EXPECT_GE(cache.peakBytes(), 2 * one);
    EXPECT_TRUE(cache.acquire(keyOf(1)).grid);
    EXPECT_TRUE(cache.acquire(keyOf(3)).grid);
    EXPECT_TRUE(cache.acquire(keyOf(2)).make);
}

// A bucket that wants a grid another is making waits for it instead of dicing it again; if the
// maker gives up, the waiter makes it.
TEST(GridCache, ABucketWaitsForTheGridAnotherIsMaking) {
    GridCache cache;
    cache.configure({256, 256, 64, 1, 1}, 1 << 20);
    const GridKey key = keyOf(9);
    ASSERT_TRUE(cache.acquire(key).make);
    // Asked again on the maker's own thread (its task stolen further up the stack): no wait.
    GridCache::Lease mine = cache.acquire(key);
    EXPECT_FALSE(mine.grid);
    EXPECT_FALSE(mine.make);

    std::atomic<bool> got{false};
    GridCache::Lease seen;
    std::thread waiter([&] {
        seen = cache.acquire(key);
        got = true;
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_FALSE(got.load());  // still waiting: nothing published
    const std::shared_ptr<const Grid> made = gridOf(4, 4, 1);
    cache.publish(key, made, 1);
    waiter.join();
    EXPECT_EQ(seen.grid, made);

    const GridKey dropped = keyOf(10);
    ASSERT_TRUE(cache.acquire(dropped).make);
    std::thread second([&] { seen = cache.acquire(dropped); });
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    cache.abandon(dropped);
    second.join();
    EXPECT_FALSE(seen.grid);
    EXPECT_TRUE(seen.make);  // the waiter makes it now
}

// A dropped grid that no bucket holds is handed out again, its vectors kept: dicing into it
// allocates nothing. One a bucket still samples is not.
TEST(GridCache, DroppedGridsAreHandedOutAgain) {
    GridCache cache;
    cache.configure({256, 256, 64, 1, 1}, 1 << 20);
    std::shared_ptr<Grid> first = cache.spare();
    first->resize(8, 8, true);
    const Vec3f* storage = first->P[1].data();
    ASSERT_TRUE(cache.acquire(keyOf(1)).make);
    cache.publish(keyOf(1), first, 1);
    first.reset();
    std::shared_ptr<const Grid> last = cache.acquire(keyOf(1)).grid;  // its last use: dropped
    ASSERT_TRUE(last);
    cache.recycle(std::move(last));  // the bucket is done with it: spare again
    std::shared_ptr<Grid> again = cache.spare();
    EXPECT_EQ(again->P[1].data(), storage);
    EXPECT_EQ(again->P[1].capacity(), 81u);

    ASSERT_TRUE(cache.acquire(keyOf(2)).make);
    cache.publish(keyOf(2), again, 1);
    const std::shared_ptr<const Grid> held = cache.acquire(keyOf(2)).grid;  // dropped while held
    ASSERT_TRUE(held);
    cache.recycle(std::move(again));  // the maker is done, another bucket is not
    EXPECT_NE(cache.spare().get(), held.get());
}

}  // namespace
}  // namespace streyes
