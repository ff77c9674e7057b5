#include "geom/nurbs.h"

#include <algorithm>

namespace streyes {

int nurbsSpan(const double* U, int n, int order, double t) {
    const int p = order - 1;
    int s = int(std::upper_bound(U + p, U + n + 1, t) - U) - 1;
    s = std::min(std::max(s, p), n - 1);
    while (s > p && !(U[s] < U[s + 1])) --s;  // at the end of the range: the last non-empty span
    return s;
}

namespace {

// The degree-p basis functions non-zero on span s at t (Piegl & Tiller, A2.2).
void basisOfDegree(const double* U, int p, int s, double t, double* N) {
    double left[kMaxNurbsOrder], right[kMaxNurbsOrder];
    N[0] = 1;
    for (int j = 1; j <= p; ++j) {
        left[j] = t - U[s + 1 - j];
        right[j] = U[s + j] - t;
        double saved = 0;
        for (int r = 0; r < j; ++r) {
            const double temp = N[r] / (right[r + 1] + left[j - r]);
            N[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        N[j] = saved;
    }
}

HPoint operator*(const HPoint& a, double s) { return {a.p * s, a.w * s}; }
HPoint operator+(const HPoint& a, const HPoint& b) { return {a.p + b.p, a.w + b.w}; }

// A homogeneous point as four doubles: trivially constructible, so the bound's scratch arrays
// (up to 32 x 32 of them) cost nothing to set up.
struct H4 {
    double c[4];
};

// The blossom of the degree-p spline on span s at arguments x[0..p-1], from the span's p + 1
// homogeneous control points d0 (de Boor's algorithm with one argument per level). Every weight
// lies in [0, 1] when the arguments lie in the span.
H4 blossom(const double* U, int p, int s, const H4* d0, const double* x) {
    H4 d[kMaxNurbsOrder];
    std::copy(d0, d0 + p + 1, d);
    for (int r = 1; r <= p; ++r)
        for (int j = p; j >= r; --j) {
            const int i = s - p + j;
            const double a = (x[r - 1] - U[i]) / (U[i + p + 1 - r] - U[i]);
            for (int k = 0; k < 4; ++k) d[j].c[k] = d[j - 1].c[k] * (1 - a) + d[j].c[k] * a;
        }
    return d[p];
}

// The non-empty spans of [t0, t1]: calls f(span, a, b) with [a, b] the part of the interval in it.
template <typename F>
void forSpans(const double* U, int n, int order, double t0, double t1, F f) {
    bool any = false;
    for (int s = order - 1; s < n; ++s) {
        const double a = std::max(t0, U[s]), b = std::min(t1, U[s + 1]);
        if (U[s] < U[s + 1] && a < b) {
            f(s, a, b);
            any = true;
        }
    }
    if (!any) f(nurbsSpan(U, n, order, t0), t0, t0);  // a zero-length interval
}

}  // namespace

void nurbsBasis(const double* U, int order, int s, double t, double* N, double* dN) {
    const int p = order - 1;
    if (!dN) {
        basisOfDegree(U, p, s, t, N);
        return;
    }
    // dN_{i,p} = p N_{i,p-1} / (U[i+p] - U[i]) - p N_{i+1,p-1} / (U[i+p+1] - U[i+1]).
    double low[kMaxNurbsOrder];
    if (p > 0) basisOfDegree(U, p - 1, s, t, low);
    for (int r = 0; r <= p; ++r) {
        const int i = s - p + r;
        double d = 0;
        if (r >= 1) d += low[r - 1] / (U[i + p] - U[i]);
        if (r <= p - 1) d -= low[r] / (U[i + p + 1] - U[i + 1]);
        dN[r] = p * d;
    }
    basisOfDegree(U, p, s, t, N);
}

void NurbsSurface::evaluate(double u, double v, Vec3d* S, Vec3d* Su, Vec3d* Sv) const {
    const int p = uorder - 1, q = vorder - 1;
    const int su = nurbsSpan(uknot, nu, uorder, u), sv = nurbsSpan(vknot, nv, vorder, v);
    double Nu[kMaxNurbsOrder], dNu[kMaxNurbsOrder], Nv[kMaxNurbsOrder], dNv[kMaxNurbsOrder];
    nurbsBasis(uknot, uorder, su, u, Nu, dNu);
    nurbsBasis(vknot, vorder, sv, v, Nv, dNv);
    Vec3d A, Au, Av;
    double W = 0, Wu = 0, Wv = 0;
    for (int b = 0; b <= q; ++b) {
        // The row's sums in u first: (p + 1) (q + 1) products instead of three times that.
        Vec3d r, ru;
        double rw = 0, rwu = 0;
        const int row = (sv - q + b) * nu + su - p;
        for (int a = 0; a <= p; ++a) {
            const double ww = w[row + a];
            const Vec3d wp = P[row + a] * ww;
            r += wp * Nu[a];
            ru += wp * dNu[a];
            rw += ww * Nu[a];
            rwu += ww * dNu[a];
        }
        A += r * Nv[b];
        Au += ru * Nv[b];
        Av += r * dNv[b];
        W += rw * Nv[b];
        Wu += rwu * Nv[b];
        Wv += rw * dNv[b];
    }
    *S = A / W;
    if (Su) *Su = (Au - *S * Wu) / W;
    if (Sv) *Sv = (Av - *S * Wv) / W;
}

Bounds3d NurbsSurface::bound(double u0, double u1, double v0, double v1) const {
    const int p = uorder - 1, q = vorder - 1;
    Bounds3d box;
    // A rectangle over many spans (the first pieces of a large patch): the box of the control
    // points of those spans, which holds the surface there too (each span lies in the hull of its
    // own points) and costs one look at each point instead of ~300 blends a span.
    int ua = nu, ub = -1, va = nv, vb = -1;
    forSpans(uknot, nu, uorder, u0, u1, [&](int s, double, double) { ua = std::min(ua, s), ub = std::max(ub, s); });
    forSpans(vknot, nv, vorder, v0, v1, [&](int s, double, double) { va = std::min(va, s), vb = std::max(vb, s); });
    if ((ub - ua + 1) * (vb - va + 1) > kMaxBezierSpans) {
        for (int j = va - q; j <= vb; ++j)
            for (int i = ua - p; i <= ub; ++i) box.extend(P[j * nu + i]);
        return box;
    }
    forSpans(uknot, nu, uorder, u0, u1, [&](int su, double a, double b) {
        forSpans(vknot, nv, vorder, v0, v1, [&](int sv, double c, double d) {
            // Bezier points in u of each of the span's q + 1 rows, then in v down each column.
            H4 rows[kMaxNurbsOrder][kMaxNurbsOrder];  // [k][row]
            double x[kMaxNurbsOrder];
            for (int j = 0; j <= q; ++j) {
                H4 d0[kMaxNurbsOrder];
                const int row = (sv - q + j) * nu + su - p;
                for (int i = 0; i <= p; ++i) {
                    const double wi = w[row + i];
                    d0[i] = {{P[row + i].x * wi, P[row + i].y * wi, P[row + i].z * wi, wi}};
                }
                for (int k = 0; k <= p; ++k) {
                    for (int m = 0; m < p; ++m) x[m] = m < p - k ? a : b;
                    rows[k][j] = blossom(uknot, p, su, d0, x);
                }
            }
            for (int k = 0; k <= p; ++k)
                for (int l = 0; l <= q; ++l) {
                    for (int m = 0; m < q; ++m) x[m] = m < q - l ? c : d;
                    const H4 h = blossom(vknot, q, sv, rows[k], x);
                    box.extend(Vec3d(h.c[0], h.c[1], h.c[2]) / h.c[3]);
                }
        });
    });
    return box;
}

void NurbsSurface::isoCurve(bool alongV, double c, std::vector<HPoint>* out) const {
    const int order = alongV ? uorder : vorder, n = alongV ? nu : nv, m = alongV ? nv : nu;
    const double* U = alongV ? uknot : vknot;
    const int s = nurbsSpan(U, n, order, c);
    double N[kMaxNurbsOrder];
    nurbsBasis(U, order, s, c, N, nullptr);
    out->assign(size_t(m), HPoint{{0, 0, 0}, 0});
    for (int j = 0; j < m; ++j)
        for (int a = 0; a < order; ++a) {
            const int i = s - order + 1 + a;
            const int idx = alongV ? j * nu + i : i * nu + j;
            (*out)[size_t(j)] = (*out)[size_t(j)] + HPoint{P[idx] * w[idx], w[idx]} * N[a];
        }
}

void nurbsCurvePolyline(int n, int order, const double* knot, double tmin, double tmax, const double* u,
                        const double* v, const double* w, int stepsPerSpan, std::vector<Vec2<double>>* out) {
    auto at = [&](double t) {
        const int s = nurbsSpan(knot, n, order, t);
        double N[kMaxNurbsOrder];
        nurbsBasis(knot, order, s, t, N, nullptr);
        double x = 0, y = 0, h = 0;
        for (int a = 0; a < order; ++a) {
            const int i = s - order + 1 + a;
            x += N[a] * u[i], y += N[a] * v[i], h += N[a] * w[i];
        }
        return Vec2<double>(x / h, y / h);
    };
    out->push_back(at(tmin));
    forSpans(knot, n, order, tmin, tmax, [&](int, double a, double b) {
        for (int k = 1; k <= stepsPerSpan; ++k)
            out->push_back(at(k == stepsPerSpan ? b : a + (b - a) * k / stepsPerSpan));
    });
}

}  // namespace streyes
