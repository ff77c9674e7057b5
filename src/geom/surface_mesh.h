// The shared part of curved bodies: the faces of one surface (a patch mesh, a subdivision mesh,
// a quadric) over one motion segment, in camera space at the segment's two keys.
//
// A face is a map from [0, 1]^2 to camera space. Bodies are pieces of faces (CurvedBody, in
// curved_body.h): a piece holds the rectangle of parameter space it covers and asks its mesh
// for positions. Faces that meet share edges and vertices, and every point on a shared edge or
// vertex is evaluated by one owner face ("canonical evaluation"), so that the pieces on both
// sides of an edge get the same bits for the same point; the rasterizer is watertight for grids
// that share vertices exactly.
//
// Positions move linearly between the two keys (the segment's ends), as control points do; a
// mesh whose keys are equal is still.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "geom/bezier.h"
#include "geom/body.h"
#include "geom/camera.h"

namespace streyes {

struct ParamRect {
    double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
};

// Which faces share which edges and vertices. Face corners are in RenderMan patch order:
// 0 = (0,0), 1 = (1,0), 2 = (0,1), 3 = (1,1). Sides: 0 is v = 0, 1 is u = 1, 2 is v = 1,
// 3 is u = 0, each running in increasing u or v. An edge's parameter runs along its owner's
// side (the first side that uses it); `reversed` says that a face's side runs the other way.
// A side whose two corners are one vertex and whose edge no other side uses is a collapsed
// edge (a sphere's pole).
struct SurfaceTopology {
    struct Face {
        std::array<int, 4> corner{};
        std::array<int, 4> side{};
        std::array<bool, 4> reversed{};
    };
    struct Owner {
        int face = -1, index = -1;  // the owner face, and its corner or side
    };
    std::vector<Face> faces;
    std::vector<Owner> edgeOwner, vertexOwner;

    // Edges are given by id (corner vertices alone cannot tell a torus's two seams apart), with
    // `reversed` marking sides that run against their edge's own direction; build() finds the
    // owners and makes `reversed` relative to the owner's side.
    static std::shared_ptr<const SurfaceTopology> build(std::vector<Face> faces, int vertexCount, int edgeCount);
};

// The (u, v) of corner c, and of parameter s along side k.
inline void cornerParam(int c, double* u, double* v) {
    *u = (c & 1) ? 1.0 : 0.0;
    *v = (c & 2) ? 1.0 : 0.0;
}
inline void sideParam(int k, double s, double* u, double* v) {
    *u = k == 1 ? 1.0 : k == 3 ? 0.0 : s;
    *v = k == 0 ? 0.0 : k == 2 ? 1.0 : s;
}

class SurfaceMesh {
  public:
    SurfaceMesh(std::shared_ptr<const SurfaceTopology> topology, TimeSpan keys, const Material* material,
                const Camera* camera);
    virtual ~SurfaceMesh() = default;

    const SurfaceTopology& topology() const { return *topology_; }
    int faceCount() const { return int(topology_->faces.size()); }
    // The segment: positions are given at keys().t0 (key 0) and keys().t1 (key 1).
    const TimeSpan& keys() const { return keys_; }
    // Whether the keys differ (a still mesh is evaluated at key 0 only).
    bool moving() const { return moving_; }
    const Material* material() const { return material_; }
    // Pixels of area per micropolygon (the ShadingRate attribute): sets the lattices' steps.
    float shadingRate() const { return shadingRate_; }
    void setShadingRate(float rate) { shadingRate_ = rate; }
    // The camera the mesh is rendered with: pieces measure edges in raster space.
    const Camera& camera() const { return *camera_; }
    const SourceLoc* source() const { return source_; }
    void setSource(const SourceLoc* s) { source_ = s; }

    // Whether face f differs between the keys.
    virtual bool faceMoving(int f) const = 0;
    // A box containing face f over r at key k.
    virtual Bounds3f bound(int f, const ParamRect& r, int k) const = 0;
    // The Bezier control points of face f over r at key k, when the face is one bicubic
    // polynomial there (their hull is then a bound that shrinks with r).
    virtual bool bezier(int f, const ParamRect& r, int k, BezierPatch* cp) const;

    // Trimming: for an nu x nv grid over r of face f, hole[j * nu + i] = 1 where micropolygon (i, j)
    // is cut away. False (hole untouched) where nothing is cut; a NuPatch with TrimCurve overrides it.
    virtual bool trimQuads(int f, const ParamRect& r, int nu, int nv, std::vector<uint8_t>& hole) const;
    // Whether a trim curve cuts away all of face f over r (false when unsure).
    virtual bool trimmedAway(int f, const ParamRect& r) const;

    // Face f's own map at (u, v), key k: position and geometric normal (not unit length). Where
    // the derivatives vanish (a pole, a collapsed edge) the normal is taken a little inside.
    void evaluate(int f, double u, double v, int k, Vec3f* P, Vec3f* N) const;
    // The same, through the owner of the shared edge or vertex the point lies on.
    void evaluatePoint(int f, double u, double v, int k, Vec3f* P, Vec3f* N) const;
    // The point at parameter s along edge e.
    void evaluateEdge(int e, double s, int k, Vec3f* P, Vec3f* N) const;

    // Surface colour at the corners of face f, bilinear across it (RenderMan's varying
    // interpolation).
    const std::array<Color, 4>& faceColors(int f) const { return colors_[size_t(f)]; }
    // The colour at (u, v) of face f: bilinear between its corners, or, where the mesh has a
    // colour lattice (a NuPatch's varying Cs at its knots), between the corners of the lattice's
    // cell holding (u, v).
    Color colorAt(int f, double u, double v) const {
        if (lattice_.c.empty()) return bilerp(colors_[size_t(f)], float(u), float(v));
        return latticeColor(u, v);
    }

  protected:
    // Colours at the face parameters u[i] x v[j] (i fastest) of a one-face mesh; empty for none.
    struct ColorLattice {
        std::vector<double> u, v;
        std::vector<Color> c;
    };
    ColorLattice lattice_;
    Color latticeColor(double u, double v) const;

    // Position and derivatives of face f at (u, v), key k, camera space.
    virtual void derivatives(int f, double u, double v, int k, Vec3d* P, Vec3d* dPdu, Vec3d* dPdv) const = 0;

    std::vector<std::array<Color, 4>> colors_;
    bool moving_ = false;

  private:
    std::shared_ptr<const SurfaceTopology> topology_;
    TimeSpan keys_;
    const Material* material_;
    float shadingRate_ = 1.0f;
    const Camera* camera_;
    const SourceLoc* source_ = nullptr;
};

// Box around points, grown by a relative epsilon so that it also holds the float rounding of
// positions evaluated in double precision.
Bounds3f paddedBound(const Vec3f* points, size_t n);
Bounds3f padded(Bounds3f b);

}  // namespace streyes
