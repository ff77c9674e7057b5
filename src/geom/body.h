// Spacetime bodies: the unit the split loop works on.
//
// A body is a piece of surface over a time span [t0, t1] (in frames) whose control points move
// linearly from t0 to t1, in camera space. It answers what the pipeline asks (DESIGN.md):
//   bound()        conservative camera-space bound at t0 and at t1 (an LBBox),
//   measure()      how large it is in raster spacetime, to choose between split and dice,
//   split(axis)    two halves along u, v or t,
//   dice(nu, nv)   a grid of micropolygon vertices at t0 and t1.
//   boundDuring()  a bound over a sub-interval of its time span (the ray tracer's hierarchy asks
//                  this for every spacetime cell it holds the body in: Glassner's "intelligent
//                  objects" answer bound requests themselves).
// Everything else (culling, the split loop, sampling) is generic over these questions.
#pragma once

#include <atomic>
#include <cmath>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "geom/camera.h"
#include "streyes/error.h"
#include "streyes/vecmath.h"

namespace streyes {

struct Grid;
struct Material;

enum class SplitAxis : unsigned char { U = 0, V = 1, T = 2 };

// A body's time span. Where another piece of the same surface continues at t1 (a later motion
// segment, the second half of a time split) the span is half-open, [t0, t1), so that a sample
// exactly at t1 belongs to one piece only; the last piece is closed, [t0, t1].
struct TimeSpan {
    double t0 = 0, t1 = 0;
    bool openEnd = false;
    // Does the span share a time with [a, b]?
    bool overlaps(double a, double b) const { return t0 <= b && (a < t1 || (a == t1 && !openEnd)); }
    // Does it contain time t?
    bool contains(double t) const { return t0 <= t && (t < t1 || (t == t1 && !openEnd)); }
};

// A body's size in raster spacetime (valid only when it lies in front of the eye plane).
struct RasterMeasure {
    LBBox3f bound;        // raster x, y and camera z, at t0 and at t1
    float extentU = 0;    // longest raster length of a u-direction edge, over t0 and t1
    float extentV = 0;    // the same along v
    float motion = 0;     // largest raster displacement of a control point from t0 to t1
};

// The same three extents in camera space, for splits that cannot project (eye splits).
struct CameraExtents {
    float u = 0, v = 0, t = 0;
};

class Body {
  public:
    virtual ~Body() = default;

    const TimeSpan& time() const { return time_; }
    bool moving() const { return moving_; }
    const Material* material() const { return material_; }
    // Where in the input the body came from (for warnings); shared by all its pieces.
    const SourceLoc* source() const { return source_; }
    void setSource(const SourceLoc* s) { source_ = s; }
    // The primitive it came from, in scene order: breaks exact depth ties between surfaces so
    // that the image does not depend on the order bodies are drawn in.
    uint64_t primitiveId() const { return primitiveId_; }
    void setPrimitiveId(uint64_t id) { primitiveId_ = id; }
    // Copies what a piece shares with the body it was cut from (material, source, primitive,
    // split counts); every kind of body calls it on its pieces.
    void inheritFrom(const Body& parent) {
        material_ = parent.material_;
        source_ = parent.source_;
        primitiveId_ = parent.primitiveId_;
        splitDepth = parent.splitDepth;
        eyeSplitDepth = parent.eyeSplitDepth;
        exposure = parent.exposure;
        uv = parent.uv;
        primvarCorners = parent.primvarCorners;
        stillInWorld = parent.stillInWorld;
    }

    // A body that is replaced by the bodies it expands into, instead of being split or diced (a
    // procedural: src/procedural/procedural.h).
    virtual bool expands() const { return false; }
    // False while the body must be split in time before it can be diced (a body with more than
    // two motion keys: a grid's corners move linearly from t0 to t1 only).
    virtual bool diceableInTime() const { return true; }
    // A body not diceable in time that dices at each of its keys instead (KeyedPatchBody::diceKey),
    // sampled one key interval at a time: dicing and shading once for a run of keys.
    virtual bool dicesAtKeys() const { return false; }
    // The shading rate a body whose pieces share one lattice is diced at (a curved body: its
    // mesh's), or 0: the body's material decides (dicingRate, bodies/material.h).
    virtual float latticeRate() const { return 0; }

    virtual LBBox3f bound() const = 0;
    // Camera-space bound of the body during [a, b], a sub-span of time(). The LBBox lerped to a
    // and to b bounds everything in between (control points that move linearly, or a bound that
    // holds at every time); bodies override this with something tighter when they can.
    virtual Bounds3f boundDuring(double a, double b) const {
        const LBBox3f b01 = bound();
        if (!moving_) return b01.b0;
        const double len = time_.t1 - time_.t0;
        return unionOf(b01.at(float((a - time_.t0) / len)), b01.at(float((b - time_.t0) / len)));
    }
    virtual RasterMeasure measure(const Camera& camera) const = 0;
    virtual CameraExtents cameraExtents() const = 0;
    // Splits into two halves; a T split cuts the time span in half.
    virtual void split(SplitAxis axis, std::unique_ptr<Body> out[2]) const = 0;
    // The body over [a, b], a sub-span of time().
    virtual std::unique_ptr<Body> restrictedTo(double a, double b) const = 0;
    // Fills grid with (nu+1) x (nv+1) vertices at t0 and t1 (and at t0 only when not moving).
    virtual void dice(int nu, int nv, Grid& grid) const = 0;
    // The memory the body holds: the object, with its allocation, and what it alone owns on the
    // heap (motion keys), not what it shares (a mesh, a material, a point cloud). BodyFactory
    // adds it up for the memory budget (memory.h).
    virtual size_t memoryBytes() const = 0;

    // How many splits led to this body (regular splits and eye splits), for the limits.
    unsigned char splitDepth = 0;
    unsigned char eyeSplitDepth = 0;
    // The frame whose exposure the split loop cut this piece to, or kNoExposure for a piece of a
    // body that spans the whole block (per-frame limits key on it: see BucketWorker).
    static constexpr int32_t kNoExposure = INT32_MIN;
    int32_t exposure = kNoExposure;
    // The piece's parameter rectangle in its primitive, (u0, u1, v0, v1): what a shader sees as u
    // and v (and s and t, by default). The split loop halves it with every split in u or v.
    std::array<float, 4> uv{0, 1, 0, 1};
    // A face of a polygon mesh with primitive variables that vary from face to face: their values
    // at its four corners (Material::primvarCorners' layout), kept by the factory. Null: the
    // material's own.
    const float* primvarCorners = nullptr;
    // Its control points do not move in world space over the shot (a still object; it moves in
    // camera space only when the camera does). Such a root under a moving camera is cut into
    // longer chunks of frames (geom/root_chunks.h) and its grids are diced once for a chunk
    // (docs/ARCHITECTURE.md, "The split loop"). Set by the factory.
    bool stillInWorld = false;
    // As a root, the frames each of its pieces spans (geom/root_chunks.h), made by the first
    // bucket that asks: it depends on the body and the camera only, and every bucket asks. 0 until
    // made; a race writes the same value.
    mutable std::atomic<uint8_t> rootChunk{0};
    // Which piece of which body this is, for sharing its diced grid between the buckets it
    // reaches (render/grid_cache.h). A body made by the scene or a procedural has a fresh
    // identity; the split loop derives a piece's from its parent's and the cut that made it, so
    // the same piece gets the same key in every bucket that makes it.
    uint64_t pieceKey = newIdentity();
    static uint64_t newIdentity();

  protected:
    // Sizes `grid` for nu x nv micropolygons and copies what every vertex shares from the body
    // (time span, motion, material, primitive): the start of every dice().
    void startGrid(int nu, int nv, Grid& grid) const;

    TimeSpan time_;
    bool moving_ = false;
    const Material* material_ = nullptr;
    const SourceLoc* source_ = nullptr;
    uint64_t primitiveId_ = 0;
};

using BodyPtr = std::unique_ptr<Body>;

// A bilinear patch whose four corners move linearly over [t0, t1]: Catmull's patch in
// spacetime, the paper's trilinear body (8 control points). Corners in RenderMan order:
// P[k][0]=(u0,v0) P[k][1]=(u1,v0) P[k][2]=(u0,v1) P[k][3]=(u1,v1), k=0 at t0 and k=1 at t1.
class TrilinearBody final : public Body {
  public:
    using Corners = std::array<Vec3f, 4>;
    TrilinearBody(TimeSpan time, const Corners& p0, const Corners& p1, const std::array<Color, 4>& cs,
                  const Material* material);

    const Corners& corners(int k) const { return P_[k]; }
    const std::array<Color, 4>& colors() const { return Cs_; }
    // The corners at time t (held outside [t0, t1]); the ray tracer's view of the body.
    Corners cornersAt(double t) const {
        if (!moving_ || t <= time_.t0) return P_[0];
        if (t >= time_.t1) return P_[1];
        const float s = float((t - time_.t0) / (time_.t1 - time_.t0));
        Corners c;
        for (size_t i = 0; i < 4; ++i) c[i] = lerp(P_[0][i], P_[1][i], s);
        return c;
    }

    LBBox3f bound() const override;
    Bounds3f boundDuring(double a, double b) const override;
    RasterMeasure measure(const Camera& camera) const override;
    CameraExtents cameraExtents() const override;
    void split(SplitAxis axis, std::unique_ptr<Body> out[2]) const override;
    std::unique_ptr<Body> restrictedTo(double a, double b) const override;
    void dice(int nu, int nv, Grid& grid) const override;
    size_t memoryBytes() const override;

  private:
    Corners P_[2];               // camera space at t0 and t1 (equal when static)
    std::array<Color, 4> Cs_;    // surface colour at the corners, bilinear over the patch
};

// A bilinear patch whose corners move through several motion keys, linearly between them: a
// chain of trilinear bodies kept as one (a swaying leaf over 64 frames is one body, not 16).
// Its bound covers every key; the split loop cuts it in time at its middle key until two keys
// remain, which makes a TrilinearBody.
class KeyedPatchBody final : public Body {
  public:
    using Corners = TrilinearBody::Corners;
    // `openEnd`: another piece of the surface continues at the last key (see TimeSpan).
    KeyedPatchBody(std::vector<double> times, std::vector<Corners> keys, const std::array<Color, 4>& cs,
                   const Material* material, bool openEnd = false);

    bool diceableInTime() const override { return false; }
    bool dicesAtKeys() const override { return true; }
    LBBox3f bound() const override { return bound_; }
    Bounds3f boundDuring(double a, double b) const override;  // the keys between a and b, and a and b
    RasterMeasure measure(const Camera& camera) const override;
    CameraExtents cameraExtents() const override;
    void split(SplitAxis axis, std::unique_ptr<Body> out[2]) const override;
    std::unique_ptr<Body> restrictedTo(double a, double b) const override;
    void dice(int nu, int nv, Grid& grid) const override;  // not diceable: throws
    size_t memoryBytes() const override;  // with its keys and their times

    size_t keyCount() const { return times_.size(); }
    double keyTime(size_t k) const { return times_[k]; }
    bool keyMoves(size_t k) const { return keys_[k] != keys_[k + 1]; }  // from key k to k + 1
    // Fills slot (0 or 1) of positions and normals of `grid`, sized by startKeyGrid, with key k's
    // (nu+1) x (nv+1) vertices, as a TrilinearBody's dice() places them.
    void startKeyGrid(int nu, int nv, Grid& grid) const;
    void diceKey(size_t k, Grid& grid, int slot) const;
    // As a root, for a render that reaches only times in [a, b] of it: the same body with only
    // the keys from the last at or before a to the first at or after b (three at least), or null
    // when that is every key. What is decided for the whole root from all its keys (whether it
    // moves, rootChunk, its bound) is decided first and kept; every piece the split loop cuts from
    // it over times in [a, b] (restrictedTo, boundDuring) is the same, bit for bit.
    std::unique_ptr<KeyedPatchBody> keysOver(double a, double b, const Camera& camera) const;

  private:
    // The pieces over keys [i, j]: a KeyedPatchBody, or a TrilinearBody for two keys.
    std::unique_ptr<Body> piece(size_t i, size_t j) const;

    std::vector<double> times_;
    std::vector<Corners> keys_;
    std::array<Color, 4> Cs_;
    LBBox3f bound_;  // the union over all keys, made once
};

// Point, colour or normal of a bilinear patch at (u, v), corners in RenderMan order. The normal
// is dP/du x dP/dv, not normalised; at collapsed edges it falls back to the mean normal.
template <typename T>
T bilerp(const std::array<T, 4>& c, float u, float v) {
    return lerp(lerp(c[0], c[1], u), lerp(c[2], c[3], u), v);
}
Vec3f bilinearNormal(const TrilinearBody::Corners& p, float u, float v);

// A heap block of n bytes, as glibc's malloc takes it: a header and rounding to 16 bytes (the
// streyes command's jemalloc keeps no header and rounds to size classes: about the same).
constexpr size_t heapBlockBytes(size_t n) { return (n + 8 + 15) / 16 * 16; }

// Squared distance in the raster plane (x, y), in double: no overflow for any float coordinates.
inline double rasterDistanceSquared(Vec3f a, Vec3f b) {
    const double dx = double(a.x) - double(b.x), dy = double(a.y) - double(b.y);
    return dx * dx + dy * dy;
}
// The distance, far cheaper than std::hypot, which the split loop's measures called millions of
// times. The root and the rounding are monotonic: the largest of several distances is the root
// of the largest square, bit for bit (KeyedPatchBody::measure takes one root, not one a pair).
inline float rasterDistance(Vec3f a, Vec3f b) { return float(std::sqrt(rasterDistanceSquared(a, b))); }

}  // namespace streyes
