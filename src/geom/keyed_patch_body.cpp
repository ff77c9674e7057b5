#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geom/body.h"
#include "geom/grid.h"
#include "geom/root_chunks.h"

namespace streyes {

KeyedPatchBody::KeyedPatchBody(std::vector<double> times, std::vector<Corners> keys, const std::array<Color, 4>& cs,
                               const Material* material, bool openEnd)
    : times_(std::move(times)), keys_(std::move(keys)), Cs_(cs) {
    time_ = {times_.front(), times_.back(), openEnd};
    material_ = material;
    moving_ = false;
    for (size_t i = 1; i < keys_.size() && !moving_; ++i) moving_ = keys_[i] != keys_[0];
    Bounds3f b;
    for (const Corners& k : keys_)
        for (const Vec3f& p : k) b.extend(p);
    bound_ = {b, b};  // the union over all keys bounds every instant
}


Bounds3f KeyedPatchBody::boundDuring(double a, double b) const {
    // Corners move linearly between keys: the corners at a and at b and at every key between.
    auto at = [&](double t) {
        size_t i = size_t(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
        if (i == 0) return keys_.front();
        if (i >= times_.size()) return keys_.back();
        const float s = float((t - times_[i - 1]) / (times_[i] - times_[i - 1]));
        Corners c;
        for (int k = 0; k < 4; ++k) c[size_t(k)] = lerp(keys_[i - 1][size_t(k)], keys_[i][size_t(k)], s);
        return c;
    };
    Bounds3f box;
    for (const Vec3f& p : at(a)) box.extend(p);
    for (const Vec3f& p : at(b)) box.extend(p);
    for (size_t k = 0; k < times_.size(); ++k)
        if (times_[k] > a && times_[k] < b)
            for (const Vec3f& p : keys_[k]) box.extend(p);
    return box;
}

RasterMeasure KeyedPatchBody::measure(const Camera& camera) const {
    // Largest squared distances first, one root each at the end: rasterDistance's result bit for
    // bit, for 3 roots, not 10 a key.
    const auto d2 = rasterDistanceSquared;
    RasterMeasure m;
    double eu = 0, ev = 0, mo = 0;
    Corners prev{};
    for (size_t k = 0; k < keys_.size(); ++k) {
        Corners r;
        for (int i = 0; i < 4; ++i) r[size_t(i)] = camera.toRaster(keys_[k][size_t(i)]);
        eu = std::max({eu, d2(r[0], r[1]), d2(r[2], r[3])});
        ev = std::max({ev, d2(r[0], r[2]), d2(r[1], r[3])});
        for (int i = 0; i < 4; ++i) {
            m.bound.b0.extend(r[size_t(i)]);
            if (k > 0) mo = std::max(mo, d2(prev[size_t(i)], r[size_t(i)]));
        }
        prev = r;
    }
    m.extentU = float(std::sqrt(eu));
    m.extentV = float(std::sqrt(ev));
    m.motion = float(std::sqrt(mo));
    m.bound.b1 = m.bound.b0;
    return m;
}

CameraExtents KeyedPatchBody::cameraExtents() const {
    CameraExtents e;
    for (size_t k = 0; k < keys_.size(); ++k) {
        const Corners& p = keys_[k];
        e.u = std::max({e.u, length(p[1] - p[0]), length(p[3] - p[2])});
        e.v = std::max({e.v, length(p[2] - p[0]), length(p[3] - p[1])});
        if (k > 0)
            for (int i = 0; i < 4; ++i) e.t = std::max(e.t, length(p[size_t(i)] - keys_[k - 1][size_t(i)]));
    }
    return e;
}

std::unique_ptr<Body> KeyedPatchBody::piece(size_t i, size_t j) const {
    // Pieces meet at keys: every piece but the last is half-open (TimeSpan).
    const bool open = j + 1 < times_.size() || time_.openEnd;
    std::unique_ptr<Body> b;
    if (j - i == 1) {
        b = std::make_unique<TrilinearBody>(TimeSpan{times_[i], times_[j], open}, keys_[i], keys_[j], Cs_, material_);
    } else {
        b = std::make_unique<KeyedPatchBody>(std::vector<double>(times_.begin() + long(i), times_.begin() + long(j) + 1),
                                             std::vector<Corners>(keys_.begin() + long(i), keys_.begin() + long(j) + 1),
                                             Cs_, material_, open);
    }
    b->inheritFrom(*this);
    return b;
}

void KeyedPatchBody::split(SplitAxis axis, std::unique_ptr<Body> out[2]) const {
    const size_t last = keys_.size() - 1;
    if (axis == SplitAxis::T) {
        const size_t mid = last / 2 + (last % 2);  // the middle key: the pieces share it exactly
        out[0] = piece(0, mid);
        out[1] = piece(mid, last);
        return;
    }
    // u or v: every key's corners, as TrilinearBody splits them (midpoints of the same edges).
    const int pairs[2][2][2] = {{{0, 1}, {2, 3}}, {{0, 2}, {1, 3}}};
    const auto& pr = pairs[axis == SplitAxis::U ? 0 : 1];
    std::vector<Corners> a(keys_), b(keys_);
    for (size_t k = 0; k < keys_.size(); ++k)
        for (const auto& e : pr) {
            const Vec3f m = (keys_[k][size_t(e[0])] + keys_[k][size_t(e[1])]) * 0.5f;
            a[k][size_t(e[1])] = m;
            b[k][size_t(e[0])] = m;
        }
    std::array<Color, 4> ca = Cs_, cb = Cs_;
    for (const auto& e : pr) {
        const Color m = (Cs_[size_t(e[0])] + Cs_[size_t(e[1])]) * 0.5f;
        ca[size_t(e[1])] = m;
        cb[size_t(e[0])] = m;
    }
    out[0] = std::make_unique<KeyedPatchBody>(times_, std::move(a), ca, material_, time_.openEnd);
    out[1] = std::make_unique<KeyedPatchBody>(times_, std::move(b), cb, material_, time_.openEnd);
    out[0]->inheritFrom(*this);
    out[1]->inheritFrom(*this);
}

// The keys inside (a, b), plus the corners at a and b.
std::unique_ptr<Body> KeyedPatchBody::restrictedTo(double a, double b) const {
    auto at = [&](double t) {
        size_t i = size_t(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
        if (i == 0) return keys_.front();
        if (i >= times_.size()) return keys_.back();
        if (t == times_[i - 1]) return keys_[i - 1];
        const float s = float((t - times_[i - 1]) / (times_[i] - times_[i - 1]));
        Corners c;
        for (int k = 0; k < 4; ++k) c[size_t(k)] = lerp(keys_[i - 1][size_t(k)], keys_[i][size_t(k)], s);
        return c;
    };
    // The keys strictly inside (a, b): none for a piece of one exposure between two keys, which
    // is then a trilinear body, made without a vector (a split loop makes many).
    const size_t first = size_t(std::upper_bound(times_.begin(), times_.end(), a) - times_.begin());
    const size_t last = size_t(std::lower_bound(times_.begin(), times_.end(), b) - times_.begin());
    // Cut short of the last key, the piece is closed at b (TrilinearBody::restrictedTo).
    const bool open = b == time_.t1 && time_.openEnd;
    std::unique_ptr<Body> r;
    if (first >= last) {
        r = std::make_unique<TrilinearBody>(TimeSpan{a, b, open}, at(a), at(b), Cs_, material_);
    } else {
        std::vector<double> ts;
        std::vector<Corners> ks;
        ts.reserve(last - first + 2);
        ks.reserve(last - first + 2);
        ts.push_back(a);
        ks.push_back(at(a));
        ts.insert(ts.end(), times_.begin() + std::ptrdiff_t(first), times_.begin() + std::ptrdiff_t(last));
        ks.insert(ks.end(), keys_.begin() + std::ptrdiff_t(first), keys_.begin() + std::ptrdiff_t(last));
        ts.push_back(b);
        ks.push_back(at(b));
        r = std::make_unique<KeyedPatchBody>(std::move(ts), std::move(ks), Cs_, material_, open);
    }
    r->inheritFrom(*this);
    return r;
}

std::unique_ptr<KeyedPatchBody> KeyedPatchBody::keysOver(double a, double b, const Camera& camera) const {
    const size_t n = times_.size();
    size_t i0 = size_t(std::upper_bound(times_.begin(), times_.end(), a) - times_.begin());  // the first key after a
    i0 = i0 > 0 ? i0 - 1 : 0;
    size_t i1 = std::min(n - 1, size_t(std::lower_bound(times_.begin(), times_.end(), b) - times_.begin()));
    while (i1 - i0 < 2 && i1 + 1 < n) ++i1;
    while (i1 - i0 < 2 && i0 > 0) --i0;
    if (i0 == 0 && i1 == n - 1) return nullptr;
    rootChunkFrames(*this, camera);  // over every key, kept below
    auto r = std::make_unique<KeyedPatchBody>(
        std::vector<double>(times_.begin() + std::ptrdiff_t(i0), times_.begin() + std::ptrdiff_t(i1) + 1),
        std::vector<Corners>(keys_.begin() + std::ptrdiff_t(i0), keys_.begin() + std::ptrdiff_t(i1) + 1), Cs_, material_,
        i1 + 1 == n && time_.openEnd);
    r->moving_ = moving_;
    r->bound_ = bound_;  // a root's bound decides no piece, but the depth layers (--layers N) read it
    r->rootChunk.store(rootChunk.load(std::memory_order_relaxed), std::memory_order_relaxed);
    r->inheritFrom(*this);
    r->pieceKey = pieceKey;
    return r;
}

size_t KeyedPatchBody::memoryBytes() const {
    return heapBlockBytes(sizeof(*this)) + heapBlockBytes(times_.capacity() * sizeof(double)) +
           heapBlockBytes(keys_.capacity() * sizeof(Corners));
}

void KeyedPatchBody::dice(int, int, Grid&) const {
    throw std::logic_error("a body with more than two motion keys is diced at its keys (diceKey), not over its span");
}

void KeyedPatchBody::startKeyGrid(int nu, int nv, Grid& grid) const {
    startGrid(nu, nv, grid);
    grid.resize(nu, nv, true);
    const float du = 1.0f / float(nu), dv = 1.0f / float(nv);
    for (int j = 0; j <= nv; ++j) {
        const float v = j == nv ? 1.0f : float(j) * dv;
        for (int i = 0; i <= nu; ++i) grid.Cs[size_t(grid.index(i, j))] = bilerp(Cs_, i == nu ? 1.0f : float(i) * du, v);
    }
}

void KeyedPatchBody::diceKey(size_t k, Grid& grid, int slot) const {
    const int nu = grid.nu, nv = grid.nv;
    const float du = 1.0f / float(nu), dv = 1.0f / float(nv);
    const Corners& c = keys_[k];
    for (int j = 0; j <= nv; ++j) {
        // Exact 0 and 1 on the borders, as TrilinearBody::dice: neighbours share edge vertices.
        const float v = j == nv ? 1.0f : float(j) * dv;
        for (int i = 0; i <= nu; ++i) {
            const float u = i == nu ? 1.0f : float(i) * du;
            const size_t idx = size_t(grid.index(i, j));
            grid.P[slot][idx] = bilerp(c, u, v);
            grid.N[slot][idx] = bilinearNormal(c, u, v);
        }
    }
}

}  // namespace streyes
