// Level of detail (Detail, DetailRange, RelativeDetail: scene.h's LevelOfDetail): which
// representation of a model a frame draws, decided frame by frame from that frame's camera, so that
// a frame draws the same whatever frames it is rendered with.
//
// A frame's detail is the raster area of the screen rectangle around the Detail box's corners, seen
// at the middle of the frame's exposure (the camera and the box's transform as they are then), times
// RelativeDetail; a box reaching behind the eye plane has an infinite one. Each representation is
// seen by a share [lo, hi) of the frame's samples, from its DetailRange (RI Spec 3.2, as Aqsis reads
// it): lo rises from 0 to 1 as the detail falls from lowertransition to minvisible, hi falls from 1
// to 0 as it rises from uppertransition to maxvisible. Neighbouring ranges ([a b c d] and [c d e f])
// give shares that split [0, 1) between them, so that in a transition every sample sees exactly one
// of the two: a dissolve, sample by sample (raster/sampler_common.h, dissolveKeeps).
#pragma once

#include <vector>

#include "geom/camera.h"
#include "streyes/scene.h"

namespace streyes {

struct DetailShare {
    float lo = 0, hi = 1;
    bool none() const { return !(lo < hi); }
    bool all() const { return lo <= 0 && hi >= 1; }
    bool operator==(const DetailShare& o) const { return lo == o.lo && hi == o.hi; }
};

// The raster area of a Detail box at time t (before RelativeDetail); +inf when it reaches behind
// the eye plane, or when no Detail box was given.
double detailArea(const LevelOfDetail& lod, const MotionTransform& worldToCamera, const Camera& camera, double t);

// The share of samples that sees a representation of DetailRange `range` at detail `area`.
DetailShare detailShare(const std::array<double, 4>& range, double area);

// Frames [first, last] grouped into runs of consecutive frames that draw one share; frames that
// draw nothing are left out. Under a zoom, `cameras` gives each frame's camera.
struct DetailRun {
    int first, last;
    DetailShare share;
};
std::vector<DetailRun> detailRuns(const LevelOfDetail& lod, int first, int last, const Shutter& shutter,
                                  const MotionTransform& worldToCamera, const Camera& camera, double relativeDetail,
                                  const FrameCameras* cameras = nullptr);

// A primitive's lifetime cut to the exposures of frames [a, b]: open at the end where the next
// frame's exposure begins there (Shutter 0 1).
Lifetime runLifetime(const Lifetime& life, int a, int b, const Shutter& shutter);

}  // namespace streyes
