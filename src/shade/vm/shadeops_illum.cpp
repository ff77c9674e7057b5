// Lights: the illuminance loop (surface side), illuminate and solar (light side), and the
// lighting functions ambient, diffuse, specular, specularbrdf and phong (RI Spec 3.2, 15.6).
//
// Each light runs once per grid (ShadingVM::lightsAt), over all of the surface's points; its
// L (turned to point from the surface towards the light), Cl and the points its illuminate or
// solar reached are then read by every loop and function of the surface.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "shade/vm/frame.h"
#include "shade/vm/grid_kernels.h"
#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

namespace {

constexpr float kPi = 3.14159265358979323846f;

bool inCategory(const LightResult& l, const std::string& cat) {
    if (cat.empty()) return true;
    const bool negate = cat[0] == '-';
    const std::string want = negate ? cat.substr(1) : cat;
    bool has = false;
    size_t start = 0;
    while (start <= l.category.size()) {
        size_t end = l.category.find(',', start);
        if (end == std::string::npos) end = l.category.size();
        std::string item = l.category.substr(start, end - start);
        while (!item.empty() && item.front() == ' ') item.erase(item.begin());
        while (!item.empty() && item.back() == ' ') item.pop_back();
        if (item == want) has = true;
        start = end + 1;
    }
    return negate ? !has : has;
}

// Is direction l within `angle` of axis a? (angle >= pi: every direction)
inline bool inCone(V3 l, V3 a, float angle) {
    if (angle >= kPi) return true;
    return dot3(normalize3(l), normalize3(a)) >= std::cos(angle);
}

// Point i's value of a light's L, Cl or Ln (one value for all points when it is uniform).
inline V3 lightVec(const LightResult& l, const std::vector<float>& v, size_t n, int i) {
    const size_t s = l.stride(n), k = l.at(i);
    return {v[k], v[s + k], v[2 * s + k]};
}

// Makes light k the one the illuminance level d runs for: its mask, L and Cl. False when it
// reaches none of the points that run.
bool enterLight(Exec& x, const Instr& in, const LightResult& l, int d) {
    Frame& f = x.frame;
    const size_t n = size_t(x.n);
    const uint8_t* below = f.mask(d - 1);
    const uint8_t* broke = f.cont(d);
    uint8_t* m = f.mask(d);
    const bool cone = in.a[2] >= 0;
    RegView axis, angle;
    if (cone) {
        axis = x.view(in.a[2]);
        angle = x.view(in.a[3]);
    }
    if (l.uniform && !l.lit[0]) return false;
    // A uniform light in a cone of uniform axis and angle: one test for all points.
    const bool oneCone = cone && l.uniform && !axis.varying && !angle.varying;
    const uint8_t inside = oneCone ? uint8_t(inCone(lightVec(l, l.L, n, 0), load3(axis, 0), angle.at(0, 0))) : 1;
    int any = 0;
    for (int i = 0; i < x.n; ++i) {
        uint8_t on = below[i] & uint8_t(!broke[i]) & l.lit[l.at(i)] & inside;
        if (on && cone && !oneCone) on = inCone(lightVec(l, l.L, n, i), load3(axis, i), angle.at(0, i)) ? 1 : 0;
        m[i] = on;
        any |= on;
    }
    if (!any) return false;
    RegView L = x.view(x.prog.globalReg[int(Global::L)]), Cl = x.view(x.prog.globalReg[int(Global::Cl)]);
    for (int c = 0; c < 3; ++c) {
        float* lp = L.comp(c);
        float* cp = Cl.comp(c);
        const float* ls = l.L.data() + size_t(c) * l.stride(n);
        const float* cs = l.Cl.data() + size_t(c) * l.stride(n);
        if (l.uniform) {
            const float lv = ls[0], cv = cs[0];
            for (int i = 0; i < x.n; ++i)
                if (m[i]) {
                    lp[i] = lv;
                    cp[i] = cv;
                }
            continue;
        }
        for (int i = 0; i < x.n; ++i)
            if (m[i]) {
                lp[i] = ls[i];
                cp[i] = cs[i];
            }
    }
    x.vm.setCurrentLight(&l);
    return true;
}

// The next light after `from` that the loop visits and that reaches a point, or -1.
int nextLight(Exec& x, const Instr& in, const std::vector<LightResult>& lights, size_t count, int from, int d) {
    static const std::string all;
    const std::string& cat = in.a[0] >= 0 ? x.str(in.a[0]) : all;
    for (int k = from + 1; k < int(count); ++k) {
        const LightResult& l = lights[size_t(k)];
        if (l.ambient || !inCategory(l, cat)) continue;
        if (enterLight(x, in, l, d)) return k;
    }
    return -1;
}

}  // namespace

void illumBegin(Exec& x, const Instr& in) {
    const std::vector<LightResult>& lights = x.vm.lightsAt(x, x.view(in.a[1]));
    const size_t count = x.vm.lightCount();
    Frame& f = x.frame;
    const int d = f.depth + 1;
    std::memset(f.cont(d), 0, size_t(x.n));
    int k = nextLight(x, in, lights, count, -1, d);
    if (k < 0) {
        x.pc = in.a[4];
        return;
    }
    f.lightIndex[size_t(d)] = k;
    setLevel(x, d);
}

void illumNext(Exec& x, const Instr& in) {
    const std::vector<LightResult>& lights = x.vm.lightsAt(x, x.view(in.a[1]));
    Frame& f = x.frame;
    const int d = f.depth;
    int k = nextLight(x, in, lights, x.vm.lightCount(), f.lightIndex[size_t(d)], d);
    if (k < 0) {
        x.vm.setCurrentLight(nullptr);
        setLevel(x, d - 1);
        return;
    }
    f.lightIndex[size_t(d)] = k;
    setLevel(x, d);
    x.pc = in.a[4];
}

// Light side: illuminate(from [, axis, angle]): L = Ps - from where Ps is in the cone.
void illuminate(Exec& x, const Instr& in) {
    Frame& f = x.frame;
    const int d = f.depth + 1;
    RegView from = x.view(in.a[0]), Ps = x.view(x.prog.globalReg[int(Global::Ps)]);
    RegView L = x.view(x.prog.globalReg[int(Global::L)]);
    const bool cone = in.a[1] >= 0;
    RegView axis, angle;
    if (cone) {
        axis = x.view(in.a[1]);
        angle = x.view(in.a[2]);
    }
    uint8_t* lit = x.vm.lit(x.n);
    const uint8_t* below = f.mask(d - 1);
    uint8_t* m = f.mask(d);
    for (int i = 0; i < x.n; ++i) {
        V3 l = sub3(load3(Ps, i), load3(from, i));
        uint8_t on = below[i];
        if (on && cone) on = inCone(l, load3(axis, i), angle.at(0, i)) ? 1 : 0;
        m[i] = on;
        if (on) {
            store3(L, i, l);
            lit[i] = 1;
        }
    }
    x.vm.illuminateFrom = in.a[0];
    setLevel(x, d);
    if (x.active == 0) x.pc = in.a[3];
}

// solar([axis, angle]): light along axis (from everywhere without one: against the normal).
void solar(Exec& x, const Instr& in) {
    Frame& f = x.frame;
    const int d = f.depth + 1;
    RegView L = x.view(x.prog.globalReg[int(Global::L)]);
    const bool hasAxis = in.a[0] >= 0;
    RegView axis, N;
    if (hasAxis) axis = x.view(in.a[0]);
    else if (x.prog.globalReg[int(Global::N)] >= 0) N = x.view(x.prog.globalReg[int(Global::N)]);
    uint8_t* lit = x.vm.lit(x.n);
    const uint8_t* below = f.mask(d - 1);
    uint8_t* m = f.mask(d);
    for (int i = 0; i < x.n; ++i) {
        m[i] = below[i];
        if (!m[i]) continue;
        V3 l = hasAxis ? load3(axis, i) : (N.p ? mul3(load3(N, i), -1.0f) : V3{0, 0, 0});
        store3(L, i, l);
        lit[i] = 1;
    }
    if (hasAxis)
        for (int i = 0; i < x.n; ++i)
            if (m[i]) {
                const V3 a = load3(axis, i);
                x.vm.solarSeen = {true, !x.varying(in.a[0]) && (in.a[1] < 0 || !x.varying(in.a[1])),
                                   Vec3f{a.x, a.y, a.z}, in.a[1] >= 0 ? x.view(in.a[1]).at(0, i) : 0.0f};
                break;
            }
    x.vm.solarAxis = in.a[0];
    setLevel(x, d);
    if (x.active == 0) x.pc = in.a[2];
}

// ---- Lighting functions ------------------------------------------------------------------------------

void ambient(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]);
    const std::vector<LightResult>& lights = x.vm.lightsAt(x, x.view(in.a[1]));
    const size_t n = size_t(x.n);
    for (int c = 0; c < 3; ++c) std::memset(d.comp(c), 0, sizeof(float) * size_t(d.w));
    for (size_t k = 0; k < x.vm.lightCount(); ++k) {
        const LightResult& l = lights[k];
        if (!l.ambient) continue;
        for (int c = 0; c < 3; ++c) {
            float* out = d.comp(c);
            const float* cl = l.Cl.data() + size_t(c) * l.stride(n);
            if (l.uniform) {
                const float v = cl[0];
                for (int i = 0; i < d.w; ++i) out[i] += v;
                continue;
            }
            for (int i = 0; i < d.w; ++i) out[i] += cl[i];
        }
    }
}

namespace {

// Sum over the lights that illuminate the points, within 90 degrees of N, of Cl times
// term(normalized L, N, point). N is normalised once for all lights (for the cone test).
thread_local std::vector<float> unitN, termBuf;

// Zeroes d, normalises N into unitN, then calls each(light, its lanes, unit normal) for every
// light the function sums over.
template <class Each>
void forLights(Exec& x, const RegView& d, const RegView& N, int Preg, bool specularOnes, Each each) {
    const std::vector<LightResult>& lights = x.vm.lightsAt(x, x.view(Preg));
    const size_t n = size_t(x.n);
    if (unitN.size() < 3 * n) unitN.resize(3 * n);
    float* const u[3] = {unitN.data(), unitN.data() + n, unitN.data() + 2 * n};
    if (N.comps == 3) {
        const float* const np[3] = {N.comp(0), N.comp(1), N.comp(2)};
        x.vm.kernels().normalize(size_t(d.w), np, N.varying, u);
    } else {
        for (int i = 0; i < d.w; ++i) {
            V3 v = normalize3(load3(N, i));
            u[0][i] = v.x;
            u[1][i] = v.y;
            u[2][i] = v.z;
        }
    }
    for (int c = 0; c < 3; ++c) std::memset(d.comp(c), 0, sizeof(float) * size_t(d.w));
    for (size_t k = 0; k < x.vm.lightCount(); ++k) {
        const LightResult& l = lights[k];
        if (l.ambient || (specularOnes ? l.nonSpecular : l.nonDiffuse)) continue;
        if (l.uniform && !l.lit[0]) continue;  // reaches no point
        const size_t s = l.stride(n);
        const LightLanes lanes{{l.Ln.data(), l.Ln.data() + s, l.Ln.data() + 2 * s},
                               {l.Cl.data(), l.Cl.data() + s, l.Cl.data() + 2 * s},
                               l.lit.data(),
                               !l.uniform};
        each(l, lanes, u);
    }
}

const float kCosHalf = std::cos(kPi / 2);

template <class Term>
void sumLights(Exec& x, const RegView& d, const RegView& N, int Preg, bool specularOnes, Term term) {
    float* out0 = d.comp(0);
    float* out1 = d.comp(1);
    float* out2 = d.comp(2);
    forLights(x, d, N, Preg, specularOnes, [&](const LightResult&, const LightLanes& l, float* const* u) {
        for (int i = 0; i < d.w; ++i) {
            const size_t j = l.varying ? size_t(i) : 0;
            if (!l.lit[j]) continue;
            const V3 ln{l.Ln[0][j], l.Ln[1][j], l.Ln[2][j]};
            if (ln.x * u[0][i] + ln.y * u[1][i] + ln.z * u[2][i] < kCosHalf) continue;
            const float t = term(ln, i);
            if (t <= 0) continue;
            out0[i] += l.Cl[0][j] * t;
            out1[i] += l.Cl[1][j] * t;
            out2[i] += l.Cl[2][j] * t;
        }
    });
}

// specularbrdf: pow(max(0, N.H), k / roughness), H = normalize(L + V), k the VM's specular
// exponent: 8 PRMan's highlight (the default), 1 the RI Spec 3.2's formula. A roughness below
// 1e-4 counts as 1e-4 (no division by zero).
inline float specularTerm(V3 l, V3 n, V3 v, float roughness, float k) {
    V3 h = normalize3(add3(l, v));
    return std::pow(std::max(0.0f, dot3(n, h)), k / std::max(roughness, 1e-4f));
}

}  // namespace

// diffuse and specular over whole grids (grid_kernels.h); a uniform result or a float N or V
// (broadcast) takes the point-by-point loop.
void diffuse(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), N = x.view(in.a[1]);
    if (!d.varying || N.comps != 3) {
        sumLights(x, d, N, in.a[2], false, [&](V3 l, int i) { return dot3(l, load3(N, i)); });
        return;
    }
    const float* const np[3] = {N.comp(0), N.comp(1), N.comp(2)};
    float* const out[3] = {d.comp(0), d.comp(1), d.comp(2)};
    const GridKernels& kern = x.vm.kernels();
    forLights(x, d, N, in.a[2], false, [&](const LightResult&, const LightLanes& l, float* const* u) {
        kern.diffuseLight(size_t(d.w), l, kCosHalf, u, np, N.varying, out);
    });
}

void specular(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), N = x.view(in.a[1]), V = x.view(in.a[2]), r = x.view(in.a[3]);
    const float k = x.vm.specularExponent();
    if (!d.varying || N.comps != 3 || V.comps != 3) {
        sumLights(x, d, N, in.a[4], true,
                  [&](V3 l, int i) { return specularTerm(l, load3(N, i), load3(V, i), r.at(0, i), k); });
        return;
    }
    const float* const np[3] = {N.comp(0), N.comp(1), N.comp(2)};
    const float* const vp[3] = {V.comp(0), V.comp(1), V.comp(2)};
    float* const out[3] = {d.comp(0), d.comp(1), d.comp(2)};
    const GridKernels& kern = x.vm.kernels();
    const size_t n = size_t(d.w);
    if (termBuf.size() < n) termBuf.resize(n);
    float* t = termBuf.data();
    // The exponent is uniform in nearly every shader: computed once then.
    const float e0 = k / std::max(r.at(0, 0), 1e-4f);
    forLights(x, d, N, in.a[4], true, [&](const LightResult&, const LightLanes& l, float* const* u) {
        kern.specularBase(n, l, kCosHalf, u, np, N.varying, vp, V.varying, t);
        // pow point by point (std::pow: the same on every machine); -1 marks points left out.
        for (size_t i = 0; i < n; ++i) {
            const float e = r.varying ? k / std::max(r.p[i], 1e-4f) : e0;
            t[i] = t[i] < 0 ? 0.0f : std::pow(t[i], e);
        }
        kern.addLight(n, l.Cl, l.varying, t, out);
    });
}

void phong(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), N = x.view(in.a[1]), V = x.view(in.a[2]), size = x.view(in.a[3]);
    sumLights(x, d, N, in.a[4], true, [&](V3 l, int i) {
        V3 nn = normalize3(load3(N, i)), vv = normalize3(load3(V, i));
        V3 r = sub3(mul3(vv, -1.0f), mul3(nn, 2.0f * dot3(mul3(vv, -1.0f), nn)));  // reflect(-V, N)
        return std::pow(std::max(0.0f, dot3(r, l)), size.at(0, i));
    });
}

void specularbrdf(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), L = x.view(in.a[1]), N = x.view(in.a[2]), V = x.view(in.a[3]), r = x.view(in.a[4]);
    const float k = x.vm.specularExponent();
    for (int i = 0; i < d.w; ++i) {
        float t = specularTerm(load3(L, i), load3(N, i), load3(V, i), r.at(0, i), k);
        store3(d, i, {t, t, t});
    }
}

// lightsource(name, var): inside an illuminance loop, the current light's output parameter.
void lightsource(Exec& x, const Instr& in) {
    float* flag = x.ptr(in.a[0]);
    flag[0] = 0;
    const LightResult* l = x.vm.currentLight();
    if (!l || !l->shader) return;
    const ShaderProgram& lp = l->shader->program();
    const int k = lp.paramIndex(x.str(in.a[1]));
    if (k < 0 || l->outOffset[size_t(k)] < 0) return;
    const ParamInfo& info = lp.params[size_t(k)];
    RegView out = x.view(in.a[2]);
    if (info.type.isString() || out.comps * out.elems != info.type.comps() * info.type.elements()) return;
    const float* src = l->outFloats.data() + l->outOffset[size_t(k)];
    const bool varying = l->outVarying[size_t(k)] != 0;
    for (int c = 0; c < out.comps * out.elems; ++c)
        for (int i = 0; i < out.w; ++i) out.p[size_t(c) * size_t(out.w) + size_t(i)] = varying ? src[size_t(c) * size_t(x.n) + size_t(i)] : src[c];
    flag[0] = 1;
}

}  // namespace streyes::sl::ops
