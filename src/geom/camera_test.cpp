#include "geom/camera.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace streyes
