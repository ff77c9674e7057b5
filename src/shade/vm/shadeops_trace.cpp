// occlusion(), indirectdiffuse(), trace() and transmission(): one RaySource call per call site
// and grid, over the points that run. Without a source the results are what an empty scene
// gives (occlusion 0, no light, transmission 1) and the call is counted in stats().raysMissing.
#include <algorithm>
#include <cstring>
#include <vector>

#include "shade/vm/ops.h"
#include "shade/vm/point_based_ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

namespace {

thread_local std::vector<float> rscratch;

int firstActive(const Exec& x) {
    for (int i = 0; i < x.n; ++i)
        if (x.mask[i]) return i;
    return 0;
}

enum class Call { Occlusion, Indirect, Trace, Transmission };

// Option pairs after the positional arguments. Names the code generator let through but no
// source reads ("adaptive", "label", ...) are ignored.
RayOptions options(Exec& x, const int32_t* r, int begin, int count) {
    RayOptions o;
    const int lane = firstActive(x);
    for (int k = begin; k + 1 < count; k += 2) {
        const std::string& name = x.str(r[k]);
        if (name == "environmentmap") {
            o.environmentmap = x.str(r[k + 1]);
            continue;
        }
        if (name == "environmentspace") {  // an unknown space is counted and warned as transform()'s
            if (x.reg(r[k + 1]).type.isString()) x.vm.currentToSpace(x.str(r[k + 1]), o.environmentFromCurrent);
            continue;
        }
        if (x.reg(r[k + 1]).type.isString()) continue;
        const float v = x.view(r[k + 1]).at(0, lane);
        if (name == "samples") o.samples = v;
        else if (name == "maxdist") o.maxdist = v > 0 ? v : 0.0f;
        else if (name == "coneangle") o.coneangle = v;
        else if (name == "bias") o.bias = v;
    }
    return o;
}

void ray(Exec& x, const Instr& in, Call call) {
    const RegView d = x.view(in.a[0]);
    const int32_t* r = x.extra(in.a[1]);
    const int count = in.a[2];
    const int k = r[0];
    const float empty = call == Call::Transmission ? 1.0f : 0.0f;
    for (int c = 0; c < d.comps; ++c) std::fill(d.comp(c), d.comp(c) + d.w, empty);
    if (x.active == 0) return;
    if ((call == Call::Occlusion || call == Call::Indirect) && pointBasedCall(x, in, call == Call::Indirect)) return;
    // The destination and the output options are varying (the code generator makes them so): n
    // floats a component, 0 (nothing hit, no map seen) unless the source writes them.
    // indirectdiffuse's "occlusion" is out[3]; occlusion()'s "environmentcolor" is env[1..3].
    float* out[4] = {d.comp(0), d.comps > 1 ? d.comp(1) : d.comp(0), d.comps > 2 ? d.comp(2) : d.comp(0), nullptr};
    float* env[4] = {d.comp(0), nullptr, nullptr, nullptr};
    const char* fn = call == Call::Indirect ? "indirectdiffuse" : call == Call::Occlusion ? "occlusion" : "";
    for (int j = 1 + k; j + 1 < count; j += 2) {
        if (!isRayOutputOption(fn, x.str(r[j]))) continue;
        const RegView v = x.view(r[j + 1]);
        for (int c = 0; c < v.comps; ++c) std::fill(v.comp(c), v.comp(c) + v.w, 0.0f);
        if (call == Call::Indirect) out[3] = v.comp(0);
        else
            for (int c = 0; c < 3; ++c) env[1 + c] = v.comp(std::min(c, v.comps - 1));
    }
    RaySource* source = x.vm.raySource();
    if (!source) {
        ++x.stats.raysMissing;
        return;
    }
    RayOptions o = options(x, r, 1 + k, count);
    o.shader = &x.prog.name;
    if ((call == Call::Occlusion || call == Call::Indirect) && k >= 3 && o.samples <= 0)
        o.samples = x.view(r[3]).at(0, firstActive(x));  // the positional count (the named one wins)
    const int n = x.n;
    if (rscratch.size() < size_t(n) * 6) rscratch.resize(size_t(n) * 6);
    float* a = rscratch.data();
    RayQuery q;
    q.n = n;
    q.active = x.allOn() ? nullptr : x.mask;
    for (int j = 0; j < 2; ++j) {
        const RegView v = x.view(r[1 + j]);
        for (int c = 0; c < 3; ++c) {
            float* dst = a + size_t(3 * j + c) * size_t(n);
            if (v.varying) std::memcpy(dst, v.comp(c), sizeof(float) * size_t(n));
            else std::fill(dst, dst + n, v.comp(c)[0]);
            (j == 0 ? q.P : q.D)[c] = dst;
        }
    }
    q.time = x.grid.time;
    q.seed = x.grid.seed;
    q.site = uint32_t(x.pc);
    switch (call) {
        case Call::Occlusion: source->occlusion(o, q, env); break;
        case Call::Indirect: source->indirectdiffuse(o, q, out); break;
        case Call::Trace: source->trace(o, q, out); break;
        case Call::Transmission: source->transmission(o, q, out); break;
    }
}

}  // namespace

void occlusion(Exec& x, const Instr& in) { ray(x, in, Call::Occlusion); }
void indirectdiffuse(Exec& x, const Instr& in) { ray(x, in, Call::Indirect); }
void trace(Exec& x, const Instr& in) { ray(x, in, Call::Trace); }
void transmission(Exec& x, const Instr& in) { ray(x, in, Call::Transmission); }

}  // namespace streyes::sl::ops
