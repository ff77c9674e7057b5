// Wind sway of Weber–Penn trees (the paper's "Wind sway"): each stem's segments turn about the
// stem's own x and y axes by angles that swing with time, so a stem carries what grows on it
// (its clones, child stems and leaves) along. The procedural keys the motion every keystep frames.
#pragma once

#include <vector>

#include "procedural/weber_penn.h"

namespace streyes {

// Degrees one segment of a stem turns about the stem's x and y axes at a time (frames):
//   a0 = 4 length_stem (1 - z) / radius_z        (z = the segment's start along the stem, 0..1)
//   a1 = WindSpeed / 50 a0,   a2 = WindGust / 50 a0 + a1 / 2
//   b  = sway_offset + radius_stem / length_stem time / 15    (time = frame windtime)
//   a  = (a1 sin b + a2 sin 0.7 b) / nCurveRes
// with sway_offset_x, sway_offset_y drawn in [0, 2 pi) for each stem from its key.
struct WeberPennSwayAngles {
    double x = 0, y = 0;
};
WeberPennSwayAngles weberPennSwayAngles(const WeberPennParams& p, const WeberPennStem& s, int segment, double frame);
// The most a segment turns about either axis at any time (degrees): (a1 + a2) / nCurveRes, since
// |a1 sin b + a2 sin 0.7 b| <= a1 + a2 whatever b. Bounds count on it (not on the shot's keys, so
// that they do not depend on the frames rendered).
double weberPennSwayAmplitude(const WeberPennParams& p, const WeberPennStem& s, int segment);
// The stem's sway_offset_x and sway_offset_y (radians).
void weberPennSwayOffsets(const WeberPennStem& s, double* x, double* y);
// Whether the parameters move the tree (WindSpeed or WindGust above zero).
bool weberPennWindy(const WeberPennParams& p);

// A rigid motion: q -> x q.x + y q.y + z q.z + t.
struct WeberPennRigid {
    Vec3d x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1}, t{0, 0, 0};
    Vec3d operator()(Vec3d q) const { return x * q.x + y * q.y + z * q.z + t; }
    Vec3d turned(Vec3d v) const { return x * v.x + y * v.y + z * v.z; }
    WeberPennRigid then(const WeberPennRigid& inner) const;  // this after inner
};

// A stem posed at one time: the motion of each segment of each path (what lies on segment j of
// path i, including its end point and whatever grows there, moves by of(i, j)).
struct WeberPennPose {
    std::vector<std::vector<WeberPennRigid>> motion;  // [path][segment - firstSegment]
    std::vector<int> firstSegment;
    const WeberPennRigid& of(int path, int segment) const;
};
// Segment j turns about its start point by the sway angles (about x, then about y), after the
// segment before it (a clone's first: its parent path's), the first after `attach` (identity for
// the trunk: its foot stays put; a child: its parent's pose where it grows).
WeberPennPose weberPennPoseStem(const WeberPennParams& p, const WeberPennStem& s, const WeberPennRigid& attach,
                                double frame);

// Key times (frames) covering [windowStart, windowEnd]: multiples of keystep, at least two, so that
// a frame's motion does not depend on the block it is rendered in. One key at windowStart when still.
std::vector<double> weberPennKeyTimes(const WeberPennParams& p, double windowStart, double windowEnd);

}  // namespace streyes
