#include "geom/quadric.h"

#include <cmath>

namespace streyes {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180;

// cos and sin of an angle in degrees, exact at multiples of 90 degrees (so that a sphere's pole
// or a quarter sweep lands exactly where it should).
double cosDeg(double d) {
    const double q = d / 90;
    if (q == std::floor(q)) {
        const long k = ((long(q) % 4) + 4) % 4;
        return k == 0 ? 1 : k == 2 ? -1 : 0;
    }
    return std::cos(d * kDeg);
}
double sinDeg(double d) { return cosDeg(d - 90); }

// Closed intervals and their products.
struct Interval {
    double lo, hi;
};
Interval mul(Interval a, Interval b) {
    const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
    return {std::min({p[0], p[1], p[2], p[3]}), std::max({p[0], p[1], p[2], p[3]})};
}
Interval span(double a, double b) { return {std::min(a, b), std::max(a, b)}; }
Interval add(Interval a, double c) { return {a.lo + c, a.hi + c}; }
Interval scale(Interval a, double c) { return mul(a, {c, c}); }

// cos over [a, b] degrees: the ends, and 1 or -1 where a multiple of 360 or an odd multiple of
// 180 lies inside.
Interval cosRange(double a, double b) {
    if (a > b) std::swap(a, b);
    if (b - a >= 360) return {-1, 1};
    Interval r = span(cosDeg(a), cosDeg(b));
    if (std::ceil(a / 360) * 360 <= b) r.hi = 1;
    if (std::ceil((a - 180) / 360) * 360 + 180 <= b) r.lo = -1;
    return r;
}
Interval sinRange(double a, double b) { return cosRange(a - 90, b - 90); }

// The profile curve of each kind: radius rho from the z axis and height z at v, and their
// derivatives in v. The hyperboloid is handled apart (its profile is a line in 3D).
struct Profile {
    double rho, z, drho, dz;
};

// Sphere: the latitude range from zmin and zmax (clamped to the sphere).
void sphereLatitudes(const QuadricMesh::Params& p, double* phiMin, double* phiMax) {
    const double r = p[0];
    const double zmin = std::max(-std::fabs(r), std::min(p[1], p[2]));
    const double zmax = std::min(std::fabs(r), std::max(p[1], p[2]));
    *phiMin = zmin <= -std::fabs(r) ? -90 : std::asin(zmin / std::fabs(r)) / kDeg;
    *phiMax = zmax >= std::fabs(r) ? 90 : std::asin(zmax / std::fabs(r)) / kDeg;
}

Profile profile(QuadricKind kind, const QuadricMesh::Params& p, double v) {
    switch (kind) {
    case QuadricKind::Sphere: {
        double a, b;
        sphereLatitudes(p, &a, &b);
        const double phi = a + v * (b - a), dphi = (b - a) * kDeg, r = std::fabs(p[0]);
        return {r * cosDeg(phi), r * sinDeg(phi), -r * sinDeg(phi) * dphi, r * cosDeg(phi) * dphi};
    }
    case QuadricKind::Cylinder: return {p[0], p[1] + v * (p[2] - p[1]), 0, p[2] - p[1]};
    case QuadricKind::Cone: return {p[1] * (1 - v), v * p[0], -p[1], p[0]};
    case QuadricKind::Disk: return {p[1] * (1 - v), p[0], -p[1], 0};
    case QuadricKind::Paraboloid: {
        const double z = p[1] + v * (p[2] - p[1]), dz = p[2] - p[1];
        const double ratio = std::max(0.0, z / p[2]);
        const double rho = p[0] * std::sqrt(ratio);
        const double drho = ratio > 0 ? p[0] * 0.5 / std::sqrt(ratio) * dz / p[2] : 0;
        return {rho, z, drho, dz};
    }
    case QuadricKind::Torus: {
        const double phi = p[2] + v * (p[3] - p[2]), dphi = (p[3] - p[2]) * kDeg;
        return {p[0] + p[1] * cosDeg(phi), p[1] * sinDeg(phi), -p[1] * sinDeg(phi) * dphi, p[1] * cosDeg(phi) * dphi};
    }
    case QuadricKind::Hyperboloid: break;
    }
    return {0, 0, 0, 0};
}

double thetaMax(QuadricKind kind, const QuadricMesh::Params& p) {
    switch (kind) {
    case QuadricKind::Sphere:
    case QuadricKind::Cylinder:
    case QuadricKind::Paraboloid: return p[3];
    case QuadricKind::Cone:
    case QuadricKind::Disk: return p[2];
    case QuadricKind::Hyperboloid: return p[6];
    case QuadricKind::Torus: return p[4];
    }
    return 360;
}

// Whether the profile end v (0 or 1) lies on the axis (a collapsed edge).
bool endOnAxis(QuadricKind kind, const QuadricMesh::Params& p, double v) {
    if (kind == QuadricKind::Hyperboloid) {
        const double x = v == 0 ? p[0] : p[3], y = v == 0 ? p[1] : p[4];
        return x == 0 && y == 0;
    }
    if (kind == QuadricKind::Torus) return false;
    return profile(kind, p, v).rho == 0;
}

// Corner vertex ids: a full sweep joins u = 0 and u = 1; an end on the axis joins its corners; a
// full torus tube joins v = 0 and v = 1.
std::shared_ptr<const SurfaceTopology> quadricTopology(QuadricKind kind, const QuadricMesh::Params p[2], int keys) {
    bool seamU = true, seamV = kind == QuadricKind::Torus, axis0 = true, axis1 = true;
    for (int k = 0; k < keys; ++k) {
        seamU = seamU && std::fabs(thetaMax(kind, p[k])) >= 360;
        if (kind == QuadricKind::Torus) seamV = seamV && std::fabs(p[k][3] - p[k][2]) >= 360;
        axis0 = axis0 && endOnAxis(kind, p[k], 0);
        axis1 = axis1 && endOnAxis(kind, p[k], 1);
    }
    SurfaceTopology::Face f;
    f.corner = {0, 1, 2, 3};
    f.side = {0, 1, 2, 3};
    if (seamU) f.corner[1] = f.corner[0], f.corner[3] = f.corner[2], f.side[3] = f.side[1];
    if (seamV) f.corner[2] = f.corner[0], f.corner[3] = f.corner[1], f.side[2] = f.side[0];
    if (axis0) f.corner[1] = f.corner[0];
    if (axis1) f.corner[3] = f.corner[2];
    return SurfaceTopology::build({f}, 4, 4);
}

// Whether the quadric differs between the keys of a segment.
bool quadricMoves(const QuadricMesh::Params params[2], const Matrix4 objectToCamera[2], TimeSpan keys) {
    return keys.t1 > keys.t0 && (params[0] != params[1] || objectToCamera[0] != objectToCamera[1]);
}

}  // namespace

QuadricMesh::QuadricMesh(QuadricKind kind, const Params params[2], const Matrix4 objectToCamera[2], TimeSpan keys,
                         const Material* material, const Camera* camera, const std::array<Color, 4>& colors)
    : SurfaceMesh(quadricTopology(kind, params, quadricMoves(params, objectToCamera, keys) ? 2 : 1), keys, material,
                  camera),
      kind_(kind) {
    moving_ = quadricMoves(params, objectToCamera, keys);
    for (int k = 0; k < 2; ++k) {
        params_[k] = params[moving_ ? k : 0];
        toCamera_[k] = objectToCamera[moving_ ? k : 0];
    }
    colors_[0] = colors;
}

void QuadricMesh::derivatives(int, double u, double v, int k, Vec3d* P, Vec3d* dPdu, Vec3d* dPdv) const {
    const Params& p = params_[k];
    const double tmax = thetaMax(kind_, p), theta = u * tmax, dtheta = tmax * kDeg;
    const double c = cosDeg(theta), s = sinDeg(theta);
    Vec3d obj, du, dv;
    if (kind_ == QuadricKind::Hyperboloid) {
        const Vec3d a(p[0], p[1], p[2]), b(p[3], p[4], p[5]);
        const Vec3d q = lerp(a, b, v), dq = b - a;
        obj = {q.x * c - q.y * s, q.x * s + q.y * c, q.z};
        du = Vec3d{-q.x * s - q.y * c, q.x * c - q.y * s, 0} * dtheta;
        dv = {dq.x * c - dq.y * s, dq.x * s + dq.y * c, dq.z};
    } else {
        const Profile pr = profile(kind_, p, v);
        obj = {pr.rho * c, pr.rho * s, pr.z};
        du = Vec3d{-pr.rho * s, pr.rho * c, 0} * dtheta;
        dv = {pr.drho * c, pr.drho * s, pr.dz};
    }
    const Matrix4& m = toCamera_[k];
    *P = m.point(obj);
    *dPdu = m.vector(du);
    *dPdv = m.vector(dv);
}

Bounds3d QuadricMesh::objectBound(const ParamRect& r, int k) const {
    const Params& p = params_[k];
    const double tmax = thetaMax(kind_, p);
    const double ta = r.u0 * tmax, tb = r.u1 * tmax;
    Interval rho, z, psiExtra{0, 0};
    switch (kind_) {
    case QuadricKind::Sphere: {
        double a, b;
        sphereLatitudes(p, &a, &b);
        const double pa = a + r.v0 * (b - a), pb = a + r.v1 * (b - a), rr = std::fabs(p[0]);
        rho = scale(cosRange(pa, pb), rr);
        z = scale(sinRange(pa, pb), rr);
        break;
    }
    case QuadricKind::Torus: {
        const double pa = p[2] + r.v0 * (p[3] - p[2]), pb = p[2] + r.v1 * (p[3] - p[2]);
        rho = add(scale(cosRange(pa, pb), p[1]), p[0]);
        z = scale(sinRange(pa, pb), p[1]);
        break;
    }
    case QuadricKind::Hyperboloid: {
        // The profile is the segment q(v0) .. q(v1); its distance from the axis is smallest at
        // the point of the segment nearest the axis, and its angle about the axis changes
        // monotonically along it.
        const Vec3d a(p[0], p[1], p[2]), b(p[3], p[4], p[5]);
        const Vec3d q0 = lerp(a, b, r.v0), q1 = lerp(a, b, r.v1);
        const double dx = q1.x - q0.x, dy = q1.y - q0.y, dd = dx * dx + dy * dy;
        double tmin = dd > 0 ? -(q0.x * dx + q0.y * dy) / dd : 0;
        tmin = std::min(1.0, std::max(0.0, tmin));
        const double nearest = std::hypot(q0.x + tmin * dx, q0.y + tmin * dy);
        rho = {nearest, std::max(std::hypot(q0.x, q0.y), std::hypot(q1.x, q1.y))};
        z = span(q0.z, q1.z);
        if (nearest > 0) {
            const double a0 = std::atan2(q0.y, q0.x) / kDeg;
            const double turn = std::atan2(q0.x * q1.y - q0.y * q1.x, q0.x * q1.x + q0.y * q1.y) / kDeg;
            psiExtra = span(a0, a0 + turn);
        } else {
            psiExtra = {0, 360};
        }
        break;
    }
    default: {  // cylinder, cone, disk, paraboloid: radius and height monotone in v
        const Profile pa = profile(kind_, p, r.v0), pb = profile(kind_, p, r.v1);
        rho = span(pa.rho, pb.rho);
        z = span(pa.z, pb.z);
    }
    }
    const double lo = std::min(ta, tb) + psiExtra.lo, hi = std::max(ta, tb) + psiExtra.hi;
    const Interval x = mul(rho, cosRange(lo, hi)), y = mul(rho, sinRange(lo, hi));
    return {{x.lo, y.lo, z.lo}, {x.hi, y.hi, z.hi}};
}

Bounds3f QuadricMesh::bound(int, const ParamRect& r, int k) const {
    const Bounds3d ob = objectBound(r, k);
    Bounds3f b;
    for (int c = 0; c < 8; ++c) {
        const Vec3d corner{(c & 1) ? ob.hi.x : ob.lo.x, (c & 2) ? ob.hi.y : ob.lo.y, (c & 4) ? ob.hi.z : ob.lo.z};
        b.extend(Vec3f(toCamera_[k].point(corner)));
    }
    return padded(b);
}

}  // namespace streyes
