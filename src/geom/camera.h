// The camera's projection from camera space to raster space.
//
// Camera space is RenderMan's: left-handed, looking down +z. Raster space has x right and y
// down, in pixels, (0,0) at the top-left corner of the image; pixel (i, j) covers
// [i, i+1) x [j, j+1). Raster z is camera-space z (not a normalised depth), which is also what
// the Z channel stores.
#pragma once

#include "streyes/scene.h"
#include "streyes/vecmath.h"

namespace streyes {

// The shutter, in frames relative to each frame: frame f is exposed during [f + open, f + close].
struct Shutter {
    double open = 0, close = 0;
};

class Camera {
  public:
    Camera() = default;
    explicit Camera(const CameraDesc& desc);

    bool perspective() const { return perspective_; }
    int width() const { return width_; }
    int height() const { return height_; }
    float nearClip() const { return near_; }
    float farClip() const { return far_; }
    // Bodies whose camera-space z reaches below this plane cannot be projected (perspective):
    // they are split ("eye split") until their pieces lie in front of it or behind the near
    // clipping plane. It sits at half the near plane so that pieces straddling it shrink to
    // lie wholly behind `near` and are culled, which bounds the number of eye splits.
    float eyePlane() const { return perspective_ ? 0.5f * near_ : -std::numeric_limits<float>::infinity(); }

    // Camera space -> raster (x, y) with camera-space z kept; needs z >= eyePlane() in perspective.
    Vec3f toRaster(Vec3f p) const {
        if (perspective_) {
            float iz = 1.0f / p.z;
            return {ax_ * p.x * iz + bx_, ay_ * p.y * iz + by_, p.z};
        }
        return {ax_ * p.x + bx_, ay_ * p.y + by_, p.z};
    }
    // Raster (x, y) at camera depth z -> camera space (for rays and tests).
    Vec3f fromRaster(float x, float y, float z) const;

    // raster = a * screen + b per axis, screen = (x/z, y/z) (perspective) or (x, y).
    float ax() const { return ax_; }
    float bx() const { return bx_; }
    float ay() const { return ay_; }
    float by() const { return by_; }

    const MotionTransform& worldToCamera() const { return worldToCamera_; }
    const CameraDesc& desc() const { return desc_; }

  private:
    CameraDesc desc_;
    MotionTransform worldToCamera_;
    bool perspective_ = false;
    int width_ = 0, height_ = 0;
    float near_ = 1e-4f, far_ = 1e30f;
    float ax_ = 1, bx_ = 0, ay_ = -1, by_ = 0;  // raster = a * screen + b
};

}  // namespace streyes
