// Shading Language interpreter throughput: points shaded per second on one core, for the
// shipped matte and plastic, the forest's shaders (scenes/forest.rib: matte, ground, sky; its
// procedural's bark and leaf) and a noise-heavy one (ground: six 3D noises a point), on 16 x 16
// and 32 x 32 micropolygon grids (289 and 1089 points) under the forest's two lights (an ambient
// and a distant light: lights:2) or those plus a point light (lights:3), and the built-in C++
// shading (shadePoint) of the same grids beside them.
//
//   build/streyes_bench --benchmark_filter=Shade
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include "shade/sl/compiler.h"
#include "shade/vm/noise.h"
#include "shade/vm/vm.h"
#include "shade/shading.h"

namespace streyes {
namespace {

using namespace sl;

struct BenchGrid {
    ShadingGrid grid;
    std::vector<Vec3f> P, N, Cs, I;
    Vec3f eye{0, 0, 0};
    // An nu x nu grid over a bulging patch in front of the eye (at the origin), bound as the
    // renderer binds them (grid_shader.cpp: P, N, Ng, Cs and I as arrays of triples).
    explicit BenchGrid(int nu = 16) {
        const int kNu = nu, kNv = nu;
        grid.setShape(kNu, kNv);
        const int n = grid.n;
        for (int k = 0; k < n; ++k) {
            float u = float(k % (kNu + 1)) / kNu, v = float(k / (kNu + 1)) / kNv;
            float a = u * 1.2f, b = v * 1.2f;
            P.push_back({std::sin(a) * 3, std::sin(b) * 3, 8 - std::cos(a) * std::cos(b) * 3});
            N.push_back({std::sin(a), std::sin(b), -std::cos(a) * std::cos(b)});
            Cs.push_back({0.8f, 0.5f + 0.3f * u, 0.3f + 0.4f * v});
        }
        I = P;
        grid.set(Global::P, ValueRef::aos(P.data()));
        grid.set(Global::N, ValueRef::aos(N.data()));
        grid.set(Global::Ng, ValueRef::aos(N.data()));
        grid.set(Global::Cs, ValueRef::aos(Cs.data()));
        grid.set(Global::I, ValueRef::aos(I.data()));
        grid.set(Global::E, ValueRef::uniform(eye));
    }
};

ProgramPtr shader(const std::string& name) {
    return compileShaderFile(std::string(STREYES_SOURCE_DIR) + "/shaders/" + name + ".sl");
}

// The forest's lights (count 2), or those and a point light (count 3).
struct Lights {
    ShaderInstance amb{shader("ambientlight")}, sun{shader("distantlight")}, bulb{shader("pointlight")};
    std::vector<LightRef> refs;
    explicit Lights(int count = 3) {
        amb.set("intensity", BaseType::Float, {0.1f});
        sun.set("from", BaseType::Point, {1, 2, -1});
        sun.set("to", BaseType::Point, {0, 0, 0});
        bulb.set("intensity", BaseType::Float, {30});
        refs = {{&amb, Matrix4()}, {&sun, Matrix4()}};
        if (count > 2) refs.push_back({&bulb, Matrix4::translate({-3, 4, 0})});
    }
};

// range(0): grid size (16 or 32 micropolygons a side); range(1): lights (2 or 3).
void shade(benchmark::State& state, const char* name) {
    BenchGrid g(int(state.range(0)));
    Lights lights(int(state.range(1)));
    ShaderInstance inst(shader(name));
    ShadingVM vm;
    for (auto _ : state) {
        vm.run(inst, g.grid, lights.refs);
        benchmark::DoNotOptimize(vm.result(Global::Ci).comp[0][7]);
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * g.grid.n);
    state.counters["points/s"] = benchmark::Counter(double(state.iterations()) * g.grid.n, benchmark::Counter::kIsRate);
    state.counters["instr/grid"] = double(vm.stats().instructions) / double(vm.stats().grids - vm.stats().lightRuns);
}

void BM_ShadeMatte(benchmark::State& state) { shade(state, "matte"); }
void BM_ShadePlastic(benchmark::State& state) { shade(state, "plastic"); }
void BM_ShadeGround(benchmark::State& state) { shade(state, "ground"); }
void BM_ShadeBark(benchmark::State& state) { shade(state, "bark"); }
void BM_ShadeLeaf(benchmark::State& state) { shade(state, "leaf"); }
void BM_ShadeSky(benchmark::State& state) { shade(state, "sky"); }

// The built-in C++ shading of the same grid, one point at a time.
void builtin(benchmark::State& state, SurfaceKind kind) {
    BenchGrid g(int(state.range(0)));
    const int lightCount = int(state.range(1));
    Material m;
    m.kind = kind;
    m.Kd = kind == SurfaceKind::Plastic ? 0.5f : 1.0f;
    m.lights = {0, 1};
    if (lightCount > 2) m.lights.push_back(2);
    Vec3f toSun = normalize(Vec3f{1, 2, -1});
    std::vector<CameraLight> lights{{LightKind::Ambient, {0.1f, 0.1f, 0.1f}, {}, {}, -1},
                                    {LightKind::Distant, {1, 1, 1}, {}, toSun, -1},
                                    {LightKind::Point, {30, 30, 30}, {-3, 4, 0}, {}, -1}};
    std::vector<Color> out(size_t(g.grid.n));
    for (auto _ : state) {
        for (int i = 0; i < g.grid.n; ++i)
            out[size_t(i)] = shadePoint(m, g.Cs[size_t(i)], g.P[size_t(i)], g.N[size_t(i)], false, lights);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * g.grid.n);
    state.counters["points/s"] = benchmark::Counter(double(state.iterations()) * g.grid.n, benchmark::Counter::kIsRate);
}
void BM_ShadeBuiltinMatte(benchmark::State& state) { builtin(state, SurfaceKind::Matte); }
void BM_ShadeBuiltinPlastic(benchmark::State& state) { builtin(state, SurfaceKind::Plastic); }

// 3D gradient noise at a grid's 289 points: the scalar reference point by point (kernel:0) or the
// SIMD kernel the CPU runs (kernel:1, noise_kernels.cpp), the shaders' noise() and pnoise().
void BM_Noise(benchmark::State& state) {
    BenchGrid g;
    std::vector<float> xyz[3], out(size_t(g.grid.n));
    for (const Vec3f& p : g.P)
        for (int k = 0; k < 3; ++k) xyz[k].push_back(p[k] * 3.7f);
    const float* p[3] = {xyz[0].data(), xyz[1].data(), xyz[2].data()};
    const NoisePointsFn noise = state.range(0) ? noisePointsKernel() : noisePointsScalar();
    for (auto _ : state) {
        noise(3, p, nullptr, out.size(), 0, out.data());
        benchmark::DoNotOptimize(out.data());
    }
    state.counters["points/s"] = benchmark::Counter(double(state.iterations()) * g.grid.n, benchmark::Counter::kIsRate);
}

BENCHMARK(BM_Noise)->ArgName("kernel")->Arg(0)->Arg(1);
void gridArgs(benchmark::internal::Benchmark* b) {
    b->ArgNames({"grid", "lights"});
    for (int size : {16, 32})
        for (int lights : {2, 3}) b->Args({size, lights});
}

BENCHMARK(BM_ShadeMatte)->Apply(gridArgs);
BENCHMARK(BM_ShadeBuiltinMatte)->Apply(gridArgs);
BENCHMARK(BM_ShadePlastic)->Apply(gridArgs);
BENCHMARK(BM_ShadeBuiltinPlastic)->Apply(gridArgs);
BENCHMARK(BM_ShadeGround)->Apply(gridArgs);
BENCHMARK(BM_ShadeBark)->Apply(gridArgs);
BENCHMARK(BM_ShadeLeaf)->Apply(gridArgs);
BENCHMARK(BM_ShadeSky)->Apply(gridArgs);

}  // namespace
}  // namespace streyes
