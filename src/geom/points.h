// Points as camera-facing discs, grouped into bodies that split spatially.
//
// A PointCloud is one motion segment of a Points primitive in camera space: each point's centre
// and radius at the segment's two keys and its colour, in an order that keeps neighbours together
// (a k-d order: the points are halved at the median of their longest axis, recursively), with a
// box per node of the implicit tree that halves index ranges the same way. A PointsBody is a node
// (two or more points): its bound is the node's box, it never dices, and a split hands out the
// node's halves, so the split loop descends only into groups it sees and the cost grows with the
// points seen, not all points. One point is a DiscBody.
//
// A disc lies in the plane z = its centre's depth (parallel to the image plane, so its outline on
// the screen is a circle in perspective as well), radius half the point's width. A DiscBody is a
// sector of it, split in angle only: its pieces meet along radii, which are straight, so dicing
// them at different rates leaves T-junctions on straight edges, which the rasterizer closes (see
// ARCHITECTURE.md, Watertightness). A grid runs around the arc (u) and from the centre to the rim
// (v); its centre row is one point, a fan of triangles.
#pragma once

#include <memory>
#include <vector>

#include "geom/body.h"

namespace streyes {

class PointCloud {
  public:
    // Camera-space centres and radii at the segment's two keys (key1 empty: still), one colour a point.
    PointCloud(TimeSpan keys, std::vector<Vec3f> centre0, std::vector<Vec3f> centre1, std::vector<float> radius0,
               std::vector<float> radius1, std::vector<Color> colors);

    size_t size() const { return centre_[0].size(); }
    const TimeSpan& keys() const { return keys_; }
    bool moving() const { return moving_; }
    Vec3f centre(size_t i, int k) const { return centre_[moving_ ? k : 0][i]; }
    float radius(size_t i, int k) const { return radius_[moving_ ? k : 0][i]; }
    Color color(size_t i) const { return colors_[i]; }
    // The box of node n (over two or more points) at key k.
    const Bounds3f& nodeBox(size_t n, int k) const { return nodes_[moving_ ? k : 0][n]; }
    // What it holds, in bytes.
    uint64_t bytes() const;
    // The root body (a PointsBody, or a DiscBody for a single point), with this material.
    std::unique_ptr<Body> root(const Material* material) const;

  private:
    void order(std::vector<size_t>& index, size_t lo, size_t hi);
    Bounds3f boxes(size_t node, size_t lo, size_t hi, int k);

    TimeSpan keys_;
    bool moving_ = false;
    std::vector<Vec3f> centre_[2];
    std::vector<float> radius_[2];
    std::vector<Color> colors_;
    std::vector<Bounds3f> nodes_[2];  // preorder: node n over [lo, hi) has its left child at n + 1
};

// A node of a cloud's tree over time [t0, t1] within the cloud's keys.
class PointsBody final : public Body {
  public:
    PointsBody(const PointCloud* cloud, size_t node, size_t lo, size_t hi, TimeSpan time, const Material* material);

    LBBox3f bound() const override;
    RasterMeasure measure(const Camera& camera) const override;
    CameraExtents cameraExtents() const override;
    void split(SplitAxis axis, std::unique_ptr<Body> out[2]) const override;
    std::unique_ptr<Body> restrictedTo(double a, double b) const override;
    void dice(int nu, int nv, Grid& grid) const override;  // never asked: a group always splits
    size_t memoryBytes() const override { return heapBlockBytes(sizeof(*this)); }  // the cloud is shared

  private:
    const PointCloud* cloud_;
    size_t node_, lo_, hi_;
};

// A sector [a0, a1] (fractions of a turn) of one point's disc over time [t0, t1].
class DiscBody final : public Body {
  public:
    DiscBody(const PointCloud* cloud, size_t point, double a0, double a1, TimeSpan time, const Material* material);

    LBBox3f bound() const override;
    RasterMeasure measure(const Camera& camera) const override;
    CameraExtents cameraExtents() const override;
    void split(SplitAxis axis, std::unique_ptr<Body> out[2]) const override;
    std::unique_ptr<Body> restrictedTo(double a, double b) const override;
    void dice(int nu, int nv, Grid& grid) const override;
    size_t memoryBytes() const override { return heapBlockBytes(sizeof(*this)); }

  private:
    Vec3f centreAt(int k) const;  // at t0 (k = 0) or t1
    float radiusAt(int k) const;
    Bounds3f sectorBox(int k) const;

    const PointCloud* cloud_;
    size_t point_;
    double a0_, a1_;
};

// The cloud's keys as fractions: where time t falls in [keys.t0, keys.t1].
float cloudFraction(const PointCloud& cloud, double t);

}  // namespace streyes
