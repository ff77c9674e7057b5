// noise, pnoise, cellnoise and random over the grid: float or triple results from 1 to 4
// dimensional inputs (a float, a point, and an optional extra float).
#include <algorithm>
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

// A pnoise period: rounded, in [1, 1e6].
inline int32_t periodOf(float v) { return std::max(1, int(std::lround(std::min(1e6f, std::max(1.0f, v))))); }

// Gradient noise over the grid through the SIMD kernel (gradientNoisePoints), kChunk points at
// a time: each coordinate (and period) a run of values, a uniform input's repeated. pa, pb: the
// periods of pnoise (of a's coordinates, and of b's), null for noise().
void gradientNoiseOver(Exec& x, const Instr& in, const RegView* pa, const RegView* pb) {
    constexpr int kChunk = 64;
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]);
    RegView b;
    const bool hasB = in.a[2] >= 0;
    if (hasB) b = x.view(in.a[2]);
    const int dims = a.comps + (hasB ? 1 : 0);
    float fill[4][kChunk], noise[3][kChunk];
    int32_t period[4][kChunk];
    const float* coord[4];
    const int32_t* periods[4] = {period[0], period[1], period[2], period[3]};
    for (int i0 = 0; i0 < d.w; i0 += kChunk) {
        const int n = std::min(kChunk, d.w - i0);
        for (int k = 0; k < dims; ++k) {
            const RegView& r = k < a.comps ? a : b;
            const int c = k < a.comps ? k : 0;
            if (r.varying) {
                coord[k] = r.comp(c) + i0;
            } else {
                std::fill(fill[k], fill[k] + n, r.at(c, 0));
                coord[k] = fill[k];
            }
            if (!pa) continue;
            const RegView& pr = k < pa->comps ? *pa : *pb;
            const int pc = k < pa->comps ? k : 0;
            if (pr.varying)
                for (int i = 0; i < n; ++i) period[k][i] = periodOf(pr.at(pc, i0 + i));
            else
                std::fill(period[k], period[k] + n, periodOf(pr.at(pc, 0)));
        }
        // Every channel before any is written: the result may share a register with an input.
        for (int c = 0; c < d.comps; ++c)
            gradientNoisePoints(dims, coord, pa ? periods : nullptr, size_t(n), kChannelSeed[c], noise[c]);
        for (int c = 0; c < d.comps; ++c) std::copy(noise[c], noise[c] + n, d.comp(c) + i0);
    }
}

}  // namespace

void noise(Exec& x, const Instr& in) { gradientNoiseOver(x, in, nullptr, nullptr); }

void cellnoise(Exec& x, const Instr& in) {
    noiseOver(x, in, [](int dims, const float* p, uint32_t seed, int) { return cellNoise(dims, p, seed); });
}

void pnoise(Exec& x, const Instr& in) {
    RegView pa = x.view(in.a[3]);
    RegView pb;
    if (in.a[4] >= 0) pb = x.view(in.a[4]);
    gradientNoiseOver(x, in, &pa, &pb);
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
