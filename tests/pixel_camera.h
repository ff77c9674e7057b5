// An orthographic camera of size x size pixels where one camera-space unit is one pixel: raster
// x = x, raster y = size - y. Header-only, for the tests and the benchmarks (bench/ includes it
// as "../tests/pixel_camera.h": it does not link the tests' helpers).
#pragma once

#include "geom/camera.h"

namespace streyes::test {

inline Camera pixelCamera(int size) {
    CameraDesc cd;
    cd.xres = cd.yres = size;
    cd.hasScreenWindow = true;
    cd.screenWindow[0] = 0, cd.screenWindow[1] = size, cd.screenWindow[2] = 0, cd.screenWindow[3] = size;
    return Camera(cd);
}

}  // namespace streyes::test
