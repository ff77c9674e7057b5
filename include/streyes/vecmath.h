// Small fixed-size vectors and axis-aligned bounds, in the style of pbrt's util/vecmath.h.
// Geometry is stored in float (camera and raster space); scene input and transforms in double,
// so that scenes far from the origin keep their precision until they are in camera space.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace streyes {

template <typename T>
struct Vec2 {
    T x = 0, y = 0;
    constexpr Vec2() = default;
    constexpr Vec2(T x_, T y_) : x(x_), y(y_) {}
    constexpr Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
    constexpr Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
    constexpr Vec2 operator*(T s) const { return {x * s, y * s}; }
    constexpr bool operator==(Vec2 o) const { return x == o.x && y == o.y; }
    constexpr bool operator!=(Vec2 o) const { return !(*this == o); }
};

template <typename T>
struct Vec3 {
    T x = 0, y = 0, z = 0;
    constexpr Vec3() = default;
    constexpr Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
    template <typename U>
    constexpr explicit Vec3(const Vec3<U>& o) : x(T(o.x)), y(T(o.y)), z(T(o.z)) {}
    constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vec3 operator+(Vec3 o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3 operator-(Vec3 o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3 operator*(T s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator*(Vec3 o) const { return {x * o.x, y * o.y, z * o.z}; }
    constexpr Vec3 operator/(T s) const { return {x / s, y / s, z / s}; }
    Vec3& operator+=(Vec3 o) { x += o.x; y += o.y; z += o.z; return *this; }
    Vec3& operator*=(T s) { x *= s; y *= s; z *= s; return *this; }
    constexpr bool operator==(Vec3 o) const { return x == o.x && y == o.y && z == o.z; }
    constexpr bool operator!=(Vec3 o) const { return !(*this == o); }
};

using Vec2f = Vec2<float>;
using Vec3f = Vec3<float>;
using Vec3d = Vec3<double>;
using Color = Vec3f;  // linear RGB

template <typename T> constexpr Vec3<T> operator*(T s, Vec3<T> v) { return v * s; }
template <typename T> constexpr T dot(Vec3<T> a, Vec3<T> b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <typename T> constexpr Vec3<T> cross(Vec3<T> a, Vec3<T> b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T> T length(Vec3<T> v) { return std::sqrt(dot(v, v)); }
template <typename T> Vec3<T> normalize(Vec3<T> v) {
    T l = length(v);
    return l > 0 ? v / l : v;
}
template <typename T> constexpr Vec3<T> vmin(Vec3<T> a, Vec3<T> b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <typename T> constexpr Vec3<T> vmax(Vec3<T> a, Vec3<T> b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
// (1-s)*a + s*b: exact at both ends, so pieces cut from one motion meet bit for bit.
template <typename T, typename S> constexpr T lerp(T a, T b, S s) { return a * (S(1) - s) + b * s; }
template <typename T> bool isFinite(Vec3<T> v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
// floor(v) clamped to [lo, hi] (lo for NaN), without converting a float beyond int's range,
// which is undefined: raster bounds of huge or degenerate bodies reach far past any image.
// Floors by truncating and stepping down, not through floorf (a library call in the sampler's
// inner loops without SSE4.1).
[[gnu::always_inline]] inline int floorClamped(float v, int lo, int hi) {
    if (!(v >= float(lo))) return lo;
    if (v >= float(hi)) return hi;
    int i = int(v);  // v is within [lo, hi): no overflow
    if (float(i) > v) --i;
    return std::min(hi, std::max(lo, i));
}

// Axis-aligned box; empty when lo > hi on any axis.
template <typename T>
struct Bounds3 {
    Vec3<T> lo{std::numeric_limits<T>::infinity(), std::numeric_limits<T>::infinity(),
               std::numeric_limits<T>::infinity()};
    Vec3<T> hi{-std::numeric_limits<T>::infinity(), -std::numeric_limits<T>::infinity(),
               -std::numeric_limits<T>::infinity()};
    constexpr Bounds3() = default;
    constexpr Bounds3(Vec3<T> a, Vec3<T> b) : lo(a), hi(b) {}
    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    void extend(Vec3<T> p) { lo = vmin(lo, p); hi = vmax(hi, p); }
    void extend(const Bounds3& b) { lo = vmin(lo, b.lo); hi = vmax(hi, b.hi); }
    Vec3<T> diagonal() const { return hi - lo; }
    bool overlaps(const Bounds3& b) const {
        return lo.x <= b.hi.x && hi.x >= b.lo.x && lo.y <= b.hi.y && hi.y >= b.lo.y &&
               lo.z <= b.hi.z && hi.z >= b.lo.z;
    }
    bool contains(Vec3<T> p) const {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
    }
};
using Bounds3f = Bounds3<float>;
using Bounds3d = Bounds3<double>;

template <typename T> Bounds3<T> unionOf(Bounds3<T> a, const Bounds3<T>& b) { a.extend(b); return a; }

// Embree's LBBox: a bound at the start and at the end of a time span. For geometry whose
// control points move linearly, lerp(b0, b1, s) bounds the geometry at relative time s.
template <typename T>
struct LBBox {
    Bounds3<T> b0, b1;
    Bounds3<T> swept() const { return unionOf(b0, b1); }
    Bounds3<T> at(T s) const { return {lerp(b0.lo, b1.lo, s), lerp(b0.hi, b1.hi, s)}; }
};
using LBBox3f = LBBox<float>;

// Integer pixel rectangle, inclusive on both ends.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
    bool empty() const { return x1 < x0 || y1 < y0; }
    int width() const { return x1 - x0 + 1; }
    int height() const { return y1 - y0 + 1; }
    long long area() const { return empty() ? 0 : (long long)width() * height(); }
};

}  // namespace streyes
