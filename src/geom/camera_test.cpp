#include "geom/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace streyes {
namespace {

TEST(Camera, PerspectiveFovSpansTheShorterSide) {
    CameraDesc cd;
    cd.projection = ProjectionKind::Perspective;
    cd.fov = 90;
    cd.xres = 200;
    cd.yres = 100;
    Camera cam(cd);
    // fov 90: y/z = +-1 spans the height; x/z = +-2 the width (aspect 2).
    Vec3f top = cam.toRaster({0, 1, 1}), right = cam.toRaster({2, 0, 1}), centre = cam.toRaster({0, 0, 5});
    EXPECT_NEAR(top.y, 0.0f, 1e-4f);
    EXPECT_NEAR(right.x, 200.0f, 1e-3f);
    EXPECT_NEAR(centre.x, 100.0f, 1e-4f);
    EXPECT_NEAR(centre.y, 50.0f, 1e-4f);
    EXPECT_EQ(centre.z, 5.0f);
    Vec3f back = cam.fromRaster(right.x, right.y, 3);
    EXPECT_NEAR(back.x, 6.0f, 1e-4f);
}

// Clipping's far plane past the float range (RenderMan's RI_INFINITY is 1e38; a scene may write
// more) is the largest finite float: a hit's depth is then never +inf.
TEST(Camera, FarClippingPlaneIsFinite) {
    CameraDesc cd;
    cd.farClip = 1e39;
    EXPECT_EQ(Camera(cd).farClip(), std::numeric_limits<float>::max());
    cd.farClip = 1e38;
    EXPECT_EQ(Camera(cd).farClip(), 1e38f);
    cd.farClip = 50;
    EXPECT_EQ(Camera(cd).farClip(), 50.0f);
}

TEST(Camera, OrthographicScreenWindow) {
    CameraDesc cd;
    cd.xres = 64;
    cd.yres = 32;
    cd.hasScreenWindow = true;
    double sw[4] = {0, 64, 0, 32};
    std::copy(sw, sw + 4, cd.screenWindow);
    Camera cam(cd);
    Vec3f r = cam.toRaster({10, 4, 7});
    EXPECT_FLOAT_EQ(r.x, 10.0f);
    EXPECT_FLOAT_EQ(r.y, 28.0f);
    EXPECT_FALSE(cam.perspective());
}

// The thin lens, computed here independently of the camera: the ray from lens point
// (Lx, 0, 0) through the camera-space point (0, 0, z) meets the focal plane z = d at
// x = Lx (1 - d / z), which the pinhole sees at screen x / d; times the raster scale ax.
TEST(Camera, DepthOfFieldCircleOfConfusionIsTheThinLens) {
    CameraDesc cd;
    cd.projection = ProjectionKind::Perspective;
    cd.fov = 40;
    cd.xres = 64;
    cd.yres = 48;
    cd.fstop = 2;
    cd.focalLength = 0.5;
    cd.focalDistance = 4;
    Camera cam(cd);
    ASSERT_TRUE(cam.depthOfField());
    const double R = 0.5 / (2 * 2), d = 4;
    EXPECT_NEAR(cam.lensRadius(), R, 1e-7);
    const double ax = (1 / std::tan(20 * M_PI / 180)) * 64 / (2 * 64.0 / 48);  // screen x spans the aspect
    for (double z : {1.0, 2.0, 4.0, 7.0, 50.0}) {
        const double focalX = R * (1 - d / z);        // where the lens edge's ray meets z = d
        const double coc = std::fabs(focalX / d) * ax;  // its screen offset, in pixels
        EXPECT_NEAR(cam.cocRadius(float(z)), coc, 1e-4 * std::max(1.0, coc)) << "z " << z;
        EXPECT_NEAR(cam.cocRadiusY(float(z)), coc, 1e-4 * std::max(1.0, coc)) << "z " << z;  // square pixels
        // The lens shift moves the point the way the lens edge's ray sees it.
        const Vec3f centre = cam.toRaster({0, 0, float(z)});
        EXPECT_NEAR(centre.x + cam.lensShift(float(z)) * cam.ax(), centre.x + focalX / d * ax, 1e-3);
    }
    EXPECT_EQ(cam.cocRadius(4), 0.0f);  // in focus
    // The bound margin over a depth range holds every depth in it, on both sides of the focus.
    const Vec2f m = cam.cocMargin(2, 9);
    for (float z = 2; z <= 9; z += 0.25f) EXPECT_GE(m.x, cam.cocRadius(z));
    EXPECT_GE(m.x, cam.cocRadius(2));
}

TEST(Camera, DepthOfFieldNeedsPerspectiveAndAFiniteFstop) {
    CameraDesc cd;
    cd.fstop = 2;
    cd.focalLength = 1;
    cd.focalDistance = 3;
    EXPECT_FALSE(Camera(cd).depthOfField());  // orthographic
    cd.projection = ProjectionKind::Perspective;
    EXPECT_TRUE(Camera(cd).depthOfField());
    cd.fstop = std::numeric_limits<double>::infinity();
    EXPECT_FALSE(Camera(cd).depthOfField());
    EXPECT_EQ(Camera(cd).cocMargin(1, 10).x, 0.0f);
}

}  // namespace
}  // namespace streyes
