// Arithmetic, comparisons, logic, arrays and the math functions, component-wise over the grid.
// Results that would be NaN or infinite from a bad operand (x/0, sqrt(-1), log(0), pow(-1, .5))
// are 0, and each point that runs and gets one is counted.
#include <algorithm>
#include <cmath>

#include "shade/vm/frame.h"
#include "shade/vm/grid_kernels.h"
#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

namespace {

constexpr float kPi = 3.14159265358979323846f;

// map2 with counting: bad(a, b) says when f's result is replaced by 0.
// (Counted before computing: the destination may be an operand.)
template <class F, class Bad>
void map2Checked(Exec& x, const Instr& in, F f, Bad bad) {
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]), b = x.view(in.a[2]);
    const int nc = d.comps * d.elems;
    int count = 0;
    for (int c = 0; c < nc; ++c) {
        const float* ap = a.comp(a.comps * a.elems > 1 ? c : 0);
        const float* bp = b.comp(b.comps * b.elems > 1 ? c : 0);
        count += countBad(x, d.w, [&](int i) { return bad(ap[a.varying ? i : 0], bp[b.varying ? i : 0]); });
    }
    if (count) x.sanitised(count);
    map2(x, in, [&](float p, float q) { return bad(p, q) ? 0.0f : f(p, q); });
}

template <class F, class Bad>
void map1Checked(Exec& x, const Instr& in, F f, Bad bad) {
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]);
    int count = 0;
    for (int c = 0; c < d.comps * d.elems; ++c) {
        const float* ap = a.comp(a.comps * a.elems > 1 ? c : 0);
        count += countBad(x, d.w, [&](int i) { return bad(ap[a.varying ? i : 0]); });
    }
    if (count) x.sanitised(count);
    map1(x, in, [&](float p) { return bad(p) ? 0.0f : f(p); });
}

// Comparisons over all components (a float beside a triple is broadcast).
template <class F>
void compare(Exec& x, const Instr& in, F f, bool all) {
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]), b = x.view(in.a[2]);
    const int nc = std::max(a.comps * a.elems, b.comps * b.elems);
    for (int i = 0; i < d.w; ++i) {
        bool r = all;
        for (int c = 0; c < nc; ++c) {
            bool t = f(a.comp(a.comps * a.elems > 1 ? c : 0)[a.varying ? i : 0],
                       b.comp(b.comps * b.elems > 1 ? c : 0)[b.varying ? i : 0]);
            r = all ? (r && t) : (r || t);
        }
        d.p[i] = r ? 1.0f : 0.0f;
    }
}

using BinaryKernel = void (*)(size_t, const float*, bool, const float*, bool, float*);
using TernaryKernel = void (*)(size_t, const float*, bool, const float*, bool, const float*, bool, float*);

// map2 and map3 through a grid kernel (grid_kernels.h: f's operations lane by lane, bit for bit)
// when the destination is varying; a uniform one is one point, computed by f.
template <class F>
void map2Kernel(Exec& x, const Instr& in, BinaryKernel k, F f) {
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]), b = x.view(in.a[2]);
    if (!d.varying) return map2(x, in, f);
    const int nc = d.comps * d.elems;
    for (int c = 0; c < nc; ++c)
        k(size_t(d.w), a.comp(a.comps * a.elems > 1 ? c : 0), a.varying, b.comp(b.comps * b.elems > 1 ? c : 0),
          b.varying, d.comp(c));
}

template <class F>
void map3Kernel(Exec& x, const Instr& in, TernaryKernel k, F f) {
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]), b = x.view(in.a[2]), e = x.view(in.a[3]);
    if (!d.varying) return map3(x, in, f);
    const int nc = d.comps * d.elems;
    for (int c = 0; c < nc; ++c)
        k(size_t(d.w), a.comp(a.comps > 1 ? c : 0), a.varying, b.comp(b.comps > 1 ? c : 0), b.varying,
          e.comp(e.comps > 1 ? c : 0), e.varying, d.comp(c));
}

// a / b and mod(a, b): a zero divisor gives 0 and is counted (sanitised). Uniform: the scalar map;
// varying: the zeros counted, then each component through the grid kernel.
template <class Kernel, class F>
void divideLike(Exec& x, const Instr& in, Kernel kernel, F f) {
    RegView d = x.view(in.a[0]);
    if (!d.varying) {
        map2Checked(x, in, f, [](float, float b) { return b == 0.0f; });
        return;
    }
    RegView a = x.view(in.a[1]), b = x.view(in.a[2]);
    const int nc = d.comps * d.elems;
    int count = 0;
    for (int c = 0; c < nc; ++c) {
        const float* bp = b.comp(b.comps * b.elems > 1 ? c : 0);
        count += countBad(x, d.w, [&](int i) { return bp[b.varying ? i : 0] == 0.0f; });
    }
    if (count) x.sanitised(count);
    for (int c = 0; c < nc; ++c)
        kernel(size_t(d.w), a.comp(a.comps * a.elems > 1 ? c : 0), a.varying, b.comp(b.comps * b.elems > 1 ? c : 0),
               b.varying, d.comp(c));
}

}  // namespace

void neg(Exec& x, const Instr& in) { map1(x, in, [](float a) { return -a; }); }
void add(Exec& x, const Instr& in) { map2Kernel(x, in, x.vm.kernels().add, [](float a, float b) { return a + b; }); }
void sub(Exec& x, const Instr& in) { map2Kernel(x, in, x.vm.kernels().sub, [](float a, float b) { return a - b; }); }
void mul(Exec& x, const Instr& in) { map2Kernel(x, in, x.vm.kernels().mul, [](float a, float b) { return a * b; }); }
void div(Exec& x, const Instr& in) {
    divideLike(x, in, x.vm.kernels().divide, [](float a, float b) { return a / b; });
}
void logNot(Exec& x, const Instr& in) { map1(x, in, [](float a) { return a == 0.0f ? 1.0f : 0.0f; }); }
void logAnd(Exec& x, const Instr& in) {
    map2(x, in, [](float a, float b) { return (a != 0.0f && b != 0.0f) ? 1.0f : 0.0f; });
}
void logOr(Exec& x, const Instr& in) {
    map2(x, in, [](float a, float b) { return (a != 0.0f || b != 0.0f) ? 1.0f : 0.0f; });
}
void eq(Exec& x, const Instr& in) { compare(x, in, [](float a, float b) { return a == b; }, true); }
void ne(Exec& x, const Instr& in) { compare(x, in, [](float a, float b) { return a != b; }, false); }
void lt(Exec& x, const Instr& in) { map2(x, in, [](float a, float b) { return a < b ? 1.0f : 0.0f; }); }
void gt(Exec& x, const Instr& in) { map2(x, in, [](float a, float b) { return a > b ? 1.0f : 0.0f; }); }
void le(Exec& x, const Instr& in) { map2(x, in, [](float a, float b) { return a <= b ? 1.0f : 0.0f; }); }
void ge(Exec& x, const Instr& in) { map2(x, in, [](float a, float b) { return a >= b ? 1.0f : 0.0f; }); }

void select(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), c = x.view(in.a[1]), a = x.view(in.a[2]), b = x.view(in.a[3]);
    const int nc = d.comps * d.elems;
    for (int k = 0; k < nc; ++k) {
        float* out = d.comp(k);
        const float* ap = a.comp(a.comps * a.elems > 1 ? k : 0);
        const float* bp = b.comp(b.comps * b.elems > 1 ? k : 0);
        for (int i = 0; i < d.w; ++i)
            out[i] = c.at(0, i) != 0.0f ? ap[a.varying ? i : 0] : bp[b.varying ? i : 0];
    }
}

// ---- Arrays ------------------------------------------------------------------------------------

namespace {
inline int clampIndex(float f, int len) {
    if (!(f >= 0)) return 0;
    if (f >= float(len - 1)) return len - 1;
    return int(f);
}
inline bool outside(float f, int len) { return !(f >= 0 && f < float(len)); }
}  // namespace

// Indices outside the array are clamped into it; the first such point that runs is reported.
void aref(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]), ix = x.view(in.a[2]);
    const int len = a.elems;
    if (len == 0) {  // an empty resizable array: 0
        if (x.active > 0) x.indexOutOfRange(in, in.a[1], ix.at(0, 0));
        for (int c = 0; c < d.comps; ++c) std::fill(d.comp(c), d.comp(c) + d.w, 0.0f);
        return;
    }
    bool reported = false;
    for (int i = 0; i < d.w; ++i) {
        const float f = ix.at(0, i);
        if (outside(f, len) && !reported && (d.w == 1 ? x.active > 0 : x.mask[i] != 0)) {
            x.indexOutOfRange(in, in.a[1], f);
            reported = true;
        }
        const int e = clampIndex(f, len);
        for (int c = 0; c < d.comps; ++c) d.comp(c)[i] = a.comp(c, e)[a.varying ? i : 0];
    }
}

void aset(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[0]), ix = x.view(in.a[1]), v = x.view(in.a[2]);
    const int len = a.elems;
    if (len == 0) {  // an empty resizable array: written nowhere
        if (x.active > 0) x.indexOutOfRange(in, in.a[0], ix.at(0, 0));
        return;
    }
    const bool all = !a.varying || x.allOn();
    bool reported = false;
    for (int i = 0; i < a.w; ++i) {
        if (!all && !x.mask[i]) continue;
        const float f = ix.at(0, i);
        if (outside(f, len) && !reported && x.active > 0) {
            x.indexOutOfRange(in, in.a[0], f);
            reported = true;
        }
        const int e = clampIndex(f, len);
        for (int c = 0; c < a.comps; ++c) a.comp(c, e)[i] = v.comp(v.comps > 1 ? c : 0)[v.varying ? i : 0];
    }
}

// ---- Math functions ----------------------------------------------------------------------------

void sin_(Exec& x, const Instr& in) { map1(x, in, [](float a) { return std::sin(a); }); }
void cos_(Exec& x, const Instr& in) { map1(x, in, [](float a) { return std::cos(a); }); }
void tan_(Exec& x, const Instr& in) { map1(x, in, [](float a) { return finiteOr0(std::tan(a)); }); }
void asin_(Exec& x, const Instr& in) {
    map1(x, in, [](float a) { return std::asin(std::min(1.0f, std::max(-1.0f, a))); });
}
void acos_(Exec& x, const Instr& in) {
    map1(x, in, [](float a) { return std::acos(std::min(1.0f, std::max(-1.0f, a))); });
}
void atan1(Exec& x, const Instr& in) { map1(x, in, [](float a) { return std::atan(a); }); }
void atan2_(Exec& x, const Instr& in) { map2(x, in, [](float y, float xx) { return std::atan2(y, xx); }); }
void radians(Exec& x, const Instr& in) { map1(x, in, [](float a) { return a * (kPi / 180.0f); }); }
void degrees(Exec& x, const Instr& in) { map1(x, in, [](float a) { return a * (180.0f / kPi); }); }
// std::pow once a point (not once to test and again to compute), then the results that are not
// finite counted where points run and replaced by 0.
void pow_(Exec& x, const Instr& in) {
    map2(x, in, [](float a, float b) { return std::pow(a, b); });
    RegView d = x.view(in.a[0]);
    const int nc = d.comps * d.elems;
    int count = 0;
    for (int c = 0; c < nc; ++c) {
        float* p = d.comp(c);
        count += countBad(x, d.w, [&](int i) { return !std::isfinite(p[i]); });
        for (int i = 0; i < d.w; ++i)
            if (!std::isfinite(p[i])) p[i] = 0.0f;
    }
    if (count) x.sanitised(count);
}
void exp_(Exec& x, const Instr& in) { map1(x, in, [](float a) { return std::exp(a); }); }
void sqrt_(Exec& x, const Instr& in) {
    map1Checked(x, in, [](float a) { return std::sqrt(a); }, [](float a) { return a < 0.0f; });
}
void inversesqrt(Exec& x, const Instr& in) {
    map1Checked(x, in, [](float a) { return 1.0f / std::sqrt(a); }, [](float a) { return !(a > 0.0f); });
}
void log1(Exec& x, const Instr& in) {
    map1Checked(x, in, [](float a) { return std::log(a); }, [](float a) { return !(a > 0.0f); });
}
void log2_(Exec& x, const Instr& in) {
    map2Checked(x, in, [](float a, float b) { return std::log(a) / std::log(b); },
                [](float a, float b) { return !(a > 0.0f) || !(b > 0.0f) || b == 1.0f; });
}
void mod(Exec& x, const Instr& in) {
    divideLike(x, in, x.vm.kernels().mod, [](float a, float b) { return a - b * std::floor(a / b); });
}
void abs_(Exec& x, const Instr& in) { map1(x, in, [](float a) { return std::fabs(a); }); }
void sign(Exec& x, const Instr& in) {
    map1(x, in, [](float a) { return a > 0.0f ? 1.0f : (a < 0.0f ? -1.0f : 0.0f); });
}
void floor_(Exec& x, const Instr& in) { map1(x, in, [](float a) { return std::floor(a); }); }
void ceil_(Exec& x, const Instr& in) { map1(x, in, [](float a) { return std::ceil(a); }); }
void round_(Exec& x, const Instr& in) { map1(x, in, [](float a) { return std::round(a); }); }
void min_(Exec& x, const Instr& in) {
    map2Kernel(x, in, x.vm.kernels().min, [](float a, float b) { return std::min(a, b); });
}
void max_(Exec& x, const Instr& in) {
    map2Kernel(x, in, x.vm.kernels().max, [](float a, float b) { return std::max(a, b); });
}
void clamp(Exec& x, const Instr& in) {
    map3(x, in, [](float a, float lo, float hi) { return std::min(std::max(a, lo), hi); });
}
void mix(Exec& x, const Instr& in) {
    map3Kernel(x, in, x.vm.kernels().mix, [](float a, float b, float t) { return a * (1.0f - t) + b * t; });
}
void step(Exec& x, const Instr& in) { map2(x, in, [](float e, float v) { return v < e ? 0.0f : 1.0f; }); }
void smoothstep(Exec& x, const Instr& in) {
    map3Kernel(x, in, x.vm.kernels().smoothstep, [](float e0, float e1, float v) {
        if (v <= e0) return 0.0f;
        if (v >= e1) return 1.0f;
        float t = (v - e0) / (e1 - e0);
        return t * t * (3.0f - 2.0f * t);
    });
}

// ---- Splines -----------------------------------------------------------------------------------

namespace {

struct Basis {
    float m[4][4];
    int step;
};

// RenderMan's basis matrices (RI Spec 3.2, RiBasis); "linear" interpolates the inner knots.
const Basis* basisNamed(const std::string& name) {
    static const Basis catmull = {{{-0.5f, 1.5f, -1.5f, 0.5f}, {1, -2.5f, 2, -0.5f}, {-0.5f, 0, 0.5f, 0}, {0, 1, 0, 0}}, 1};
    static const Basis bezier = {{{-1, 3, -3, 1}, {3, -6, 3, 0}, {-3, 3, 0, 0}, {1, 0, 0, 0}}, 3};
    static const Basis bspline = {
        {{-1 / 6.f, 3 / 6.f, -3 / 6.f, 1 / 6.f}, {3 / 6.f, -6 / 6.f, 3 / 6.f, 0}, {-3 / 6.f, 0, 3 / 6.f, 0}, {1 / 6.f, 4 / 6.f, 1 / 6.f, 0}},
        1};
    static const Basis hermite = {{{2, 1, -2, 1}, {-3, -2, 3, -1}, {0, 1, 0, 0}, {1, 0, 0, 0}}, 2};
    static const Basis linear = {{{0, 0, 0, 0}, {0, 0, 0, 0}, {0, -1, 1, 0}, {0, 1, 0, 0}}, 1};
    if (name.empty() || name == "catmull-rom") return &catmull;
    if (name == "bezier") return &bezier;
    if (name == "bspline" || name == "b-spline") return &bspline;
    if (name == "hermite") return &hermite;
    if (name == "linear") return &linear;
    return nullptr;
}

// knot(k, c, i): component c of knot k at point i.
template <class Knot>
float evalSpline(const Basis& b, int nknots, float value, int c, int i, Knot knot) {
    const int nseg = (nknots - 4) / b.step + 1;
    float t = std::min(1.0f, std::max(0.0f, value)) * float(nseg);
    int seg = std::min(nseg - 1, int(t));
    t -= float(seg);
    const int k0 = seg * b.step;
    float r = 0;
    const float tt[4] = {t * t * t, t * t, t, 1};
    for (int j = 0; j < 4; ++j) {
        float w = 0;
        for (int r4 = 0; r4 < 4; ++r4) w += tt[r4] * b.m[r4][j];
        r += w * knot(k0 + j, c, i);
    }
    return r;
}

}  // namespace

void spline(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]);
    const int32_t* regs = x.extra(in.a[1]);
    const int count = in.a[2];
    static const std::string none;
    const Basis* b = basisNamed(regs[0] >= 0 ? x.str(regs[0]) : none);
    if (!b) b = basisNamed("");
    RegView value = x.view(regs[1]);
    const int nknots = count - 2;
    RegView knots[64];
    const int kn = std::min(nknots, 64);
    for (int k = 0; k < kn; ++k) knots[k] = x.view(regs[2 + k]);
    for (int c = 0; c < d.comps; ++c)
        for (int i = 0; i < d.w; ++i)
            d.comp(c)[i] = evalSpline(*b, kn, value.at(0, i), c, i,
                                      [&](int k, int cc, int ii) { return knots[k].at(knots[k].comps > 1 ? cc : 0, ii); });
}

void splineArray(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), value = x.view(in.a[2]), arr = x.view(in.a[3]);
    static const std::string none;
    const Basis* b = basisNamed(in.a[1] >= 0 ? x.str(in.a[1]) : none);
    if (!b) b = basisNamed("");
    if (arr.elems < 4) {  // a resizable array of knots shorter than a spline needs: 0
        for (int c = 0; c < d.comps; ++c) std::fill(d.comp(c), d.comp(c) + d.w, 0.0f);
        return;
    }
    for (int c = 0; c < d.comps; ++c)
        for (int i = 0; i < d.w; ++i)
            d.comp(c)[i] = evalSpline(*b, arr.elems, value.at(0, i), c, i,
                                      [&](int k, int cc, int ii) { return arr.comp(cc, k)[arr.varying ? ii : 0]; });
}

}  // namespace streyes::sl::ops
