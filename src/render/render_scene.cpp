#include "streyes/render_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <map>

namespace streyes {

namespace {

// Camera space is single precision. Corners beyond this magnitude would overflow to infinity
// when a split adds two of them or a measure squares their distance.
constexpr double kMaxCameraCoordinate = 1e37;

// Far from the world's origin, double precision runs out: a point at world distance M comes to
// camera space with an error of a few units in M's last place (2^-52 M), however near the camera
// is. Past this error in raster pixels the renderer says so.
constexpr double kMaxPrecisionPixels = 0.01;

// The largest magnitude a corner passes through on its way to camera space: its world position,
// or the camera's translation (the world origin in camera space).
double worldMagnitude(const Matrix4& objectToWorld, const Matrix4& worldToCamera, const std::array<Vec3d, 4>& obj) {
    double m = std::max({std::fabs(worldToCamera(3, 0)), std::fabs(worldToCamera(3, 1)), std::fabs(worldToCamera(3, 2))});
    for (const Vec3d& c : obj) {
        Vec3d w = objectToWorld.point(c);
        m = std::max({m, std::fabs(w.x), std::fabs(w.y), std::fabs(w.z)});
    }
    return m;
}

// That rounding error (4 ulps of the world magnitude) in raster pixels at camera-space point v.
double precisionInPixels(const Camera& camera, double worldScale, Vec3d v) {
    const double error = 4 * worldScale * std::numeric_limits<double>::epsilon();
    const double scale = std::max(std::fabs(camera.ax()), std::fabs(camera.ay()));
    if (!camera.perspective()) return error * scale;
    return v.z > camera.nearClip() ? error * scale / v.z : 0;  // nearer than `near`: clipped anyway
}

std::string formatShort(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

// The primitive's object-space corners at time t: linear between its keys, held outside.
std::array<Vec3d, 4> cornersAt(const BilinearPatchDesc& p, double t) {
    if (p.P.size() == 1 || t <= p.times.front()) return p.P.front();
    if (t >= p.times.back()) return p.P.back();
    size_t i = size_t(std::upper_bound(p.times.begin(), p.times.end(), t) - p.times.begin());
    double s = (t - p.times[i - 1]) / (p.times[i] - p.times[i - 1]);
    std::array<Vec3d, 4> r;
    for (int c = 0; c < 4; ++c) r[size_t(c)] = lerp(p.P[i - 1][size_t(c)], p.P[i][size_t(c)], s);
    return r;
}

// Key times of everything that moves the primitive in camera space, inside (a, b), plus a and b.
std::vector<double> segmentTimes(const BilinearPatchDesc& p, const MotionTransform& objectToCamera, double a,
                                 double b) {
    std::vector<double> keys = objectToCamera.isStatic() ? std::vector<double>{} : objectToCamera.times();
    if (p.P.size() > 1) keys = unionTimes(keys, p.times);
    std::vector<double> ts{a};
    for (double t : keys)
        if (t > a && t < b) ts.push_back(t);
    if (b > a) ts.push_back(b);
    return ts;
}

}  // namespace

std::unique_ptr<RenderScene> buildRenderScene(const Scene& scene, int firstFrame, int lastFrame, int xres, int yres,
                                              Log& log) {
    auto rs = std::make_unique<RenderScene>();
    CameraDesc cam = scene.camera;
    if (xres > 0 && yres > 0) {
        cam.xres = xres;
        cam.yres = yres;
    }
    rs->camera = Camera(cam);
    rs->shutter = {scene.settings.shutterOpen, scene.settings.shutterClose};
    rs->lights = LightSet(scene.lights, cam.worldToCamera);
    rs->windowStart = firstFrame + rs->shutter.open;
    rs->windowEnd = lastFrame + rs->shutter.close;

    std::map<const Attributes*, const Material*> materialOf;
    for (const BilinearPatchDesc& p : scene.patches) {
        const Attributes* attr = p.attributes.get();
        static const Attributes kDefault;
        if (!attr) attr = &kDefault;
        auto it = materialOf.find(attr);
        if (it == materialOf.end()) {
            rs->materials.push_back(makeMaterial(*attr));
            it = materialOf.emplace(attr, &rs->materials.back()).first;
        }
        const Material* material = it->second;
        std::array<Color, 4> cs;
        for (int c = 0; c < 4; ++c) cs[size_t(c)] = p.hasCs ? p.Cs[size_t(c)] : attr->color;

        MotionTransform objectToCamera = p.objectToWorld.then(cam.worldToCamera);
        std::vector<double> ts = segmentTimes(p, objectToCamera, rs->windowStart, rs->windowEnd);
        std::vector<TrilinearBody::Corners> corners(ts.size());
        bool finite = true, fits = true;
        double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin, rasterError = 0;
        for (size_t i = 0; i < ts.size(); ++i) {
            Matrix4 m = objectToCamera.at(ts[i]);
            std::array<Vec3d, 4> obj = cornersAt(p, ts[i]);
            const double worldScale = worldMagnitude(p.objectToWorld.at(ts[i]), cam.worldToCamera.at(ts[i]), obj);
            for (int c = 0; c < 4; ++c) {
                // Checked in double: converting a value beyond float's range would be undefined.
                Vec3d v = m.point(obj[size_t(c)]);
                finite = finite && isFinite(v);
                fits = fits && std::fabs(v.x) <= kMaxCameraCoordinate && std::fabs(v.y) <= kMaxCameraCoordinate &&
                       std::fabs(v.z) <= kMaxCameraCoordinate;
                if (finite && fits) corners[i][size_t(c)] = Vec3f(v);
                zmin = std::min(zmin, v.z), zmax = std::max(zmax, v.z);
                rasterError = std::max(rasterError, precisionInPixels(rs->camera, worldScale, v));
            }
        }
        if (!finite) {
            log.warn(p.loc, "primitive has non-finite coordinates in camera space: skipped");
            continue;
        }
        if (!fits) {
            log.warn(p.loc, "primitive reaches beyond 1e37 in camera space, where single precision overflows when "
                            "it is split: skipped (scale the scene down)");
            continue;
        }
        if (zmin > 0 && zmax < cam.nearClip)
            log.warnOnce("nearclip", p.loc,
                         "primitive lies wholly between the camera and the near clipping plane (Clipping near = " +
                             formatShort(cam.nearClip) +
                             "): it cannot be seen (lower the near plane with Clipping, or scale the scene up)");
        if (rasterError > kMaxPrecisionPixels)
            log.warnOnce("precision", p.loc,
                         "primitive lies so far from the world's origin that double precision moves it by up to " +
                             formatShort(rasterError) +
                             " pixels on its way to camera space (translate the scene and the camera nearer the "
                             "origin)");
        rs->sources.push_back(p.loc);
        const SourceLoc* source = &rs->sources.back();
        // Segments meet at their keys: all but the last are half-open, so that a sample exactly
        // at a key belongs to the segment that starts there.
        auto add = [&](double t0, double t1, const TrilinearBody::Corners& c0, const TrilinearBody::Corners& c1) {
            auto body = std::make_unique<TrilinearBody>(TimeSpan{t0, t1, t1 < ts.back()}, c0, c1, cs, material);
            body->setSource(source);
            rs->roots.push_back(std::move(body));
        };
        if (ts.size() == 1) {  // a single instant (one frame, shutter open == close)
            add(ts[0], ts[0], corners[0], corners[0]);
            continue;
        }
        // One body per segment between keys; a run of still segments is one still body.
        for (size_t i = 0; i + 1 < ts.size();) {
            size_t j = i + 1;
            if (corners[j] == corners[i])
                while (j + 1 < ts.size() && corners[j + 1] == corners[i]) ++j;
            add(ts[i], ts[j], corners[i], corners[j]);
            i = j;
        }
    }
    return rs;
}

}  // namespace streyes
