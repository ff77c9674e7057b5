#include <cmath>

#include "geom/body.h"
#include "geom/grid.h"

namespace streyes {

namespace {

float dist2(Vec3f a, Vec3f b) {
    float dx = a.x - b.x, dy = a.y - b.y;
    return dx * dx + dy * dy;
}

Vec3f mid(Vec3f a, Vec3f b) { return (a + b) * 0.5f; }

}  // namespace

// Normal of a bilinear patch at (u, v). At collapsed edges and poles the derivatives vanish;
// fall back to the cross product of the diagonals, which is the patch's mean normal.
Vec3f bilinearNormal(const TrilinearBody::Corners& p, float u, float v) {
    Vec3f dPdu = lerp(p[1] - p[0], p[3] - p[2], v);
    Vec3f dPdv = lerp(p[2] - p[0], p[3] - p[1], u);
    Vec3f n = cross(dPdu, dPdv);
    float scale = dot(dPdu, dPdu) * dot(dPdv, dPdv);
    if (dot(n, n) > 1e-12f * scale && dot(n, n) > 0) return n;
    Vec3f d = cross(p[3] - p[0], p[2] - p[1]);
    if (dot(d, d) > 0) return d;
    return {0, 0, -1};  // zero-area patch: face the camera
}

TrilinearBody::TrilinearBody(TimeSpan time, const Corners& p0, const Corners& p1,
                             const std::array<Color, 4>& cs, const Material* material)
    : P_{p0, p1}, Cs_(cs) {
    time_ = time;
    material_ = material;
    moving_ = p0 != p1;
    if (!moving_) P_[1] = P_[0];
}

LBBox3f TrilinearBody::bound() const {
    LBBox3f b;
    for (int i = 0; i < 4; ++i) {
        b.b0.extend(P_[0][i]);
        b.b1.extend(P_[1][i]);
    }
    return b;
}

// The corners move on straight lines, so the box of the corners at a and at b holds the patch
// at every time in between (a bilinear patch lies in the convex hull of its corners).
Bounds3f TrilinearBody::boundDuring(double a, double b) const {
    Bounds3f box;
    if (!moving_) {
        for (const Vec3f& p : P_[0]) box.extend(p);
        return box;
    }
    const Corners ca = cornersAt(a), cb = cornersAt(b);
    for (int i = 0; i < 4; ++i) {
        box.extend(ca[size_t(i)]);
        box.extend(cb[size_t(i)]);
    }
    return box;
}

RasterMeasure TrilinearBody::measure(const Camera& camera) const {
    RasterMeasure m;
    Corners r[2];
    for (int k = 0; k < (moving_ ? 2 : 1); ++k)
        for (int i = 0; i < 4; ++i) r[k][i] = camera.toRaster(P_[k][i]);
    if (!moving_) r[1] = r[0];
    float eu = 0, ev = 0, mo = 0;
    for (int k = 0; k < 2; ++k) {
        eu = std::max({eu, dist2(r[k][0], r[k][1]), dist2(r[k][2], r[k][3])});
        ev = std::max({ev, dist2(r[k][0], r[k][2]), dist2(r[k][1], r[k][3])});
        for (int i = 0; i < 4; ++i) {
            (k == 0 ? m.bound.b0 : m.bound.b1).extend(r[k][i]);
            if (k == 1) mo = std::max(mo, dist2(r[0][i], r[1][i]));
        }
    }
    m.extentU = std::sqrt(eu);
    m.extentV = std::sqrt(ev);
    m.motion = std::sqrt(mo);
    return m;
}

CameraExtents TrilinearBody::cameraExtents() const {
    CameraExtents e;
    for (int k = 0; k < 2; ++k) {
        const Corners& p = P_[k];
        e.u = std::max({e.u, length(p[1] - p[0]), length(p[3] - p[2])});
        e.v = std::max({e.v, length(p[2] - p[0]), length(p[3] - p[1])});
    }
    for (int i = 0; i < 4; ++i) e.t = std::max(e.t, length(P_[1][i] - P_[0][i]));
    return e;
}

void TrilinearBody::split(SplitAxis axis, std::unique_ptr<Body> out[2]) const {
    Corners a[2], b[2];
    std::array<Color, 4> ca = Cs_, cb = Cs_;
    TimeSpan ta = time_, tb = time_;
    if (axis == SplitAxis::T) {
        double tm = 0.5 * (time_.t0 + time_.t1);
        ta.t1 = tb.t0 = tm;
        ta.openEnd = true;  // a sample exactly at tm belongs to the second half
        for (int i = 0; i < 4; ++i) {
            Vec3f m = mid(P_[0][i], P_[1][i]);
            a[0][i] = P_[0][i];
            a[1][i] = m;
            b[0][i] = m;
            b[1][i] = P_[1][i];
        }
    } else {
        // Corner pairs along the split direction: (0,1),(2,3) for u; (0,2),(1,3) for v.
        const int pairs[2][2][2] = {{{0, 1}, {2, 3}}, {{0, 2}, {1, 3}}};
        const auto& pr = pairs[axis == SplitAxis::U ? 0 : 1];
        for (int k = 0; k < 2; ++k) {
            a[k] = b[k] = P_[k];
            for (const auto& e : pr) {
                Vec3f m = mid(P_[k][e[0]], P_[k][e[1]]);
                a[k][e[1]] = m;  // first half keeps the low end
                b[k][e[0]] = m;  // second half keeps the high end
            }
        }
        for (const auto& e : pr) {
            Color m = mid(Cs_[e[0]], Cs_[e[1]]);
            ca[e[1]] = m;
            cb[e[0]] = m;
        }
    }
    auto make = [&](TimeSpan t, const Corners* c, const std::array<Color, 4>& cs) {
        auto body = std::make_unique<TrilinearBody>(t, c[0], c[1], cs, material_);
        body->inheritFrom(*this);  // the split loop counts the kind of split
        return body;
    };
    out[0] = make(ta, a, ca);
    out[1] = make(tb, b, cb);
}

std::unique_ptr<Body> TrilinearBody::restrictedTo(double a, double b) const {
    Corners p0 = P_[0], p1 = P_[1];
    if (moving_) {
        double len = time_.t1 - time_.t0;
        float sa = float((a - time_.t0) / len), sb = float((b - time_.t0) / len);
        if (a == time_.t0) sa = 0;
        if (b == time_.t1) sb = 1;
        for (int i = 0; i < 4; ++i) {
            p0[i] = lerp(P_[0][i], P_[1][i], sa);
            p1[i] = lerp(P_[0][i], P_[1][i], sb);
        }
    }
    // Cut short of t1, the piece is closed at b: nothing else covers b within [a, b].
    auto body = std::make_unique<TrilinearBody>(TimeSpan{a, b, b == time_.t1 && time_.openEnd}, p0, p1, Cs_, material_);
    body->inheritFrom(*this);
    return body;
}

// Identities are handed out in runs of 2^20 per thread: no shared counter per body made. They
// need be unique only, not the same from run to run.
uint64_t Body::newIdentity() {
    static std::atomic<uint64_t> runs{1};
    thread_local uint64_t next = 0, end = 0;
    if (next == end) {
        next = runs.fetch_add(1, std::memory_order_relaxed) << 20;
        end = next + (uint64_t(1) << 20);
    }
    return next++;
}

void Body::startGrid(int nu, int nv, Grid& grid) const {
    grid.resize(nu, nv, moving_);
    grid.hole.clear();
    grid.paramU.clear();
    grid.paramV.clear();
    grid.t0 = time_.t0;
    grid.t1 = time_.t1;
    grid.openEnd = time_.openEnd;
    grid.material = material_;
    grid.primitiveId = primitiveId_;
    grid.u0 = uv[0], grid.u1 = uv[1], grid.v0 = uv[2], grid.v1 = uv[3];
    grid.primvarCorners = primvarCorners;
}

size_t TrilinearBody::memoryBytes() const { return heapBlockBytes(sizeof(*this)); }

void TrilinearBody::dice(int nu, int nv, Grid& grid) const {
    startGrid(nu, nv, grid);
    const float du = 1.0f / float(nu), dv = 1.0f / float(nv);
    for (int j = 0; j <= nv; ++j) {
        // Exact 0 and 1 on the borders so that neighbouring grids share edge vertices.
        float v = j == nv ? 1.0f : float(j) * dv;
        for (int i = 0; i <= nu; ++i) {
            float u = i == nu ? 1.0f : float(i) * du;
            int idx = grid.index(i, j);
            for (int k = 0; k < (moving_ ? 2 : 1); ++k) {
                grid.P[k][idx] = bilerp(P_[k], u, v);
                grid.N[k][idx] = bilinearNormal(P_[k], u, v);
            }
            grid.Cs[idx] = bilerp(Cs_, u, v);
        }
    }
}

}  // namespace streyes
