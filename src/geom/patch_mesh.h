// Patch meshes: Patch "bicubic", PatchMesh "bicubic" and PatchMesh "bilinear" as SurfaceMeshes
// whose faces are Bezier patches (bilinear patches are degree-elevated, which is exact).
//
// PatchMeshShape is what does not change over motion keys: the patch grid (RenderMan's nupatches
// x nvpatches with periodic wrap), the topology it gives (patches that share an edge of the
// grid share it as a mesh edge) and the change of basis to Bezier form. BezierMesh is one
// motion segment of it: the Bezier control points at the segment's two keys.
#pragma once

#include <memory>
#include <vector>

#include "geom/surface_mesh.h"

namespace streyes {

class PatchMeshShape {
  public:
    explicit PatchMeshShape(const PatchMeshDesc& desc);

    int patchCount() const { return nup_ * nvp_; }
    const std::shared_ptr<const SurfaceTopology>& topology() const { return topology_; }
    // The Bezier control points of every patch, from the mesh's control points (u fastest).
    std::vector<BezierPatch> patches(const std::vector<Vec3d>& P) const;
    // The surface colour at each patch's corners: the primitive's "Cs" by its class, else `color`.
    std::vector<std::array<Color, 4>> colors(const ColorPrimvar& Cs, Color color) const;

  private:
    template <typename V>
    void patchControls(const std::vector<V>& P, int pi, int pj, Vec3d g[16]) const;

    bool bicubic_;
    int nu_, nv_, nup_, nvp_, ustep_, vstep_;
    bool uPeriodic_, vPeriodic_;
    Matrix4x4 cu_, cv_;
    std::shared_ptr<const SurfaceTopology> topology_;
};

class BezierMesh final : public SurfaceMesh {
  public:
    // `key1` empty: a still mesh.
    BezierMesh(std::shared_ptr<const SurfaceTopology> topology, TimeSpan keys, const Material* material,
               const Camera* camera, std::vector<BezierPatch> key0, std::vector<BezierPatch> key1,
               std::vector<std::array<Color, 4>> colors);

    bool faceMoving(int f) const override;
    Bounds3f bound(int f, const ParamRect& r, int k) const override;
    bool bezier(int f, const ParamRect& r, int k, BezierPatch* cp) const override;

  protected:
    void derivatives(int f, double u, double v, int k, Vec3d* P, Vec3d* dPdu, Vec3d* dPdv) const override;

  private:
    const BezierPatch& patch(int f, int k) const { return patches_[moving() ? k : 0][size_t(f)]; }
    std::vector<BezierPatch> patches_[2];
};

}  // namespace streyes
