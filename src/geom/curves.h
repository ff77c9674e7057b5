// Curves as ribbons: each segment of each curve is one bicubic Bezier face of a surface mesh,
// cubic along the curve (in the curve's basis, converted to Bezier form) and linear across its
// width, so the curved-body machinery (curved_body.h) bounds, splits and dices it and keeps it
// watertight along the curve (neighbouring segments share their joint as one mesh edge).
//
// At each joint (segment end) the ribbon is centred on the curve and spans the joint's width
// along its side direction: perpendicular to the curve's tangent and to the line of sight (a
// camera-facing ribbon), or to the curve's normal N when one is given, in camera space at each
// motion key. Both segments at a joint use the same joint point, direction and width, so their
// shared edge is one line. Inside a segment the half-width offset is the cubic through its values
// at u = 0, 1/3, 2/3, 1 (the same rule at the curve's own tangent there, the width linear in u):
// exact for a straight ribbon.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "geom/surface_mesh.h"
#include "streyes/scene.h"
#include "streyes/transform.h"

namespace streyes {

// The shape of a Curves primitive (what does not change over its keys): its segments, joints and
// topology. It reads `desc` (widths, normals, colours) while it is used: made and used within one
// call of the body factory.
class CurveRibbons {
  public:
    explicit CurveRibbons(const CurvesDesc& desc);

    int faceCount() const { return int(segments_.size()); }
    const std::shared_ptr<const SurfaceTopology>& topology() const { return topology_; }
    // Every segment's Bezier face at one key: the control points P (all curves, camera space) and
    // the key's object-to-camera matrix (for widths and normals); `perspective` says where the
    // eye is (the origin, or at infinity looking down +z).
    std::vector<BezierPatch> patches(const std::vector<Vec3d>& P, const Matrix4& toCamera, bool perspective) const;
    // The colour at each face's corners: the primitive's "Cs" by its class, else `color`.
    std::vector<std::array<Color, 4>> colors(Color color) const;

  private:
    struct Segment {
        int curve;
        int first;           // its first control point, within the curve
        int joint0, joint1;  // joint indices (global): the segment runs from joint0 to joint1
    };
    // A per-joint value of a primitive variable given by class (one per curve, joint or vertex).
    template <typename V>
    V atJoint(ParamClass cls, const std::vector<V>& values, int joint) const;

    const CurvesDesc& desc_;
    bool cubic_;
    int step_;
    Matrix4x4 toBezier_;
    std::vector<Segment> segments_;
    std::vector<int> curveOfJoint_, vertexOffset_, jointOffset_;
    std::shared_ptr<const SurfaceTopology> topology_;
};

}  // namespace streyes
