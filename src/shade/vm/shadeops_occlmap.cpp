// occlusion(mapname, P, N [, samples], ...): the map-based occlusion of Aqsis and early PRMan,
// read from the depth maps of a multi-map file through TextureSource::occlusionMap (one call per
// call site and grid). "raytrace" or an empty name is the ray-traced occlusion(P, N, ...).
// Options: "blur" (a fraction of each map's size), "bias" (0: Option "shadow" "bias"),
// "samples" (the positional count when not named). A map that cannot be read gives 0 (open sky)
// and is counted in stats().textureErrors, as shadow() is.
#include <cstring>
#include <string>
#include <vector>

#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

namespace {

thread_local std::vector<float> mscratch;

int firstLane(const Exec& x) {
    for (int i = 0; i < x.n; ++i)
        if (x.mask[i]) return i;
    return 0;
}

}  // namespace

void occlusionmap(Exec& x, const Instr& in) {
    const int32_t* r = x.extra(in.a[1]);
    const std::string& name = x.str(r[0]);
    if (name.empty() || name == "raytrace") {  // the traced form: the same layout after the name
        Instr traced = in;
        traced.a[1] = in.a[1] + 1;
        traced.a[2] = in.a[2] - 1;
        occlusion(x, traced);
        return;
    }
    const RegView d = x.view(in.a[0]);
    std::fill(d.comp(0), d.comp(0) + d.w, 0.0f);
    if (x.active == 0) return;
    const int count = in.a[2];
    const int k = r[1];
    const int lane = firstLane(x);
    TextureOptions o;
    o.shader = &x.prog.name;
    if (k >= 3) o.samples = x.view(r[4]).at(0, lane);
    for (int j = 2 + k; j + 1 < count; j += 2) {
        if (x.reg(r[j + 1]).type.isString()) continue;
        const std::string& opt = x.str(r[j]);
        const float v = x.view(r[j + 1]).at(0, lane);
        if (opt == "blur") o.sblur = o.tblur = v;
        else if (opt == "bias") o.bias = v;
        else if (opt == "samples") o.samples = v;
    }
    TextureSource* source = x.vm.textureSource();
    const int n = x.n;
    if (mscratch.size() < size_t(n) * 6) mscratch.resize(size_t(n) * 6);
    float* a = mscratch.data();
    DirectionQuery q;
    q.n = n;
    q.active = x.allOn() ? nullptr : x.mask;
    const float* normal[3];
    for (int j = 0; j < 2; ++j) {
        const RegView v = x.view(r[2 + j]);
        for (int c = 0; c < 3; ++c) {
            float* dst = a + size_t(3 * j + c) * size_t(n);
            if (v.varying) std::memcpy(dst, v.comp(c), sizeof(float) * size_t(n));
            else std::fill(dst, dst + n, v.comp(c)[0]);
            if (j == 0) q.R[c] = dst;
            else normal[c] = dst;
        }
    }
    const ValueRef& t = x.grid.globals[size_t(Global::time)];
    q.time = t.valid() ? t.at(0, 0) : 0.0f;
    if (!source || !source->occlusionMap(name, o, q, normal, d.comp(0))) {
        std::fill(d.comp(0), d.comp(0) + d.w, 0.0f);
        ++x.stats.textureErrors;
    }
}

}  // namespace streyes::sl::ops
