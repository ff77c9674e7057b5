#include "geom/points.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "geom/grid.h"
#include "geom/surface_mesh.h"

namespace streyes {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
// The fewest chords around a whole disc: 16 lose 2.6% of its area, at a grid of 16 micropolygons.
constexpr double kMinSegments = 16;

// The halves of an index range, as the tree and the k-d order cut it.
size_t middle(size_t lo, size_t hi) { return lo + (hi - lo) / 2; }

// A disc's direction at a fraction a of a turn. A full turn is the ray a = 0 itself, so the seam
// of a whole disc is one line, bit for bit.
void direction(double a, float* c, float* s) {
    const double t = kTwoPi * (a == 1.0 ? 0.0 : a);
    *c = float(std::cos(t));
    *s = float(std::sin(t));
}

// The raster box of a camera-space box (in front of the eye plane): its corners projected.
Bounds3f rasterBox(const Camera& camera, const Bounds3f& b) {
    Bounds3f r;
    for (int i = 0; i < 8; ++i)
        r.extend(camera.toRaster({(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z}));
    return r;
}

// Raster pixels per camera-space unit across the image plane at depth z.
float pixelsPerUnit(const Camera& camera, float z) {
    const float a = std::max(std::fabs(camera.ax()), std::fabs(camera.ay()));
    return camera.perspective() ? a / z : a;
}

}  // namespace

// ---- The cloud ---------------------------------------------------------------------------------------
PointCloud::PointCloud(TimeSpan keys, std::vector<Vec3f> centre0, std::vector<Vec3f> centre1,
                       std::vector<float> radius0, std::vector<float> radius1, std::vector<Color> colors)
    : keys_(keys) {
    moving_ = !centre1.empty() && (centre1 != centre0 || radius1 != radius0);
    const size_t n = centre0.size();
    std::vector<size_t> index(n);
    std::iota(index.begin(), index.end(), size_t(0));
    centre_[0] = std::move(centre0);
    order(index, 0, n);
    auto permuted = [&](const auto& v) {
        std::decay_t<decltype(v)> r(n);
        for (size_t i = 0; i < n; ++i) r[i] = v[index[i]];
        return r;
    };
    centre_[0] = permuted(centre_[0]);
    radius_[0] = permuted(radius0);
    colors_ = permuted(colors);
    if (moving_) {
        centre_[1] = permuted(centre1);
        radius_[1] = permuted(radius1);
    }
    for (int k = 0; k < (moving_ ? 2 : 1); ++k) {
        nodes_[k].resize(n > 1 ? n - 1 : 0);
        if (n > 1) boxes(0, 0, n, k);
    }
}

// The k-d order: the median of the range's longest axis at the range's middle, recursively.
void PointCloud::order(std::vector<size_t>& index, size_t lo, size_t hi) {
    if (hi - lo < 2) return;
    Bounds3f b;
    for (size_t i = lo; i < hi; ++i) b.extend(centre_[0][index[i]]);
    const Vec3f d = b.diagonal();
    const int axis = d.x >= d.y && d.x >= d.z ? 0 : d.y >= d.z ? 1 : 2;
    const size_t mid = middle(lo, hi);
    std::nth_element(index.begin() + std::ptrdiff_t(lo), index.begin() + std::ptrdiff_t(mid),
                     index.begin() + std::ptrdiff_t(hi),
                     [&](size_t a, size_t c) { return centre_[0][a][axis] < centre_[0][c][axis]; });
    order(index, lo, mid);
    order(index, mid, hi);
}

// Node `node` over [lo, hi) (two or more points): its box, and its children's. Nodes are in
// preorder; a range of one point has none, so the left child's subtree holds (mid - lo - 1) nodes.
Bounds3f PointCloud::boxes(size_t node, size_t lo, size_t hi, int k) {
    auto disc = [&](size_t i) {
        const Vec3f c = centre_[k][i];
        const float r = radius_[k][i];
        return Bounds3f({c.x - r, c.y - r, c.z}, {c.x + r, c.y + r, c.z});
    };
    const size_t mid = middle(lo, hi);
    Bounds3f b = mid - lo >= 2 ? boxes(node + 1, lo, mid, k) : disc(lo);
    b.extend(hi - mid >= 2 ? boxes(node + mid - lo, mid, hi, k) : disc(mid));
    nodes_[k][node] = padded(b);
    return b;
}

std::unique_ptr<Body> PointCloud::root(const Material* material) const {
    if (size() == 1) return std::make_unique<DiscBody>(this, 0, 0.0, 1.0, keys_, material);
    return std::make_unique<PointsBody>(this, 0, 0, size(), keys_, material);
}

uint64_t PointCloud::bytes() const {
    uint64_t b = sizeof(*this) + colors_.capacity() * sizeof(Color);
    for (int k = 0; k < 2; ++k)
        b += centre_[k].capacity() * sizeof(Vec3f) + radius_[k].capacity() * sizeof(float) +
             nodes_[k].capacity() * sizeof(Bounds3f);
    return b;
}

float cloudFraction(const PointCloud& cloud, double t) {
    const TimeSpan& k = cloud.keys();
    if (!cloud.moving() || !(k.t1 > k.t0) || t <= k.t0) return 0.0f;
    if (t >= k.t1) return 1.0f;
    return float((t - k.t0) / (k.t1 - k.t0));
}

namespace {

// A body's time span as fractions of its cloud's keys.
void fractions(const PointCloud& cloud, const TimeSpan& t, float s[2]) {
    s[0] = cloudFraction(cloud, t.t0);
    s[1] = cloudFraction(cloud, t.t1);
}

// The halves of a span in time: the first ends open at the middle (TimeSpan).
void halves(const TimeSpan& t, TimeSpan out[2]) {
    const double tm = 0.5 * (t.t0 + t.t1);
    out[0] = {t.t0, tm, true};
    out[1] = {tm, t.t1, t.openEnd};
}

// The span cut to [a, b]: closed at b unless b is the end of an open span.
TimeSpan restricted(const TimeSpan& t, double a, double b) { return {a, b, b == t.t1 && t.openEnd}; }

}  // namespace

// ---- Groups of points ----------------------------------------------------------------------------------
PointsBody::PointsBody(const PointCloud* cloud, size_t node, size_t lo, size_t hi, TimeSpan time,
                       const Material* material)
    : cloud_(cloud), node_(node), lo_(lo), hi_(hi) {
    time_ = time;
    material_ = material;
    moving_ = cloud->moving() && time.t1 > time.t0;
}

LBBox3f PointsBody::bound() const {
    if (!cloud_->moving()) {
        const Bounds3f& b = cloud_->nodeBox(node_, 0);
        return {b, b};
    }
    float s[2];
    fractions(*cloud_, time_, s);
    const LBBox3f keys{cloud_->nodeBox(node_, 0), cloud_->nodeBox(node_, 1)};
    return {keys.at(s[0]), keys.at(s[1])};
}

// A group is never diced: its extents ask the split loop for a split, which hands out its halves.
RasterMeasure PointsBody::measure(const Camera& camera) const {
    const LBBox3f b = bound();
    RasterMeasure m;
    m.bound = {rasterBox(camera, b.b0), rasterBox(camera, b.b1)};
    m.extentU = m.extentV = 1e9f;
    if (moving_) m.motion = std::max(rasterDistance(m.bound.b0.lo, m.bound.b1.lo), rasterDistance(m.bound.b0.hi, m.bound.b1.hi));
    return m;
}

CameraExtents PointsBody::cameraExtents() const {
    const LBBox3f b = bound();
    CameraExtents e;
    e.u = e.v = std::max(length(b.b0.diagonal()), length(b.b1.diagonal()));
    e.t = std::max(length(b.b1.lo - b.b0.lo), length(b.b1.hi - b.b0.hi));
    return e;
}

void PointsBody::split(SplitAxis axis, std::unique_ptr<Body> out[2]) const {
    if (axis == SplitAxis::T) {
        TimeSpan t[2];
        halves(time_, t);
        for (int i = 0; i < 2; ++i) {
            auto body = std::make_unique<PointsBody>(cloud_, node_, lo_, hi_, t[i], material_);
            body->inheritFrom(*this);
            out[i] = std::move(body);
        }
        return;
    }
    const size_t mid = middle(lo_, hi_);
    const size_t range[2][2] = {{lo_, mid}, {mid, hi_}};
    const size_t node[2] = {node_ + 1, node_ + mid - lo_};
    for (int i = 0; i < 2; ++i) {
        const size_t a = range[i][0], b = range[i][1];
        if (b - a >= 2) out[i] = std::make_unique<PointsBody>(cloud_, node[i], a, b, time_, material_);
        else out[i] = std::make_unique<DiscBody>(cloud_, a, 0.0, 1.0, time_, material_);
        out[i]->inheritFrom(*this);
    }
}

std::unique_ptr<Body> PointsBody::restrictedTo(double a, double b) const {
    auto body = std::make_unique<PointsBody>(cloud_, node_, lo_, hi_, restricted(time_, a, b), material_);
    body->inheritFrom(*this);
    return body;
}

void PointsBody::dice(int, int, Grid&) const { throw std::logic_error("a group of points is split, never diced"); }

// ---- One disc ----------------------------------------------------------------------------------------------
DiscBody::DiscBody(const PointCloud* cloud, size_t point, double a0, double a1, TimeSpan time, const Material* material)
    : cloud_(cloud), point_(point), a0_(a0), a1_(a1) {
    time_ = time;
    material_ = material;
    moving_ = cloud->moving() && time.t1 > time.t0 &&
              (cloud->centre(point, 0) != cloud->centre(point, 1) || cloud->radius(point, 0) != cloud->radius(point, 1));
}

Vec3f DiscBody::centreAt(int k) const {
    const float s = cloudFraction(*cloud_, k == 0 ? time_.t0 : time_.t1);
    return lerp(cloud_->centre(point_, 0), cloud_->centre(point_, 1), s);
}

float DiscBody::radiusAt(int k) const {
    const float s = cloudFraction(*cloud_, k == 0 ? time_.t0 : time_.t1);
    return lerp(cloud_->radius(point_, 0), cloud_->radius(point_, 1), s);
}

// The sector's box: its centre and the arc's ends, and where the arc crosses an axis.
Bounds3f DiscBody::sectorBox(int k) const {
    const Vec3f c = centreAt(k);
    const float r = radiusAt(k);
    Bounds3f b;
    b.extend(c);
    auto add = [&](double a) {
        float x, y;
        direction(a, &x, &y);
        b.extend(Vec3f(c.x + r * x, c.y + r * y, c.z));
    };
    add(a0_);
    add(a1_);
    for (int q = 1; q < 4; ++q)
        if (a0_ < q * 0.25 && q * 0.25 < a1_) add(q * 0.25);
    return padded(b);
}

LBBox3f DiscBody::bound() const {
    const Bounds3f b0 = sectorBox(0);
    return {b0, moving_ ? sectorBox(1) : b0};
}

RasterMeasure DiscBody::measure(const Camera& camera) const {
    RasterMeasure m;
    float arc = 0, radial = 0;
    Vec3f centre[2];
    for (int k = 0; k < 2; ++k) {
        const int key = moving_ ? k : 0;
        const Vec3f c = centreAt(key);
        const float r = radiusAt(key) * pixelsPerUnit(camera, c.z);
        arc = std::max(arc, r * float(kTwoPi * (a1_ - a0_)));
        radial = std::max(radial, r);
        centre[k] = camera.toRaster(c);
        (k == 0 ? m.bound.b0 : m.bound.b1) = rasterBox(camera, sectorBox(key));
    }
    // Around the arc, chords of half a micropolygon edge: the outline is an inscribed polygon,
    // whose area falls short of the disc's by about pi c^2 / 6 (c the chord), 0.13 pixels at
    // ShadingRate 1 whatever the radius. Along the radius, no finer than around: the radii are
    // straight, and a sector is never split along them (its pieces would meet on arcs, which are not).
    m.extentU = 2 * arc;
    m.extentV = std::min(radial, arc);
    m.motion = moving_ ? rasterDistance(centre[0], centre[1]) + std::fabs(radiusAt(1) - radiusAt(0)) *
                                                                    pixelsPerUnit(camera, std::min(centre[0].z, centre[1].z))
                       : 0.0f;
    return m;
}

// Asked by eye splits only. A disc is flat at its centre's depth, so what reaches the eye plane is
// its motion: splitting it in angle would never free it, in time does.
CameraExtents DiscBody::cameraExtents() const {
    CameraExtents e;
    if (moving_) {
        e.t = length(centreAt(1) - centreAt(0)) + std::fabs(radiusAt(1) - radiusAt(0));
    } else {
        const float r = radiusAt(0);
        e.u = r * float(kTwoPi * (a1_ - a0_));
        e.v = r;
    }
    return e;
}

// In time, or in angle (whatever the axis): see the header.
void DiscBody::split(SplitAxis axis, std::unique_ptr<Body> out[2]) const {
    TimeSpan t[2] = {time_, time_};
    double a[2][2] = {{a0_, a1_}, {a0_, a1_}};
    if (axis == SplitAxis::T) {
        halves(time_, t);
    } else {
        const double am = 0.5 * (a0_ + a1_);
        a[0][1] = a[1][0] = am;
    }
    for (int i = 0; i < 2; ++i) {
        out[i] = std::make_unique<DiscBody>(cloud_, point_, a[i][0], a[i][1], t[i], material_);
        out[i]->inheritFrom(*this);
    }
}

std::unique_ptr<Body> DiscBody::restrictedTo(double a, double b) const {
    auto body = std::make_unique<DiscBody>(cloud_, point_, a0_, a1_, restricted(time_, a, b), material_);
    body->inheritFrom(*this);
    return body;
}

// u around the arc from a0 to a1, v from the centre (a fan: the row is one point) to the rim.
void DiscBody::dice(int nu, int nv, Grid& grid) const {
    // At least kMinSegments chords around a whole disc, however small: a square is not a disc.
    nu = std::max(nu, int(std::ceil(kMinSegments * (a1_ - a0_))));
    startGrid(nu, nv, grid);
    const Color cs = cloud_->color(point_);
    for (int k = 0; k < (moving_ ? 2 : 1); ++k) {
        const Vec3f c = centreAt(k);
        const float r = radiusAt(k);
        for (int i = 0; i <= nu; ++i) {
            // Exact ends, so that the sectors on either side of a radius share its vertices.
            const double a = i == 0 ? a0_ : i == nu ? a1_ : a0_ + (a1_ - a0_) * (double(i) / nu);
            float x, y;
            direction(a, &x, &y);
            for (int j = 0; j <= nv; ++j) {
                const float rho = j == nv ? r : r * (float(j) / float(nv));
                const int idx = grid.index(i, j);
                grid.P[k][size_t(idx)] = j == 0 ? c : Vec3f(c.x + rho * x, c.y + rho * y, c.z);
                grid.N[k][size_t(idx)] = Vec3f(0, 0, -1);  // facing the eye
            }
        }
    }
    for (int idx = 0; idx < grid.vertexCount(); ++idx) grid.Cs[size_t(idx)] = cs;
}

}  // namespace streyes
