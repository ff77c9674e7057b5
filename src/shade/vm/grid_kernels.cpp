// grid_kernels.h: the reference loops (once), then the Highway kernels (once per instruction set,
// foreach_target), which make the reference's operations in the same order on each lane.
#ifndef STREYES_GRID_KERNELS_REFERENCE
#define STREYES_GRID_KERNELS_REFERENCE

#include <algorithm>
#include <cmath>
#include <cstring>

#include "shade/vm/grid_kernels.h"

namespace streyes::sl::gridref {

// Points [b, e) of each loop: the scalar table runs them all, a SIMD kernel its tail.
inline size_t at(bool varying, size_t i) { return varying ? i : 0; }

inline void normalize(size_t b, size_t e, const float* const a[3], bool av, float* const out[3]) {
    for (size_t i = b; i < e; ++i) {
        const size_t k = at(av, i);
        const float x = a[0][k], y = a[1][k], z = a[2][k];
        const float l2 = x * x + y * y + z * z;
        if (!(l2 > 0) || !std::isfinite(l2)) {
            out[0][i] = out[1][i] = out[2][i] = 0;
            continue;
        }
        const float s = 1.0f / std::sqrt(l2);
        out[0][i] = x * s;
        out[1][i] = y * s;
        out[2][i] = z * s;
    }
}

inline void dot(size_t b, size_t e, const float* const a[3], bool av, const float* const c[3], bool cv, float* out) {
    for (size_t i = b; i < e; ++i) {
        const size_t p = at(av, i), q = at(cv, i);
        out[i] = a[0][p] * c[0][q] + a[1][p] * c[1][q] + a[2][p] * c[2][q];
    }
}

inline void faceforward(size_t b, size_t e, const float* const N[3], bool nv, const float* const I[3], bool iv,
                        const float* const ref[3], bool rv, float* const out[3]) {
    for (size_t i = b; i < e; ++i) {
        const size_t p = at(iv, i), q = at(rv, i), k = at(nv, i);
        const float d = I[0][p] * ref[0][q] + I[1][p] * ref[1][q] + I[2][p] * ref[2][q];
        const float s = d < 0 ? 1.0f : -1.0f;
        const float x = N[0][k], y = N[1][k], z = N[2][k];
        out[0][i] = d < 0 ? x : x * s;
        out[1][i] = d < 0 ? y : y * s;
        out[2][i] = d < 0 ? z : z * s;
    }
}

inline void divide(size_t b, size_t e, const float* a, bool av, const float* c, bool cv, float* out) {
    for (size_t i = b; i < e; ++i) {
        const float p = a[at(av, i)], q = c[at(cv, i)];
        out[i] = q == 0.0f ? 0.0f : p / q;
    }
}

// The map operations: f on each point, as shadeops_math.cpp's lambdas.
inline float addOf(float a, float c) { return a + c; }
inline float subOf(float a, float c) { return a - c; }
inline float mulOf(float a, float c) { return a * c; }
inline float minOf(float a, float c) { return std::min(a, c); }
inline float maxOf(float a, float c) { return std::max(a, c); }
inline float modOf(float a, float c) { return c == 0.0f ? 0.0f : a - c * std::floor(a / c); }
inline float filterstepOf(float edge, float s, float su, float sv, float wscale) {
    const float w = (std::fabs(su) + std::fabs(sv)) * wscale;
    const float lo = s - 0.5f * w, hi = s + 0.5f * w;
    return hi > lo ? std::min(1.0f, std::max(0.0f, (hi - edge) / (hi - lo))) : (s < edge ? 0.0f : 1.0f);
}
inline void filterstep(size_t b, size_t e, const float* edge, bool ev, const float* s, bool sv_, const float* su,
                       const float* sv, float wscale, float* out) {
    for (size_t i = b; i < e; ++i) out[i] = filterstepOf(edge[at(ev, i)], s[at(sv_, i)], su[i], sv[i], wscale);
}
inline float mixOf(float a, float c, float t) { return a * (1.0f - t) + c * t; }
inline float smoothstepOf(float e0, float e1, float v) {
    if (v <= e0) return 0.0f;
    if (v >= e1) return 1.0f;
    const float t = (v - e0) / (e1 - e0);
    return t * t * (3.0f - 2.0f * t);
}

template <float (*F)(float, float)>
inline void binary(size_t b, size_t e, const float* a, bool av, const float* c, bool cv, float* out) {
    for (size_t i = b; i < e; ++i) out[i] = F(a[at(av, i)], c[at(cv, i)]);
}

template <float (*F)(float, float, float)>
inline void ternary(size_t b, size_t e, const float* a, bool av, const float* c, bool cv, const float* d, bool dv,
                    float* out) {
    for (size_t i = b; i < e; ++i) out[i] = F(a[at(av, i)], c[at(cv, i)], d[at(dv, i)]);
}

// Whether light l takes part at point i: lit, and within 90 degrees of the unit normal.
inline bool facing(const LightLanes& l, float cosHalf, const float* const u[3], size_t i) {
    const size_t j = at(l.varying, i);
    return l.lit[j] && !(l.Ln[0][j] * u[0][i] + l.Ln[1][j] * u[1][i] + l.Ln[2][j] * u[2][i] < cosHalf);
}

inline void diffuseLight(size_t b, size_t e, const LightLanes& l, float cosHalf, const float* const u[3],
                         const float* const N[3], bool nv, float* const out[3]) {
    for (size_t i = b; i < e; ++i) {
        if (!facing(l, cosHalf, u, i)) continue;
        const size_t k = at(nv, i), j = at(l.varying, i);
        const float t = l.Ln[0][j] * N[0][k] + l.Ln[1][j] * N[1][k] + l.Ln[2][j] * N[2][k];
        if (t <= 0) continue;
        for (int c = 0; c < 3; ++c) out[c][i] += l.Cl[c][j] * t;
    }
}

inline void specularBase(size_t b, size_t e, const LightLanes& l, float cosHalf, const float* const u[3],
                         const float* const N[3], bool nv, const float* const V[3], bool vv, float* base) {
    for (size_t i = b; i < e; ++i) {
        if (!facing(l, cosHalf, u, i)) {
            base[i] = -1;
            continue;
        }
        const size_t k = at(nv, i), q = at(vv, i), j = at(l.varying, i);
        float h[3] = {l.Ln[0][j] + V[0][q], l.Ln[1][j] + V[1][q], l.Ln[2][j] + V[2][q]};
        const float* hp[3] = {&h[0], &h[1], &h[2]};
        float* hq[3] = {&h[0], &h[1], &h[2]};
        normalize(0, 1, hp, false, hq);
        base[i] = std::max(0.0f, N[0][k] * h[0] + N[1][k] * h[1] + N[2][k] * h[2]);
    }
}

inline void addLight(size_t b, size_t e, const float* const Cl[3], bool clv, const float* t, float* const out[3]) {
    for (size_t i = b; i < e; ++i) {
        if (t[i] <= 0) continue;
        for (int c = 0; c < 3; ++c) out[c][i] += Cl[c][at(clv, i)] * t[i];
    }
}

inline void deinterleave3(size_t b, size_t e, const float* xyz, float* const out[3]) {
    for (size_t i = b; i < e; ++i)
        for (int c = 0; c < 3; ++c) out[c][i] = xyz[3 * i + size_t(c)];
}

}  // namespace streyes::sl::gridref

#endif  // STREYES_GRID_KERNELS_REFERENCE

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "shade/vm/grid_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace streyes::sl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace {

const hn::ScalableTag<float> kF;
using VF = hn::Vec<decltype(kF)>;
using MF = hn::Mask<decltype(kF)>;

HWY_INLINE VF load(const float* p, bool varying, size_t i) { return varying ? hn::LoadU(kF, p + i) : hn::Set(kF, p[0]); }

HWY_INLINE VF dot3(const VF* a, const VF* b) {
    return hn::Add(hn::Add(hn::Mul(a[0], b[0]), hn::Mul(a[1], b[1])), hn::Mul(a[2], b[2]));
}

// exec.h's normalize3 on each lane: 0 unless 0 < |a|^2 < infinity.
HWY_INLINE void normalize3(VF* a) {
    const VF l2 = dot3(a, a);
    const MF ok = hn::And(hn::Gt(l2, hn::Zero(kF)), hn::Lt(l2, hn::Set(kF, HUGE_VALF)));
    const VF s = hn::Div(hn::Set(kF, 1.0f), hn::Sqrt(hn::IfThenElse(ok, l2, hn::Set(kF, 1.0f))));
    for (int c = 0; c < 3; ++c) a[c] = hn::IfThenElseZero(ok, hn::Mul(a[c], s));
}

// The light takes part: lit, and Ln . unitN not below cosHalf.
HWY_INLINE MF facing(const LightLanes& l, VF cosHalf, const float* const u[3], size_t i, const VF* ln) {
    const VF un[3] = {hn::LoadU(kF, u[0] + i), hn::LoadU(kF, u[1] + i), hn::LoadU(kF, u[2] + i)};
    const MF facingN = hn::Not(hn::Lt(dot3(ln, un), cosHalf));
    if (!l.varying) return l.lit[0] ? facingN : hn::FirstN(kF, 0);
    const hn::Rebind<uint8_t, decltype(kF)> k8;
    const hn::RebindToUnsigned<decltype(kF)> k32;
    const auto lit = hn::PromoteTo(k32, hn::LoadU(k8, l.lit + i));
    const MF isLit = hn::RebindMask(kF, hn::Ne(lit, hn::Zero(k32)));
    return hn::And(facingN, isLit);
}

void Normalize(size_t n, const float* const a[3], bool av, float* const out[3]) {
    const size_t N = hn::Lanes(kF);
    size_t i = 0;
    for (; i + N <= n; i += N) {
        VF v[3] = {load(a[0], av, i), load(a[1], av, i), load(a[2], av, i)};
        normalize3(v);
        for (int c = 0; c < 3; ++c) hn::StoreU(v[c], kF, out[c] + i);
    }
    gridref::normalize(i, n, a, av, out);
}

void Dot(size_t n, const float* const a[3], bool av, const float* const b[3], bool bv, float* out) {
    const size_t N = hn::Lanes(kF);
    size_t i = 0;
    for (; i + N <= n; i += N) {
        const VF p[3] = {load(a[0], av, i), load(a[1], av, i), load(a[2], av, i)};
        const VF q[3] = {load(b[0], bv, i), load(b[1], bv, i), load(b[2], bv, i)};
        hn::StoreU(dot3(p, q), kF, out + i);
    }
    gridref::dot(i, n, a, av, b, bv, out);
}

void Faceforward(size_t n, const float* const Nn[3], bool nv, const float* const I[3], bool iv, const float* const ref[3],
                 bool rv, float* const out[3]) {
    const size_t N = hn::Lanes(kF);
    size_t i = 0;
    const VF minusOne = hn::Set(kF, -1.0f);
    for (; i + N <= n; i += N) {
        const VF p[3] = {load(I[0], iv, i), load(I[1], iv, i), load(I[2], iv, i)};
        const VF q[3] = {load(ref[0], rv, i), load(ref[1], rv, i), load(ref[2], rv, i)};
        const MF front = hn::Lt(dot3(p, q), hn::Zero(kF));
        for (int c = 0; c < 3; ++c) {
            const VF v = load(Nn[c], nv, i);
            hn::StoreU(hn::IfThenElse(front, v, hn::Mul(v, minusOne)), kF, out[c] + i);
        }
    }
    gridref::faceforward(i, n, Nn, nv, I, iv, ref, rv, out);
}

void Divide(size_t n, const float* a, bool av, const float* b, bool bv, float* out) {
    const size_t N = hn::Lanes(kF);
    size_t i = 0;
    for (; i + N <= n; i += N) {
        const VF q = load(b, bv, i);
        const MF zero = hn::Eq(q, hn::Zero(kF));
        // Divides by 1 where q is 0 (no spurious infinities), then puts the 0.
        hn::StoreU(hn::IfThenZeroElse(zero, hn::Div(load(a, av, i), hn::IfThenElse(zero, hn::Set(kF, 1.0f), q))), kF,
                   out + i);
    }
    gridref::divide(i, n, a, av, b, bv, out);
}

// The map operations, lane by lane as gridref's: the same IEEE operations in the same order.
struct AddOp {
    static HWY_INLINE VF f(VF a, VF b) { return hn::Add(a, b); }
    static HWY_INLINE float ref(float a, float b) { return gridref::addOf(a, b); }
};
struct SubOp {
    static HWY_INLINE VF f(VF a, VF b) { return hn::Sub(a, b); }
    static HWY_INLINE float ref(float a, float b) { return gridref::subOf(a, b); }
};
struct MulOp {
    static HWY_INLINE VF f(VF a, VF b) { return hn::Mul(a, b); }
    static HWY_INLINE float ref(float a, float b) { return gridref::mulOf(a, b); }
};
// std::min(a, b) is b < a ? b : a, std::max(a, b) a < b ? b : a: a NaN in b gives a
// (hn::Min and hn::Max do not promise that).
// The divisor 0 replaced by 1 before dividing (no spurious infinities), then the 0 put.
struct ModOp {
    static HWY_INLINE VF f(VF a, VF b) {
        const MF zero = hn::Eq(b, hn::Zero(kF));
        const VF q = hn::IfThenElse(zero, hn::Set(kF, 1.0f), b);
        // floor(x) has x's sign (-0 stays -0), which Highway's emulated Floor (SSSE3, scalar)
        // loses: put it back.
        const VF r = hn::Div(a, q);
        return hn::IfThenZeroElse(zero, hn::Sub(a, hn::Mul(q, hn::CopySign(hn::Floor(r), r))));
    }
    static HWY_INLINE float ref(float a, float b) { return gridref::modOf(a, b); }
};
struct MinOp {
    static HWY_INLINE VF f(VF a, VF b) { return hn::IfThenElse(hn::Lt(b, a), b, a); }
    static HWY_INLINE float ref(float a, float b) { return gridref::minOf(a, b); }
};
struct MaxOp {
    static HWY_INLINE VF f(VF a, VF b) { return hn::IfThenElse(hn::Lt(a, b), b, a); }
    static HWY_INLINE float ref(float a, float b) { return gridref::maxOf(a, b); }
};

template <class Op>
void Binary(size_t n, const float* a, bool av, const float* b, bool bv, float* out) {
    const size_t N = hn::Lanes(kF);
    size_t i = 0;
    for (; i + N <= n; i += N) hn::StoreU(Op::f(load(a, av, i), load(b, bv, i)), kF, out + i);
    // The tail written here, not through gridref::binary<&Op::ref>: a call to this target's ref
    // from the reference's code is not inlined, and GCC then returns without vzeroupper, leaving
    // the wide registers' upper halves dirty for the SSE code after it (measured: the leaf
    // shader 1.4x slower).
    for (; i < n; ++i) out[i] = Op::ref(a[av ? i : 0], b[bv ? i : 0]);
}

void Filterstep(size_t n, const float* edge, bool ev, const float* s, bool sv_, const float* su, const float* sv,
                float wscale, float* out) {
    const size_t N = hn::Lanes(kF);
    const VF ws = hn::Set(kF, wscale), half = hn::Set(kF, 0.5f), one = hn::Set(kF, 1.0f), zero = hn::Zero(kF);
    size_t i = 0;
    for (; i + N <= n; i += N) {
        const VF e = load(edge, ev, i), x = load(s, sv_, i);
        const VF w = hn::Mul(hn::Add(hn::Abs(hn::LoadU(kF, su + i)), hn::Abs(hn::LoadU(kF, sv + i))), ws);
        const VF lo = hn::Sub(x, hn::Mul(half, w)), hi = hn::Add(x, hn::Mul(half, w));
        const VF q = hn::Div(hn::Sub(hi, e), hn::Sub(hi, lo));
        const VF m = hn::IfThenElseZero(hn::Lt(zero, q), q);     // std::max(0, q): 0 for NaN
        const VF c = hn::IfThenElse(hn::Lt(m, one), m, one);      // std::min(1, m)
        const VF step = hn::IfThenZeroElse(hn::Lt(x, e), one);
        hn::StoreU(hn::IfThenElse(hn::Gt(hi, lo), c, step), kF, out + i);
    }
    for (; i < n; ++i) out[i] = gridref::filterstepOf(edge[ev ? i : 0], s[sv_ ? i : 0], su[i], sv[i], wscale);
}

void Mix(size_t n, const float* a, bool av, const float* b, bool bv, const float* t, bool tv, float* out) {
    const size_t N = hn::Lanes(kF);
    const VF one = hn::Set(kF, 1.0f);
    size_t i = 0;
    for (; i + N <= n; i += N) {
        const VF tt = load(t, tv, i);
        hn::StoreU(hn::Add(hn::Mul(load(a, av, i), hn::Sub(one, tt)), hn::Mul(load(b, bv, i), tt)), kF, out + i);
    }
    gridref::ternary<&gridref::mixOf>(i, n, a, av, b, bv, t, tv, out);
}

// The reference's branches as masks: v <= e0 gives 0, else v >= e1 gives 1, else the cubic (a
// NaN v or edge falls through to the cubic in both).
void Smoothstep(size_t n, const float* e0, bool e0v, const float* e1, bool e1v, const float* v, bool vv, float* out) {
    const size_t N = hn::Lanes(kF);
    const VF one = hn::Set(kF, 1.0f), two = hn::Set(kF, 2.0f), three = hn::Set(kF, 3.0f);
    size_t i = 0;
    for (; i + N <= n; i += N) {
        const VF lo = load(e0, e0v, i), hi = load(e1, e1v, i), x = load(v, vv, i);
        const VF t = hn::Div(hn::Sub(x, lo), hn::Sub(hi, lo));
        const VF cubic = hn::Mul(hn::Mul(t, t), hn::Sub(three, hn::Mul(two, t)));
        hn::StoreU(hn::IfThenZeroElse(hn::Le(x, lo), hn::IfThenElse(hn::Ge(x, hi), one, cubic)), kF, out + i);
    }
    gridref::ternary<&gridref::smoothstepOf>(i, n, e0, e0v, e1, e1v, v, vv, out);
}

void DiffuseLight(size_t n, const LightLanes& l, float cosHalf, const float* const u[3], const float* const Nn[3],
                  bool nv, float* const out[3]) {
    const size_t N = hn::Lanes(kF);
    const VF ch = hn::Set(kF, cosHalf);
    size_t i = 0;
    for (; i + N <= n; i += N) {
        const VF ln[3] = {load(l.Ln[0], l.varying, i), load(l.Ln[1], l.varying, i), load(l.Ln[2], l.varying, i)};
        const VF nn[3] = {load(Nn[0], nv, i), load(Nn[1], nv, i), load(Nn[2], nv, i)};
        const VF t = dot3(ln, nn);
        const MF on = hn::AndNot(hn::Le(t, hn::Zero(kF)), facing(l, ch, u, i, ln));  // NaN too, as the reference
        if (hn::AllFalse(kF, on)) continue;
        for (int c = 0; c < 3; ++c) {
            const VF o = hn::LoadU(kF, out[c] + i);
            hn::StoreU(hn::IfThenElse(on, hn::Add(o, hn::Mul(load(l.Cl[c], l.varying, i), t)), o), kF, out[c] + i);
        }
    }
    gridref::diffuseLight(i, n, l, cosHalf, u, Nn, nv, out);
}

void SpecularBase(size_t n, const LightLanes& l, float cosHalf, const float* const u[3], const float* const Nn[3],
                  bool nv, const float* const V[3], bool vv, float* base) {
    const size_t N = hn::Lanes(kF);
    const VF ch = hn::Set(kF, cosHalf);
    size_t i = 0;
    for (; i + N <= n; i += N) {
        const VF ln[3] = {load(l.Ln[0], l.varying, i), load(l.Ln[1], l.varying, i), load(l.Ln[2], l.varying, i)};
        const MF on = facing(l, ch, u, i, ln);
        VF h[3];
        for (int c = 0; c < 3; ++c) h[c] = hn::Add(ln[c], load(V[c], vv, i));
        normalize3(h);
        const VF nn[3] = {load(Nn[0], nv, i), load(Nn[1], nv, i), load(Nn[2], nv, i)};
        const VF d = dot3(nn, h);
        const VF b = hn::IfThenElseZero(hn::Lt(hn::Zero(kF), d), d);  // std::max(0, d): 0 for NaN
        hn::StoreU(hn::IfThenElse(on, b, hn::Set(kF, -1.0f)), kF, base + i);
    }
    gridref::specularBase(i, n, l, cosHalf, u, Nn, nv, V, vv, base);
}

void AddLight(size_t n, const float* const Cl[3], bool clv, const float* t, float* const out[3]) {
    const size_t N = hn::Lanes(kF);
    size_t i = 0;
    for (; i + N <= n; i += N) {
        const VF tv = hn::LoadU(kF, t + i);
        const MF on = hn::Not(hn::Le(tv, hn::Zero(kF)));
        if (hn::AllFalse(kF, on)) continue;
        for (int c = 0; c < 3; ++c) {
            const VF o = hn::LoadU(kF, out[c] + i);
            hn::StoreU(hn::IfThenElse(on, hn::Add(o, hn::Mul(load(Cl[c], clv, i), tv)), o), kF, out[c] + i);
        }
    }
    gridref::addLight(i, n, Cl, clv, t, out);
}

void Deinterleave3(size_t n, const float* xyz, float* const out[3]) {
    const size_t N = hn::Lanes(kF);
    size_t i = 0;
    for (; i + N <= n; i += N) {
        VF x, y, z;
        hn::LoadInterleaved3(kF, xyz + 3 * i, x, y, z);
        hn::StoreU(x, kF, out[0] + i);
        hn::StoreU(y, kF, out[1] + i);
        hn::StoreU(z, kF, out[2] + i);
    }
    gridref::deinterleave3(i, n, xyz, out);
}

}  // namespace

const GridKernels* Kernels() {
    static const GridKernels k{hwy::TargetName(HWY_TARGET), &Normalize, &Dot, &Faceforward, &Divide,
                               &Binary<AddOp>, &Binary<SubOp>, &Binary<MulOp>, &Binary<MinOp>, &Binary<MaxOp>,
                               &Binary<ModOp>, &Filterstep, &Mix, &Smoothstep, &DiffuseLight, &SpecularBase, &AddLight, &Deinterleave3};
    return &k;
}

}  // namespace HWY_NAMESPACE
}  // namespace streyes::sl
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace streyes::sl {

HWY_EXPORT(Kernels);

namespace {

void refNormalize(size_t n, const float* const a[3], bool av, float* const out[3]) { gridref::normalize(0, n, a, av, out); }
void refDot(size_t n, const float* const a[3], bool av, const float* const b[3], bool bv, float* out) {
    gridref::dot(0, n, a, av, b, bv, out);
}
void refFaceforward(size_t n, const float* const N[3], bool nv, const float* const I[3], bool iv, const float* const ref[3],
                    bool rv, float* const out[3]) {
    gridref::faceforward(0, n, N, nv, I, iv, ref, rv, out);
}
void refDivide(size_t n, const float* a, bool av, const float* b, bool bv, float* out) { gridref::divide(0, n, a, av, b, bv, out); }
template <float (*F)(float, float)>
void refBinary(size_t n, const float* a, bool av, const float* b, bool bv, float* out) {
    gridref::binary<F>(0, n, a, av, b, bv, out);
}
template <float (*F)(float, float, float)>
void refTernary(size_t n, const float* a, bool av, const float* b, bool bv, const float* c, bool cv, float* out) {
    gridref::ternary<F>(0, n, a, av, b, bv, c, cv, out);
}
void refFilterstep(size_t n, const float* edge, bool ev, const float* s, bool sv_, const float* su, const float* sv,
                   float wscale, float* out) {
    gridref::filterstep(0, n, edge, ev, s, sv_, su, sv, wscale, out);
}
void refDiffuseLight(size_t n, const LightLanes& l, float cosHalf, const float* const u[3], const float* const N[3], bool nv,
                     float* const out[3]) {
    gridref::diffuseLight(0, n, l, cosHalf, u, N, nv, out);
}
void refSpecularBase(size_t n, const LightLanes& l, float cosHalf, const float* const u[3], const float* const N[3], bool nv,
                     const float* const V[3], bool vv, float* base) {
    gridref::specularBase(0, n, l, cosHalf, u, N, nv, V, vv, base);
}
void refAddLight(size_t n, const float* const Cl[3], bool clv, const float* t, float* const out[3]) {
    gridref::addLight(0, n, Cl, clv, t, out);
}
void refDeinterleave3(size_t n, const float* xyz, float* const out[3]) { gridref::deinterleave3(0, n, xyz, out); }

}  // namespace

const GridKernels& gridKernels() {
    static const GridKernels* const kernels = HWY_DYNAMIC_DISPATCH(Kernels)();
    return *kernels;
}

const GridKernels& gridKernelsScalar() {
    static const GridKernels k{"SCALAR reference", &refNormalize, &refDot, &refFaceforward, &refDivide,
                               &refBinary<&gridref::addOf>, &refBinary<&gridref::subOf>, &refBinary<&gridref::mulOf>,
                               &refBinary<&gridref::minOf>, &refBinary<&gridref::maxOf>, &refBinary<&gridref::modOf>,
                               &refFilterstep, &refTernary<&gridref::mixOf>,
                               &refTernary<&gridref::smoothstepOf>, &refDiffuseLight, &refSpecularBase, &refAddLight, &refDeinterleave3};
    return k;
}

std::vector<const GridKernels*> gridKernelsOfEveryTarget() {
    std::vector<const GridKernels*> out;
    for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
        hwy::SetSupportedTargetsForTest(target);  // the next dispatch chooses it
        out.push_back(HWY_DYNAMIC_DISPATCH(Kernels)());
    }
    hwy::SetSupportedTargetsForTest(0);
    return out;
}

}  // namespace streyes::sl
#endif  // HWY_ONCE
