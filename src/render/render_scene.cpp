#include "streyes/render_scene.h"

#include <algorithm>

#include "streyes/procedural.h"
#include "streyes/util/sampling.h"

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

// Key times of a motion inside (a, b), plus a and b.
std::vector<double> segmentTimes(const std::vector<double>& keys, double a, double b) {
    std::vector<double> ts{a};
    for (double t : keys)
        if (t > a && t < b) ts.push_back(t);
    if (b > a) ts.push_back(b);
    return ts;
}

std::vector<double> keysOf(const MotionTransform& m) { return m.isStatic() ? std::vector<double>{} : m.times(); }

// Child ids: a hash of the parent's id and the child's index (never 0 or the "no hit" value).
uint32_t childId(uint32_t parent, uint64_t index) {
    uint32_t id = uint32_t(mix64((uint64_t(parent) << 32) ^ (index + 1)) >> 32);
    return id == 0 || id == UINT32_MAX ? 1 : id;
}

}  // namespace

BodyFactory::BodyFactory(const MotionTransform& worldToCamera, double windowStart, double windowEnd, Log& log)
    : worldToCamera_(worldToCamera), windowStart_(windowStart), windowEnd_(windowEnd), log_(log) {}

const Material* BodyFactory::material(const AttributesPtr& attributes) {
    static const AttributesPtr kDefault = std::make_shared<const Attributes>();
    const AttributesPtr& a = attributes ? attributes : kDefault;
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = materialOf_.find(a.get());
    if (it != materialOf_.end()) return it->second;
    keepAlive_.push_back(a);
    materials_.push_back(makeMaterial(*a));
    return materialOf_.emplace(a.get(), &materials_.back()).first->second;
}

const SourceLoc* BodyFactory::source(const SourceLoc& loc) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto key = std::make_pair(loc.file.get(), loc.line);
    auto it = sourceOf_.find(key);
    if (it != sourceOf_.end()) return it->second;
    sources_.push_back(loc);
    return sourceOf_.emplace(key, &sources_.back()).first->second;
}

void BodyFactory::addPatch(const BilinearPatchDesc& p, uint32_t primitiveId, std::vector<BodyPtr>& out) {
    const Material* mat = material(p.attributes);
    std::array<Color, 4> cs;
    for (int c = 0; c < 4; ++c) cs[size_t(c)] = p.hasCs ? p.Cs[size_t(c)] : mat->Cs;

    MotionTransform objectToCamera = p.objectToWorld.then(worldToCamera_);
    std::vector<double> keys = keysOf(objectToCamera);
    if (p.P.size() > 1) keys = unionTimes(keys, p.times);
    std::vector<double> ts = segmentTimes(keys, windowStart_, windowEnd_);
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
        log_.warn(p.loc, "primitive has non-finite coordinates in camera space: skipped");
        return;
    }
    const SourceLoc* src = source(p.loc);
    auto add = [&](double t0, double t1, const TrilinearBody::Corners& c0, const TrilinearBody::Corners& c1) {
        auto body = std::make_unique<TrilinearBody>(TimeSpan{t0, t1}, c0, c1, cs, mat);
        body->setSource(src);
        body->setPrimitiveId(primitiveId);
        out.push_back(std::move(body));
        ++bodiesMade_;
    };
    if (ts.size() == 1) {  // a single instant (one frame, shutter open == close)
        add(ts[0], ts[0], corners[0], corners[0]);
        return;
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

Bounds3f BodyFactory::cameraBound(const Bounds3d& b, const MotionTransform& objectToWorld) const {
    MotionTransform objectToCamera = objectToWorld.then(worldToCamera_);
    Bounds3f r;
    for (double t : segmentTimes(keysOf(objectToCamera), windowStart_, windowEnd_)) {
        Matrix4 m = objectToCamera.at(t);
        for (int i = 0; i < 8; ++i)
            r.extend(Vec3f(m.point({(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z})));
    }
    return r;
}

void BodyFactory::addProcedural(const ProceduralDesc& p, uint32_t primitiveId, int depth, std::vector<BodyPtr>& out) {
    if (depth > kMaxProceduralDepth) {
        log_.warnOnce("procedural-depth", p.loc,
                      "procedurals nested more than " + std::to_string(kMaxProceduralDepth) +
                          " deep (does a procedural produce itself?): the deeper ones are dropped");
        return;
    }
    Bounds3f b = cameraBound(p.bound, p.objectToWorld);
    if (!isFinite(b.lo) || !isFinite(b.hi)) {
        log_.warn(p.loc, "procedural bound is not finite in camera space: skipped");
        return;
    }
    auto body = std::make_unique<ProceduralBody>(p, b, TimeSpan{windowStart_, windowEnd_}, depth);
    body->setSource(source(p.loc));
    body->setPrimitiveId(primitiveId);
    out.push_back(std::move(body));
    ++proceduralsMade_;
    std::lock_guard<std::mutex> lock(mutex_);
    if (proceduralsByDepth_.size() <= size_t(depth)) proceduralsByDepth_.resize(size_t(depth) + 1, 0);
    ++proceduralsByDepth_[size_t(depth)];
}

std::vector<uint64_t> BodyFactory::proceduralsMadeByDepth() const {
    std::lock_guard<std::mutex> lock(const_cast<std::mutex&>(mutex_));
    return proceduralsByDepth_;
}

void BodyFactory::addChildren(const Scene& fragment, uint32_t parentId, int depth, std::vector<BodyPtr>& out) {
    uint64_t index = 0;
    for (const BilinearPatchDesc& p : fragment.patches) addPatch(p, childId(parentId, index++), out);
    for (const ProceduralDesc& p : fragment.procedurals) addProcedural(p, childId(parentId, index++), depth, out);
}

void BodyFactory::reportOutgrown(ProceduralBody* p) {
    std::lock_guard<std::mutex> lock(mutex_);
    outgrown_.push_back(p);
}

std::vector<ProceduralBody*> BodyFactory::takeOutgrown() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<ProceduralBody*> r;
    r.swap(outgrown_);
    return r;
}

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
    rs->factory = std::make_unique<BodyFactory>(cam.worldToCamera, rs->windowStart, rs->windowEnd, log);
    // Primitive ids in scene order from 1: patches, then procedurals.
    uint32_t id = 0;
    for (const BilinearPatchDesc& p : scene.patches) rs->factory->addPatch(p, ++id, rs->roots);
    for (const ProceduralDesc& p : scene.procedurals) rs->factory->addProcedural(p, ++id, 0, rs->roots);
    return rs;
}

}  // namespace streyes
