// Google Benchmark of point-based occlusion and colour bleeding: building the disc hierarchy of
// a cloud, and one shading point's microbuffer (draw and integrate) inside a closed box of
// 24576 discs, at microbufres 10 and 20, occlusion only and with colour.
//
//   build/streyes_bench --benchmark_filter=PointBased
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "shade/point_based_buffer.h"

namespace streyes {
namespace {

// A unit box [-1, 1]^3 of discs facing inward, 64 x 64 a face.
BakedPointCloud boxCloud() {
    std::vector<float> data;
    const int n = 64;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const int a = f / 2;
                const float s = f % 2 ? -1.0f : 1.0f;
                float p[3], nn[3] = {0, 0, 0};
                p[a] = s;
                p[(a + 1) % 3] = -1 + (i + 0.5f) * 2 / n;
                p[(a + 2) % 3] = -1 + (j + 0.5f) * 2 / n;
                nn[a] = -s;
                const float cell = 2.0f / n;
                const float rec[] = {p[0], p[1], p[2], nn[0], nn[1], nn[2], cell * 0.7072f, cell * cell, 0.5f, 0.6f, float(f) / 6};
                data.insert(data.end(), std::begin(rec), std::end(rec));
            }
    return BakedPointCloud({{"_area", 1}, {"_radiosity", 3}}, data);
}

void BM_PointBasedBuildHierarchy(benchmark::State& state) {
    const BakedPointCloud cloud = boxCloud();
    for (auto _ : state) {
        DiscHierarchy tree(cloud);
        benchmark::DoNotOptimize(tree.clusters().data());
    }
    state.SetItemsProcessed(state.iterations() * int64_t(cloud.size()));
}
BENCHMARK(BM_PointBasedBuildHierarchy);

// A point on the floor's inside, looking up; points spread over the floor.
void BM_PointBasedShadePoint(benchmark::State& state) {
    const DiscHierarchy tree(boxCloud());
    CubeMicrobuffer buffer;
    PointBasedSettings s;
    s.res = int(state.range(0));
    const bool colour = state.range(1) != 0;
    int k = 0;
    for (auto _ : state) {
        const float P[3] = {-0.9f + 1.8f * float(k % 17) / 16, -0.99999f, -0.9f + 1.8f * float((k / 17) % 17) / 16};
        const float N[3] = {0, 1, 0};
        float occ = 0, rgb[3];
        buffer.integrate(tree, P, N, s, &occ, colour ? rgb : nullptr);
        benchmark::DoNotOptimize(occ);
        ++k;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PointBasedShadePoint)->Args({10, 0})->Args({10, 1})->Args({20, 1});

}  // namespace
}  // namespace streyes
