#include "geom/surface_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace streyes {

// ---- Topology --------------------------------------------------------------------------------------
std::shared_ptr<const SurfaceTopology> SurfaceTopology::build(std::vector<Face> faces, int vertexCount, int edgeCount) {
    auto t = std::make_shared<SurfaceTopology>();
    t->vertexOwner.assign(size_t(vertexCount), Owner{});
    t->edgeOwner.assign(size_t(edgeCount), Owner{});
    std::vector<bool> ownerReversed(size_t(edgeCount), false);
    for (size_t f = 0; f < faces.size(); ++f) {
        Face& face = faces[f];
        for (int c = 0; c < 4; ++c) {
            Owner& o = t->vertexOwner[size_t(face.corner[size_t(c)])];
            if (o.face < 0) o = {int(f), c};
        }
        for (int k = 0; k < 4; ++k) {
            const size_t e = size_t(face.side[size_t(k)]);
            if (t->edgeOwner[e].face < 0) {
                t->edgeOwner[e] = {int(f), k};
                ownerReversed[e] = face.reversed[size_t(k)];
            }
            face.reversed[size_t(k)] = face.reversed[size_t(k)] != ownerReversed[e];
        }
    }
    t->faces = std::move(faces);
    return t;
}

// ---- Evaluation -------------------------------------------------------------------------------------
SurfaceMesh::SurfaceMesh(std::shared_ptr<const SurfaceTopology> topology, TimeSpan keys, const Material* material,
                         const Camera* camera)
    : topology_(std::move(topology)), keys_(keys), material_(material), camera_(camera) {
    colors_.assign(topology_->faces.size(), std::array<Color, 4>{});
}

bool SurfaceMesh::bezier(int, const ParamRect&, int, BezierPatch*) const { return false; }
bool SurfaceMesh::trimQuads(int, const ParamRect&, int, int, std::vector<uint8_t>&) const { return false; }
bool SurfaceMesh::trimmedAway(int, const ParamRect&) const { return false; }

void SurfaceMesh::evaluate(int f, double u, double v, int k, Vec3f* P, Vec3f* N) const {
    Vec3d p, du, dv;
    derivatives(f, u, v, k, &p, &du, &dv);
    *P = Vec3f(p);
    if (!N) return;
    Vec3d n = cross(du, dv);
    const double scale = dot(du, du) * dot(dv, dv);
    if (!(dot(n, n) > 1e-20 * scale && dot(n, n) > 0)) {
        // Derivatives vanish or are parallel here (a pole, a collapsed edge): take the normal a
        // little way towards the middle of the face, the same wherever the point is evaluated.
        Vec3d p2;
        derivatives(f, u + 1e-3 * (0.5 - u), v + 1e-3 * (0.5 - v), k, &p2, &du, &dv);
        n = cross(du, dv);
        if (!(dot(n, n) > 0)) n = {0, 0, -1};
    }
    *N = Vec3f(n);
}

void SurfaceMesh::evaluateEdge(int e, double s, int k, Vec3f* P, Vec3f* N) const {
    const SurfaceTopology::Owner& o = topology_->edgeOwner[size_t(e)];
    double u, v;
    sideParam(o.index, s, &u, &v);
    evaluate(o.face, u, v, k, P, N);
}

void SurfaceMesh::evaluatePoint(int f, double u, double v, int k, Vec3f* P, Vec3f* N) const {
    const bool uEnd = u == 0 || u == 1, vEnd = v == 0 || v == 1;
    const SurfaceTopology::Face& face = topology_->faces[size_t(f)];
    if (uEnd && vEnd) {
        const int c = (u == 1 ? 1 : 0) + (v == 1 ? 2 : 0);
        const SurfaceTopology::Owner& o = topology_->vertexOwner[size_t(face.corner[size_t(c)])];
        double ou, ov;
        cornerParam(o.index, &ou, &ov);
        evaluate(o.face, ou, ov, k, P, N);
    } else if (uEnd || vEnd) {
        const int side = vEnd ? (v == 0 ? 0 : 2) : (u == 0 ? 3 : 1);
        double s = vEnd ? u : v;
        if (face.reversed[size_t(side)]) s = 1 - s;
        evaluateEdge(face.side[size_t(side)], s, k, P, N);
    } else {
        evaluate(f, u, v, k, P, N);
    }
}

Color SurfaceMesh::latticeColor(double u, double v) const {
    // The cell of a non-decreasing list of parameters holding t (the last non-empty one at a
    // repeated value), and t's fraction across it.
    auto cell = [](const std::vector<double>& p, double t, float* f) {
        size_t i = size_t(std::upper_bound(p.begin(), p.end(), t) - p.begin());
        i = std::min(std::max(i, size_t(1)), p.size() - 1) - 1;
        while (i > 0 && !(p[i] < p[i + 1])) --i;
        *f = p[i] < p[i + 1] ? float((t - p[i]) / (p[i + 1] - p[i])) : 0.0f;
        return i;
    };
    float fu, fv;
    const size_t i = cell(lattice_.u, u, &fu), j = cell(lattice_.v, v, &fv), n = lattice_.u.size();
    const Color* c = lattice_.c.data();
    return bilerp(std::array<Color, 4>{c[j * n + i], c[j * n + i + 1], c[(j + 1) * n + i], c[(j + 1) * n + i + 1]}, fu,
                  fv);
}

// ---- Bounds -----------------------------------------------------------------------------------------
Bounds3f padded(Bounds3f b) {
    if (b.empty()) return b;
    const float m = std::max({std::fabs(b.lo.x), std::fabs(b.lo.y), std::fabs(b.lo.z), std::fabs(b.hi.x),
                              std::fabs(b.hi.y), std::fabs(b.hi.z)});
    const float e = 4e-6f * m + 1e-30f;
    const Vec3f pad{e, e, e};
    return {b.lo - pad, b.hi + pad};
}

Bounds3f paddedBound(const Vec3f* points, size_t n) {
    Bounds3f b;
    for (size_t i = 0; i < n; ++i) b.extend(points[i]);
    return padded(b);
}

}  // namespace streyes
