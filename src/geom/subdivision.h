// Catmull-Clark subdivision surfaces through OpenSubdiv 3.5: Far for topology, Bfr for the limit
// surface.
//
// SubdivisionShape holds what does not change over motion keys. The mesh's topology (with its
// crease, corner, hole and boundary tags) goes into a Far::TopologyRefiner and is refined once,
// uniformly, to level 1: every face is then a quad (an n-sided face becomes n quads) with at
// most two extraordinary corners, and the level-1 mesh with its tags (sharpness one lower) has
// the same limit surface. A Bfr::RefinerSurfaceFactory on that level-1 mesh gives each face a
// Bfr::Surface, made in parallel (TBB) through Bfr's thread-safe cache, which shares the
// patch trees of irregular faces with equal topology.
//
// SubdivisionKey holds one set of positions (a motion key): the level-1 points (Far's
// PrimvarRefiner) and, per face, what its bodies evaluate and bound:
//   - a regular face is one bicubic B-spline patch: its Bezier form (exact: fitted through 16
//     Bfr evaluations), evaluated and split like any bicubic patch;
//   - an irregular face is evaluated by Bfr from its patch points. Bfr represents it as a tree of
//     leaves, each a bicubic B-spline patch, a Gregory patch or a linear patch; every one of these
//     is a convex combination of its own patch points (B-spline and Bernstein weights, and
//     Gregory's rational blends, are all non-negative). Which patch points a leaf uses is read
//     from Bfr itself: evaluating with the identity matrix as patch points gives each point's
//     weight, and a dyadic cell whose four quadrant centres see the same set of points lies in
//     one leaf. A polynomial leaf gets its Bezier form (as for regular faces) and shrinking
//     bounds; any other leaf is bounded by the box of its own patch points. So the bound of any
//     rectangle of an irregular face is the union of its leaves' bounds: conservative by
//     construction, not by sampling.
// SubdivisionMesh is one motion segment: the shape and the keys at its two ends.
#pragma once

#include <memory>
#include <vector>

#include "geom/surface_mesh.h"

namespace streyes {

class SubdivisionKey;

class SubdivisionShape {
  public:
    // Builds the topology once; throws InputError (at desc.loc) when OpenSubdiv rejects it.
    explicit SubdivisionShape(const SubdivisionMeshDesc& desc);
    ~SubdivisionShape();

    // Faces with a limit surface (level-1 faces that are not holes, and, without
    // interpolateboundary, not on the boundary).
    int faceCount() const;
    int irregularFaceCount() const;
    const std::shared_ptr<const SurfaceTopology>& topology() const;
    // What a set of mesh positions (desc.vertexCount, camera space) gives.
    std::shared_ptr<const SubdivisionKey> key(const std::vector<Vec3d>& P) const;
    // Surface colour at each face's corners from "Cs" by its class, else `color`.
    std::vector<std::array<Color, 4>> colors(const ColorPrimvar& Cs, Color color) const;

    struct Impl;  // OpenSubdiv's objects, kept out of this header
    const Impl& impl() const { return *impl_; }

  private:
    std::unique_ptr<Impl> impl_;
};

// One set of positions: opaque outside src/geom/subdivision.cpp.
class SubdivisionKey {
  public:
    struct Data;
    explicit SubdivisionKey(std::unique_ptr<Data> data);
    ~SubdivisionKey();
    const Data& data() const { return *data_; }

  private:
    std::unique_ptr<Data> data_;
};

class SubdivisionMesh final : public SurfaceMesh {
  public:
    // `key1` may equal `key0` (a still segment).
    SubdivisionMesh(std::shared_ptr<const SubdivisionShape> shape, std::shared_ptr<const SubdivisionKey> key0,
                    std::shared_ptr<const SubdivisionKey> key1, TimeSpan keys, const Material* material,
                    const Camera* camera, std::vector<std::array<Color, 4>> colors);

    bool faceMoving(int f) const override;
    Bounds3f bound(int f, const ParamRect& r, int k) const override;
    bool bezier(int f, const ParamRect& r, int k, BezierPatch* cp) const override;
    // Whether face f is evaluated as one bicubic patch (regular) rather than by Bfr.
    bool regular(int f) const;

  protected:
    void derivatives(int f, double u, double v, int k, Vec3d* P, Vec3d* dPdu, Vec3d* dPdv) const override;

  private:
    const SubdivisionKey::Data& key(int k) const { return (moving() && k == 1 ? key1_ : key0_)->data(); }
    std::shared_ptr<const SubdivisionShape> shape_;
    std::shared_ptr<const SubdivisionKey> key0_, key1_;
};

}  // namespace streyes
