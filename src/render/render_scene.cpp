#include "streyes/render_scene.h"

#include <algorithm>
#include <map>

namespace streyes {

namespace {

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
    uint32_t primitiveId = 0;
    for (const BilinearPatchDesc& p : scene.patches) {
        ++primitiveId;  // scene order, from 1; skipped primitives keep their number
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
        bool finite = true;
        for (size_t i = 0; i < ts.size(); ++i) {
            Matrix4 m = objectToCamera.at(ts[i]);
            std::array<Vec3d, 4> obj = cornersAt(p, ts[i]);
            for (int c = 0; c < 4; ++c) {
                Vec3f v(m.point(obj[size_t(c)]));
                finite = finite && isFinite(v);
                corners[i][size_t(c)] = v;
            }
        }
        if (!finite) {
            log.warn(p.loc, "primitive has non-finite coordinates in camera space: skipped");
            continue;
        }
        rs->sources.push_back(p.loc);
        const SourceLoc* source = &rs->sources.back();
        auto add = [&](double t0, double t1, const TrilinearBody::Corners& c0, const TrilinearBody::Corners& c1) {
            auto body = std::make_unique<TrilinearBody>(TimeSpan{t0, t1}, c0, c1, cs, material);
            body->setSource(source);
            body->setPrimitiveId(primitiveId);
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
