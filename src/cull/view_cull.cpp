#include "cull/view_cull.h"

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
    for (const Side& s : sides) {
        bool allOut = true;
        for (int i = 0; i < 8 && allOut; ++i) {
            Vec3f p{(i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y, (i & 4) ? box.hi.z : box.lo.z};
            float q = s.axis == 0 ? p.x : p.y;
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
    return rasterOutside(raster, rect);
}

}  // namespace streyes
