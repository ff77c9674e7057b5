// The RenderMan quadrics (Sphere, Cylinder, Cone, Disk, Paraboloid, Hyperboloid, Torus) as
// one-face SurfaceMeshes, with RenderMan's parameterisation: u sweeps the angle theta from 0
// to thetamax about z, v runs along the profile (from zmin to zmax, from the rim to the apex of a
// cone or disk, from phimin to phimax around a torus's tube).
//
// Bounds are analytic: over a rectangle of (u, v) the profile's radius and height lie in
// intervals, and so do cos and sin of the swept angle; their products bound x and y. A full
// sweep closes the surface: its u = 0 and u = 1 sides are one edge (a seam); a profile end on
// the axis (a sphere's pole, a cone's apex) is a collapsed edge.
#pragma once

#include <array>

#include "geom/surface_mesh.h"
#include "streyes/transform.h"

namespace streyes {

class QuadricMesh final : public SurfaceMesh {
  public:
    using Params = std::array<double, 7>;
    // params and objectToCamera at the keys; key 1 is ignored when the mesh is still (keys equal).
    QuadricMesh(QuadricKind kind, const Params params[2], const Matrix4 objectToCamera[2], TimeSpan keys,
                const Material* material, const Camera* camera, const std::array<Color, 4>& colors);

    bool faceMoving(int) const override { return moving(); }
    Bounds3f bound(int f, const ParamRect& r, int k) const override;

    // The object-space box of the quadric over r (exposed for tests).
    Bounds3d objectBound(const ParamRect& r, int k) const;

  protected:
    void derivatives(int f, double u, double v, int k, Vec3d* P, Vec3d* dPdu, Vec3d* dPdv) const override;

  private:
    QuadricKind kind_;
    Params params_[2];
    Matrix4 toCamera_[2];
};

}  // namespace streyes
