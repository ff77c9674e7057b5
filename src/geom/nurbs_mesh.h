// A NuPatch as a one-face SurfaceMesh over one motion segment: face parameter (s, t) in [0, 1]^2
// is the patch's (umin + s (umax - umin), vmin + t (vmax - vmin)). Pieces are CurvedBodies that
// split in this parameter space; their bound is the hull of the piece's own rational Bezier net
// (NurbsSurface::bound), so it shrinks with the piece; dicing evaluates the surface exactly, with
// normals from its exact derivatives. A patch whose u = umin and u = umax boundary curves are one
// curve (a surface of revolution) has a seam there, one edge evaluated by one side, so its
// pieces meet without cracks; a boundary curve that is one point (a disc's centre, a pole) is a
// collapsed side. The same for v.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "geom/nurbs.h"
#include "geom/nurbs_trim.h"
#include "geom/surface_mesh.h"

namespace streyes {

// What the motion segments of one NuPatch share: knots, weights, range and trim region.
struct NurbsShape {
    int nu = 0, uorder = 0, nv = 0, vorder = 0;
    std::vector<double> uknot, vknot, w;
    double umin = 0, umax = 1, vmin = 0, vmax = 1;
    std::shared_ptr<const NurbsTrim> trim;  // none when untrimmed
};

class NurbsMesh final : public SurfaceMesh {
  public:
    // Camera-space control points at the segment's two keys (key1 empty or equal: still).
    // `varying`: Cs at the knots (RenderMan's varying class: (spans + 1) per direction, u fastest)
    // when given for a patch of several spans; otherwise the corners' `colors`.
    NurbsMesh(std::shared_ptr<const NurbsShape> shape, std::vector<Vec3d> key0, std::vector<Vec3d> key1, TimeSpan keys,
              const Material* material, const Camera* camera, const std::array<Color, 4>& colors,
              const std::vector<Color>& varying = {});

    bool faceMoving(int) const override { return moving(); }
    Bounds3f bound(int f, const ParamRect& r, int k) const override;
    bool trimQuads(int f, const ParamRect& r, int nu, int nv, std::vector<uint8_t>& hole) const override;
    bool trimmedAway(int f, const ParamRect& r) const override;

    // The surface at key k over the patch's own (u, v) (exposed for tests).
    NurbsSurface surface(int k) const;

  protected:
    void derivatives(int f, double u, double v, int k, Vec3d* P, Vec3d* dPdu, Vec3d* dPdv) const override;

  private:
    std::shared_ptr<const NurbsShape> shape_;
    std::vector<Vec3d> points_[2];
};

}  // namespace streyes
