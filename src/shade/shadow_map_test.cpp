// shadow() on depth maps (shadow_map.h): closed forms on synthetic maps.
#include "shade/shadow_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "geom/camera.h"
#include "shade/vm/texture_source.h"

namespace streyes {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A light camera at the world origin looking down +z: the map's matrices.
DepthMap emptyMap(ProjectionKind kind, int res, double fov = 40) {
    CameraDesc d;
    d.projection = kind;
    d.fov = fov;
    d.xres = d.yres = res;
    const Camera cam(d);
    DepthMap m;
    m.width = m.height = res;
    m.z.assign(size_t(res) * size_t(res), DepthMap::kNoDepth);
    m.worldToScreen = screenProjection(cam.perspective(), cam.ax(), cam.bx(), cam.ay(), cam.by(), res, res);
    return m;
}

TEST(ShadowMap, ScreenProjectionMapsCameraPointsToTheirRasterPixels) {
    for (ProjectionKind kind : {ProjectionKind::Perspective, ProjectionKind::Orthographic}) {
        CameraDesc d;
        d.projection = kind;
        d.fov = 33;
        d.xres = 320, d.yres = 200;
        d.hasScreenWindow = true;
        d.screenWindow[0] = -1.3, d.screenWindow[1] = 1.1, d.screenWindow[2] = -0.7, d.screenWindow[3] = 0.9;
        const Camera cam(d);
        const Matrix4 s = screenProjection(cam.perspective(), cam.ax(), cam.bx(), cam.ay(), cam.by(), 320, 200);
        for (const Vec3d p : {Vec3d{0.3, -0.2, 4}, Vec3d{-1.1, 0.5, 2.5}, Vec3d{0, 0, 1}}) {
            const Vec3f r = cam.toRaster(Vec3f(p));
            const Vec3d q = s.point(p);  // screen: [-1, 1] across the image, y up
            EXPECT_NEAR((q.x + 1) * 0.5 * 320, r.x, 1e-3);
            EXPECT_NEAR((1 - q.y) * 0.5 * 200, r.y, 1e-3);
        }
    }
}

// A plane tilted 80 degrees from the light (its normal 80 degrees from the light's direction),
// depth map made as the renderer makes it with depthfilter "min": the nearest of jittered samples
// in each pixel. Looked up at points of a micropolygon grid on the plane at the default bias
// (0), it shadows itself nowhere; without its tangent plane (no derivatives) it would, widely.
TEST(ShadowMap, APlaneTiltedEightyDegreesFromTheLightDoesNotShadowItself) {
    const int res = 256;
    DepthMap map = emptyMap(ProjectionKind::Perspective, res);
    CameraDesc d;
    d.projection = ProjectionKind::Perspective;
    d.fov = 40;
    d.xres = d.yres = res;
    const Camera cam(d);
    const double tilt = 80 * kPi / 180;
    const Vec3d p0{0, 0, 10}, n{std::sin(tilt), 0, -std::cos(tilt)};
    auto depthAt = [&](double x, double y) {  // the plane's depth through raster (x, y)
        const Vec3d dir{(x - cam.bx()) / cam.ax(), (y - cam.by()) / cam.ay(), 1};
        return dot(n, p0) / dot(n, dir);
    };
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u01(0, 1);
    for (int j = 0; j < res; ++j)
        for (int i = 0; i < res; ++i) {
            double z = DepthMap::kNoDepth;
            for (int s = 0; s < 4; ++s) {
                const double zs = depthAt(i + u01(rng), j + u01(rng));
                if (zs > 0) z = std::min(z, zs);
            }
            map.z[size_t(j) * res + size_t(i)] = float(z);
        }
    ShadowLookup look;
    std::string error;
    ASSERT_TRUE(look.set(map, Matrix4(), &error)) << error;
    // Two directions in the plane; micropolygons a third of a texel to three texels across.
    const Vec3d a = normalize(cross(n, Vec3d{0, 1, 0})), b = normalize(cross(n, a));
    const ShadowFilter f;
    int lit = 0, acne = 0, acneWithoutPlane = 0;
    for (double step : {0.01, 0.05, 0.2})
        for (int jv = -40; jv <= 40; ++jv)
            for (int iu = -40; iu <= 40; ++iu) {
                const Vec3d p = p0 + a * (iu * step * 3.1) + b * (jv * step * 1.7);
                if (p.z < 1) continue;
                const float occ = look.occlusion(p, a * step, b * step, f);
                ++lit;
                acne += occ > 0;
                acneWithoutPlane += look.occlusion(p, {0, 0, 0}, {0, 0, 0}, f) > 0;
            }
    EXPECT_GT(lit, 10000);
    EXPECT_EQ(acne, 0);
    EXPECT_GT(acneWithoutPlane, lit / 10);  // the test can fail: a constant depth shadows itself
}

// "blur" b: a box b wide (a fraction of the map) is averaged, so a straight shadow edge becomes a
// linear ramp b x width texels wide: 0.8 b x width from 10% to 90% occlusion.
TEST(ShadowMap, BlurWidensThePenumbraByItsShareOfTheMap) {
    const int res = 200;
    DepthMap map = emptyMap(ProjectionKind::Orthographic, res);
    for (int j = 0; j < res; ++j)
        for (int i = 0; i < res / 2; ++i) map.z[size_t(j) * res + size_t(i)] = 1;  // an occluder over the left half
    ShadowLookup look;
    std::string error;
    ASSERT_TRUE(look.set(map, Matrix4(), &error)) << error;
    // Orthographic, default screen window: texel x = (X + 1) / 2 * res; receiver at z = 5.
    auto occlusionAtTexel = [&](double x, const ShadowFilter& f) {
        const Vec3d p{2 * x / res - 1, 0.013, 5};
        return look.occlusion(p, {0, 0, 0}, {0, 0, 0}, f);
    };
    auto penumbra = [&](const ShadowFilter& f) {  // texels from 90% to 10% occlusion
        double at90 = NAN, at10 = NAN;
        for (double x = 40; x <= res - 40; x += 0.01) {  // away from the map's own edges
            const float o = occlusionAtTexel(x, f);
            if (std::isnan(at90) && o <= 0.9f) at90 = x;
            if (std::isnan(at10) && o <= 0.1f) at10 = x;
        }
        return at10 - at90;
    };
    ShadowFilter sharp;
    const double base = penumbra(sharp);  // the one-texel box: 0.8 texel
    EXPECT_NEAR(base, 0.8, 0.02);
    for (float blur : {0.02f, 0.1f, 0.2f}) {
        ShadowFilter f;
        f.sblur = blur;
        EXPECT_NEAR(penumbra(f), 0.8 * blur * res, 0.02) << "blur " << blur;
    }
    // A footprint beyond kExactTexels texels: stratified taps, the ramp the same on average.
    ShadowFilter wide;
    wide.sblur = wide.tblur = 0.2f;
    wide.samples = 64;
    double err = 0;
    int n = 0;
    for (double x = 70; x <= 130; x += 0.5, ++n)
        err += occlusionAtTexel(x, wide) - std::clamp((120 - x) / 40, 0.0, 1.0);
    EXPECT_LT(std::fabs(err / n), 0.02);
    EXPECT_EQ(occlusionAtTexel(50, wide), 1.0f);
    EXPECT_EQ(occlusionAtTexel(150, wide), 0.0f);
}

TEST(ShadowMap, PointsOutsideTheMapOrBehindTheLightAreLit) {
    DepthMap map = emptyMap(ProjectionKind::Perspective, 64);
    std::fill(map.z.begin(), map.z.end(), 1.0f);  // a wall at depth 1 everywhere the light sees
    ShadowLookup look;
    std::string error;
    ASSERT_TRUE(look.set(map, Matrix4(), &error)) << error;
    const ShadowFilter f;
    EXPECT_EQ(look.occlusion({0, 0, 5}, {}, {}, f), 1.0f);    // behind the wall
    EXPECT_EQ(look.occlusion({0, 0, 0.5}, {}, {}, f), 0.0f);  // in front of it
    EXPECT_EQ(look.occlusion({0, 0, -5}, {}, {}, f), 0.0f);   // behind the light
    EXPECT_EQ(look.occlusion({50, 0, 5}, {}, {}, f), 0.0f);   // outside its field of view
    // The light moved: the current space is another one (current -> world given).
    ASSERT_TRUE(look.set(map, Matrix4::translate({0, 0, -4}), &error));
    EXPECT_EQ(look.occlusion({0, 0, 5.5}, {}, {}, f), 1.0f);  // world z = 1.5
    EXPECT_EQ(look.occlusion({0, 0, 4.5}, {}, {}, f), 0.0f);  // world z = 0.5
}

}  // namespace
}  // namespace streyes
