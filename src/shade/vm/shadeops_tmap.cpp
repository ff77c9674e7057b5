// texture(), environment() and shadow(): one TextureSource call per call site and grid, with
// each point's footprint from its neighbours on the grid (or from the four corners given).
// Without a source, or when it refuses the name, results are the "fill" value (0 for shadow:
// unoccluded) and the refusal is counted in stats().textureErrors. shadow("raytrace") is 0
// without asking a source: the renderer traces that light's shadow rays itself, per sample at
// the sample's time (geom/lights.h), and the shader's light must reach the surface unshadowed.
#include <algorithm>
#include <cstring>
#include <vector>

#include "shade/vm/deriv.h"
#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

namespace {

thread_local std::vector<float> tscratch;

float* scratchArrays(int n, int count) {
    const size_t need = size_t(n) * size_t(count);
    if (tscratch.size() < need) tscratch.resize(need);
    return tscratch.data();
}

int firstActive(const Exec& x) {
    for (int i = 0; i < x.n; ++i)
        if (x.mask[i]) return i;
    return 0;
}

// Options after the coordinates: (name, value) pairs. Values are taken at the first point
// that runs (they are meant to be uniform).
TextureOptions options(Exec& x, const int32_t* r, int begin, int count) {
    TextureOptions o;
    const int lane = firstActive(x);
    for (int k = begin; k + 1 < count; k += 2) {
        const std::string& name = x.str(r[k]);
        if (name == "filter") {
            o.filter = x.str(r[k + 1]);
            continue;
        }
        const float v = x.view(r[k + 1]).at(0, lane);
        if (name == "blur") o.sblur = o.tblur = v;
        else if (name == "sblur") o.sblur = v;
        else if (name == "tblur") o.tblur = v;
        else if (name == "width") o.swidth = o.twidth = v;
        else if (name == "swidth") o.swidth = v;
        else if (name == "twidth") o.twidth = v;
        else if (name == "fill") o.fill = v;
        else if (name == "samples") o.samples = v;
        else if (name == "bias") o.bias = v;
    }
    return o;
}

void copyComp(const RegView& v, int c, int n, float* out) {
    if (v.varying) std::memcpy(out, v.comp(c), sizeof(float) * size_t(n));
    else
        for (int i = 0; i < n; ++i) out[i] = v.comp(c)[0];
}

// Centre and footprint from one value per point (grid differences) or four corners.
void footprint(Exec& x, const int32_t* regs, int corners, int comp, float* centre, float* du, float* dv) {
    const int n = x.n;
    if (corners == 1) {
        RegView v = x.view(regs[0]);
        copyComp(v, comp, n, centre);
        if (v.varying) {
            diffU(x.grid, centre, du);
            diffV(x.grid, centre, dv);
        } else {
            std::memset(du, 0, sizeof(float) * size_t(n));
            std::memset(dv, 0, sizeof(float) * size_t(n));
        }
        return;
    }
    RegView a = x.view(regs[0]), b = x.view(regs[1]), c = x.view(regs[2]), d = x.view(regs[3]);
    for (int i = 0; i < n; ++i) {
        float v1 = a.at(comp, i), v2 = b.at(comp, i), v3 = c.at(comp, i), v4 = d.at(comp, i);
        centre[i] = 0.25f * (v1 + v2 + v3 + v4);
        du[i] = 0.5f * ((v2 - v1) + (v4 - v3));
        dv[i] = 0.5f * ((v3 - v1) + (v4 - v2));
    }
}

void fill(const RegView& d, float v) {
    for (int c = 0; c < d.comps; ++c)
        for (int i = 0; i < d.w; ++i) d.comp(c)[i] = v;
}

float timeOf(const Exec& x) {
    const ValueRef& t = x.grid.globals[size_t(Global::time)];
    return t.valid() ? t.at(0, 0) : 0.0f;
}

enum class Lookup { Texture, Environment, Shadow };

// environment("raytrace", R): the colour seen from P along R, as trace() gives it (the first
// of the four directions of the four-corner form). A float lookup takes the first channel.
void rayEnvironment(Exec& x, int rReg, const TextureOptions& opt, const RegView& d) {
    RaySource* rays = x.vm.raySource();
    if (!rays) {
        ++x.stats.raysMissing;
        return;
    }
    const int n = x.n;
    float* a = scratchArrays(n, 9);
    const int preg = x.prog.globalReg[size_t(Global::P)];
    const ValueRef& gp = x.grid.globals[size_t(Global::P)];
    RegView R = x.view(rReg);
    RayQuery q;
    q.n = n;
    q.active = x.allOn() ? nullptr : x.mask;
    for (int c = 0; c < 3; ++c) {
        float* p = a + size_t(c) * size_t(n);
        float* r = a + size_t(3 + c) * size_t(n);
        if (preg >= 0) copyComp(x.view(preg), c, n, p);
        else
            for (int i = 0; i < n; ++i) p[i] = gp.valid() ? gp.at(c, i) : 0.0f;
        copyComp(R, c, n, r);
        q.P[c] = p;
        q.D[c] = r;
    }
    q.time = x.grid.time;
    q.seed = x.grid.seed;
    q.site = uint32_t(x.pc);
    RayOptions o;
    if (opt.samples > 0) o.samples = opt.samples;
    if (opt.bias > 0) o.bias = opt.bias;
    if (opt.sblur > 0) o.coneangle = opt.sblur;  // a blurred lookup: rays over a cone of that half-angle
    float* out[3] = {a + 6 * size_t(n), a + 7 * size_t(n), a + 8 * size_t(n)};
    for (int c = 0; c < 3; ++c) std::fill(out[c], out[c] + n, 0.0f);
    rays->trace(o, q, out);
    for (int c = 0; c < d.comps; ++c) std::memcpy(d.comp(c), out[std::min(2, opt.firstChannel + c)], sizeof(float) * size_t(n));
}

void lookup(Exec& x, const Instr& in, Lookup kind) {
    RegView d = x.view(in.a[0]);
    const int32_t* r = x.extra(in.a[1]);
    const int count = in.a[2];
    const std::string& name = x.str(r[0]);
    const int k = r[2];
    TextureOptions opt = options(x, r, 3 + k, count);
    opt.channels = d.comps;
    opt.shader = &x.prog.name;
    if (r[1] >= 0) opt.firstChannel = std::max(0, int(x.view(r[1]).at(0, firstActive(x))));
    float* out[3] = {d.comp(0), d.comps > 1 ? d.comp(1) : nullptr, d.comps > 2 ? d.comp(2) : nullptr};
    TextureSource* source = x.vm.textureSource();
    const float fillValue = kind == Lookup::Shadow ? 0.0f : opt.fill;
    fill(d, fillValue);
    if (x.active == 0) return;
    if (kind == Lookup::Shadow && name == "raytrace") return;  // traced per sample by the renderer
    if (kind == Lookup::Environment && name == "raytrace") {
        rayEnvironment(x, r[3], opt, d);
        return;
    }
    bool ok = false;
    const int n = x.n;
    if (source && !name.empty()) {
        if (kind == Lookup::Texture) {
            float* a = scratchArrays(n, 6);
            TextureQuery q;
            q.n = n;
            q.active = x.allOn() ? nullptr : x.mask;
            const int corners = k == 2 ? 1 : 4;
            int32_t sregs[4] = {r[3], r[3] + 0, 0, 0}, tregs[4] = {r[4], 0, 0, 0};
            if (corners == 4)
                for (int c = 0; c < 4; ++c) {
                    sregs[c] = r[3 + 2 * c];
                    tregs[c] = r[4 + 2 * c];
                }
            footprint(x, sregs, corners, 0, a, a + n, a + 2 * n);
            footprint(x, tregs, corners, 0, a + 3 * n, a + 4 * n, a + 5 * n);
            q.s = a;
            q.dsdu = a + n;
            q.dsdv = a + 2 * n;
            q.t = a + 3 * n;
            q.dtdu = a + 4 * n;
            q.dtdv = a + 5 * n;
            q.time = timeOf(x);
            ok = source->texture(name, opt, q, out);
        } else {
            float* a = scratchArrays(n, 15);
            DirectionQuery q;
            q.n = n;
            q.active = x.allOn() ? nullptr : x.mask;
            for (int c = 0; c < 3; ++c) {
                footprint(x, r + 3, k == 1 ? 1 : 4, c, a + size_t(c) * n, a + size_t(3 + c) * n, a + size_t(6 + c) * n);
                q.R[c] = a + size_t(c) * n;
                q.dRdu[c] = a + size_t(3 + c) * n;
                q.dRdv[c] = a + size_t(6 + c) * n;
            }
            if (kind == Lookup::Shadow) {
                const int light = x.vm.illuminateFrom >= 0 ? x.vm.illuminateFrom : x.vm.solarAxis;
                if (light >= 0) {
                    RegView l = x.view(light);
                    for (int c = 0; c < 3; ++c) {
                        copyComp(l, c, n, a + size_t(9 + c) * n);
                        (x.vm.illuminateFrom >= 0 ? q.lightFrom : q.lightDir)[c] = a + size_t(9 + c) * n;
                    }
                }
            }
            q.time = timeOf(x);
            ok = kind == Lookup::Environment ? source->environment(name, opt, q, out) : source->shadow(name, opt, q, out);
        }
    }
    if (!ok) {
        fill(d, fillValue);
        if (!name.empty()) ++x.stats.textureErrors;
    }
}

}  // namespace

void texture(Exec& x, const Instr& in) { lookup(x, in, Lookup::Texture); }
void environment(Exec& x, const Instr& in) { lookup(x, in, Lookup::Environment); }
void shadow(Exec& x, const Instr& in) { lookup(x, in, Lookup::Shadow); }

}  // namespace streyes::sl::ops
