// CurvedBody: a piece of one face of a SurfaceMesh (a bicubic patch, a subdivision face, a
// quadric, a NuPatch) over a rectangle of its parameter space and a span of time: the spacetime
// body of every curved primitive.
//
// Bound: the hull of the piece's Bezier control points at t0 and t1 where the face is a bicubic
// polynomial there (split by de Casteljau with the piece), otherwise the box the mesh gives for
// the rectangle (analytic for quadrics, the hull of the patch points for irregular subdivision
// faces, the hull of the piece's rational Bezier nets for NuPatches). Split: at the parameter
// midpoint, so pieces cover dyadic rectangles; t splits halve the time span.
//
// Crack-free dicing, "shared edges diced identically": every side of a piece lies on a line of
// parameter space (a mesh edge, or an iso-line u = c or v = c of its face), and the vertices
// on a side are the points of that line's lattice inside the side, plus the side's two corners.
// A line's lattice is a function of the line alone (not of the piece): a binary tree over the
// line's parameter whose nodes are refined while their raster length at the mesh's keys is more
// than 8 micropolygons; a leaf holds 2^k equal steps, the fewest no longer than two micropolygon edges.
// So two pieces that meet along a line, however deeply each was split, put the same vertices
// on their common part of it, evaluated by the same owner (SurfaceMesh::evaluatePoint): the
// same bits. A corner made by a split lies on the parent's side; where that point is not on the
// side's lattice (the side was shorter than one step), it is placed on the lattice's chord, where
// the coarser neighbour's edge runs. A grid whose side has fewer vertices than its rows repeats
// vertices there (degenerate quads, which the rasterizer skips).
#pragma once

#include "geom/body.h"
#include "geom/surface_mesh.h"

namespace streyes {

// A line of parameter space: a mesh edge (parameter along the edge's owner side), or the
// iso-line u = c (parameter v) or v = c (parameter u) of one face.
struct SurfaceLine {
    enum Kind : unsigned char { Edge, IsoU, IsoV };
    Kind kind = Edge;
    int id = 0;  // edge or face
    double c = 0;
};

// One side of a piece: the segment [a, b] of a line, and what is known of the line's lattice
// there: nothing yet, the leaf [la, lb] with `rate` equal steps that holds it, or that [a, b]
// is a refined node of the tree (its midpoint is a vertex).
struct PieceSide {
    enum State : unsigned char { Unknown, BelowRefined, InLeaf, Refined };
    SurfaceLine line;
    double a = 0, b = 1;
    bool reversed = false;  // the piece's side runs from b to a
    State state = Unknown;  // BelowRefined: unknown, but every ancestor node is refined
    double la = 0, lb = 1;
    int rate = 1;
};

// A corner of a piece: its position and normal at the mesh's two keys.
struct PieceCorner {
    Vec3f P[2], N[2];
};

class CurvedBody final : public Body {
  public:
    // The whole face f over the mesh's time span.
    CurvedBody(const SurfaceMesh* mesh, int face);

    const SurfaceMesh& mesh() const { return *mesh_; }
    int face() const { return face_; }
    const ParamRect& rect() const { return rect_; }
    bool hasBezier() const { return hasBezier_; }

    LBBox3f bound() const override;
    RasterMeasure measure(const Camera& camera) const override;
    CameraExtents cameraExtents() const override;
    void split(SplitAxis axis, std::unique_ptr<Body> out[2]) const override;
    std::unique_ptr<Body> restrictedTo(double a, double b) const override;
    // Dices at least nu x nv micropolygons, more where a side's lattice has more vertices.
    void dice(int nu, int nv, Grid& grid) const override;
    size_t memoryBytes() const override { return heapBlockBytes(sizeof(*this)); }  // the mesh is shared
    float latticeRate() const override { return mesh_->shadingRate(); }

  private:
    CurvedBody() = default;
    void setPayload();                       // control points or box for the rectangle
    float keyFraction(double t) const;       // t as a fraction of the mesh's key span
    Vec3f atTime(const Vec3f p[2], float s) const { return moving_ ? lerp(p[0], p[1], s) : p[0]; }
    void sampleGrid(int n, Vec3f* out, int k) const;  // n x n points of the face at key k
    std::unique_ptr<CurvedBody> child() const;

    const SurfaceMesh* mesh_ = nullptr;
    int face_ = 0;
    ParamRect rect_;
    PieceCorner corner_[4];
    PieceSide side_[4];
    bool hasBezier_ = false;
    BezierPatch cp_[2];      // at t0 and t1 (when hasBezier_)
    Bounds3f box_[2];        // at t0 and t1 (otherwise)
    // A whole face is culled in every bucket it misses: its bound and raster measure are
    // computed once, when it is made (they do not change, and the camera is the mesh's).
    bool cached_ = false;
    LBBox3f cachedBound_;
    RasterMeasure cachedMeasure_;
};

}  // namespace streyes
