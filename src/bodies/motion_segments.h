// Motion segments, as the body factory cuts a primitive's time window at its keys: shared by the
// factory's files (body_factory.cpp, surface_bodies.cpp, curve_bodies.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "geom/body.h"
#include "streyes/transform.h"

namespace streyes {

// Segments meet at their keys: all but the last are half-open (TimeSpan), so that a sample exactly
// at a key belongs to the segment that starts there.
// The last is open too where the primitive's lifetime ends open (the next frame's exposure begins there).
inline TimeSpan segmentSpan(double t0, double t1, const std::vector<double>& ts, bool lastOpen) {
    return {t0, t1, t1 < ts.back() || (lastOpen && t1 > t0)};
}

// Calls add(t0, t1, i, j) for each segment between consecutive times, with i and j the indices
// of its keys in `keys`; a run of segments over which the keys do not change is one still
// segment; a single time (one frame, no shutter) is a segment of length zero. Segments wholly
// outside [wantA, wantB] (the exposures of the frames rendered) are not made: nothing samples
// them, and the others are the same without them.
template <typename Key, typename Add>
void forEachSegment(const std::vector<double>& ts, const std::vector<Key>& keys, Add add,
                    double wantA = -std::numeric_limits<double>::infinity(),
                    double wantB = std::numeric_limits<double>::infinity()) {
    if (ts.size() == 1) {
        add(ts[0], ts[0], size_t(0), size_t(0));
        return;
    }
    for (size_t i = 0; i + 1 < ts.size();) {
        size_t j = i + 1;
        if (keys[j] == keys[i])
            while (j + 1 < ts.size() && keys[j + 1] == keys[i]) ++j;
        if (ts[i] <= wantB && ts[j] >= wantA) add(ts[i], ts[j], i, j);
        i = j;
    }
}

// Key times of a motion inside (a, b), plus a and b.
inline std::vector<double> segmentTimes(const std::vector<double>& keys, double a, double b) {
    std::vector<double> ts{a};
    for (double t : keys)
        if (t > a && t < b) ts.push_back(t);
    if (b > a) ts.push_back(b);
    return ts;
}

// A transform's key times, less the keys it passes through on a straight line: a key equal (to
// 1e-10 of its entries' size) to the interpolation of the last key kept and the next key is not
// a key of the motion, since matrices interpolate linearly (streyes/transform.h) and points with
// them. A camera keyed every frame along a straight pan or dolly (a motion block with a key per
// frame) is then one segment, whose still-in-world bodies are diced once for a chunk of frames
// (docs/ARCHITECTURE.md, "The split loop") instead of once a frame. Every later key of a run is
// checked against its chord, so the error does not drift; a run is cut after kMaxRun keys, which
// bounds the work. A function of the transform alone: the same in every frame block.
inline std::vector<double> keysOf(const MotionTransform& m) {
    if (m.isStatic()) return {};
    const std::vector<double>& ts = m.times();
    const std::vector<Matrix4>& ks = m.keys();
    constexpr size_t kMaxRun = 64;
    auto onChord = [&](size_t a, size_t k, size_t b) {
        const Matrix4 l = lerp(ks[a], ks[b], (ts[k] - ts[a]) / (ts[b] - ts[a]));
        for (size_t e = 0; e < 16; ++e)
            if (!(std::fabs(ks[k].m[e] - l.m[e]) <= 1e-10 * (1 + std::fabs(ks[k].m[e])))) return false;
        return true;
    };
    std::vector<double> out{ts.front()};
    size_t a = 0;  // the last key kept
    for (size_t k = 1; k + 1 < ts.size(); ++k) {
        bool drop = k - a < kMaxRun;
        for (size_t i = a + 1; i <= k && drop; ++i) drop = onChord(a, i, k + 1);
        if (drop) continue;
        out.push_back(ts[k]);
        a = k;
    }
    if (ts.size() > 1) out.push_back(ts.back());
    return out;
}

// Marks the bodies a primitive appended to `out` (from `first` on) as still in world space when
// neither its transform nor its own points move: they move in camera space with the camera only
// (Body::stillInWorld). Marked when the add function returns, whichever way it returns.
struct MarkStillInWorld {
    std::vector<BodyPtr>& out;
    size_t first;
    bool still;
    MarkStillInWorld(std::vector<BodyPtr>& o, const MotionTransform& objectToWorld, size_t ownKeys)
        : out(o), first(o.size()), still(objectToWorld.isStatic() && ownKeys <= 1) {}
    ~MarkStillInWorld() {
        if (still)
            for (size_t b = first; b < out.size(); ++b) out[b]->stillInWorld = true;
    }
};

// Where time t falls among a primitive's keys: between key i and i + 1 at fraction s (held
// before the first key and after the last, where s = 0).
inline void keyInterval(const std::vector<double>& times, size_t keys, double t, size_t* i, double* s) {
    *s = 0;
    if (keys == 1 || t <= times.front()) {
        *i = 0;
    } else if (t >= times.back()) {
        *i = keys - 1;
    } else {
        *i = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
        *s = (t - times[*i]) / (times[*i + 1] - times[*i]);
    }
}

// The warning, given once, for a primitive whose camera-space points are not finite.
inline constexpr const char* kNonFiniteWarning =
    "primitive has non-finite coordinates in camera space: skipped (so are any others)";

}  // namespace streyes
