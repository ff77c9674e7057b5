#include "streyes/transform.h"

#include <algorithm>
#include <cmath>

namespace streyes {

Matrix4 Matrix4::fromRowMajor(const double v[16]) {
    Matrix4 r;
    std::copy(v, v + 16, r.m.begin());
    return r;
}

Matrix4 Matrix4::translate(Vec3d d) {
    Matrix4 r;
    r(3, 0) = d.x;
    r(3, 1) = d.y;
    r(3, 2) = d.z;
    return r;
}

Matrix4 Matrix4::scale(Vec3d s) {
    Matrix4 r;
    r(0, 0) = s.x;
    r(1, 1) = s.y;
    r(2, 2) = s.z;
    return r;
}

// RenderMan's RiRotate: rotation by `degrees` about `axis`, for row vectors.
Matrix4 Matrix4::rotate(double degrees, Vec3d axis) {
    Matrix4 r;
    double len = length(axis);
    if (!(len > 0)) return r;
    Vec3d a = axis / len;
    double rad = degrees * M_PI / 180.0;
    double s = std::sin(rad), c = std::cos(rad), t = 1 - c;
    // Column-vector rotation R; the row-vector form is its transpose.
    double R[3][3] = {{t * a.x * a.x + c, t * a.x * a.y - s * a.z, t * a.x * a.z + s * a.y},
                      {t * a.x * a.y + s * a.z, t * a.y * a.y + c, t * a.y * a.z - s * a.x},
                      {t * a.x * a.z - s * a.y, t * a.y * a.z + s * a.x, t * a.z * a.z + c}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r(i, j) = R[j][i];
    return r;
}

Bounds3d Matrix4::box(const Bounds3d& b) const {
    Bounds3d r;
    if (b.empty()) return r;
    for (int c = 0; c < 8; ++c) r.extend(point({c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z}));
    return r;
}

Vec3d Matrix4::point(Vec3d p) const {
    double x = p.x * m[0] + p.y * m[4] + p.z * m[8] + m[12];
    double y = p.x * m[1] + p.y * m[5] + p.z * m[9] + m[13];
    double z = p.x * m[2] + p.y * m[6] + p.z * m[10] + m[14];
    double w = p.x * m[3] + p.y * m[7] + p.z * m[11] + m[15];
    if (w != 1.0 && w != 0.0) return {x / w, y / w, z / w};
    return {x, y, z};
}

Vec3d Matrix4::vector(Vec3d v) const {
    return {v.x * m[0] + v.y * m[4] + v.z * m[8], v.x * m[1] + v.y * m[5] + v.z * m[9],
            v.x * m[2] + v.y * m[6] + v.z * m[10]};
}

bool Matrix4::isFinite() const {
    for (double v : m)
        if (!std::isfinite(v)) return false;
    return true;
}

Matrix4 operator*(const Matrix4& a, const Matrix4& b) {
    Matrix4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a(i, k) * b(k, j);
            r(i, j) = s;
        }
    return r;
}

Matrix4 lerp(const Matrix4& a, const Matrix4& b, double s) {
    Matrix4 r;
    for (int i = 0; i < 16; ++i) r.m[i] = a.m[i] + (b.m[i] - a.m[i]) * s;
    return r;
}

bool invert(const Matrix4& a, Matrix4* out) {
    // Gauss-Jordan with partial pivoting.
    double w[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            w[i][j] = a(i, j);
            w[i][j + 4] = i == j ? 1 : 0;
        }
    for (int c = 0; c < 4; ++c) {
        int piv = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::fabs(w[r][c]) > std::fabs(w[piv][c])) piv = r;
        if (!(std::fabs(w[piv][c]) > 0)) return false;
        if (piv != c)
            for (int j = 0; j < 8; ++j) std::swap(w[c][j], w[piv][j]);
        double inv = 1.0 / w[c][c];
        for (int j = 0; j < 8; ++j) w[c][j] *= inv;
        for (int r = 0; r < 4; ++r) {
            if (r == c) continue;
            double f = w[r][c];
            if (f == 0) continue;
            for (int j = 0; j < 8; ++j) w[r][j] -= f * w[c][j];
        }
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) (*out)(i, j) = w[i][j + 4];
    return true;
}

MotionTransform::MotionTransform(std::vector<double> times, std::vector<Matrix4> keys)
    : times_(std::move(times)), keys_(std::move(keys)) {
    if (times_.empty()) {
        times_ = {0.0};
        keys_ = {Matrix4{}};
    }
    // Keys that are all equal are one static transform.
    bool same = true;
    for (const Matrix4& k : keys_) same = same && k == keys_.front();
    if (same) {
        times_.resize(1);
        keys_.resize(1);
    }
}

Matrix4 MotionTransform::at(double t) const {
    if (keys_.size() == 1 || t <= times_.front()) return keys_.front();
    if (t >= times_.back()) return keys_.back();
    size_t i = std::upper_bound(times_.begin(), times_.end(), t) - times_.begin();  // times_[i-1] <= t < times_[i]
    double s = (t - times_[i - 1]) / (times_[i] - times_[i - 1]);
    return lerp(keys_[i - 1], keys_[i], s);
}

MotionTransform MotionTransform::then(const MotionTransform& after) const {
    if (isStatic() && after.isStatic()) return MotionTransform(keys_[0] * after.keys_[0]);
    std::vector<double> ts = unionTimes(isStatic() ? std::vector<double>{} : times_,
                                        after.isStatic() ? std::vector<double>{} : after.times_);
    std::vector<Matrix4> ks;
    ks.reserve(ts.size());
    for (double t : ts) ks.push_back(at(t) * after.at(t));
    return MotionTransform(std::move(ts), std::move(ks));
}

std::vector<double> unionTimes(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> r(a);
    r.insert(r.end(), b.begin(), b.end());
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    return r;
}

double largestStretch(const MotionTransform& m) {
    double worst = 0;
    for (const Matrix4& k : m.keys()) {
        double f = 0;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) f += k(r, c) * k(r, c);
        worst = std::max(worst, std::sqrt(f));
    }
    return worst;
}

}  // namespace streyes
