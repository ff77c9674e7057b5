// The camera's projection from camera space to raster space.
//
// Camera space is RenderMan's: left-handed, looking down +z. Raster space has x right and y
// down, in pixels, (0,0) at the top-left corner of the image; pixel (i, j) covers
// [i, i+1) x [j, j+1). Raster z is camera-space z (not a normalised depth), which is also what
// the Z channel stores.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>

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

    // Depth of field: a thin lens (Potmesil and Chakravarty's model, as the RenderMan Interface
    // 3.2 DepthOfField request gives it): lens radius R = focallength / (2 fstop), focallength and
    // focaldistance in camera-space units, the lens in the plane z = 0 centred on the eye. The ray
    // from lens point L = R (lu, lv) through a camera-space point P meets the focal plane z = d where
    // the pinhole ray through the eye sees screen position P.xy / P.z + L (1/d - 1/P.z): so with
    // the sample's lens point P appears shifted by (lu, lv) lensShift(P.z) in screen units, (ax, ay)
    // times that in raster units. Perspective only (an orthographic camera has none). Aqsis
    // (SetDepthOfFieldData) takes the same radius, 0.5 focallength / fstop, and the same
    // |1/d - 1/z| law, with an extra factor d / (d + focallength / fstop), within a hair of 1.
    bool depthOfField() const { return lensRadius_ > 0; }
    float lensRadius() const { return lensRadius_; }
    float focalDistance() const { return focalDistance_; }
    // Screen-space shift per unit lens coordinate of a point at depth z (> 0): R (1/d - 1/z).
    float lensShift(float z) const { return lensRadius_ * (invFocal_ - 1.0f / z); }
    float invFocalDistance() const { return invFocal_; }  // lensShift's 1/d, as it rounds it
    // The circle of confusion's radius in raster pixels along x (y: cocRadiusY) of a point at
    // depth z: R |1/d - 1/z| |ax|. Zero at the focal distance and without depth of field.
    float cocRadius(float z) const { return std::fabs(lensShift(z) * ax_); }
    float cocRadiusY(float z) const { return std::fabs(lensShift(z) * ay_); }
    // The largest raster shift (x, y) any lens point gives a point with depth in [zmin, zmax]
    // (zmin > 0): |1/d - 1/z| grows away from d on either side, so one end of the range holds it.
    // Slightly over, so that bounds made with it hold the shifted float positions. (0, 0) without
    // depth of field.
    Vec2f cocMargin(float zmin, float zmax) const {
        if (!depthOfField()) return {0, 0};
        const float s = std::max(std::fabs(lensShift(zmin)), std::fabs(lensShift(zmax))) * 1.0001f;
        return {s * std::fabs(ax_) + 1e-4f, s * std::fabs(ay_) + 1e-4f};
    }
    // Raster bound grown by the circle of confusion over the depths [zmin, zmax]: where a point in
    // `raster` at those depths may be seen through some point of the lens.
    Bounds3f grownByCoc(Bounds3f raster, float zmin, float zmax) const {
        if (!depthOfField()) return raster;
        const Vec2f m = cocMargin(zmin, zmax);
        raster.lo.x -= m.x, raster.hi.x += m.x;
        raster.lo.y -= m.y, raster.hi.y += m.y;
        return raster;
    }

    const MotionTransform& worldToCamera() const { return worldToCamera_; }
    const CameraDesc& desc() const { return desc_; }

  private:
    CameraDesc desc_;
    MotionTransform worldToCamera_;
    bool perspective_ = false;
    int width_ = 0, height_ = 0;
    float near_ = 1e-4f, far_ = 1e30f;
    float ax_ = 1, bx_ = 0, ay_ = -1, by_ = 0;  // raster = a * screen + b
    float lensRadius_ = 0, focalDistance_ = 0, invFocal_ = 0;
};

// The cameras of a render's frames: one, or under a zoom (docs/ARCHITECTURE.md, "Zooms") one per
// frame whose projection or screen window differs from the render's first frame's. Camera space,
// clipping, the lens and the resolution are one for all frames (the passes see to it). A body
// lives within frames of one projection (the frame sequence cuts still runs where it changes), so
// every raster-space question about it takes the camera of any time of its life.
class FrameCameras {
  public:
    explicit FrameCameras(const Camera* common = nullptr) : common_(common) {}
    void setShutter(Shutter s) { centre_ = 0.5 * (s.open + s.close); }
    void add(int frame, const CameraDesc& desc) { frames_.insert_or_assign(frame, Camera(desc)); }
    bool zooms() const { return !frames_.empty(); }
    const Camera& common() const { return *common_; }
    // The frames rendered: a sequence block's runs may live over frames around them, whose
    // cameras the block does not have; a run's frames share one projection, so the nearest
    // frame rendered answers for them.
    void setRendered(int first, int last) { first_ = first, last_ = last; }
    // The camera of the frame whose exposure holds the middle of [t0, t1].
    const Camera& during(double t0, double t1) const {
        const double mid = 0.5 * (t0 + t1) - centre_;
        if (frames_.empty() || !(std::fabs(mid) < 1e9)) return *common_;  // an ordinary scene's bodies live always
        return ofFrame(int(std::lround(mid)));
    }
    const Camera& ofFrame(int frame) const {
        if (frames_.empty()) return *common_;
        const auto it = frames_.find(first_ <= last_ ? std::clamp(frame, first_, last_) : frame);
        return it == frames_.end() ? *common_ : it->second;
    }

  private:
    const Camera* common_;
    std::map<int, Camera> frames_;
    double centre_ = 0;
    int first_ = 0, last_ = -1;  // setRendered; none: every frame its own
};

}  // namespace streyes
