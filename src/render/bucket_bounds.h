// The bounds the bucket worker culls with: shared by its split loop (bucket.cpp) and its
// procedurals (bucket_procedurals.cpp), so that what releases an expansion takes a procedural's
// reach exactly as the view cull does. Internal to src/render.
#pragma once

#include "geom/body.h"
#include "geom/camera.h"
#include "bodies/material.h"

namespace streyes::bucket {

// A body's camera-space bound grown by how far its displacement shader may move its points
// (Attribute "displacementbound"): culling stays conservative for displaced surfaces.
inline Bounds3f displaced(const Body& body, Bounds3f box) {
    const float r = body.material() ? body.material()->displacementBound : 0.0f;
    if (r > 0) {
        box.lo = box.lo - Vec3f{r, r, r};
        box.hi = box.hi + Vec3f{r, r, r};
    }
    return box;
}

// The raster bound of a camera-space box in front of the eye plane: its corners projected.
inline Bounds3f rasterOfBox(const Camera& cam, const Bounds3f& box) {
    Bounds3f r;
    for (int c = 0; c < 8; ++c)
        r.extend(cam.toRaster({c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y, c & 4 ? box.hi.z : box.lo.z}));
    return r;
}

// The raster bound a body in front of the eye plane is culled with: its measure's (`m`), the box
// of its displaced camera bound (`swept`) where a shader displaces it, and, with depth of field,
// grown by the circle of confusion (what the lens blurs reaches samples that far away).
inline Bounds3f cullRaster(const Camera& cam, const Body& body, const RasterMeasure& m, const Bounds3f& swept) {
    Bounds3f raster = m.bound.swept();
    if (body.material() && body.material()->displacementBound > 0) raster.extend(rasterOfBox(cam, swept));
    return cam.grownByCoc(raster, swept.lo.z, swept.hi.z);
}

}  // namespace streyes::bucket
