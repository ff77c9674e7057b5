#include "geom/nurbs_mesh.h"

#include <cmath>

#include "geom/nurbs.h"

namespace streyes {

namespace {

NurbsSurface surfaceOf(const NurbsShape& s, const std::vector<Vec3d>& points) {
    NurbsSurface n;
    n.nu = s.nu, n.uorder = s.uorder, n.nv = s.nv, n.vorder = s.vorder;
    n.uknot = s.uknot.data(), n.vknot = s.vknot.data(), n.w = s.w.data(), n.P = points.data();
    return n;
}

// Whether two boundary curves are one curve (points within `tol`, weights in one ratio), and
// whether one is a single point.
bool sameCurve(const std::vector<HPoint>& a, const std::vector<HPoint>& b, double tol) {
    const double ratio = a[0].w / b[0].w;
    for (size_t i = 0; i < a.size(); ++i)
        if (length(a[i].p / a[i].w - b[i].p / b[i].w) > tol || std::fabs(a[i].w / b[i].w - ratio) > 1e-9 * ratio)
            return false;
    return true;
}
bool onePoint(const std::vector<HPoint>& a, double tol) {
    for (const HPoint& h : a)
        if (length(h.p / h.w - a[0].p / a[0].w) > tol) return false;
    return true;
}

// Seams and collapsed sides, as quadricTopology makes them, where they hold at every key.
std::shared_ptr<const SurfaceTopology> nurbsTopology(const NurbsShape& s, const std::vector<Vec3d>& key0,
                                                     const std::vector<Vec3d>& key1, bool moving) {
    const std::vector<Vec3d>* keys[2] = {&key0, &key1};
    const int count = moving ? 2 : 1;
    bool seamU = true, seamV = true, collapsed[4] = {true, true, true, true};  // sides v0, u1, v1, u0
    std::vector<HPoint> lo, hi;
    for (int k = 0; k < count; ++k) {
        const NurbsSurface n = surfaceOf(s, *keys[k]);
        Bounds3d box;
        for (const Vec3d& p : *keys[k]) box.extend(p);
        const Vec3d d = box.diagonal();
        const Vec3d far = vmax(Vec3d(std::fabs(box.lo.x), std::fabs(box.lo.y), std::fabs(box.lo.z)),
                               Vec3d(std::fabs(box.hi.x), std::fabs(box.hi.y), std::fabs(box.hi.z)));
        const double tol = 1e-9 * std::max({d.x, d.y, d.z, far.x, far.y, far.z});
        n.isoCurve(true, s.umin, &lo);
        n.isoCurve(true, s.umax, &hi);
        seamU = seamU && sameCurve(lo, hi, tol);
        collapsed[3] = collapsed[3] && onePoint(lo, tol);
        collapsed[1] = collapsed[1] && onePoint(hi, tol);
        n.isoCurve(false, s.vmin, &lo);
        n.isoCurve(false, s.vmax, &hi);
        seamV = seamV && sameCurve(lo, hi, tol);
        collapsed[0] = collapsed[0] && onePoint(lo, tol);
        collapsed[2] = collapsed[2] && onePoint(hi, tol);
    }
    SurfaceTopology::Face f;
    f.corner = {0, 1, 2, 3};
    f.side = {0, 1, 2, 3};
    if (seamU) f.corner[1] = f.corner[0], f.corner[3] = f.corner[2], f.side[1] = f.side[3];
    if (seamV) f.corner[2] = f.corner[0], f.corner[3] = f.corner[1], f.side[2] = f.side[0];
    // A collapsed side joins its two corners (a side that is also a seam's is left as it is).
    if (collapsed[0] && !seamV) f.corner[1] = f.corner[0];
    if (collapsed[2] && !seamV) f.corner[3] = f.corner[2];
    if (collapsed[3] && !seamU) f.corner[2] = f.corner[0];
    if (collapsed[1] && !seamU) f.corner[3] = f.corner[1];
    return SurfaceTopology::build({f}, 4, 4);
}

bool keysDiffer(const std::vector<Vec3d>& key1, const std::vector<Vec3d>& key0, TimeSpan keys) {
    return keys.t1 > keys.t0 && !key1.empty() && key1 != key0;
}

}  // namespace

NurbsMesh::NurbsMesh(std::shared_ptr<const NurbsShape> shape, std::vector<Vec3d> key0, std::vector<Vec3d> key1,
                     TimeSpan keys, const Material* material, const Camera* camera, const std::array<Color, 4>& colors,
                     const std::vector<Color>& varying)
    : SurfaceMesh(nurbsTopology(*shape, key0, key1, keysDiffer(key1, key0, keys)), keys, material, camera),
      shape_(std::move(shape)) {
    moving_ = keysDiffer(key1, key0, keys);
    points_[0] = std::move(key0);
    if (moving_) points_[1] = std::move(key1);
    colors_[0] = colors;
    if (!varying.empty()) {
        // The knots knot[order - 1] .. knot[n] as face parameters.
        const NurbsShape& s = *shape_;
        for (int i = s.uorder - 1; i <= s.nu; ++i)
            lattice_.u.push_back((s.uknot[size_t(i)] - s.umin) / (s.umax - s.umin));
        for (int j = s.vorder - 1; j <= s.nv; ++j)
            lattice_.v.push_back((s.vknot[size_t(j)] - s.vmin) / (s.vmax - s.vmin));
        lattice_.c = varying;
    }
}

NurbsSurface NurbsMesh::surface(int k) const { return surfaceOf(*shape_, points_[moving_ ? k : 0]); }

void NurbsMesh::derivatives(int, double s, double t, int k, Vec3d* P, Vec3d* dPdu, Vec3d* dPdv) const {
    const NurbsShape& sh = *shape_;
    const double du = sh.umax - sh.umin, dv = sh.vmax - sh.vmin;
    // The ends map exactly onto umin and umax (lerp), so a seam's two sides meet bit for bit.
    surface(k).evaluate(lerp(sh.umin, sh.umax, s), lerp(sh.vmin, sh.vmax, t), P, dPdu, dPdv);
    *dPdu = *dPdu * du;
    *dPdv = *dPdv * dv;
}

Bounds3f NurbsMesh::bound(int, const ParamRect& r, int k) const {
    const NurbsShape& sh = *shape_;
    const Bounds3d b = surface(k).bound(lerp(sh.umin, sh.umax, r.u0), lerp(sh.umin, sh.umax, r.u1),
                                        lerp(sh.vmin, sh.vmax, r.v0), lerp(sh.vmin, sh.vmax, r.v1));
    return padded(Bounds3f(Vec3f(b.lo), Vec3f(b.hi)));
}

bool NurbsMesh::trimQuads(int, const ParamRect& r, int nu, int nv, std::vector<uint8_t>& hole) const {
    const NurbsShape& sh = *shape_;
    if (!sh.trim) return false;
    return sh.trim->mark(lerp(sh.umin, sh.umax, r.u0), lerp(sh.umin, sh.umax, r.u1), lerp(sh.vmin, sh.vmax, r.v0),
                         lerp(sh.vmin, sh.vmax, r.v1), nu, nv, hole);
}

bool NurbsMesh::trimmedAway(int, const ParamRect& r) const {
    const NurbsShape& sh = *shape_;
    return sh.trim && sh.trim->covers(lerp(sh.umin, sh.umax, r.u0), lerp(sh.umin, sh.umax, r.u1),
                                      lerp(sh.vmin, sh.vmax, r.v0), lerp(sh.vmin, sh.vmax, r.v1));
}

}  // namespace streyes
