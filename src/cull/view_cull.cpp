#include "cull/view_cull.h"

#include <cmath>

namespace streyes {

bool outsideFrustum(const Camera& camera, const Bounds3f& box, const PixelRect& rect) {
    if (!camera.perspective()) return false;
    // Sides: raster x >= x0, raster x <= x1 + 1, raster y >= y0, raster y <= y1 + 1.
    struct Side {
        int axis;       // 0: x, 1: y
        float a, c;     // raster = a * (q / z) + b; c = (edge - b) / a
        float sign;     // +1: keep raster >= edge, -1: keep raster <= edge
    };
    const Side sides[4] = {
        {0, camera.ax(), (float(rect.x0) - camera.bx()) / camera.ax(), 1},
        {0, camera.ax(), (float(rect.x1 + 1) - camera.bx()) / camera.ax(), -1},
        {1, camera.ay(), (float(rect.y0) - camera.by()) / camera.ay(), 1},
        {1, camera.ay(), (float(rect.y1 + 1) - camera.by()) / camera.ay(), -1},
    };
    // Depth of field: P is seen through lens point L = (Lx, Ly) with |L| <= R at screen position
    // (P.x - Lx) / z + Lx / d, so the side's half-space for that lens point is
    // sign a ((q - c z) - Lx (1 - z / d)) >= 0, and P misses all of them when
    // sign a (q - c z) + |a| R |1 - z / d| < 0. That is convex in P: all eight corners decide.
    const float R = camera.lensRadius() * 1.0001f, invD = camera.depthOfField() ? 1.0f / camera.focalDistance() : 0.0f;
    for (const Side& s : sides) {
        bool allOut = true;
        for (int i = 0; i < 8 && allOut; ++i) {
            Vec3f p{(i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y, (i & 4) ? box.hi.z : box.lo.z};
            float q = s.axis == 0 ? p.x : p.y;
            if (camera.depthOfField())
                allOut = s.sign * s.a * (q - s.c * p.z) + std::fabs(s.a) * R * std::fabs(1 - p.z * invD) < 0;
            else
                allOut = s.sign * s.a * (q - s.c * p.z) < 0;
        }
        if (allOut) return true;
    }
    return false;
}

bool boxOutside(const Camera& camera, const Bounds3f& box, const PixelRect& rect) {
    if (camera.perspective() && !(box.lo.z >= camera.eyePlane())) return outsideFrustum(camera, box, rect);
    Bounds3f raster;
    for (int i = 0; i < 8; ++i)
        raster.extend(camera.toRaster({(i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y,
                                       (i & 4) ? box.hi.z : box.lo.z}));
    return rasterOutside(camera.grownByCoc(raster, box.lo.z, box.hi.z), rect);  // depth of field: grown
}

}  // namespace streyes
