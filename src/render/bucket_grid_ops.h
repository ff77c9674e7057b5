// What the bucket worker does to a diced grid before shading it: shared by its split loop
// (bucket.cpp) and the still-in-world path (bucket_world.cpp). Internal to src/render.
#pragma once

#include "bodies/material.h"
#include "geom/body.h"
#include "geom/camera.h"
#include "geom/grid.h"

namespace streyes::bucket {

// Sides and Orientation on a diced grid (slot k: the positions and normals at t0 or t1): turns
// the normals to the side Orientation calls outside.
void orientNormals(Grid& grid, int k, const Material* m);
// A solid's boundary: which way round a micropolygon runs in raster space where its outside faces
// the eye (Grid::frontWinding).
void setSolid(Grid& grid, const Material* m, const Camera& cam);
// Sides 1: marks in grid.hole the micropolygons whose outside faces away from the eye at every
// end of the grid's span. False when none is left to draw.
bool cullBackFacing(Grid& grid, const Camera& cam);

// Does a body's span [t0, t1] reach a sample time in [a, b] (at a only, when a == b)? Motion
// segments meet at keys: a segment that only touches [a, b] at its end is left to the next one,
// which covers that instant too (a segment is open at its end exactly when one follows); one that
// starts where [a, b] ends is not reached while the shutter is open (sample times stay below b),
// but is when it is closed (`instantExposures`: Shutter 0 0, RenderMan's default, samples every
// frame at the instant b of the last frame).
inline bool reachesSamples(const TimeSpan& span, double a, double b, bool instantExposures) {
    if (!span.overlaps(a, b)) return false;
    if (span.t1 == a && span.t0 < span.t1 && span.openEnd) return false;
    if (span.t0 == b && a < b && !instantExposures) return false;
    return true;
}

}  // namespace streyes::bucket
