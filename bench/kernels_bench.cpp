// Google Benchmark kernels of the REYES pipeline. Performance lives here, never in tests.
//
//   build/streyes_bench                          all kernels
//   build/streyes_bench --benchmark_filter=Sampler
//   STREYES_SIMD=AVX2 build/streyes_bench       the sample kernels on AVX2 (any of simdTargets())
//
// Counters: micropolygons/s and sample tests/s are per core (single-threaded kernels);
// hit_efficiency is sample hits / sample tests.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "geom/body.h"
#include "film/film.h"
#include "geom/grid.h"
#include "raster/image_block.h"
#include "raster/rasterizer.h"
#include "raster/sample_kernels.h"
#include "shade/shading.h"
#include "split_loop.h"
#include "../tests/pixel_camera.h"

namespace streyes {
namespace {

using test::pixelCamera;

// A 16-pixel square centred at (cx, cy) in raster space, turned by 30 degrees so that its
// micropolygons do not line up with pixels, at camera depth 10.
TrilinearBody::Corners turnedSquare(float cx, float cy, int size) {
    const float c = std::cos(0.5236f) * 8, s = std::sin(0.5236f) * 8;
    auto p = [&](float u, float v) { return Vec3f{cx + u * c - v * s, float(size) - (cy + u * s + v * c), 10}; };
    return {{p(-1, -1), p(1, -1), p(-1, 1), p(1, 1)}};
}

Camera perspectiveCamera(int w, int h) {
    CameraDesc cd;
    cd.projection = ProjectionKind::Perspective;
    cd.fov = 60;
    cd.xres = w;
    cd.yres = h;
    return Camera(cd);
}

// The split loop's decision (the renderer's own, render/split_decision.h) and recursion, without
// culling or sampling: a patch seen at an angle, split until each piece dices to at most 256
// micropolygons (default options, shading rate 1).
void BM_SplitLoop(benchmark::State& state) {
    Camera cam = perspectiveCamera(1920, 1080);
    Material m;
    TrilinearBody::Corners c{{{-4, -2, 4}, {4, -2, 4}, {-4, -2, 40}, {4, -2, 40}}};
    TrilinearBody root({0, 1}, c, c, {}, &m);
    const RenderOptions options;
    std::vector<BodyPtr> stack;
    uint64_t splits = 0, dices = 0;
    for (auto _ : state) splitToGrids(root, cam, options, 1.0, stack, splits, dices);
    state.counters["splits/s"] = benchmark::Counter(double(splits), benchmark::Counter::kIsRate);
    state.counters["grids"] = double(dices) / double(state.iterations());
}
BENCHMARK(BM_SplitLoop);

void BM_Dice(benchmark::State& state) {
    Material m;
    TrilinearBody::Corners a{{{0, 0, 5}, {16, 0, 5}, {0, 16, 6}, {16, 16, 6}}}, b = a;
    for (auto& p : b) p.x += 3;
    TrilinearBody body({0, 1}, a, b, {}, &m);
    Grid g;
    for (auto _ : state) {
        body.dice(16, 16, g);
        benchmark::DoNotOptimize(g.P[0].data());
    }
    state.counters["micropolygons/s"] = benchmark::Counter(256.0 * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Dice);

// Samples a 16x16 grid diced from `body` into one frame of a 64x64 block, 16 samples per pixel,
// shutter open the whole frame. The block is made afresh (untimed) for each pass, as a bucket
// is: sampled again into a block that holds it already, every hit would tie at equal depth and
// take SampleHit::beatenBy's slow path, which a render seldom does.
void sampleGrid(benchmark::State& state, const Camera& cam, const TrilinearBody& body) {
    Grid g;
    body.dice(16, 16, g);
    for (int k = 0; k < 2; ++k) g.Ci[k].assign(g.P[0].size(), Color{1, 1, 1});
    const PatternTable patterns(SamplePattern{4, 4, 1});
    ImageBlock block;
    GridRasterizer raster;
    RasterCounters counters;
    for (auto _ : state) {
        state.PauseTiming();
        block.reset({0, 0, 63, 63}, 0, 1, patterns, false);
        state.ResumeTiming();
        raster.rasterize(g, cam, Shutter{0, 1}, block, counters);
    }
    state.counters["micropolygons/s"] = benchmark::Counter(double(counters.micropolygons), benchmark::Counter::kIsRate);
    state.counters["sample_tests/s"] = benchmark::Counter(double(counters.sampleTests), benchmark::Counter::kIsRate);
    state.counters["hit_efficiency"] = double(counters.sampleHits) / double(std::max<uint64_t>(1, counters.sampleTests));
}

// Sampling a 16x16 grid of 1-pixel micropolygons (turned 30 degrees) moving `motion` pixels per
// frame (diagonally when the second argument is 1), orthographic.
void BM_Sampler(benchmark::State& state) {
    const float motion = float(state.range(0));
    const bool diagonal = state.range(1) != 0;
    const int size = 64;
    Material m;
    TrilinearBody::Corners a = turnedSquare(24.37f, 24.61f, size), b = a;
    for (auto& c : b) {
        c.x += motion;
        if (diagonal) c.y -= motion;
    }
    sampleGrid(state, pixelCamera(size), TrilinearBody({0, 1}, a, b, {}, &m));
}
BENCHMARK(BM_Sampler)->ArgNames({"px_per_frame", "diagonal"})->Args({0, 0})->Args({4, 0})->Args({16, 0})->Args({4, 1})->Args({16, 1});

// The same under a perspective camera: the grid is the turned square at depth 10, moving
// `motion` pixels right per frame and receding to depth 10.5, so its raster path is not linear
// in time. Under perspective the sampler projects each tested quad at the sample's time.
void BM_SamplerPerspective(benchmark::State& state) {
    const float motion = float(state.range(0));
    const int size = 64;
    Camera cam = perspectiveCamera(size, size);
    Material m;
    TrilinearBody::Corners r = turnedSquare(24.37f, 24.61f, size), a, b;
    for (int i = 0; i < 4; ++i) {
        const float x = r[size_t(i)].x, y = float(size) - r[size_t(i)].y;  // raster position
        a[size_t(i)] = cam.fromRaster(x, y, 10.0f);
        b[size_t(i)] = cam.fromRaster(x + motion, y, 10.5f);
    }
    sampleGrid(state, cam, TrilinearBody({0, 1}, a, b, {}, &m));
}
BENCHMARK(BM_SamplerPerspective)->ArgNames({"px_per_frame"})->Arg(4)->Arg(16);

// A camera pan over still geometry (issue 48 pt 3), what most shots of a film are: the turned
// square still in world at depth 10 under a perspective camera (60 degrees over 64 pixels) that
// turns about its vertical axis by enough to move the square's centre `px_per_frame` pixels in
// the frame, and with dolly 1 also moves 0.5 towards it. Every camera-space point then moves by
// the same map (a rotation, and a translation with the dolly), which the moving sampler today
// treats as an independent mover a micropolygon: sample_tests/s per core is the figure to bring
// to the still kernel's (BM_SamplerStillBlock).
void BM_SamplerCameraPan(benchmark::State& state) {
    const float motion = float(state.range(0));
    const bool dolly = state.range(1) != 0;
    const int size = 64;
    Camera cam = perspectiveCamera(size, size);
    Material m;
    TrilinearBody::Corners r = turnedSquare(24.37f, 24.61f, size), a, b;
    const float pixelsPerRadian = float(size) / 2 / std::tan(0.5236f);  // at the centre of the frame
    const float angle = motion / pixelsPerRadian, c = std::cos(angle), s = std::sin(angle);
    for (int i = 0; i < 4; ++i) {
        const Vec3f p = cam.fromRaster(r[size_t(i)].x, float(size) - r[size_t(i)].y, 10.0f);
        a[size_t(i)] = p;
        b[size_t(i)] = Vec3f{c * p.x - s * p.z, p.y, s * p.x + c * p.z - (dolly ? 0.5f : 0.0f)};
    }
    sampleGrid(state, cam, TrilinearBody({0, 1}, a, b, {}, &m));
}
BENCHMARK(BM_SamplerCameraPan)->ArgNames({"px_per_frame", "dolly"})->Args({4, 0})->Args({16, 0})->Args({4, 1});

// A still grid over a block of 48 frames: the spacetime case, diced once and sampled once into the
// still layer (the samples sit at the same positions in every frame).
// The still kernels' grid: the turned square on a size x size frame, still over frames 0-100,
// diced 16 x 16 (1-pixel micropolygons), white.
Grid stillSquare(int size, const Material& m) {
    TrilinearBody::Corners a = turnedSquare(15.37f, 15.61f, size);
    TrilinearBody body({0, 100}, a, a, {}, &m);
    Grid g;
    body.dice(16, 16, g);
    g.Ci[0].assign(g.P[0].size(), Color{1, 1, 1});
    return g;
}

// The still grid on a size x size frame, sampled into a fresh block (untimed, as sampleGrid) of
// its top-left blockSize x blockSize pixels over `frames` frames.
void sampleStillGrid(benchmark::State& state, int size, int blockSize, int frames) {
    Camera cam = pixelCamera(size);
    Material m;
    const Grid g = stillSquare(size, m);
    const PatternTable patterns(SamplePattern{4, 4, 1});
    ImageBlock block;
    GridRasterizer raster;
    RasterCounters counters;
    for (auto _ : state) {
        state.PauseTiming();
        block.reset({0, 0, blockSize - 1, blockSize - 1}, 0, frames, patterns, false);
        state.ResumeTiming();
        raster.rasterize(g, cam, Shutter{0, 0.5}, block, counters);
    }
    state.counters["micropolygons/s"] = benchmark::Counter(double(counters.micropolygons), benchmark::Counter::kIsRate);
    state.counters["sample_tests/s"] = benchmark::Counter(double(counters.sampleTests), benchmark::Counter::kIsRate);
    state.counters["hit_efficiency"] = double(counters.sampleHits) / double(std::max<uint64_t>(1, counters.sampleTests));
}

void BM_SamplerStillBlock(benchmark::State& state) { sampleStillGrid(state, 40, 32, 48); }
BENCHMARK(BM_SamplerStillBlock);

// The same grid in a block the size a render's bucket is (64 pixels and the default gaussian
// filter's margin, 66 x 66), over 1 or 48 frames: what the block's reset writes before a grid is
// sampled (the still layer, the frames' rows of records) decides what is still in the cache.
void BM_SamplerStillBucket(benchmark::State& state) { sampleStillGrid(state, 66, 66, int(state.range(0))); }
BENCHMARK(BM_SamplerStillBucket)->ArgNames({"frames"})->Arg(1)->Arg(48);

// The still quad test alone (sample_kernels.h, quadTestKernel): the same grid and block as
// BM_SamplerStillBlock, each quad projected, bounded and set up beforehand, so that only the
// kernel is timed: the inside test of the samples in each quad's strata, and the barycentrics of
// its hits. BM_SamplerStillBlock adds the rest of the still sampler (each hit's depth test,
// colour and write).
void BM_QuadTestKernel(benchmark::State& state) {
    const int size = 40;
    Camera cam = pixelCamera(size);
    Material m;
    const Grid g = stillSquare(size, m);
    const PatternTable patterns(SamplePattern{4, 4, 1});
    ImageBlock block;
    block.reset({0, 0, 31, 31}, 0, 1, patterns, false);
    const PixelRect R = block.rect();
    const int S = block.samplesPerPixel();
    std::vector<micropolygon::QuadSetup> quads;
    const int stride = g.nu + 1;
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i) {
            const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
            micropolygon::QuadSetup q;
            for (int c = 0; c < 4; ++c) {
                const Vec3f r = cam.toRaster(g.P[0][size_t(idx[c])]);
                q.x[c] = r.x, q.y[c] = r.y, q.z[c] = r.z;
            }
            if (!micropolygon::boundQuad(q, nullptr, nullptr, nullptr, R, cam.nearClip(), cam.farClip())) continue;
            micropolygon::setupEdges(q);
            quads.push_back(q);
        }
    const SampleLayout layout{block.xs(), block.ys(), R.x0, R.y0, R.width(), S, 4, 4};
    std::vector<QuadHit> hits(size_t(block.pixelCount()) * size_t(S));
    const QuadTestFn test = quadTestKernel();
    uint64_t tests = 0, found = 0;
    for (auto _ : state)
        for (const micropolygon::QuadSetup& q : quads) {
            size_t n = 0;
            tests += test(q, layout, nullptr, hits.data(), &n);
            found += n;
            benchmark::DoNotOptimize(hits.data());
        }
    state.counters["sample_tests/s"] = benchmark::Counter(double(tests), benchmark::Counter::kIsRate);
    state.counters["hit_efficiency"] = double(found) / double(std::max<uint64_t>(1, tests));
    state.counters["micropolygons/s"] =
        benchmark::Counter(double(quads.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_QuadTestKernel);

// The moving quad test alone (sample_kernels.h, movingTestKernel), as BM_QuadTestKernel is for
// still quads: BM_Sampler/px_per_frame:4's grid (1-pixel quads moving 4 pixels a frame), each
// quad's lanes over each group of slices laid out beforehand as the sampler reads them (a call a
// row of the quad's pixels: the samples of the group's slices in those pixels, the group as long
// as GridRasterizer::kGroupMotion allows), so that only the kernel is timed: each lane's quad at
// its own time, its five edges, the inside tests and the edge values of the hits.
// BM_Sampler/px_per_frame:4 adds the rest of the moving sampler (grouping and projection, each
// quad's bound, gathering the group's samples, each hit's depth test, colour and write).
void BM_MovingTestKernel(benchmark::State& state) {
    const int size = 64;
    const float motion = 4;
    Camera cam = pixelCamera(size);
    Material m;
    TrilinearBody::Corners a = turnedSquare(24.37f, 24.61f, size), b = a;
    for (auto& c : b) c.x += motion;
    Grid g;
    TrilinearBody({0, 1}, a, b, {}, &m).dice(16, 16, g);
    const PatternTable patterns(SamplePattern{4, 4, 1});
    ImageBlock block;
    block.reset({0, 0, size - 1, size - 1}, 0, 1, patterns, false);
    block.needTimes(0);
    const PixelRect R = block.rect();
    const int S = block.samplesPerPixel(), stride = g.nu + 1;
    float moved = 0;  // the grid's largest raster motion over the frame, as the sampler finds it
    for (size_t v = 0; v < g.P[0].size(); ++v) {
        const Vec3f ra = cam.toRaster(g.P[0][v]), rb = cam.toRaster(g.P[1][v]);
        moved = std::max({moved, std::fabs(rb.x - ra.x), std::fabs(rb.y - ra.y)});
    }
    const int group = int(GridRasterizer::slicesPerGroup(double(moved) / S, S));
    struct Batch {
        MovingQuad q;
        size_t first;
        int n;
    };
    std::vector<Batch> batches;
    std::vector<float> xs, ys, tfs, zs;  // every batch's lanes, each batch padded to edgeStride
    for (int k0 = 0; k0 < S; k0 += group) {
        const int k1 = std::min(S, k0 + group);
        const float wa = float(k0) / float(S), wb = float(k1) / float(S);
        for (int j = 0; j < g.nv; ++j)
            for (int i = 0; i < g.nu; ++i) {
                const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
                Batch bt{};
                micropolygon::QuadSetup q;
                float xb[4], yb[4], zb[4];
                for (int c = 0; c < 4; ++c) {
                    const Vec3f p0 = g.P[0][size_t(idx[c])], p1 = g.P[1][size_t(idx[c])];
                    const Vec3f ra = cam.toRaster(lerp(p0, p1, wa)), rb = cam.toRaster(lerp(p0, p1, wb));
                    q.x[c] = bt.q.x[0][c] = ra.x, q.y[c] = bt.q.y[0][c] = ra.y, q.z[c] = bt.q.z[0][c] = ra.z;
                    xb[c] = bt.q.x[1][c] = rb.x, yb[c] = bt.q.y[1][c] = rb.y, zb[c] = bt.q.z[1][c] = rb.z;
                    bt.q.exact[c] = false;
                }
                if (!micropolygon::boundQuad(q, xb, yb, zb, R, cam.nearClip(), cam.farClip())) continue;
                bt.q.tfA = wa, bt.q.invSpan = 1.0f / (wb - wa);
                bt.q.xmin = q.xmin, bt.q.xmax = q.xmax, bt.q.ymin = q.ymin, bt.q.ymax = q.ymax, bt.q.zmin = q.zmin;
                for (int py = q.py0; py <= q.py1; ++py) {
                    bt.first = xs.size(), bt.n = 0;
                    for (int px = q.px0; px <= q.px1; ++px) {
                        const size_t pi = block.pixelIndex(px, py);
                        const int perm = block.permutation(0, pi);
                        for (int k = k0; k < k1; ++k) {
                            const size_t si = pi * size_t(S) + patterns.sampleOfStratum(perm)[k];
                            xs.push_back(block.xs()[si]), ys.push_back(block.ys()[si]);
                            tfs.push_back(patterns.stratumTimes(perm)[k]), zs.push_back(INFINITY);
                            ++bt.n;
                        }
                    }
                    if (bt.n > 64) state.SkipWithError("a row over the kernel's 64 lanes");
                    for (int p = bt.n; p < edgeStride(bt.n); ++p) xs.push_back(0), ys.push_back(0), tfs.push_back(0), zs.push_back(0);
                    batches.push_back(bt);
                }
            }
    }
    std::vector<float> edges(kMaxEdgeValues);
    const MovingTestFn test = movingTestKernel();
    uint64_t tests = 0, found = 0, lanes = 0;
    for (auto _ : state)
        for (const Batch& bt : batches) {
            const MovingTest t = test(bt.q, &xs[bt.first], &ys[bt.first], &tfs[bt.first], &zs[bt.first], nullptr, nullptr,
                                      bt.n, edges.data());
            tests += uint64_t(__builtin_popcountll(t.tested));
            found += uint64_t(__builtin_popcountll(t.first | t.second));
            lanes += uint64_t(bt.n);
            benchmark::DoNotOptimize(edges.data());
        }
    state.counters["sample_tests/s"] = benchmark::Counter(double(tests), benchmark::Counter::kIsRate);
    state.counters["hit_efficiency"] = double(found) / double(std::max<uint64_t>(1, tests));
    state.counters["lanes/test"] = double(lanes) / double(std::max<uint64_t>(1, tests));
}
BENCHMARK(BM_MovingTestKernel);

// Placing a bucket's samples: positions from the pattern table, a time permutation per pixel
// and frame (the samples themselves are not stored per frame).
void BM_BlockReset(benchmark::State& state) {
    const PatternTable patterns(SamplePattern{4, 4, 3});
    ImageBlock block;
    for (auto _ : state) block.reset({0, 0, 33, 33}, 0, 8, patterns, false);
    state.counters["samples/s"] =
        benchmark::Counter(double(34 * 34 * 8 * 16) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_BlockReset);

// Resolving a 32x32 tile over 8 frames with a gaussian 2x2 filter, a third of the samples hit.
// dense: every frame has its own samples (the ray tracer's and shadows' case: each frame is
// gathered); sparse: everything in the still layer (gathered once, shared by the frames).
void BM_Resolve(benchmark::State& state) {
    const bool dense = state.range(0) != 0;
    const PatternTable patterns(SamplePattern{4, 4, 3});
    ImageBlock block;
    block.reset({0, 0, 33, 33}, 0, 8, patterns, dense);
    for (int fi = 0; fi < (dense ? 8 : 1); ++fi)
        for (size_t i = 0; i < size_t(block.pixelCount()); ++i) {
            SampleHit* h = dense ? block.record(fi, i) : block.still(i);
            for (int j = 0; j < 16; j += 3) h[j] = {5.0f, {0.5f, 0.5f, 0.5f}, 1};
        }
    const FilterWeights weights(PixelFilter(FilterDesc{"gaussian", 2, 2}), patterns);
    TiledFrames frames;
    frames.reset(34, 34, {PixelRect{1, 1, 32, 32}}, 0, 8, {});
    ResolveScratch scratch;
    for (auto _ : state) resolveTile(block, weights, frames, 0, scratch);
    state.counters["samples/s"] =
        benchmark::Counter(double(34 * 34 * 8 * 16) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Resolve)->ArgNames({"dense"})->Arg(1)->Arg(0);

}  // namespace
}  // namespace streyes

// STREYES_SIMD=AVX2 (or any name of streyes::simdTargets) runs the sample kernels on that
// instruction set, as `streyes render --simd` does; the context names the one they ran.
int main(int argc, char** argv) {
    if (const char* simd = std::getenv("STREYES_SIMD")) {
        std::string error;
        if (!streyes::capSimd(simd, &error)) {
            std::fprintf(stderr, "streyes_bench: STREYES_SIMD: %s\n", error.c_str());
            return 2;
        }
    }
    benchmark::AddCustomContext("simd", streyes::pixelTestTarget());
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
