// 4x4 transforms in double precision, and transforms that move over time.
//
// Conventions follow RenderMan: points are row vectors, p' = p * M, and a request such as
// Translate premultiplies the current transform (CTM = T * CTM), so the request written last
// in the file applies first to the geometry.
#pragma once

#include <array>
#include <vector>

#include "streyes/vecmath.h"

namespace streyes {

struct Matrix4 {
    std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // row-major

    static Matrix4 identity() { return {}; }
    static Matrix4 fromRowMajor(const double v[16]);
    static Matrix4 translate(Vec3d d);
    static Matrix4 scale(Vec3d s);
    static Matrix4 rotate(double degrees, Vec3d axis);

    double operator()(int r, int c) const { return m[r * 4 + c]; }
    double& operator()(int r, int c) { return m[r * 4 + c]; }
    bool operator==(const Matrix4& o) const { return m == o.m; }
    bool operator!=(const Matrix4& o) const { return m != o.m; }

    Vec3d point(Vec3d p) const;    // p * M, with the homogeneous divide
    Vec3d vector(Vec3d v) const;   // v * M, no translation
    Bounds3d box(const Bounds3d& b) const;  // the box of b's eight corners, each p * M (empty stays empty)
    bool isFinite() const;
};

Matrix4 operator*(const Matrix4& a, const Matrix4& b);  // apply a, then b
Matrix4 lerp(const Matrix4& a, const Matrix4& b, double s);
// Inverse; returns false (and leaves *out untouched) for a singular matrix.
bool invert(const Matrix4& a, Matrix4* out);

// A transform given at motion keys (times in frames), linear between keys and held outside
// them. Interpolating matrix elements linearly is the same as interpolating the transformed
// points linearly, which is how streyes defines motion everywhere (rasterizer and ray tracer).
class MotionTransform {
  public:
    MotionTransform() : times_{0.0}, keys_{Matrix4{}} {}
    explicit MotionTransform(const Matrix4& m) : times_{0.0}, keys_{m} {}
    MotionTransform(std::vector<double> times, std::vector<Matrix4> keys);

    bool isStatic() const { return keys_.size() == 1; }
    const std::vector<double>& times() const { return times_; }
    const std::vector<Matrix4>& keys() const { return keys_; }
    Matrix4 at(double t) const;

    // this (applied first) then `after`: keys at the union of both key times.
    MotionTransform then(const MotionTransform& after) const;

  private:
    std::vector<double> times_;
    std::vector<Matrix4> keys_;
};

// Sorted union of key times (exactly equal times merged).
std::vector<double> unionTimes(const std::vector<double>& a, const std::vector<double>& b);

// An upper bound on how much `m` stretches a vector over all its keys (the Frobenius norm of
// the linear part, never below the largest singular value).
double largestStretch(const MotionTransform& m);

}  // namespace streyes
