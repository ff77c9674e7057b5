// noise, pnoise, cellnoise and random over the grid: float or triple results from 1 to 4
// dimensional inputs (a float, a point, and an optional extra float).
#include <cmath>

#include "shade/vm/noise.h"
#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

namespace {

// Gathers the input point i of (a [, b]) into p; returns the dimension count.
inline int gather(const RegView& a, const RegView* b, int i, float* p) {
    int dims = 0;
    for (int c = 0; c < a.comps; ++c) p[dims++] = a.at(c, i);
    if (b) p[dims++] = b->at(0, i);
    return dims;
}

// Channels differ by seed: color noise is three independent noises.
constexpr uint32_t kChannelSeed[3] = {0u, 0x68e31da4u, 0xb5297a4du};

template <class F>
void noiseOver(Exec& x, const Instr& in, F f) {
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]);
    RegView b;
    const bool hasB = in.a[2] >= 0;
    if (hasB) b = x.view(in.a[2]);
    float p[4];
    for (int i = 0; i < d.w; ++i) {
        const int dims = gather(a, hasB ? &b : nullptr, i, p);
        for (int c = 0; c < d.comps; ++c) d.comp(c)[i] = f(dims, p, kChannelSeed[c], i);
    }
}

}  // namespace

void noise(Exec& x, const Instr& in) {
    noiseOver(x, in, [](int dims, const float* p, uint32_t seed, int) { return gradientNoise(dims, p, nullptr, seed); });
}

void cellnoise(Exec& x, const Instr& in) {
    noiseOver(x, in, [](int dims, const float* p, uint32_t seed, int) { return cellNoise(dims, p, seed); });
}

void pnoise(Exec& x, const Instr& in) {
    RegView pa = x.view(in.a[3]);
    RegView pb;
    const bool hasB = in.a[4] >= 0;
    if (hasB) pb = x.view(in.a[4]);
    noiseOver(x, in, [&](int dims, const float* p, uint32_t seed, int i) {
        int period[4];
        int k = 0;
        for (int c = 0; c < pa.comps; ++c) period[k++] = std::max(1, int(std::lround(std::min(1e6f, std::max(1.0f, pa.at(c, i))))));
        if (hasB) period[k++] = std::max(1, int(std::lround(std::min(1e6f, std::max(1.0f, pb.at(0, i))))));
        (void)dims;
        return gradientNoise(k, p, period, seed);
    });
}

// A value in [0, 1) per point and call: a hash of the grid's seed, the point and the call.
void random(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]);
    const int call = x.vm.nextRandom();
    for (int i = 0; i < d.w; ++i)
        for (int c = 0; c < d.comps; ++c) {
            int32_t key[3] = {int32_t(x.grid.seed), i, call * 3 + c};
            d.comp(c)[i] = float(hashInts(key, 3, 0x2545f491u) >> 8) * (1.0f / 16777216.0f);
        }
}

}  // namespace streyes::sl::ops
