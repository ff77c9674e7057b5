// View culling: is a body's bound outside a bucket's block of raster spacetime?
#pragma once

#include "geom/camera.h"
#include "streyes/vecmath.h"

namespace streyes {

// True when the raster-space bound (x, y) misses the pixels of `rect`: pixel (i, j) holds
// samples in [i, i+1) x [j, j+1). NaN bounds count as outside.
inline bool rasterOutside(const Bounds3f& raster, const PixelRect& rect) {
    return !(raster.hi.x >= float(rect.x0) && raster.lo.x < float(rect.x1 + 1) && raster.hi.y >= float(rect.y0) &&
             raster.lo.y < float(rect.y1 + 1));
}

// True when a camera-space box lies wholly outside one side of the perspective frustum through
// `rect`. Works for boxes that reach behind the eye, which cannot be projected: each side is
// the half-space a * (q - c z) >= 0 with c the screen coordinate of the rect's edge.
bool outsideFrustum(const Camera& camera, const Bounds3f& box, const PixelRect& rect);

// True when a camera-space box surely misses the pixels of `rect`: its projected corners miss
// them (a box in front of the eye projects inside its corners' raster bound), or, for a box
// reaching the eye plane, it lies outside the frustum through `rect`.
bool boxOutside(const Camera& camera, const Bounds3f& box, const PixelRect& rect);

}  // namespace streyes
