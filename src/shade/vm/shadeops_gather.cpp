// gather(): one sample of a gather loop (the parser writes the loop; sl/parser.cpp parseGather).
// One RaySource call per sample and grid over the points that run; the outputs are written where
// the ray hit ("ray:direction" and "ray:origin" everywhere, for the else branch's environment).
#include <algorithm>
#include <cstring>
#include <vector>

#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

namespace {

thread_local std::vector<float> gscratch;
thread_local std::vector<uint8_t> ghit;

enum Field { kCi, kOi, kP, kN, kDir, kOrigin, kLength, kNone };

Field fieldOf(const std::string& name) {
    if (name == "surface:Ci") return kCi;
    if (name == "surface:Oi") return kOi;
    if (name == "surface:P") return kP;
    if (name == "surface:N") return kN;
    if (name == "ray:direction") return kDir;
    if (name == "ray:origin") return kOrigin;
    if (name == "ray:length") return kLength;
    return kNone;
}

}  // namespace

void gather(Exec& x, const Instr& in) {
    const RegView hit = x.view(in.a[0]);
    std::fill(hit.p, hit.p + hit.w, 0.0f);
    const int32_t* r = x.extra(in.a[1]);
    const int count = in.a[2];
    if (x.active == 0) return;
    int lane = 0;
    while (lane + 1 < x.n && !x.mask[lane]) ++lane;
    RayOptions o;
    o.shader = &x.prog.name;
    o.coneangle = x.view(r[3]).at(0, lane);
    o.samples = x.view(r[4]).at(0, lane);
    const int sample = int(x.view(r[5]).at(0, lane));
    for (int k = 6; k + 1 < count; k += 2) {
        const std::string& name = x.str(r[k]);
        if (name == "distribution") o.uniform = x.str(r[k + 1]) == "uniform";
        else if (name == "maxdist") o.maxdist = std::max(0.0f, x.view(r[k + 1]).at(0, lane));
        else if (name == "bias") o.bias = x.view(r[k + 1]).at(0, lane);
    }
    const int n = x.n;
    const size_t N = size_t(n);
    // P, D, then the hit's fields: dir, Ci, Oi, P, N (3 each), length.
    if (gscratch.size() < N * 19) gscratch.resize(N * 19);
    if (ghit.size() < N) ghit.resize(N);
    float* a = gscratch.data();
    RayQuery q;
    q.n = n;
    q.active = x.allOn() ? nullptr : x.mask;
    for (int j = 0; j < 2; ++j) {
        const RegView v = x.view(r[1 + j]);
        for (int c = 0; c < 3; ++c) {
            float* dst = a + size_t(3 * j + c) * N;
            if (v.varying) std::memcpy(dst, v.comp(c), sizeof(float) * N);
            else std::fill(dst, dst + n, v.comp(c)[0]);
            (j == 0 ? q.P : q.D)[c] = dst;
        }
    }
    q.time = x.grid.time;
    q.seed = x.grid.seed;
    q.site = uint32_t(x.pc);
    GatherHits g;
    g.hit = ghit.data();
    std::fill(g.hit, g.hit + n, uint8_t(0));
    float* const fields[5][3] = {{a + 6 * N, a + 7 * N, a + 8 * N}, {a + 9 * N, a + 10 * N, a + 11 * N},
                                 {a + 12 * N, a + 13 * N, a + 14 * N}, {a + 15 * N, a + 16 * N, a + 17 * N}, {}};
    for (int c = 0; c < 3; ++c) {
        g.dir[c] = fields[0][c];
        g.Ci[c] = fields[1][c];
        g.Oi[c] = fields[2][c];
        g.P[c] = fields[3][c];
    }
    g.length = a + 18 * N;
    static thread_local std::vector<float> gN;
    if (gN.size() < 3 * N) gN.resize(3 * N);
    for (int c = 0; c < 3; ++c) g.N[c] = gN.data() + size_t(c) * N;
    RaySource* source = x.vm.raySource();
    if (source) {
        source->gather(o, q, sample, g);
    } else {  // an empty scene: every ray misses, along D
        ++x.stats.raysMissing;
        RaySource::missAll(q, g);
    }
    for (int i = 0; i < n; ++i) hit.p[i] = x.mask[i] && g.hit[i] ? 1.0f : 0.0f;
    for (int k = 6; k + 1 < count; k += 2) {
        const Field f = fieldOf(x.str(r[k]));
        if (f == kNone) continue;
        const RegView out = x.view(r[k + 1]);  // a varying copy of the variable
        const bool everywhere = f == kDir || f == kOrigin;
        const float* src[3] = {};
        switch (f) {
            case kCi: src[0] = g.Ci[0], src[1] = g.Ci[1], src[2] = g.Ci[2]; break;
            case kOi: src[0] = g.Oi[0], src[1] = g.Oi[1], src[2] = g.Oi[2]; break;
            case kP: src[0] = g.P[0], src[1] = g.P[1], src[2] = g.P[2]; break;
            case kN: src[0] = g.N[0], src[1] = g.N[1], src[2] = g.N[2]; break;
            case kDir: src[0] = g.dir[0], src[1] = g.dir[1], src[2] = g.dir[2]; break;
            case kOrigin: src[0] = q.P[0], src[1] = q.P[1], src[2] = q.P[2]; break;
            case kLength: src[0] = g.length; break;
            case kNone: break;
        }
        for (int c = 0; c < out.comps; ++c)
            for (int i = 0; i < n; ++i)
                if (x.mask[i] && (everywhere || g.hit[i])) out.comp(c)[i] = src[c][i];
    }
}

}  // namespace streyes::sl::ops
