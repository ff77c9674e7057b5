#include "raster/rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geom/body.h"
#include "pixel_camera.h"
#include "shade/shading.h"

namespace streyes {
namespace {

using test::pixelCamera;

// A square grid from raster (x0, y0) to (x1, y1) at depth z, moved by `dx` pixels from t=0 to t=1.
void diceSquare(float x0, float y0, float x1, float y1, float z, float dx, int n, const Material* m, int size,
                Grid& g) {
    auto p = [&](float x, float y) { return Vec3f{x, float(size) - y, z}; };
    TrilinearBody::Corners a{{p(x0, y0), p(x1, y0), p(x0, y1), p(x1, y1)}}, b = a;
    for (auto& c : b) c.x += dx;
    TrilinearBody body({0, 1}, a, b, {}, m);
    body.dice(n, n, g);
    for (int k = 0; k < 2; ++k) g.Ci[k].assign(g.P[0].size(), Color{1, 1, 1});
}

struct Fixture {
    int size = 8;
    Camera cam = pixelCamera(8);
    Material material;
    ImageBlock block;
    GridRasterizer raster;
    RasterCounters counters;
    PatternTable patterns{SamplePattern{1, 1, 0}};
    // One sample per pixel, at (x, y) + offset in every pixel (where the table's own pattern puts
    // it when offset is empty), at time times[q] in pixels given permutation q. Positions come
    // from the pattern table only: both samplers read them from there.
    void reset(const std::vector<float>& times = {0.0f}, const std::vector<float>& offset = {}) {
        std::vector<std::vector<float>> perPermutation;
        for (float t : times) perPermutation.push_back({t});
        patterns = PatternTable(SamplePattern{1, 1, 0}, perPermutation, offset);
        block.reset({0, 0, size - 1, size - 1}, 0, 1, patterns, false);
        counters = {};
    }
    // Pixel (x, y)'s sample, which reset's offset put at (sx, sy), takes permutation q.
    void place(int x, int y, float sx, float sy, int permutation = 0) {
        const size_t i = block.pixelIndex(x, y);
        ASSERT_EQ(block.xs()[i], sx);
        ASSERT_EQ(block.ys()[i], sy);
        block.setPermutation(0, i, permutation);
    }
    const SampleHit& hit(int x, int y) const { return block.hits(0, block.pixelIndex(x, y))[0]; }
};

TEST(GridRasterizer, SamplesOnSharedEdgesAndVerticesAreHitExactlyOnce) {
    for (float shift : {0.0f, 0.5f}) {  // lattice vertices, then edge midpoints
        Fixture f;
        f.reset({0.0f}, {shift, 0.0f});
        // Samples at (x + shift, y): on the grid's vertex lattice or on its vertical edges.
        int inside = 0;
        for (int y = 0; y < f.size; ++y)
            for (int x = 0; x < f.size; ++x) {
                f.place(x, y, float(x) + shift, float(y));
                // The tie rule: a sample on an edge counts as if nudged by (-e^2, e).
                float sx = float(x) + shift;
                bool nudgedInside = sx > 1 && sx <= 5 && y >= 1 && y < 5;
                inside += nudgedInside;
            }
        // Two grids sharing the edge x = 3: 2 x 4 and 2 x 4 micropolygons of one pixel.
        Grid left, right;
        TrilinearBody::Corners lc{{{1, 7, 10}, {3, 7, 10}, {1, 3, 10}, {3, 3, 10}}};
        TrilinearBody::Corners rc{{{3, 7, 10}, {5, 7, 10}, {3, 3, 10}, {5, 3, 10}}};
        TrilinearBody lb({0, 1}, lc, lc, {}, &f.material), rb({0, 1}, rc, rc, {}, &f.material);
        lb.dice(2, 4, left);
        rb.dice(2, 4, right);
        left.Ci[0].assign(left.P[0].size(), Color{1, 1, 1});
        right.Ci[0].assign(right.P[0].size(), Color{1, 1, 1});
        Shutter shutter{0, 0};
        f.raster.rasterize(left, f.cam, shutter, f.block, f.counters);
        f.raster.rasterize(right, f.cam, shutter, f.block, f.counters);
        // Every sample inside the union is hit exactly once, however it sits on shared edges
        // and vertices; samples on the outer boundary follow the tie rule.
        EXPECT_EQ(f.counters.sampleHits, uint64_t(inside)) << "shift " << shift;
        EXPECT_EQ(inside, 16);
        for (int y = 2; y <= 4; ++y)
            for (int x = 2; x <= 4; ++x) EXPECT_FALSE(f.hit(x, y).empty()) << x << "," << y;
    }
}

TEST(GridRasterizer, MovingGridIsSampledWhereItIsAtTheSampleTime) {
    Fixture f;
    f.reset({0.5f}, {0.5f, 0.5f});  // every sample at t = 0.5, when the square covers x in [2, 4]
    // A 2x2-pixel square moving 4 pixels right during [0, 1].
    Grid g;
    diceSquare(0, 2, 2, 4, 10, 4, 2, &f.material, f.size, g);
    for (int y = 0; y < f.size; ++y)
        for (int x = 0; x < f.size; ++x) f.place(x, y, float(x) + 0.5f, float(y) + 0.5f);
    f.raster.rasterize(g, f.cam, Shutter{0, 1}, f.block, f.counters);
    for (int y = 0; y < f.size; ++y)
        for (int x = 0; x < f.size; ++x) {
            bool expected = (x == 2 || x == 3) && (y == 2 || y == 3);
            EXPECT_EQ(!f.hit(x, y).empty(), expected) << x << "," << y;
        }
    EXPECT_EQ(f.counters.sampleHits, 4u);
    EXPECT_EQ(f.counters.micropolygons, 4u);
}

// Two grids sharing an edge, diced at different rates along it (2 and 3 micropolygons): the
// vertices of one lie on the other's edges (T-junctions). Under perspective, while the plane
// tilts in depth within one time slice, every sample of the image lies on the plane and must be
// hit exactly once: interpolating raster positions linearly within the slice would move the
// T-junction vertices off the edges they lie on and open cracks (and overlaps) along it.
TEST(GridRasterizer, TJunctionsDoNotCrackUnderPerspectiveMotion) {
    const int size = 16;
    CameraDesc cd;
    cd.projection = ProjectionKind::Perspective;
    cd.fov = 90;
    cd.xres = cd.yres = size;
    Camera cam(cd);
    Material material;
    // The plane z = 4 at t = 0 turns to z = 4 + x/4 at t = 1; the grids meet along y = 1.
    const float L = 12;
    auto at = [](float x, float y, bool end) { return Vec3f{x, y, end ? 4 + x / 4 : 4}; };
    auto patch = [&](float y0, float y1, bool end) {
        return TrilinearBody::Corners{{at(-L, y0, end), at(L, y0, end), at(-L, y1, end), at(L, y1, end)}};
    };
    TrilinearBody top({0, 1}, patch(1, L, false), patch(1, L, true), {}, &material);
    TrilinearBody bottom({0, 1}, patch(-L, 1, false), patch(-L, 1, true), {}, &material);
    Grid gt, gb;
    top.dice(2, 2, gt);
    bottom.dice(3, 2, gb);
    for (Grid* g : {&gt, &gb})
        for (int k = 0; k < 2; ++k) g->Ci[k].assign(g->P[0].size(), Color{1, 1, 1});
    ImageBlock block;
    GridRasterizer raster;
    uint64_t samples = 0, hits = 0;
    for (uint64_t seed = 0; seed < 200; ++seed) {
        const PatternTable patterns(SamplePattern{1, 1, seed});  // one slice: the whole exposure
        block.reset({0, 0, size - 1, size - 1}, 0, 1, patterns, false);
        RasterCounters counters;
        raster.rasterize(gt, cam, Shutter{0, 1}, block, counters);
        raster.rasterize(gb, cam, Shutter{0, 1}, block, counters);
        samples += uint64_t(block.pixelCount());
        hits += counters.sampleHits;
        for (size_t i = 0; i < size_t(block.pixelCount()); ++i)
            ASSERT_FALSE(block.hits(0, i)[0].empty()) << "seed " << seed;
    }
    EXPECT_EQ(hits, samples);
}

// Two pieces of one surface meeting at time `tm` (motion segments meeting at a key, or the halves
// of a time split): [t0, tm) and [tm, t1], each covering the whole 8x8 image, moving 0.5 pixel
// per unit of time when `moving`.
struct TimePieces {
    Material material;
    Grid first, second;
    TimePieces(double t0, double tm, double t1, bool moving) {
        auto at = [&](double t) {
            const float dx = moving ? float(0.5 * t) : 0.0f;
            return TrilinearBody::Corners{{{-4 + dx, -4, 10}, {12 + dx, -4, 10}, {-4 + dx, 12, 10}, {12 + dx, 12, 10}}};
        };
        TrilinearBody a({t0, tm, true}, at(t0), at(tm), {}, &material), b({tm, t1, false}, at(tm), at(t1), {}, &material);
        a.dice(2, 2, first);
        b.dice(2, 2, second);
        for (Grid* g : {&first, &second})
            for (int k = 0; k < 2; ++k) g->Ci[k].assign(g->P[0].size(), Color{1, 1, 1});
    }
};

// Samples exactly at the start of the exposure, at a key inside it, at its end (as near as a
// sample gets) and between: each is hit by exactly one of the two pieces.
TEST(GridRasterizer, SamplesAtExposureEndsAndKeysAreHitExactlyOnce) {
    for (bool moving : {false, true}) {
        Fixture f;
        f.reset({0.0f, 0.5f, 0.5f, 0x1.fffffep-1f, 0.25f, 0.75f, 0.49999997f, 0.50000006f}, {0.5f, 0.5f});
        for (int y = 0; y < f.size; ++y)
            for (int x = 0; x < f.size; ++x) f.place(x, y, float(x) + 0.5f, float(y) + 0.5f, (x + y) % 8);
        TimePieces p(0, 0.5, 1, moving);
        f.raster.rasterize(p.first, f.cam, Shutter{0, 1}, f.block, f.counters);
        f.raster.rasterize(p.second, f.cam, Shutter{0, 1}, f.block, f.counters);
        EXPECT_EQ(f.counters.sampleHits, 64u) << (moving ? "moving" : "still");
    }
}

// With the shutter closed, a frame is one instant: at a key exactly, only the piece that starts
// there is sampled; at the end of the last piece, it is.
TEST(GridRasterizer, InstantAtAKeyIsSampledOnce) {
    for (bool moving : {false, true})
        for (double frameTime : {-1.0, 0.0, 1.0}) {  // the first piece's start, the key, the last piece's end
            Fixture f;
            f.reset();
            TimePieces p(-1, 0, 1, moving);
            const Shutter instant{frameTime, frameTime};  // frame 0 exposed at frameTime only
            f.raster.rasterize(p.first, f.cam, instant, f.block, f.counters);
            f.raster.rasterize(p.second, f.cam, instant, f.block, f.counters);
            EXPECT_EQ(f.counters.sampleHits, 64u) << (moving ? "moving" : "still") << " at t = " << frameTime;
        }
}

// Pieces meeting at a slice boundary (4 slices per frame): a sample of slice 0 whose time rounds
// to the boundary itself belongs to one piece only.
TEST(GridRasterizer, PiecesMeetingAtASliceBoundary) {
    for (bool moving : {false, true}) {
        // Every sample of slice 0 exactly at its end, 0.25; the others inside their slices.
        const PatternTable patterns(SamplePattern{2, 2, 3}, {{0.25f, 0.375f, 0.625f, 0.875f}});
        ImageBlock block;
        block.reset({0, 0, 7, 7}, 0, 1, patterns, false);
        for (size_t i = 0; i < size_t(block.pixelCount()); ++i) block.setPermutation(0, i, 0);
        TimePieces p(0, 0.25, 1, moving);
        GridRasterizer raster;
        RasterCounters counters;
        Camera cam = pixelCamera(8);
        raster.rasterize(p.first, cam, Shutter{0, 1}, block, counters);
        raster.rasterize(p.second, cam, Shutter{0, 1}, block, counters);
        EXPECT_EQ(counters.sampleHits, 64u * 4u) << (moving ? "moving" : "still");
    }
}

TEST(GridRasterizer, NearerHitWinsAndEqualDepthGoesToTheEarlierPrimitiveInAnyOrder) {
    Grid far, near, tie;
    Material material;
    diceSquare(0, 0, 8, 8, 20, 0, 4, &material, 8, far);
    diceSquare(0, 0, 4, 8, 10, 0, 4, &material, 8, near);
    diceSquare(0, 0, 8, 8, 10, 0, 4, &material, 8, tie);
    far.Ci[0].assign(far.P[0].size(), Color{0, 0, 1});
    near.Ci[0].assign(near.P[0].size(), Color{1, 0, 0});
    tie.Ci[0].assign(tie.P[0].size(), Color{0, 1, 0});
    far.primitiveId = 3;
    near.primitiveId = 1;  // declared first: wins the tie at z = 10
    tie.primitiveId = 2;
    const std::vector<std::vector<Grid*>> orders = {{&far, &near, &tie}, {&tie, &near, &far}, {&near, &tie, &far}};
    for (const auto& order : orders) {
        Fixture f;
        f.reset({0.0f}, {0.5f, 0.5f});
        for (int y = 0; y < f.size; ++y)
            for (int x = 0; x < f.size; ++x) f.place(x, y, float(x) + 0.5f, float(y) + 0.5f);
        for (Grid* g : order) f.raster.rasterize(*g, f.cam, Shutter{0, 0}, f.block, f.counters);
        EXPECT_FLOAT_EQ(f.hit(1, 1).z, 10.0f);
        EXPECT_EQ(f.hit(1, 1).c.x, 1.0f);  // near (red, primitive 1) beats the tie (green, primitive 2)
        EXPECT_EQ(f.hit(1, 1).id, 1u);
        EXPECT_EQ(f.hit(6, 1).c.y, 1.0f);  // the tie beats the far blue
        EXPECT_EQ(f.hit(6, 1).id, 2u);
    }
}

// A moving grid folded onto itself: its first row of quads (depth 3 to 6.5) lies over its second
// (6.5 to 10), over the same pixels. The moving sampler gathers a group's samples once, before any
// quad; the first row's hits must reach what the second row reads, so that the second row finds
// those samples behind it (not tested, not hit) rather than testing them against stale depths.
TEST(GridRasterizer, AMovingGridsLaterQuadsSeeItsEarlierHits) {
    Fixture f;
    f.reset({0.5f}, {0.5f, 0.5f});  // every sample at t = 0.5
    for (int y = 0; y < f.size; ++y)
        for (int x = 0; x < f.size; ++x) f.place(x, y, float(x) + 0.5f, float(y) + 0.5f);
    // x in [1.2, 4.2] moving 1 pixel right; vertex rows at y = 2, 6, 2 (the fold) and depths 3, 6.5, 10.
    Grid g;
    diceSquare(1.2f, 2, 4.2f, 6, 3, 1, 1, &f.material, f.size, g);
    ASSERT_TRUE(g.moving);
    g.nv = 2;
    for (int k = 0; k < 2; ++k) {
        const Vec3f r0a = g.P[k][0], r0b = g.P[k][1];  // the row at y = 2
        g.P[k] = {r0a, r0b, g.P[k][2], g.P[k][3], r0a, r0b};
        for (int v = 2; v < 4; ++v) g.P[k][size_t(v)].z = 6.5f;
        for (int v = 4; v < 6; ++v) g.P[k][size_t(v)].z = 10;
        g.Ci[k].assign(6, Color{1, 1, 1});
    }
    f.raster.rasterize(g, f.cam, Shutter{0, 1}, f.block, f.counters);
    // At t = 0.5 both rows cover x in [1.7, 4.7], y in [2, 6]: the samples of columns 2-4, rows
    // 2-5, which the first row hits. Each row's bound over the frame (x in [1.2, 5.2]) adds
    // column 1, which neither hits.
    EXPECT_EQ(f.counters.sampleHits, 12u);
    EXPECT_EQ(f.counters.samplesBehind, 12u);  // the second row, at the first row's hits
    EXPECT_EQ(f.counters.sampleTests, 16u + 4u);
    for (int y = 2; y <= 5; ++y)
        for (int x = 2; x <= 4; ++x) {
            const float z = f.hit(x, y).z;
            EXPECT_NEAR(z, 3 + 3.5f * (float(y) + 0.5f - 2) / 4, 1e-5f) << x << "," << y;
        }
    EXPECT_EQ(f.hit(1, 3).z, std::numeric_limits<float>::infinity());
}

// A moving grid wholly behind what every pixel it can reach already sees (a still wall, nearer in
// every sample) is not sampled at all: not a sample tested, the block unchanged, and the skip
// counted. The same grid passing in front of the wall is sampled as usual; so is one whose reach
// includes pixels that see nothing.
TEST(GridRasterizer, AMovingGridBehindEverySampleItCanReachIsSkipped) {
    Material material;
    auto start = [](Fixture& f, int size) {
        f.size = size;
        f.cam = pixelCamera(size);
        f.reset({0.5f}, {0.5f, 0.5f});  // every sample at t = 0.5
        for (int y = 0; y < f.size; ++y)
            for (int x = 0; x < f.size; ++x) f.place(x, y, float(x) + 0.5f, float(y) + 0.5f);
    };
    auto wallOf = [&](Fixture& f, int width) {  // x in [0, width), every row, z = 5, still
        Grid wall;
        diceSquare(0, 0, float(width), float(f.size), 5, 0, 4, &material, f.size, wall);
        wall.Ci[0].assign(wall.P[0].size(), Color{0, 0, 1});
        wall.primitiveId = 1;
        f.raster.rasterize(wall, f.cam, Shutter{0, 1}, f.block, f.counters);
    };
    Fixture f;
    start(f, 8);
    wallOf(f, 8);
    ASSERT_EQ(f.counters.sampleHits, 64u);
    const RasterCounters afterWall = f.counters;
    Grid behind, front;
    diceSquare(2, 2, 4, 4, 10, 2, 2, &material, 8, behind);  // z = 10, moving 2 pixels right
    diceSquare(2, 2, 4, 4, 3, 2, 2, &material, 8, front);    // z = 3: nearer than the wall
    f.raster.rasterize(behind, f.cam, Shutter{0, 1}, f.block, f.counters);
    EXPECT_GE(f.counters.gridGroupsBehind, 1u);
    EXPECT_EQ(f.counters.sampleTests, afterWall.sampleTests);
    EXPECT_EQ(f.counters.samplesBehind, afterWall.samplesBehind);
    for (int y = 0; y < f.size; ++y)
        for (int x = 0; x < f.size; ++x) ASSERT_EQ(f.hit(x, y).id, 1u) << x << "," << y;
    const uint64_t skipped = f.counters.gridGroupsBehind;
    f.raster.rasterize(front, f.cam, Shutter{0, 1}, f.block, f.counters);
    EXPECT_EQ(f.counters.gridGroupsBehind, skipped);
    EXPECT_GT(f.counters.sampleTests, afterWall.sampleTests);
    EXPECT_FLOAT_EQ(f.hit(3, 3).z, 3.0f);  // at t = 0.5 the square covers x in [3, 5]
    EXPECT_FLOAT_EQ(f.hit(1, 1).z, 5.0f);

    // 12 pixels wide, the wall covering x < 8: a square at z = 10 moving from x in [5, 7] to
    // [11, 13] reaches pixels that see nothing, so it is sampled, and seen where it is at t = 0.5
    // (x in [8, 10]), beyond the wall.
    Fixture wide;
    start(wide, 12);
    wallOf(wide, 8);
    Grid past;
    diceSquare(5, 2, 7, 4, 10, 6, 2, &material, 12, past);
    wide.raster.rasterize(past, wide.cam, Shutter{0, 1}, wide.block, wide.counters);
    EXPECT_EQ(wide.counters.gridGroupsBehind, 0u);
    EXPECT_FLOAT_EQ(wide.hit(8, 2).z, 10.0f);
    EXPECT_FLOAT_EQ(wide.hit(9, 3).z, 10.0f);
    EXPECT_FLOAT_EQ(wide.hit(6, 2).z, 5.0f);
}

// A moving grid partly hidden: its patches of 4 x 4 quads that lie behind what every pixel they
// reach already sees are skipped (counted), the rest sampled as usual. A still wall covers x < 8 at
// z = 5; an 8 x 8 grid at z = 10 spans x in [2, 10] moving 1 pixel right: its left patches (x up
// to 7) are hidden, its right ones reach pixels that see nothing.
TEST(GridRasterizer, HiddenPatchesOfAMovingGridAreSkipped) {
    Material material;
    Fixture f;
    f.size = 12;
    f.cam = pixelCamera(12);
    f.reset({0.5f}, {0.5f, 0.5f});
    for (int y = 0; y < f.size; ++y)
        for (int x = 0; x < f.size; ++x) f.place(x, y, float(x) + 0.5f, float(y) + 0.5f);
    Grid wall, grid;
    diceSquare(0, 0, 8, 12, 5, 0, 4, &material, 12, wall);
    wall.Ci[0].assign(wall.P[0].size(), Color{0, 0, 1});
    wall.primitiveId = 1;
    f.raster.rasterize(wall, f.cam, Shutter{0, 1}, f.block, f.counters);
    diceSquare(2, 2, 10, 10, 10, 1, 8, &material, 12, grid);
    grid.primitiveId = 2;
    f.raster.rasterize(grid, f.cam, Shutter{0, 1}, f.block, f.counters);
    EXPECT_EQ(f.counters.gridGroupsBehind, 0u);
    EXPECT_EQ(f.counters.patchGroupsBehind, 2u);  // the two left patches, in the one group of slices
    for (int y = 0; y < f.size; ++y)
        for (int x = 0; x < f.size; ++x) {
            // At t = 0.5 the grid covers x in [2.5, 10.5], y in [2, 10].
            const bool onGrid = x >= 8 && float(x) + 0.5f <= 10.5f && y >= 2 && y < 10;
            ASSERT_EQ(f.hit(x, y).id, x < 8 ? 1u : onGrid ? 2u : kNoHit.id) << x << "," << y;
        }
}

// A moving grid that reaches past the block: its patches of 4 x 4 quads whose bound over a group
// misses the block are skipped (counted), and the block's samples are those the same grid gives a
// block over the whole frame. A 12 x 12 grid over x in [2, 14], moving 1 pixel right, on a
// 16-pixel frame: the left block (x < 8) misses its right patches (x from 10 on).
TEST(GridRasterizer, PatchesOfAMovingGridOutsideTheBlockAreSkipped) {
    Material material;
    auto run = [&](Fixture& f, int blockWidth) {
        f.size = 16;
        f.cam = pixelCamera(16);
        f.reset({0.3f}, {0.5f, 0.5f});
        f.block.reset({0, 0, blockWidth - 1, 15}, 0, 1, f.patterns, false);
        Grid grid;
        diceSquare(2, 2, 14, 14, 10, 1, 12, &material, 16, grid);
        for (int k = 0; k < 2; ++k)
            for (size_t i = 0; i < grid.Ci[k].size(); ++i) grid.Ci[k][i] = Color{float(i) / 169.0f, float(k), 0.5f};
        grid.primitiveId = 2;
        f.raster.rasterize(grid, f.cam, Shutter{0, 1}, f.block, f.counters);
    };
    Fixture whole, left;
    run(whole, 16);
    run(left, 8);
    EXPECT_EQ(whole.counters.patchGroupsOutside, 0u);
    EXPECT_EQ(left.counters.patchGroupsOutside, 3u);  // the right column of 3 x 3 patches, one group
    uint64_t hitsLeft = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 8; ++x) {
            const SampleHit &a = whole.hit(x, y), &b = left.hit(x, y);
            ASSERT_EQ(a.id, b.id) << x << "," << y;
            ASSERT_EQ(a.z, b.z) << x << "," << y;
            ASSERT_EQ(a.c.x, b.c.x) << x << "," << y;
            ASSERT_EQ(a.c.y, b.c.y) << x << "," << y;
            ASSERT_EQ(a.c.z, b.c.z) << x << "," << y;
            hitsLeft += a.id == 2u;
        }
    EXPECT_EQ(left.counters.sampleHits, hitsLeft);
    EXPECT_EQ(hitsLeft, 6u * 12u);  // at t = 0.3 the grid covers x in [2.3, 14.3]: columns 2-7, rows 2-13
}

}  // namespace
}  // namespace streyes
