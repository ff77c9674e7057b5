#include "geom/patch_mesh.h"

namespace streyes {

// ---- The patch grid ---------------------------------------------------------------------------------
PatchMeshShape::PatchMeshShape(const PatchMeshDesc& d)
    : bicubic_(d.bicubic), nu_(d.nu), nv_(d.nv), nup_(d.uPatches()), nvp_(d.vPatches()),
      ustep_(d.bicubic ? d.uBasis.step : 1), vstep_(d.bicubic ? d.vBasis.step : 1), uPeriodic_(d.uPeriodic),
      vPeriodic_(d.vPeriodic) {
    if (bicubic_) {
        cu_ = basisToBezier(d.uBasis);
        cv_ = basisToBezier(d.vBasis);
    }
    // Patch corners are the nodes of the varying grid; its lines are the edges: a row of
    // horizontal edges per grid row, a column of vertical ones per grid column. Periodic meshes
    // wrap around.
    const int nuv = d.uVarying(), nvv = d.vVarying();
    const int horizontal = nup_ * nvv;
    std::vector<SurfaceTopology::Face> faces;
    for (int pj = 0; pj < nvp_; ++pj)
        for (int pi = 0; pi < nup_; ++pi) {
            const int i1 = (pi + 1) % nuv, j1 = (pj + 1) % nvv;
            SurfaceTopology::Face f;
            f.corner = {pj * nuv + pi, pj * nuv + i1, j1 * nuv + pi, j1 * nuv + i1};
            f.side = {pj * nup_ + pi, horizontal + pj * nuv + i1, j1 * nup_ + pi, horizontal + pj * nuv + pi};
            faces.push_back(f);
        }
    topology_ = SurfaceTopology::build(std::move(faces), nuv * nvv, horizontal + nuv * nvp_);
}

template <typename V>
void PatchMeshShape::patchControls(const std::vector<V>& P, int pi, int pj, Vec3d g[16]) const {
    const int n = bicubic_ ? 4 : 2;
    for (int l = 0; l < n; ++l)
        for (int k = 0; k < n; ++k) {
            const int i = (pi * ustep_ + k) % nu_, j = (pj * vstep_ + l) % nv_;
            g[l * n + k] = Vec3d(P[size_t(j * nu_ + i)]);
        }
}

std::vector<BezierPatch> PatchMeshShape::patches(const std::vector<Vec3d>& P) const {
    std::vector<BezierPatch> out(static_cast<size_t>(patchCount()));
    for (int pj = 0; pj < nvp_; ++pj)
        for (int pi = 0; pi < nup_; ++pi) {
            Vec3d g[16];
            patchControls(P, pi, pj, g);
            BezierPatch& b = out[size_t(pj * nup_ + pi)];
            if (bicubic_) {
                b = patchToBezier(cu_, cv_, g);
            } else {
                // A bilinear patch is the bicubic with control points at thirds of its corners.
                for (int j = 0; j < 4; ++j)
                    for (int i = 0; i < 4; ++i) {
                        const double u = i / 3.0, v = j / 3.0;
                        b[size_t(j * 4 + i)] = Vec3f(lerp(lerp(g[0], g[1], u), lerp(g[2], g[3], u), v));
                    }
            }
        }
    return out;
}

std::vector<std::array<Color, 4>> PatchMeshShape::colors(const ColorPrimvar& Cs, Color color) const {
    std::vector<std::array<Color, 4>> out(static_cast<size_t>(patchCount()));
    const int nuv = uPeriodic_ ? nup_ : nup_ + 1;
    for (int pj = 0; pj < nvp_; ++pj)
        for (int pi = 0; pi < nup_; ++pi) {
            std::array<Color, 4>& c = out[size_t(pj * nup_ + pi)];
            c.fill(color);
            if (!Cs.given()) continue;
            switch (Cs.cls) {
            case ParamClass::Constant: c.fill(Cs.values[0]); break;
            case ParamClass::Uniform: c.fill(Cs.values[size_t(pj * nup_ + pi)]); break;
            case ParamClass::Vertex: {
                // Vertex colours follow the basis like positions; the corners of the Bezier form
                // are the colours there, interpolated bilinearly in between.
                std::vector<Vec3d> values(Cs.values.begin(), Cs.values.end());
                Vec3d g[16];
                patchControls(values, pi, pj, g);
                if (bicubic_) {
                    BezierPatch b = patchToBezier(cu_, cv_, g);
                    c = {b[0], b[3], b[12], b[15]};
                } else {
                    c = {Vec3f(g[0]), Vec3f(g[1]), Vec3f(g[2]), Vec3f(g[3])};
                }
                break;
            }
            default: {  // varying (and facevarying, read as varying): the corners of the patch grid
                const int nvv = vPeriodic_ ? nvp_ : nvp_ + 1;
                const int i1 = (pi + 1) % nuv, j1 = (pj + 1) % nvv;
                c = {Cs.values[size_t(pj * nuv + pi)], Cs.values[size_t(pj * nuv + i1)],
                     Cs.values[size_t(j1 * nuv + pi)], Cs.values[size_t(j1 * nuv + i1)]};
            }
            }
        }
    return out;
}

// ---- One motion segment -----------------------------------------------------------------------------
BezierMesh::BezierMesh(std::shared_ptr<const SurfaceTopology> topology, TimeSpan keys, const Material* material,
                       const Camera* camera, std::vector<BezierPatch> key0, std::vector<BezierPatch> key1,
                       std::vector<std::array<Color, 4>> colors)
    : SurfaceMesh(std::move(topology), keys, material, camera) {
    moving_ = !key1.empty() && key1 != key0;
    patches_[0] = std::move(key0);
    if (moving_) patches_[1] = std::move(key1);
    colors_ = std::move(colors);
}

bool BezierMesh::faceMoving(int f) const { return moving() && patches_[0][size_t(f)] != patches_[1][size_t(f)]; }

Bounds3f BezierMesh::bound(int f, const ParamRect& r, int k) const {
    return paddedBound(bezierSubPatch(patch(f, k), r.u0, r.u1, r.v0, r.v1).data(), 16);
}

bool BezierMesh::bezier(int f, const ParamRect& r, int k, BezierPatch* cp) const {
    const BezierPatch& p = patch(f, k);
    *cp = r.u0 == 0 && r.u1 == 1 && r.v0 == 0 && r.v1 == 1 ? p : bezierSubPatch(p, r.u0, r.u1, r.v0, r.v1);
    return true;
}

void BezierMesh::derivatives(int f, double u, double v, int k, Vec3d* P, Vec3d* dPdu, Vec3d* dPdv) const {
    evalBezier(patch(f, k), u, v, P, dPdu, dPdv);
}

}  // namespace streyes
