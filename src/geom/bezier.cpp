#include "geom/bezier.h"

namespace streyes {

namespace {

// The inverse of the Bezier basis matrix: power-basis coefficients [a b c d] (a u^3 + ...) of a
// cubic become Bezier control values. Bezier = B^-1 * power.
constexpr Matrix4x4 kBezierInverse = {0, 0, 0, 1,  //
                                      0, 0, 1.0 / 3, 1,
                                      0, 1.0 / 3, 2.0 / 3, 1,
                                      1, 1, 1, 1};

// The inverse of the matrix of Bernstein values at t = 0, 1/3, 2/3, 1: samples -> control values.
constexpr Matrix4x4 kThirdsInverse = {1, 0, 0, 0,  //
                                      -5.0 / 6, 3, -1.5, 1.0 / 3,
                                      1.0 / 3, -1.5, 3, -5.0 / 6,
                                      0, 0, 0, 1};

Matrix4x4 multiply(const Matrix4x4& a, const Matrix4x4& b) {
    Matrix4x4 r{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a[size_t(i * 4 + k)] * b[size_t(k * 4 + j)];
            r[size_t(i * 4 + j)] = s;
        }
    return r;
}

// Q[j][i] = sum_l sum_k cv[j][l] cu[i][k] g[l][k]: the tensor-product change of basis.
template <typename In>
BezierPatch tensorApply(const Matrix4x4& cu, const Matrix4x4& cv, const In g[16]) {
    Vec3d rows[16];  // u converted, row by row
    for (int l = 0; l < 4; ++l)
        for (int i = 0; i < 4; ++i) {
            Vec3d s;
            for (int k = 0; k < 4; ++k) s += Vec3d(g[l * 4 + k]) * cu[size_t(i * 4 + k)];
            rows[l * 4 + i] = s;
        }
    BezierPatch q;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            Vec3d s;
            for (int l = 0; l < 4; ++l) s += rows[l * 4 + i] * cv[size_t(j * 4 + l)];
            q[size_t(j * 4 + i)] = Vec3f(s);
        }
    return q;
}

// de Casteljau on one cubic at parameter t: the control values of [0, t] and of [t, 1].
void casteljau(const Vec3d p[4], double t, Vec3d lo[4], Vec3d hi[4]) {
    Vec3d a = lerp(p[0], p[1], t), b = lerp(p[1], p[2], t), c = lerp(p[2], p[3], t);
    Vec3d d = lerp(a, b, t), e = lerp(b, c, t);
    Vec3d m = lerp(d, e, t);
    lo[0] = p[0], lo[1] = a, lo[2] = d, lo[3] = m;
    hi[0] = m, hi[1] = e, hi[2] = c, hi[3] = p[3];
}

// The control values of the cubic over [a, b] within [0, 1].
void subCurve(const Vec3d p[4], double a, double b, Vec3d out[4]) {
    Vec3d left[4], unused[4];
    if (b < 1) casteljau(p, b, left, unused);
    else std::copy(p, p + 4, left);
    if (a > 0 && b > 0) casteljau(left, a / b, unused, out);
    else std::copy(left, left + 4, out);
}

}  // namespace

Matrix4x4 basisToBezier(const BasisDesc& basis) { return multiply(kBezierInverse, basis.m); }

BezierPatch patchToBezier(const Matrix4x4& cu, const Matrix4x4& cv, const Vec3d g[16]) {
    return tensorApply(cu, cv, g);
}

BezierPatch fitBezier(const Vec3d samples[16]) { return tensorApply(kThirdsInverse, kThirdsInverse, samples); }

void bernstein(double t, double b[4], double db[4]) {
    const double s = 1 - t;
    b[0] = s * s * s;
    b[1] = 3 * t * s * s;
    b[2] = 3 * t * t * s;
    b[3] = t * t * t;
    db[0] = -3 * s * s;
    db[1] = 3 * s * s - 6 * t * s;
    db[2] = 6 * t * s - 3 * t * t;
    db[3] = 3 * t * t;
}

void evalBezier(const BezierPatch& cp, double u, double v, Vec3d* P, Vec3d* dPdu, Vec3d* dPdv) {
    double bu[4], dbu[4], bv[4], dbv[4];
    bernstein(u, bu, dbu);
    bernstein(v, bv, dbv);
    Vec3d p, du, dv;
    for (int j = 0; j < 4; ++j) {
        // Each row along u first, then the rows along v: a point on the edge v = 0 or v = 1 is
        // then exactly the edge curve evaluated at u.
        Vec3d row, drow;
        for (int i = 0; i < 4; ++i) {
            Vec3d c(cp[size_t(j * 4 + i)]);
            row += c * bu[i];
            drow += c * dbu[i];
        }
        p += row * bv[j];
        du += drow * bv[j];
        dv += row * dbv[j];
    }
    *P = p;
    if (dPdu) *dPdu = du;
    if (dPdv) *dPdv = dv;
}

void splitBezier(const BezierPatch& cp, int axis, BezierPatch& lo, BezierPatch& hi) {
    for (int line = 0; line < 4; ++line) {
        // The four control points of one row (axis u) or column (axis v).
        auto at = [&](int k) { return size_t(axis == 0 ? line * 4 + k : k * 4 + line); };
        const Vec3f p0 = cp[at(0)], p1 = cp[at(1)], p2 = cp[at(2)], p3 = cp[at(3)];
        const Vec3f a = (p0 + p1) * 0.5f, b = (p1 + p2) * 0.5f, c = (p2 + p3) * 0.5f;
        const Vec3f d = (a + b) * 0.5f, e = (b + c) * 0.5f;
        const Vec3f m = (d + e) * 0.5f;
        lo[at(0)] = p0, lo[at(1)] = a, lo[at(2)] = d, lo[at(3)] = m;
        hi[at(0)] = m, hi[at(1)] = e, hi[at(2)] = c, hi[at(3)] = p3;
    }
}

BezierPatch bezierSubPatch(const BezierPatch& cp, double u0, double u1, double v0, double v1) {
    Vec3d rows[16];
    for (int j = 0; j < 4; ++j) {
        Vec3d p[4];
        for (int i = 0; i < 4; ++i) p[i] = Vec3d(cp[size_t(j * 4 + i)]);
        subCurve(p, u0, u1, &rows[j * 4]);
    }
    BezierPatch out;
    for (int i = 0; i < 4; ++i) {
        Vec3d p[4], q[4];
        for (int j = 0; j < 4; ++j) p[j] = rows[j * 4 + i];
        subCurve(p, v0, v1, q);
        for (int j = 0; j < 4; ++j) out[size_t(j * 4 + i)] = Vec3f(q[j]);
    }
    return out;
}

Bounds3f bezierBound(const BezierPatch& cp) {
    Bounds3f b;
    for (const Vec3f& p : cp) b.extend(p);
    return b;
}

}  // namespace streyes
