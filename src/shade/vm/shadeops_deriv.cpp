// Derivatives over the grid: Du, Dv, Deriv, area, calculatenormal, filterstep.
//
// Du(f) at column i is (f[i+1] - f[i-1]) / (2 du) inside the grid and the one-sided
// difference over du on the first and last columns (Dv likewise along rows). The derivative
// of a uniform value is 0; a grid without a shape (nu = nv = 0) has none (0). A zero du gives 0.
// Inside varying conditionals, neighbours that do not run hold whatever they held before.
#include <cmath>
#include <cstring>

#include "shade/vm/deriv.h"
#include "shade/vm/grid_kernels.h"
#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl {

namespace {
bool hasShape(const ShadingGrid& g) { return g.nu > 0 && g.nv >= 0 && g.n == (g.nu + 1) * (g.nv + 1); }
}  // namespace

namespace {
// Along u over one grid of (nu + 1) x (nv + 1) points.
void diffUShape(int nu, int nv, const float* f, float* out) {
    if (nu < 1) {
        std::memset(out, 0, sizeof(float) * size_t(nu + 1) * size_t(nv + 1));
        return;
    }
    const int w = nu + 1;
    for (int j = 0; j <= nv; ++j) {
        const float* r = f + size_t(j) * size_t(w);
        float* o = out + size_t(j) * size_t(w);
        o[0] = r[1] - r[0];
        for (int i = 1; i < nu; ++i) o[i] = 0.5f * (r[i + 1] - r[i - 1]);
        o[nu] = r[nu] - r[nu - 1];
    }
}

void diffVShape(int nu, int nv, const float* f, float* out) {
    const size_t w = size_t(nu + 1);
    if (nv < 1) {
        std::memset(out, 0, sizeof(float) * w * size_t(nv + 1));
        return;
    }
    for (int j = 0; j <= nv; ++j) {
        const float* up = f + size_t(j == nv ? j : j + 1) * w;
        const float* dn = f + size_t(j == 0 ? 0 : j - 1) * w;
        const float k = (j == 0 || j == nv) ? 1.0f : 0.5f;
        float* o = out + size_t(j) * w;
        for (size_t i = 0; i < w; ++i) o[i] = k * (up[i] - dn[i]);
    }
}

// A batch of grids (ShadingGrid::parts): each differenced on its own, as if shaded alone.
bool partsCover(const ShadingGrid& g) {
    int n = 0;
    for (int p = 0; p < g.partCount; ++p) {
        const ShadingGridPart& q = g.parts[p];
        if (q.offset != n || q.nu < 0 || q.nv < 0) return false;
        n += (q.nu + 1) * (q.nv + 1);
    }
    return n == g.n;
}

void diffParts(const ShadingGrid& g, const float* f, float* out, bool alongU) {
    if (!partsCover(g)) {
        std::memset(out, 0, sizeof(float) * size_t(g.n));
        return;
    }
    for (int p = 0; p < g.partCount; ++p) {
        const ShadingGridPart& q = g.parts[p];
        if (q.nu < 1) {  // a part without a shape (as a grid alone: nu > 0 or no derivatives)
            std::memset(out + q.offset, 0, sizeof(float) * size_t(q.nu + 1) * size_t(q.nv + 1));
            continue;
        }
        (alongU ? diffUShape : diffVShape)(q.nu, q.nv, f + q.offset, out + q.offset);
    }
}
}  // namespace

void diffU(const ShadingGrid& g, const float* f, float* out) {
    if (g.parts) return diffParts(g, f, out, true);
    if (!hasShape(g)) return void(std::memset(out, 0, sizeof(float) * size_t(g.n)));
    diffUShape(g.nu, g.nv, f, out);
}

void diffV(const ShadingGrid& g, const float* f, float* out) {
    if (g.parts) return diffParts(g, f, out, false);
    if (!hasShape(g)) return void(std::memset(out, 0, sizeof(float) * size_t(g.n)));
    diffVShape(g.nu, g.nv, f, out);
}

float duAt(const ShadingGrid& g, int i) {
    const ValueRef& v = g.globals[size_t(Global::du)];
    if (v.valid()) return v.at(0, i);
    return g.nu > 0 ? 1.0f / float(g.nu) : 0.0f;
}

float dvAt(const ShadingGrid& g, int i) {
    const ValueRef& v = g.globals[size_t(Global::dv)];
    if (v.valid()) return v.at(0, i);
    return g.nv > 0 ? 1.0f / float(g.nv) : 0.0f;
}

namespace ops {

namespace {

// d = D?(a) component by component; a uniform source has derivative 0.
void derivative(Exec& x, const Instr& in, bool alongU) {
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]);
    for (int c = 0; c < d.comps; ++c) {
        float* out = d.comp(c);
        if (!a.varying || !d.varying) {
            for (int i = 0; i < d.w; ++i) out[i] = 0;
            continue;
        }
        (alongU ? diffU : diffV)(x.grid, a.comp(c), out);
        for (int i = 0; i < d.w; ++i) {
            float step = alongU ? duAt(x.grid, i) : dvAt(x.grid, i);
            out[i] = step != 0.0f ? out[i] / step : 0.0f;
        }
    }
}

// Scratch arrays for derivatives, kept per thread between grids.
struct Scratch {
    std::vector<float> a, b, c;
    void size(int n) {
        if (a.size() < size_t(n) * 3) {
            a.resize(size_t(n) * 3);
            b.resize(size_t(n) * 3);
            c.resize(size_t(n) * 3);
        }
    }
};
thread_local Scratch scratch;

}  // namespace

void Du(Exec& x, const Instr& in) { derivative(x, in, true); }
void Dv(Exec& x, const Instr& in) { derivative(x, in, false); }

void Deriv(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), num = x.view(in.a[1]), den = x.view(in.a[2]);
    scratch.size(x.n);
    float* dden_u = scratch.a.data();
    float* dden_v = scratch.a.data() + x.n;
    float* t = scratch.b.data();
    if (den.varying) {
        diffU(x.grid, den.p, dden_u);
        diffV(x.grid, den.p, dden_v);
    }
    for (int c = 0; c < d.comps; ++c) {
        float* out = d.comp(c);
        if (!num.varying || !den.varying || !d.varying) {
            for (int i = 0; i < d.w; ++i) out[i] = 0;
            continue;
        }
        // (dnum/du)/(dden/du): the du cancels, so differences divide directly.
        diffU(x.grid, num.comp(c), t);
        for (int i = 0; i < d.w; ++i) out[i] = dden_u[i] != 0.0f ? t[i] / dden_u[i] : 0.0f;
        diffV(x.grid, num.comp(c), t);
        for (int i = 0; i < d.w; ++i) out[i] += dden_v[i] != 0.0f ? t[i] / dden_v[i] : 0.0f;
    }
}

namespace {
// dPu, dPv: the change of P across one micropolygon along u and v (3 x n each).
void positionDiffs(Exec& x, const RegView& P, float* pu, float* pv) {
    for (int c = 0; c < 3; ++c) {
        diffU(x.grid, P.comp(c), pu + size_t(c) * size_t(x.n));
        diffV(x.grid, P.comp(c), pv + size_t(c) * size_t(x.n));
    }
}
}  // namespace

// |Du(P) du x Dv(P) dv|: the area of a micropolygon.
void area(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), P = x.view(in.a[1]);
    if (!P.varying) {
        for (int i = 0; i < d.w; ++i) d.p[i] = 0;
        return;
    }
    scratch.size(x.n);
    float* pu = scratch.a.data();
    float* pv = scratch.b.data();
    positionDiffs(x, P, pu, pv);
    const size_t n = size_t(x.n);
    for (size_t i = 0; i < n; ++i) {
        V3 a{pu[i], pu[n + i], pu[2 * n + i]}, b{pv[i], pv[n + i], pv[2 * n + i]};
        V3 c = cross3(a, b);
        d.p[i] = std::sqrt(dot3(c, c));
    }
}

// Du(P) ^ Dv(P), reversed when the grid says its orientation is the other handedness.
void calculatenormal(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), P = x.view(in.a[1]);
    if (!P.varying) {
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < d.w; ++i) d.comp(c)[i] = 0;
        return;
    }
    scratch.size(x.n);
    float* pu = scratch.a.data();
    float* pv = scratch.b.data();
    positionDiffs(x, P, pu, pv);
    const size_t n = size_t(x.n);
    const float flip = x.grid.flipNormals ? -1.0f : 1.0f;
    for (size_t i = 0; i < n; ++i) {
        float du = duAt(x.grid, int(i)), dv = dvAt(x.grid, int(i));
        float s = (du != 0.0f && dv != 0.0f) ? flip / (du * dv) : 0.0f;
        V3 a{pu[i], pu[n + i], pu[2 * n + i]}, b{pv[i], pv[n + i], pv[2 * n + i]};
        store3(d, int(i), mul3(cross3(a, b), s));
    }
}

// filterstep(edge, s1 [, s2] [, "width", w]): step(edge, s) averaged over [s1, s2], or over
// the change of s1 across the micropolygon (times w).
void filterstep(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), e = x.view(in.a[1]), s1 = x.view(in.a[2]);
    const bool two = in.a[3] >= 0;
    RegView s2;
    if (two) s2 = x.view(in.a[3]);
    const float wscale = in.a[4] >= 0 ? x.view(in.a[4]).at(0, 0) : 1.0f;
    scratch.size(x.n);
    float* su = scratch.a.data();
    float* sv = scratch.b.data();
    if (!two) {
        if (s1.varying) {
            diffU(x.grid, s1.p, su);
            diffV(x.grid, s1.p, sv);
        } else {
            std::memset(su, 0, sizeof(float) * size_t(x.n));
            std::memset(sv, 0, sizeof(float) * size_t(x.n));
        }
    }
    if (!two && d.varying) {  // the one-argument form over the grid: the kernel, bit for bit
        x.vm.kernels().filterstep(size_t(d.w), e.p, e.varying, s1.p, s1.varying, su, sv, wscale, d.p);
        return;
    }
    for (int i = 0; i < d.w; ++i) {
        float lo, hi;
        if (two) {
            lo = std::min(s1.at(0, i), s2.at(0, i));
            hi = std::max(s1.at(0, i), s2.at(0, i));
        } else {
            float w = (std::fabs(su[i]) + std::fabs(sv[i])) * wscale;
            lo = s1.at(0, i) - 0.5f * w;
            hi = s1.at(0, i) + 0.5f * w;
        }
        const float edge = e.at(0, i);
        d.p[i] = hi > lo ? std::min(1.0f, std::max(0.0f, (hi - edge) / (hi - lo))) : (s1.at(0, i) < edge ? 0.0f : 1.0f);
    }
}

}  // namespace ops
}  // namespace streyes::sl
