// Geometry (dot, cross, normalize, reflect, refract, fresnel ...), named spaces and matrices.
// Points are row vectors, p' = p M, as everywhere in streyes.
#include <cmath>
#include <cstring>

#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

namespace {

struct M4 {
    float m[16];
    float operator()(int r, int c) const { return m[r * 4 + c]; }
};

M4 loadM(const RegView& r, int i) {
    M4 out;
    for (int c = 0; c < 16; ++c) out.m[c] = r.comp(c)[r.varying ? i : 0];
    return out;
}
void storeM(const RegView& r, int i, const M4& v) {
    for (int c = 0; c < 16; ++c) r.comp(c)[i] = v.m[c];
}
M4 mulM(const M4& a, const M4& b) {
    M4 o;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            float s = 0;
            for (int k = 0; k < 4; ++k) s += a(r, k) * b(k, c);
            o.m[r * 4 + c] = s;
        }
    return o;
}
M4 identityM() {
    M4 o;
    for (int c = 0; c < 16; ++c) o.m[c] = c % 5 == 0 ? 1.0f : 0.0f;
    return o;
}
// Inverse by cofactors (in double); a singular matrix gives the identity.
M4 invertM(const M4& a, bool* ok = nullptr) {
    Matrix4 d, inv;
    for (int c = 0; c < 16; ++c) d.m[size_t(c)] = a.m[c];
    bool good = invert(d, &inv);
    if (ok) *ok = good;
    if (!good) return identityM();
    M4 o;
    for (int c = 0; c < 16; ++c) o.m[c] = float(inv.m[size_t(c)]);
    return o;
}
double determinantOf(const M4& a) {
    double m[16];
    for (int c = 0; c < 16; ++c) m[c] = a.m[c];
    auto det3 = [&](int r0, int r1, int r2, int c0, int c1, int c2) {
        return m[r0 * 4 + c0] * (m[r1 * 4 + c1] * m[r2 * 4 + c2] - m[r1 * 4 + c2] * m[r2 * 4 + c1]) -
               m[r0 * 4 + c1] * (m[r1 * 4 + c0] * m[r2 * 4 + c2] - m[r1 * 4 + c2] * m[r2 * 4 + c0]) +
               m[r0 * 4 + c2] * (m[r1 * 4 + c0] * m[r2 * 4 + c1] - m[r1 * 4 + c1] * m[r2 * 4 + c0]);
    };
    return m[0] * det3(1, 2, 3, 1, 2, 3) - m[1] * det3(1, 2, 3, 0, 2, 3) + m[2] * det3(1, 2, 3, 0, 1, 3) -
           m[3] * det3(1, 2, 3, 0, 1, 2);
}

V3 xformPoint(const M4& m, V3 p) {
    float x = p.x * m(0, 0) + p.y * m(1, 0) + p.z * m(2, 0) + m(3, 0);
    float y = p.x * m(0, 1) + p.y * m(1, 1) + p.z * m(2, 1) + m(3, 1);
    float z = p.x * m(0, 2) + p.y * m(1, 2) + p.z * m(2, 2) + m(3, 2);
    float w = p.x * m(0, 3) + p.y * m(1, 3) + p.z * m(2, 3) + m(3, 3);
    if (w != 1.0f && w != 0.0f) return {x / w, y / w, z / w};
    return {x, y, z};
}
V3 xformVector(const M4& m, V3 v) {
    return {v.x * m(0, 0) + v.y * m(1, 0) + v.z * m(2, 0), v.x * m(0, 1) + v.y * m(1, 1) + v.z * m(2, 1),
            v.x * m(0, 2) + v.y * m(1, 2) + v.z * m(2, 2)};
}
// Normals by the inverse transpose: pass the inverse.
V3 xformNormal(const M4& inv, V3 n) {
    return {n.x * inv(0, 0) + n.y * inv(0, 1) + n.z * inv(0, 2), n.x * inv(1, 0) + n.y * inv(1, 1) + n.z * inv(1, 2),
            n.x * inv(2, 0) + n.y * inv(2, 1) + n.z * inv(2, 2)};
}

V3 reflect3(V3 i, V3 n) { return sub3(i, mul3(n, 2.0f * dot3(i, n))); }
V3 refract3(V3 i, V3 n, float eta) {
    float c = dot3(i, n);
    float k = 1.0f - eta * eta * (1.0f - c * c);
    if (k < 0) return {0, 0, 0};
    return sub3(mul3(i, eta), mul3(n, eta * c + std::sqrt(k)));
}

// A per-point function of triples and floats into a triple or float destination.
template <class F>
void perPoint(Exec& x, const Instr& in, F f) {
    RegView d = x.view(in.a[0]);
    for (int i = 0; i < d.w; ++i) f(d, i);
}

}  // namespace

// Triples of a register, for the grid kernels.
struct Comps3 {
    const float* p[3];
    explicit Comps3(const RegView& r) : p{r.comp(0), r.comp(1), r.comp(2)} {}
};
struct Out3 {
    float* p[3];
    explicit Out3(const RegView& r) : p{r.comp(0), r.comp(1), r.comp(2)} {}
};

// dot, normalize and faceforward of triples into a varying result run as grid kernels.
void dot(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]), b = x.view(in.a[2]), d = x.view(in.a[0]);
    if (d.varying && a.comps == 3 && b.comps == 3) {
        x.vm.kernels().dot(size_t(d.w), Comps3(a).p, a.varying, Comps3(b).p, b.varying, d.p);
        return;
    }
    perPoint(x, in, [&](const RegView& d, int i) { d.p[i] = dot3(load3(a, i), load3(b, i)); });
}
void cross(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]), b = x.view(in.a[2]);
    perPoint(x, in, [&](const RegView& d, int i) { store3(d, i, cross3(load3(a, i), load3(b, i))); });
}
void length(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]);
    perPoint(x, in, [&](const RegView& d, int i) {
        V3 v = load3(a, i);
        d.p[i] = std::sqrt(dot3(v, v));
    });
}
void normalize(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]), d = x.view(in.a[0]);
    if (d.varying && a.comps == 3 && d.comps == 3) {
        x.vm.kernels().normalize(size_t(d.w), Comps3(a).p, a.varying, Out3(d).p);
        return;
    }
    perPoint(x, in, [&](const RegView& d, int i) { store3(d, i, normalize3(load3(a, i))); });
}
void distance(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]), b = x.view(in.a[2]);
    perPoint(x, in, [&](const RegView& d, int i) {
        V3 v = sub3(load3(a, i), load3(b, i));
        d.p[i] = std::sqrt(dot3(v, v));
    });
}
// N turned to face against I, judged by Nref (the geometric normal Ng by default).
void faceforward(Exec& x, const Instr& in) {
    RegView n = x.view(in.a[1]), I = x.view(in.a[2]), ref = x.view(in.a[3]), d = x.view(in.a[0]);
    if (d.varying && n.comps == 3 && I.comps == 3 && ref.comps == 3 && d.comps == 3) {
        x.vm.kernels().faceforward(size_t(d.w), Comps3(n).p, n.varying, Comps3(I).p, I.varying, Comps3(ref).p, ref.varying,
                                   Out3(d).p);
        return;
    }
    perPoint(x, in, [&](const RegView& d, int i) {
        V3 v = load3(n, i);
        store3(d, i, dot3(load3(I, i), load3(ref, i)) < 0 ? v : mul3(v, -1.0f));
    });
}
void reflect(Exec& x, const Instr& in) {
    RegView I = x.view(in.a[1]), n = x.view(in.a[2]);
    perPoint(x, in, [&](const RegView& d, int i) { store3(d, i, reflect3(load3(I, i), load3(n, i))); });
}
void refract(Exec& x, const Instr& in) {
    RegView I = x.view(in.a[1]), n = x.view(in.a[2]), eta = x.view(in.a[3]);
    perPoint(x, in, [&](const RegView& d, int i) { store3(d, i, refract3(load3(I, i), load3(n, i), eta.at(0, i))); });
}

// fresnel(I, N, eta, Kr, Kt [, R, T]): reflected and transmitted fractions of unpolarised light
// (Cook and Torrance's form; eta is the ratio of the indices, outside over inside).
void fresnel(Exec& x, const Instr& in) {
    const int32_t* r = x.extra(in.a[1]);
    const int count = in.a[2];
    RegView I = x.view(r[0]), N = x.view(r[1]), eta = x.view(r[2]), Kr = x.view(r[3]), Kt = x.view(r[4]);
    for (int i = 0; i < Kr.w; ++i) {
        V3 iv = normalize3(load3(I, i)), nv = normalize3(load3(N, i));
        float e = eta.at(0, i);
        float c = std::fabs(dot3(iv, nv));
        float g2 = e != 0.0f ? 1.0f / (e * e) + c * c - 1.0f : -1.0f;
        float kr = 1.0f;
        if (g2 >= 0.0f) {
            float g = std::sqrt(g2);
            float a = (g - c) / (g + c);
            float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
            kr = finiteOr0(0.5f * a * a * (1.0f + b * b));
            kr = std::min(1.0f, kr);
        }
        Kr.p[i] = kr;
        Kt.p[i] = 1.0f - kr;
        if (count > 5) {
            RegView R = x.view(r[5]), T = x.view(r[6]);
            V3 ii = load3(I, i), nn = load3(N, i);
            store3(R, i, reflect3(ii, nn));
            store3(T, i, refract3(normalize3(ii), normalize3(nn), e));
        }
    }
}

void comp(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]), k = x.view(in.a[2]);
    perPoint(x, in, [&](const RegView& d, int i) {
        int c = std::min(2, std::max(0, int(k.at(0, i))));
        d.p[i] = a.at(c, i);
    });
}
void setcomp(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]), k = x.view(in.a[2]), v = x.view(in.a[3]);
    perPoint(x, in, [&](const RegView& d, int i) {
        V3 t = load3(a, i);
        float val = v.at(0, i);
        int c = std::min(2, std::max(0, int(k.at(0, i))));
        (c == 0 ? t.x : c == 1 ? t.y : t.z) = val;
        store3(d, i, t);
    });
}
void mcomp(Exec& x, const Instr& in) {
    RegView m = x.view(in.a[1]), r = x.view(in.a[2]), c = x.view(in.a[3]);
    perPoint(x, in, [&](const RegView& d, int i) {
        int rr = std::min(3, std::max(0, int(r.at(0, i)))), cc = std::min(3, std::max(0, int(c.at(0, i))));
        d.p[i] = m.comp(rr * 4 + cc)[m.varying ? i : 0];
    });
}
void msetcomp(Exec& x, const Instr& in) {
    RegView m = x.view(in.a[1]), r = x.view(in.a[2]), c = x.view(in.a[3]), v = x.view(in.a[4]);
    perPoint(x, in, [&](const RegView& d, int i) {
        M4 t = loadM(m, i);
        int rr = std::min(3, std::max(0, int(r.at(0, i)))), cc = std::min(3, std::max(0, int(c.at(0, i))));
        t.m[rr * 4 + cc] = v.at(0, i);
        storeM(d, i, t);
    });
}

// a0 = a1 from space a2 to space a3 (-1: current), or by matrix a4; a5 the kind of value.
void xform(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), s = x.view(in.a[1]);
    const int kind = in.a[5];
    // transform(from, m, p): p taken from space `from` to current, then through m.
    M4 fromToCurrent = identityM();
    const bool fromThenMatrix = in.a[4] >= 0 && in.a[2] >= 0 && x.str(in.a[2]) != "current";
    if (fromThenMatrix) x.vm.spaceToCurrent(x.str(in.a[2]), fromToCurrent.m);
    if (in.a[4] >= 0 && x.varying(in.a[4])) {
        RegView mv = x.view(in.a[4]);
        for (int i = 0; i < d.w; ++i) {
            M4 m = fromThenMatrix ? mulM(fromToCurrent, loadM(mv, i)) : loadM(mv, i);
            V3 v = load3(s, i);
            store3(d, i, kind == 0 ? xformPoint(m, v) : kind == 1 ? xformVector(m, v) : xformNormal(invertM(m), v));
        }
        return;
    }
    M4 m;
    if (in.a[4] >= 0) {
        m = mulM(fromToCurrent, loadM(x.view(in.a[4]), 0));
    } else {
        M4 a = identityM(), b = identityM();
        const std::string* from = in.a[2] >= 0 ? &x.str(in.a[2]) : nullptr;
        const std::string* to = in.a[3] >= 0 ? &x.str(in.a[3]) : nullptr;
        if (from && to && *from == *to) from = to = nullptr;
        if (from && *from != "current") x.vm.spaceToCurrent(*from, a.m);
        if (to && *to != "current") x.vm.currentToSpace(*to, b.m);
        m = mulM(a, b);
    }
    const M4 inv = kind == 2 ? invertM(m) : m;
    for (int i = 0; i < d.w; ++i) {
        V3 v = load3(s, i);
        store3(d, i, kind == 0 ? xformPoint(m, v) : kind == 1 ? xformVector(m, v) : xformNormal(inv, v));
    }
}

// matrix "space" m: m given in that space, as a matrix from current space terms: m * (space -> current).
void spaceMatrix(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), s = x.view(in.a[2]);
    M4 toCurrent;
    x.vm.spaceToCurrent(x.str(in.a[1]), toCurrent.m);
    for (int i = 0; i < d.w; ++i) storeM(d, i, mulM(loadM(s, i), toCurrent));
}

void matMul(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]), b = x.view(in.a[2]);
    perPoint(x, in, [&](const RegView& d, int i) { storeM(d, i, mulM(loadM(a, i), loadM(b, i))); });
}
void matDiv(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]), b = x.view(in.a[2]);
    int bad = 0;
    perPoint(x, in, [&](const RegView& d, int i) {
        bool ok = true;
        M4 inv = invertM(loadM(b, i), &ok);
        if (!ok && (d.w == 1 || x.mask[i])) ++bad;
        storeM(d, i, mulM(loadM(a, i), inv));
    });
    if (bad) x.sanitised(bad);
}
void determinant(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]);
    perPoint(x, in, [&](const RegView& d, int i) { d.p[i] = float(determinantOf(loadM(a, i))); });
}
void translateM(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]), t = x.view(in.a[2]);
    perPoint(x, in, [&](const RegView& d, int i) {
        V3 v = load3(t, i);
        M4 tm = identityM();
        tm.m[12] = v.x;
        tm.m[13] = v.y;
        tm.m[14] = v.z;
        storeM(d, i, mulM(tm, loadM(a, i)));
    });
}
void scaleM(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]), t = x.view(in.a[2]);
    perPoint(x, in, [&](const RegView& d, int i) {
        V3 v = load3(t, i);
        M4 sm = identityM();
        sm.m[0] = v.x;
        sm.m[5] = v.y;
        sm.m[10] = v.z;
        storeM(d, i, mulM(sm, loadM(a, i)));
    });
}
void rotateM(Exec& x, const Instr& in) {
    RegView a = x.view(in.a[1]), ang = x.view(in.a[2]), axis = x.view(in.a[3]);
    perPoint(x, in, [&](const RegView& d, int i) {
        V3 k = load3(axis, i);
        Matrix4 r = Matrix4::rotate(double(ang.at(0, i)) * 180.0 / 3.14159265358979323846, Vec3d(k.x, k.y, k.z));
        M4 rm;
        for (int c = 0; c < 16; ++c) rm.m[c] = float(r.m[size_t(c)]);
        storeM(d, i, mulM(rm, loadM(a, i)));
    });
}

void depth(Exec& x, const Instr& in) {
    RegView p = x.view(in.a[1]);
    const float n0 = x.grid.nearClip, f0 = x.grid.farClip;
    const float span = f0 - n0;
    perPoint(x, in, [&](const RegView& d, int i) { d.p[i] = span != 0.0f ? (p.at(2, i) - n0) / span : 0.0f; });
}

void ptlined(Exec& x, const Instr& in) {
    RegView p0 = x.view(in.a[1]), p1 = x.view(in.a[2]), q = x.view(in.a[3]);
    perPoint(x, in, [&](const RegView& d, int i) {
        V3 a = load3(p0, i), b = load3(p1, i), p = load3(q, i);
        V3 ab = sub3(b, a);
        float l2 = dot3(ab, ab);
        float t = l2 > 0 ? std::min(1.0f, std::max(0.0f, dot3(sub3(p, a), ab) / l2)) : 0.0f;
        V3 c = sub3(p, add3(a, mul3(ab, t)));
        d.p[i] = std::sqrt(dot3(c, c));
    });
}

void rotatePoint(Exec& x, const Instr& in) {
    RegView q = x.view(in.a[1]), ang = x.view(in.a[2]), p0 = x.view(in.a[3]), p1 = x.view(in.a[4]);
    perPoint(x, in, [&](const RegView& d, int i) {
        V3 a = load3(p0, i), k = normalize3(sub3(load3(p1, i), a));
        V3 v = sub3(load3(q, i), a);
        float th = ang.at(0, i), c = std::cos(th), s = std::sin(th);
        // Rodrigues: v cos + (k x v) sin + k (k.v)(1 - cos)
        V3 r = add3(add3(mul3(v, c), mul3(cross3(k, v), s)), mul3(k, dot3(k, v) * (1.0f - c)));
        store3(d, i, add3(r, a));
    });
}

}  // namespace streyes::sl::ops
