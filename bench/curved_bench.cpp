// Google Benchmark kernels of curved bodies: dicing each kind of face, the split loop over a
// bicubic mesh (with its edge lattices), and building a subdivision surface.
//
//   build/streyes_bench --benchmark_filter=Curved
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "geom/curved_body.h"
#include "geom/grid.h"
#include "geom/patch_mesh.h"
#include "geom/quadric.h"
#include "shade/shading.h"
#include "geom/subdivision.h"
#include "split_loop.h"

namespace streyes {
namespace {

Camera benchCamera() {
    CameraDesc cd;
    cd.projection = ProjectionKind::Perspective;
    cd.fov = 40;
    cd.xres = 640;
    cd.yres = 360;
    return Camera(cd);
}

// A cube cage with one corner pulled out and a crease, in front of the camera.
SubdivisionMeshDesc cubeCage() {
    SubdivisionMeshDesc d;
    d.faceSizes = {4, 4, 4, 4, 4, 4};
    d.faceVertices = {0, 1, 3, 2, 2, 3, 5, 4, 4, 5, 7, 6, 6, 7, 1, 0, 1, 7, 5, 3, 6, 0, 2, 4};
    d.vertexCount = 8;
    d.P = {{{-1, -1, 1}, {1, -1, 1}, {-1, 1, 1}, {1.6, 1.3, 1.4}, {-1, 1, -1}, {1, 1, -1}, {-1, -1, -1}, {1, -1, -1}}};
    for (Vec3d& p : d.P[0]) p.z += 6;
    d.creaseEdges = {1, 3};
    d.creaseSharpness = {2};
    return d;
}

struct Meshes {
    Camera camera = benchCamera();
    Material material;
    std::unique_ptr<SurfaceMesh> bezier, quadric, subdivision;
    Meshes() {
        PatchMeshDesc d;
        d.nu = d.nv = 4;
        d.P.resize(1);
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) d.P[0].push_back({i - 1.5, j - 1.5, 6 + 0.5 * std::sin(i + j)});
        PatchMeshShape shape(d);
        bezier = std::make_unique<BezierMesh>(shape.topology(), TimeSpan{0, 1}, &material, &camera,
                                              shape.patches(d.P[0]), std::vector<BezierPatch>{},
                                              shape.colors({}, Color{1, 1, 1}));
        const QuadricMesh::Params p[2] = {{2, -2, 2, 360}, {2, -2, 2, 360}};
        const Matrix4 m[2] = {Matrix4::translate({0, 0, 8}), Matrix4::translate({0, 0, 8})};
        quadric = std::make_unique<QuadricMesh>(QuadricKind::Sphere, p, m, TimeSpan{0, 1}, &material, &camera,
                                                std::array<Color, 4>{});
        auto sd = std::make_shared<SubdivisionShape>(cubeCage());
        auto key = sd->key(cubeCage().P[0]);
        subdivision = std::make_unique<SubdivisionMesh>(sd, key, key, TimeSpan{0, 1}, &material, &camera,
                                                        sd->colors({}, Color{1, 1, 1}));
    }
};

// Dicing a grid-sized piece of a face (its first half, split until the split loop's decision is
// to dice it: at most 256 micropolygons) at the rate that decision asks for.
// Arguments: 0 Bezier patch, 1 sphere, 2 regular subdivision face, 3 irregular subdivision face.
void BM_CurvedDice(benchmark::State& state) {
    static Meshes meshes;
    const SurfaceMesh* mesh = state.range(0) == 0   ? meshes.bezier.get()
                              : state.range(0) == 1 ? meshes.quadric.get()
                                                    : meshes.subdivision.get();
    int face = 0;
    if (state.range(0) >= 2) {
        const auto& sd = static_cast<const SubdivisionMesh&>(*mesh);
        for (int f = 0; f < sd.faceCount(); ++f)
            if (sd.regular(f) == (state.range(0) == 2)) face = f;
    }
    BodyPtr piece = CurvedBody(mesh, face).restrictedTo(0, 1);
    const RenderOptions options;
    SplitDecision d;
    while (!(d = decideSplit(*piece, piece->measure(meshes.camera), options, 1.0)).dice) {
        BodyPtr h[2];
        piece->split(d.axis, h);
        piece = std::move(h[0]);
    }
    const int nu = d.nu, nv = d.nv;
    Grid g;
    uint64_t micropolygons = 0;
    for (auto _ : state) {
        piece->dice(nu, nv, g);
        micropolygons += uint64_t(g.nu * g.nv);
        benchmark::DoNotOptimize(g.P[0].data());
    }
    state.counters["micropolygons/s"] = benchmark::Counter(double(micropolygons), benchmark::Counter::kIsRate);
    state.counters["grid"] = double(g.nu * g.nv);
}
BENCHMARK(BM_CurvedDice)->ArgName("kind")->Arg(0)->Arg(1)->Arg(2)->Arg(3);

// The split loop over the sphere: measures, splits with their corners and lattices, down to
// grids of at most 256 micropolygons.
void BM_CurvedSplitLoop(benchmark::State& state) {
    static Meshes meshes;
    CurvedBody root(meshes.quadric.get(), 0);
    const RenderOptions options;
    std::vector<BodyPtr> stack;
    uint64_t splits = 0, grids = 0;
    for (auto _ : state) splitToGrids(root, meshes.camera, options, 1.0, stack, splits, grids);
    state.counters["splits/s"] = benchmark::Counter(double(splits), benchmark::Counter::kIsRate);
    state.counters["grids"] = double(grids) / double(state.iterations());
}
BENCHMARK(BM_CurvedSplitLoop);

// Building a subdivision surface: topology, refinement, Bfr surfaces and leaves (once per mesh),
// then the limit surface for one set of positions (once per motion key).
void BM_SubdivisionBuild(benchmark::State& state) {
    const SubdivisionMeshDesc d = cubeCage();
    for (auto _ : state) {
        SubdivisionShape shape(d);
        auto key = shape.key(d.P[0]);
        benchmark::DoNotOptimize(key.get());
    }
}
BENCHMARK(BM_SubdivisionBuild);

void BM_SubdivisionKey(benchmark::State& state) {
    const SubdivisionMeshDesc d = cubeCage();
    SubdivisionShape shape(d);
    for (auto _ : state) {
        auto key = shape.key(d.P[0]);
        benchmark::DoNotOptimize(key.get());
    }
    state.counters["faces/s"] =
        benchmark::Counter(double(shape.faceCount()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SubdivisionKey);

}  // namespace
}  // namespace streyes
