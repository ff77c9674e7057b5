#include "geom/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace streyes {

Camera::Camera(const CameraDesc& desc) : desc_(desc), worldToCamera_(desc.worldToCamera) {
    perspective_ = desc.projection == ProjectionKind::Perspective;
    width_ = desc.xres;
    height_ = desc.yres;
    near_ = float(desc.nearClip);
    // A finite far plane, whatever the scene's (Clipping's far may be beyond the float range): a
    // hit inside the clipping range then has a finite depth, so a sample of the still layer has
    // no hit exactly where its depth is +inf (the still write kernel counts first hits by that).
    far_ = std::min(float(desc.farClip), std::numeric_limits<float>::max());

    // RenderMan's default screen window: the shorter image side spans [-1, 1].
    double aspect = desc.frameAspect > 0 ? desc.frameAspect : desc.pixelAspect * desc.xres / desc.yres;
    double l, r, b, t;
    if (desc.hasScreenWindow) {
        l = desc.screenWindow[0];
        r = desc.screenWindow[1];
        b = desc.screenWindow[2];
        t = desc.screenWindow[3];
    } else if (aspect >= 1) {
        l = -aspect, r = aspect, b = -1, t = 1;
    } else {
        l = -1, r = 1, b = -1 / aspect, t = 1 / aspect;
    }
    // Perspective: screen = (x/z, y/z) / tan(fov/2).
    double s = perspective_ ? 1.0 / std::tan(desc.fov * M_PI / 360.0) : 1.0;
    ax_ = float(s * width_ / (r - l));
    bx_ = float(-l * width_ / (r - l));
    ay_ = float(-s * height_ / (t - b));
    by_ = float(t * height_ / (t - b));
    if (perspective_ && desc.depthOfField()) {
        lensRadius_ = float(desc.focalLength / (2 * desc.fstop));
        focalDistance_ = float(desc.focalDistance);
        invFocal_ = float(1 / desc.focalDistance);
    }
}

Vec3f Camera::fromRaster(float x, float y, float z) const {
    float sx = (x - bx_) / ax_, sy = (y - by_) / ay_;
    if (perspective_) return {sx * z, sy * z, z};
    return {sx, sy, z};
}

}  // namespace streyes
