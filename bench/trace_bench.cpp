// Google Benchmark kernels of the ray tracer (src/trace): the ray/bilinear-patch intersection,
// and eye and shadow rays through scenes/atom.rib with the frame-by-frame hierarchies and with
// the spacetime hierarchy at several time resolutions (HierarchyOptions::minTimeCut).
//
//   build/streyes_bench --benchmark_filter=Trace
//
// Counters: bounding_volumes and build_cpu_s for frames 1-16; tests per ray; rays/s per core.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "streyes/rib.h"
#include "trace/trace.h"
#include "util/sampling.h"

namespace streyes {
namespace {

void BM_RayPatch(benchmark::State& state) {
    HashRng rng(5);
    auto r = [&](float a, float b) { return a + (b - a) * rng.nextFloat(); };
    std::vector<std::array<Vec3f, 4>> patches(256);
    for (auto& p : patches)
        for (Vec3f& c : p) c = {r(-1, 1), r(-1, 1), r(4, 6)};
    std::vector<Ray> rays(256);
    for (Ray& ray : rays) ray = {{0, 0, 0}, {r(-0.3f, 0.3f), r(-0.3f, 0.3f), 1}};
    uint64_t tests = 0, hits = 0;
    for (auto _ : state)
        for (const auto& p : patches)
            for (const Ray& ray : rays) {
                PatchHit h;
                hits += intersectBilinearPatch(p, ray, 0, 100, &h);
                ++tests;
            }
    state.counters["tests/s"] = benchmark::Counter(double(tests), benchmark::Counter::kIsRate);
    state.counters["hit_rate"] = double(hits) / double(tests);
}
BENCHMARK(BM_RayPatch);

// scenes/atom.rib, frames 1-16, with one kind of hierarchy (built once per kind and kept).
struct AtomTrace {
    Log log;
    Scene scene;
    std::unique_ptr<RenderScene> rs;
    std::unique_ptr<TraceScene> trace;
};
const AtomTrace& atom(int mode) {
    static std::map<int, std::unique_ptr<AtomTrace>> cache;
    std::unique_ptr<AtomTrace>& a = cache[mode];
    if (!a) {
        a = std::make_unique<AtomTrace>();
        a->log.setQuiet(true);
        a->scene = parseRibFile(std::string(STREYES_SOURCE_DIR) + "/scenes/atom.rib", a->log);
        a->rs = buildRenderScene(a->scene, 1, 16, 0, 0, a->log);
        a->trace = std::make_unique<TraceScene>(*a->rs, RenderOptions{}, a->log);
        HierarchyOptions o;
        if (mode == 0) {
            a->trace->buildFrames(1, 16, o);
        } else {
            o.minTimeCut = 1.0 / double(1 << (mode - 1));
            a->trace->buildSpacetime(o);
        }
    }
    return *a;
}

// Mode 0: a 3D hierarchy per frame. Mode m > 0: the spacetime hierarchy with time cells no
// shorter than 2^-(m-1) frames. Every second pixel of each frame sends an eye ray at a hashed
// time in the exposure and, where it hits, a shadow ray to the light.
void BM_TraceAtom(benchmark::State& state) {
    const AtomTrace& a = atom(int(state.range(0)));
    const Camera& cam = a.rs->camera;
    const CameraLight light = [&] {
        std::vector<CameraLight> l;
        a.rs->lights.at(1, l);
        return l[size_t(a.rs->lights.shadowLight(0))];
    }();
    TraceContext ctx;
    uint64_t rays = 0;
    for (auto _ : state) {
        for (int f = 1; f <= 16; ++f) {
            const SpacetimeBVH& bvh = a.trace->hierarchy(f);
            for (int y = 0; y < cam.height(); y += 2)
                for (int x = 0; x < cam.width(); x += 2) {
                    const double t = f + HashRng(hashCombine(uint64_t(f), uint64_t(y * 1024 + x))).nextFloat();
                    const Ray eye{{0, 0, 0}, cam.fromRaster(float(x) + 0.5f, float(y) + 0.5f, 1)};
                    TraceHit h;
                    ++rays;
                    if (!bvh.intersect(eye, t, cam.nearClip(), cam.farClip(), &h, ctx)) continue;
                    const Vec3f p = eye.d * h.t;
                    ++rays;
                    const float bias = a.trace->shadowBias(p.z, 0);
                    benchmark::DoNotOptimize(bvh.occluded(Ray{p, light.direction}, t, bias, 1e30f, ctx));
                }
        }
    }
    state.counters["bounding_volumes"] = double(a.trace->boundingVolumes);
    state.counters["build_cpu_s"] = a.trace->buildSeconds;
    state.counters["body_tests/ray"] = double(ctx.bodyTests) / double(rays);
    state.counters["box_tests/ray"] = double(ctx.boxTests) / double(rays);
    state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_TraceAtom)->ArgName("mode")->DenseRange(0, 4)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace streyes
