#include "streyes/rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "streyes/body.h"
#include "streyes/shading.h"

namespace streyes {
namespace {

// Orthographic camera with raster x = x and raster y = size - y.
Camera pixelCamera(int size) {
    CameraDesc cd;
    cd.xres = cd.yres = size;
    cd.hasScreenWindow = true;
    cd.screenWindow[0] = 0;
    cd.screenWindow[1] = size;
    cd.screenWindow[2] = 0;
    cd.screenWindow[3] = size;
    return Camera(cd);
}

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
    // One sample per pixel, placed by the test.
    void reset() {
        SamplePattern one{1, 1, 0};
        block.reset({0, 0, size - 1, size - 1}, 0, 1, one);
        counters = {};
    }
    SamplePosition& sample(int x, int y) { return block.positions()[block.sliceIndex(0, 0, x, y)]; }
    SampleHit& hit(int x, int y) { return block.hits()[block.sliceIndex(0, 0, x, y)]; }
};

TEST(GridRasterizer, SamplesOnSharedEdgesAndVerticesAreHitExactlyOnce) {
    for (float shift : {0.0f, 0.5f}) {  // lattice vertices, then edge midpoints
        Fixture f;
        f.reset();
        // Samples at (x + shift, y): on the grid's vertex lattice or on its vertical edges.
        int inside = 0;
        for (int y = 0; y < f.size; ++y)
            for (int x = 0; x < f.size; ++x) {
                f.sample(x, y).x = float(x) + shift;
                f.sample(x, y).y = float(y);
                f.sample(x, y).tf = 0;
                // The tie rule: a sample on an edge counts as if nudged by (-e^2, e).
                float sx = f.sample(x, y).x;
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
            for (int x = 2; x <= 4; ++x) EXPECT_EQ(f.hit(x, y).a, 1.0f) << x << "," << y;
    }
}

TEST(GridRasterizer, MovingGridIsSampledWhereItIsAtTheSampleTime) {
    Fixture f;
    f.reset();
    // A 2x2-pixel square moving 4 pixels right during [0, 1]; sample times chosen per pixel.
    Grid g;
    diceSquare(0, 2, 2, 4, 10, 4, 2, &f.material, f.size, g);
    for (int y = 0; y < f.size; ++y)
        for (int x = 0; x < f.size; ++x) {
            f.sample(x, y).x = float(x) + 0.5f;
            f.sample(x, y).y = float(y) + 0.5f;
            f.sample(x, y).tf = 0.5f;  // square covers x in [2, 4] at t = 0.5
        }
    f.raster.rasterize(g, f.cam, Shutter{0, 1}, f.block, f.counters);
    for (int y = 0; y < f.size; ++y)
        for (int x = 0; x < f.size; ++x) {
            bool expected = (x == 2 || x == 3) && (y == 2 || y == 3);
            EXPECT_EQ(f.hit(x, y).a, expected ? 1.0f : 0.0f) << x << "," << y;
        }
    EXPECT_EQ(f.counters.sampleHits, 4u);
    EXPECT_EQ(f.counters.micropolygons, 4u);
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
        f.reset();
        for (int y = 0; y < f.size; ++y)
            for (int x = 0; x < f.size; ++x) {
                f.sample(x, y).x = float(x) + 0.5f;
                f.sample(x, y).y = float(y) + 0.5f;
            }
        for (Grid* g : order) f.raster.rasterize(*g, f.cam, Shutter{0, 0}, f.block, f.counters);
        EXPECT_FLOAT_EQ(f.hit(1, 1).z, 10.0f);
        EXPECT_EQ(f.hit(1, 1).c.x, 1.0f);  // near (red, primitive 1) beats the tie (green, primitive 2)
        EXPECT_EQ(f.hit(1, 1).id, 1u);
        EXPECT_EQ(f.hit(6, 1).c.y, 1.0f);  // the tie beats the far blue
        EXPECT_EQ(f.hit(6, 1).id, 2u);
    }
}

}  // namespace
}  // namespace streyes
