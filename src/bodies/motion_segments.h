// Motion segments, as the body factory cuts a primitive's time window at its keys: shared by the
// factory's files (body_factory.cpp, curve_bodies.cpp).
#pragma once

#include <limits>
#include <vector>

#include "geom/body.h"

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

}  // namespace streyes
