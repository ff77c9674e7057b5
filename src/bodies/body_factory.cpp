#include "bodies/body_factory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "bodies/level_of_detail.h"
#include "bodies/motion_segments.h"
#include "geom/curved_body.h"
#include "geom/nurbs_mesh.h"
#include "geom/patch_mesh.h"
#include "procedural/procedural.h"
#include "geom/quadric.h"
#include "geom/root_chunks.h"
#include "geom/subdivision.h"
#include "util/sampling.h"

namespace streyes {

namespace {

// Camera space is single precision. Corners beyond this magnitude would overflow to infinity
// when a split adds two of them or a measure squares their distance.
constexpr double kMaxCameraCoordinate = 1e37;

// Checked in double: converting a value beyond float's range would be undefined.
bool fitsCameraSpace(Vec3d v) {
    return std::fabs(v.x) <= kMaxCameraCoordinate && std::fabs(v.y) <= kMaxCameraCoordinate &&
           std::fabs(v.z) <= kMaxCameraCoordinate;
}

// Said once per render, for the first primitive it happens to: a mesh with a million bad faces
// must not write a million lines.
const char* kTooLargeWarning =
    "primitive reaches beyond 1e37 in camera space, where single precision overflows when it is split: skipped "
    "(scale the scene down; said once for all such primitives)";

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

// That rounding error (4 ulps of the world magnitude) in raster pixels at camera depth z (any
// depth without perspective).
double roundingInPixels(const Camera& camera, double worldScale, double z) {
    const double error = 4 * worldScale * std::numeric_limits<double>::epsilon();
    const double scale = std::max(std::fabs(camera.ax()), std::fabs(camera.ay()));
    return camera.perspective() ? error * scale / z : error * scale;
}

// The same at camera-space point v: nothing nearer than `near`, which is clipped anyway.
double precisionInPixels(const Camera& camera, double worldScale, Vec3d v) {
    if (camera.perspective() && !(v.z > camera.nearClip())) return 0;
    return roundingInPixels(camera, worldScale, v.z);
}

std::string formatShort(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

// An upper bound of what precisionInPixels finds at any corner of the patch at any time, from
// its largest object-space coordinate c (each world coordinate is at most c sum_j |m_ji| + |t_i|;
// corners between keys are convex combinations of the keys'). It costs a few operations where
// the exact measure transforms 4 corners a key, and lies far below kMaxPrecisionPixels unless
// the scene is far from the origin (then the exact measure decides). Static affine transforms
// only: +inf otherwise.
double precisionBound(const Camera& camera, const MotionTransform& objectToWorld, const MotionTransform& worldToCamera,
                      const BilinearPatchDesc& p) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    if (!objectToWorld.isStatic() || !worldToCamera.isStatic()) return kInf;
    const Matrix4 &m = objectToWorld.at(0), &v = worldToCamera.at(0);
    if (m(0, 3) != 0 || m(1, 3) != 0 || m(2, 3) != 0 || m(3, 3) != 1) return kInf;
    double c = 0;
    for (const std::array<Vec3d, 4>& key : p.P)
        for (const Vec3d& q : key) c = std::max({c, std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
    double world = std::max({std::fabs(v(3, 0)), std::fabs(v(3, 1)), std::fabs(v(3, 2))});
    for (int i = 0; i < 3; ++i)
        world = std::max(world, c * (std::fabs(m(0, i)) + std::fabs(m(1, i)) + std::fabs(m(2, i))) + std::fabs(m(3, i)));
    world *= 1 + 1e-9;  // over the rounding of the sums above and of the interpolation between keys
    if (camera.perspective() && !(camera.nearClip() > 0)) return kInf;
    return roundingInPixels(camera, world, camera.nearClip());  // the nearest depth a corner counts at
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

// ---- Motion segments of curved primitives ----------------------------------------------------------
// Points at time t: linear between the keys.
std::vector<Vec3d> pointsAt(const std::vector<double>& times, const std::vector<std::vector<Vec3d>>& keys, double t) {
    size_t i;
    double s;
    keyInterval(times, keys.size(), t, &i, &s);
    if (s == 0) return keys[i];
    std::vector<Vec3d> r(keys[i].size());
    for (size_t c = 0; c < r.size(); ++c) r[c] = lerp(keys[i][c], keys[i + 1][c], s);
    return r;
}

}  // namespace

BodyFactory::BodyFactory(const MotionTransform& worldToCamera, double windowStart, double windowEnd, Log& log)
    : worldToCamera_(worldToCamera), windowStart_(windowStart), windowEnd_(windowEnd), log_(log) {}

BodyFactory::Window BodyFactory::windowOf(const Lifetime& life) const {
    Window w{std::max(windowStart_, life.t0), std::min(windowEnd_, life.t1), false};
    w.openEnd = life.openEnd && w.b == life.t1 && w.b > w.a;
    return w;
}

const Material* BodyFactory::material(const AttributesPtr& attributes, const MotionTransform& objectToWorld,
                                      bool cameraFacing, const ParamList* primvars, uint64_t primitiveId,
                                      bool primvarBezier) {
    static const AttributesPtr kDefault = std::make_shared<const Attributes>();
    const AttributesPtr& a = attributes ? attributes : kDefault;
    Facing facing = Facing::Camera;
    if (!cameraFacing) {
        // The 3x3 part's determinant (at the first key: a transform does not turn inside out as it moves).
        const Matrix4 m = objectToWorld.then(worldToCamera_).keys()[0];
        const double det = m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) -
                           m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
                           m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
        facing = det < 0 ? Facing::Mirrored : Facing::Object;
    }
    const bool own = primvars && !primvars->params.empty();
    std::lock_guard<std::mutex> lock(mutex_);
    if (own) {
        auto it = ownMaterialOf_.find({a.get(), facing, primitiveId});
        if (it != ownMaterialOf_.end()) return it->second;
    } else {
        auto it = materialOf_.find({a.get(), facing});
        if (it != materialOf_.end()) return withObjectSpace(it->second, objectToWorld, facing, primitiveId);
    }
    keepAlive_.push_back(a);
    Material m = makeMaterial(*a, facing);
    if (auto share = dissolveOf_.find(a.get()); share != dissolveOf_.end())
        m.dissolveLo = share->second.first, m.dissolveHi = share->second.second;
    if (own) {
        m.primvars = *primvars;
        m.objectToWorld = objectToWorld;
        m.objectSpaceKnown = true;
        m.primvarBezier = primvarBezier;
        for (const Param& v : primvars->params)  // a single face's corners (a mesh's faces carry theirs)
            if (v.cls != ParamClass::Constant && v.nums.size() == 4 * size_t(v.componentsPerItem()))
                for (double x : v.nums) m.primvarCorners.push_back(float(x));
    }
    if (binder_) binder_->bind(m, *a);
    if (own) m.displacementBound = objectSpaceBound(m, objectToWorld);
    // A camera-facing primitive's N turns with the eye: a shader reading it reads the view (the
    // analysis takes N as still in world). Only the built-in constant reads no N.
    if (facing == Facing::Camera && (m.surface || m.kind != SurfaceKind::Constant)) m.viewUse = ViewUse::Reads;
    materials_.push_back(std::move(m));
    if (own) return ownMaterialOf_.emplace(std::make_tuple(a.get(), facing, primitiveId), &materials_.back()).first->second;
    const Material* shared = materialOf_.emplace(std::make_pair(a.get(), facing), &materials_.back()).first->second;
    return withObjectSpace(shared, objectToWorld, facing, primitiveId);
}

// The displacement bound of `m` on a primitive with `objectToWorld`: a bound given in "object"
// space scales with the primitive's transform (the shared material's took the displacement
// shader's, which is the primitive's in most files).
float BodyFactory::objectSpaceBound(const Material& m, const MotionTransform& objectToWorld) const {
    if (!(m.displacementBoundInObject > 0) || !m.attributes) return m.displacementBound;
    const double stretch = largestStretch(objectToWorld);
    if (stretch == largestStretch(m.attributes->displacement.shaderToWorld)) return m.displacementBound;
    return float(double(m.displacementBoundInObject) * stretch * largestStretch(worldToCamera_));
}

// A shared material whose shaders name "object" space, or whose displacement bound is given in
// object space and the primitive's transform stretches otherwise than the shader's, is copied per
// primitive with its transform (the RI Spec's "object" space is the primitive's, not the
// shader's); called with mutex_ held. Other materials stay shared.
const Material* BodyFactory::withObjectSpace(const Material* shared, const MotionTransform& objectToWorld, Facing facing,
                                             uint64_t primitiveId) {
    const float bound = objectSpaceBound(*shared, objectToWorld);
    if (!shared->readsObjectSpace && bound == shared->displacementBound) return shared;
    const auto key = std::make_tuple(shared->attributes, facing, primitiveId);
    auto it = ownMaterialOf_.find(key);
    if (it != ownMaterialOf_.end()) return it->second;
    Material m = *shared;
    m.displacementBound = bound;
    m.objectToWorld = objectToWorld;
    m.objectSpaceKnown = true;
    materials_.push_back(std::move(m));
    return ownMaterialOf_.emplace(key, &materials_.back()).first->second;
}

const SourceLoc* BodyFactory::source(const SourceLoc& loc) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto key = std::make_pair(loc.file.get(), loc.line);
    auto it = sourceOf_.find(key);
    if (it != sourceOf_.end()) return it->second;
    sources_.push_back(loc);
    return sourceOf_.emplace(key, &sources_.back()).first->second;
}

void BodyFactory::addPatch(const BilinearPatchDesc& p, uint64_t primitiveId, std::vector<BodyPtr>& out,
                           const float* primvarCorners) {
    const MarkStillInWorld still(out, p.objectToWorld, p.P.size());
    const Material* mat = material(p.attributes, p.objectToWorld, false, &p.primvars, primitiveId);
    std::array<Color, 4> cs;
    for (int c = 0; c < 4; ++c) cs[size_t(c)] = p.hasCs ? p.Cs[size_t(c)] : mat->Cs;

    MotionTransform objectToCamera = p.objectToWorld.then(worldToCamera_);
    std::vector<double> keys = keysOf(objectToCamera);
    if (p.P.size() > 1) keys = unionTimes(keys, p.times);
    const Window w = windowOf(p.life);
    if (w.empty()) return;
    std::vector<double> ts = segmentTimes(keys, w.a, w.b);
    std::vector<TrilinearBody::Corners> corners(ts.size());
    bool finite = true, fits = true;
    double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin, rasterError = 0;
    // The exact precision measure only where the cheap bound cannot rule the warning out.
    const bool precision = camera_ && !(precisionBound(*cameraOf(p.life), p.objectToWorld, worldToCamera_, p) <= kMaxPrecisionPixels);
    for (size_t i = 0; i < ts.size(); ++i) {
        Matrix4 m = objectToCamera.at(ts[i]);
        std::array<Vec3d, 4> obj = cornersAt(p, ts[i]);
        const double worldScale = precision ? worldMagnitude(p.objectToWorld.at(ts[i]), worldToCamera_.at(ts[i]), obj) : 0;
        for (int c = 0; c < 4; ++c) {
            Vec3d v = m.point(obj[size_t(c)]);
            finite = finite && isFinite(v);
            fits = fits && fitsCameraSpace(v);
            if (finite && fits) corners[i][size_t(c)] = Vec3f(v);
            zmin = std::min(zmin, v.z), zmax = std::max(zmax, v.z);
            if (precision) rasterError = std::max(rasterError, precisionInPixels(*cameraOf(p.life), worldScale, v));
        }
    }
    if (!finite) {
        log_.warnOnce("nonfinite", p.loc, kNonFiniteWarning);
        return;
    }
    if (!fits) {
        log_.warnOnce("toolarge", p.loc, kTooLargeWarning);
        return;
    }
    if (camera_ && zmin > 0 && zmax < camera_->nearClip())
        log_.warnOnce("nearclip", p.loc,
                      "primitive lies wholly between the camera and the near clipping plane (Clipping near = " +
                          formatShort(camera_->nearClip()) +
                          "): it cannot be seen (lower the near plane with Clipping, or scale the scene up)");
    if (rasterError > kMaxPrecisionPixels)
        log_.warnOnce("precision", p.loc,
                      "primitive lies so far from the world's origin that double precision moves it by up to " +
                          formatShort(rasterError) +
                          " pixels on its way to camera space (translate the scene and the camera nearer the origin)");
    const SourceLoc* src = source(p.loc);
    auto add = [&](double t0, double t1, const TrilinearBody::Corners& c0, const TrilinearBody::Corners& c1) {
        auto body = std::make_unique<TrilinearBody>(segmentSpan(t0, t1, ts, w.openEnd), c0, c1, cs, mat);
        body->setSource(src);
        body->setPrimitiveId(primitiveId);
        body->primvarCorners = primvarCorners;
        out.push_back(std::move(body));
        ++bodiesMade_;
    };
    if (ts.size() == 1) {  // a single instant (one frame, shutter open == close)
        add(ts[0], ts[0], corners[0], corners[0]);
        return;
    }
    bool moves = false;
    for (size_t i = 1; i < ts.size() && !moves; ++i) moves = corners[i] != corners[0];
    if (moves && ts.size() > 2) {
        // Several keys: one body for all of them; the split loop cuts it in time where needed.
        auto body = std::make_unique<KeyedPatchBody>(std::move(ts), std::move(corners), cs, mat, w.openEnd);
        // A render of part of a long shot keeps only the keys the chunks of its frames reach
        // (a leaf keyed every few frames of a long shot, one frame rendered).
        if (camera_ && std::isfinite(wantedStart_) && std::isfinite(wantedEnd_)) {
            // A chunk (geom/root_chunks.h) holding a frame's exposure lies within a chunk's length of it.
            const double chunk = rootChunkFrames(*body, *cameraOf(p.life));
            std::unique_ptr<KeyedPatchBody> part = body->keysOver(wantedStart_ - chunk, wantedEnd_ + chunk, *cameraOf(p.life));
            if (part) body = std::move(part);
        }
        body->setSource(src);
        body->setPrimitiveId(primitiveId);
        body->primvarCorners = primvarCorners;
        out.push_back(std::move(body));
        ++bodiesMade_;
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
    return cameraBound(b, objectToWorld, windowStart_, windowEnd_);
}

Bounds3f BodyFactory::cameraBound(const Bounds3d& b, const MotionTransform& objectToWorld, double ta, double tb) const {
    MotionTransform objectToCamera = objectToWorld.then(worldToCamera_);
    Bounds3d r;
    for (double t : segmentTimes(keysOf(objectToCamera), ta, tb)) {
        Matrix4 m = objectToCamera.at(t);
        for (int i = 0; i < 8; ++i)
            r.extend(m.point({(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z}));
    }
    // In float; beyond its range (where the conversion would be undefined) the bound is infinite.
    auto toFloat = [](Vec3d v) {
        Vec3f f;
        for (int a = 0; a < 3; ++a)
            f[a] = float(std::fabs(v[a]) <= kMaxCameraCoordinate ? v[a] : std::copysign(HUGE_VAL, v[a]));
        return f;
    };
    return Bounds3f(toFloat(r.lo), toFloat(r.hi));
}

// ---- Curved and polygon-mesh primitives ------------------------------------------------------------
bool BodyFactory::keyedPoints(const PrimitiveDesc& p, const std::vector<std::vector<Vec3d>>& P,
                              std::vector<double>* ts, std::vector<std::vector<Vec3d>>* points) {
    const Window w = windowOf(p.life);
    if (w.empty()) return false;
    const MotionTransform objectToCamera = p.objectToWorld.then(worldToCamera_);
    std::vector<double> keys = keysOf(objectToCamera);
    if (P.size() > 1) keys = unionTimes(keys, p.times);
    *ts = segmentTimes(keys, w.a, w.b);
    points->resize(ts->size());
    for (size_t i = 0; i < ts->size(); ++i) {
        const Matrix4 m = objectToCamera.at((*ts)[i]);
        std::vector<Vec3d>& pts = (*points)[i];
        pts = pointsAt(p.times, P, (*ts)[i]);
        for (Vec3d& q : pts) {
            q = m.point(q);
            if (!isFinite(q)) {
                log_.warnOnce("nonfinite", p.loc, kNonFiniteWarning);
                return false;
            }
            if (!fitsCameraSpace(q)) {
                log_.warnOnce("toolarge", p.loc, kTooLargeWarning);
                return false;
            }
        }
    }
    return true;
}

const float* BodyFactory::meshPrimvars(const ParamList& primvars, size_t faces,
                                       const std::function<std::vector<std::array<Color, 4>>(const ColorPrimvar&)>& cornersOf,
                                       Keep* keep, size_t* width,
                                       const std::function<std::vector<BezierPatch>(const std::vector<Vec3d>&)>& bezierOf) {
    auto controls = [&](const Param& v) -> size_t { return bezierOf && v.cls == ParamClass::Vertex ? 16 : 4; };
    *width = 0;
    for (const Param& v : primvars.params)
        if (v.cls != ParamClass::Constant) *width += controls(v) * size_t(v.componentsPerItem());
    if (*width == 0) return nullptr;
    auto values = std::make_shared<std::vector<float>>(*width * faces);
    size_t offset = 0;  // of the variable in a face's block
    for (const Param& v : primvars.params) {
        if (v.cls == ParamClass::Constant) continue;
        const size_t w = size_t(v.componentsPerItem()), items = v.nums.size() / w;
        if (controls(v) == 16) {
            for (size_t g = 0; g < w; g += 3) {  // three components a pass, as points
                std::vector<Vec3d> points(items);
                for (size_t i = 0; i < items; ++i)
                    points[i] = Vec3d(v.nums[i * w + g], g + 1 < w ? v.nums[i * w + g + 1] : 0.0,
                                      g + 2 < w ? v.nums[i * w + g + 2] : 0.0);
                const std::vector<BezierPatch> patches = bezierOf(points);
                for (size_t f = 0; f < faces && f < patches.size(); ++f)
                    for (size_t c = 0; c < 16; ++c)
                        for (size_t k = g; k < std::min(w, g + 3); ++k)
                            (*values)[f * *width + offset + c * w + k] = patches[f][c][int(k - g)];
            }
            offset += 16 * w;
            continue;
        }
        for (size_t g = 0; g < w; g += 3) {  // three components a pass, as colours
            ColorPrimvar cp;
            cp.cls = v.cls;
            for (size_t i = 0; i < items; ++i)
                cp.values.push_back(Color(float(v.nums[i * w + g]), g + 1 < w ? float(v.nums[i * w + g + 1]) : 0.0f,
                                          g + 2 < w ? float(v.nums[i * w + g + 2]) : 0.0f));
            const std::vector<std::array<Color, 4>> corners = cornersOf(cp);
            for (size_t f = 0; f < faces && f < corners.size(); ++f)
                for (size_t c = 0; c < 4; ++c)
                    for (size_t k = g; k < std::min(w, g + 3); ++k)
                        (*values)[f * *width + offset + c * w + k] = corners[f][c][int(k - g)];
        }
        offset += 4 * w;
    }
    const float* block = values->data();
    if (keep) {
        keep->push_back(std::shared_ptr<const void>(values));
    } else {
        std::lock_guard<std::mutex> lock(mutex_);
        primvarBlocks_.push_back(std::move(*values));
        block = primvarBlocks_.back().data();
    }
    return block;
}

void BodyFactory::addPolygonFaces(const PolygonMeshDesc& p, const PolygonFaces& faces, uint64_t primitiveId,
                                  std::vector<BodyPtr>& out) {
    BilinearPatchDesc face;
    face.times = p.times;
    face.objectToWorld = p.objectToWorld;
    face.attributes = p.attributes;
    face.loc = p.loc;
    face.life = p.life;
    face.primvars = p.primvars;  // the faces share one material (by primitive id)
    face.P.resize(p.P.size());
    // Primitive variables that vary from face to face: each face's corner values, as Cs is read.
    size_t width = 0;
    const float* block = meshPrimvars(p.primvars, faces.faces.size(),
                                      [&](const ColorPrimvar& v) { return faceCorners(faces, v); }, nullptr, &width);
    for (size_t f = 0; f < faces.faces.size(); ++f) {
        for (size_t k = 0; k < p.P.size(); ++k)
            for (size_t c = 0; c < 4; ++c) face.P[k][c] = p.P[k][size_t(faces.faces[f][c])];
        face.hasCs = !faces.faceCs.empty();
        if (face.hasCs) face.Cs = faces.faceCs[f];
        addPatch(face, primitiveId, out, block ? block + f * width : nullptr);
    }
}

void BodyFactory::addProcedural(const ProceduralDesc& p, uint64_t primitiveId, int depth, std::vector<BodyPtr>& out) {
    addProcedural(p, makeProceduralGenerator(p), primitiveId, depth, out);
}

void BodyFactory::addProcedural(const ProceduralDesc& p, std::shared_ptr<const ProceduralGenerator> generator,
                                uint64_t primitiveId, int depth, std::vector<BodyPtr>& out) {
    if (depth > kMaxProceduralDepth) {
        log_.warnOnce("procedural-depth", p.loc,
                      "procedurals nested more than " + std::to_string(kMaxProceduralDepth) +
                          " deep (does a procedural produce itself?): the deeper ones are dropped");
        return;
    }
    const Window w = windowOf(p.life);
    if (w.empty()) return;
    Bounds3f b = cameraBound(p.bound, p.objectToWorld, w.a, w.b);
    if (!isFinite(b.lo) || !isFinite(b.hi)) {
        log_.warnOnce("procedural-nonfinite", p.loc, "procedural bound is not finite in camera space: skipped");
        return;
    }
    // Moving in camera space over the shot (the camera or its transform moves): its bound and level
    // of detail are taken frame by frame.
    const std::vector<double> keys = keysOf(p.objectToWorld.then(worldToCamera_));
    auto any = [&](auto pred) { return std::any_of(keys.begin(), keys.end(), pred); };
    const bool moving = any([&](double t) { return t > w.a && t < w.b; }) ||
                        (any([&](double t) { return t <= w.a; }) && any([&](double t) { return t >= w.b; }));
    auto body = std::make_unique<ProceduralBody>(p, std::move(generator), b, TimeSpan{w.a, w.b, w.openEnd}, depth,
                                                 moving, this);
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

template <class Desc, class Add>
void BodyFactory::addWithDetail(const Desc& p, Add add) {
    const LevelOfDetail* lod = p.attributes ? p.attributes->detail.get() : nullptr;
    if (!lod || !detailFrames_.set || !camera_) {
        add(p);
        return;
    }
    const DetailFrames& f = detailFrames_;
    for (const DetailRun& run : detailRuns(*lod, f.first, f.last, f.shutter, worldToCamera_, *camera_, f.relative, cameras_)) {
        Desc q = p;
        q.life = runLifetime(p.life, run.first, run.last, f.shutter);
        if (!run.share.all()) q.attributes = dissolving(p.attributes, run.share.lo, run.share.hi);
        add(q);
    }
}

void BodyFactory::addPrimitives(const Scene& scene, const std::vector<GeneratedProcedural>& generated, int depth,
                                const std::function<uint64_t()>& nextId, std::vector<BodyPtr>& out, Keep* keep) {
    const size_t first = out.size();  // the bodies made here start there (bodyBytes_)
    // Polygons first: each is a patch, faces, or nothing (no area, warned).
    struct Polygon {
        std::optional<BilinearPatchDesc> patch;
        PolygonFaces faces;
    };
    const std::vector<PolygonMeshDesc>& meshes = scene.polygonMeshes;
    std::vector<Polygon> polygons(meshes.size());
    for (size_t i = 0; i < meshes.size(); ++i) {
        polygons[i].patch = polygonAsPatch(meshes[i]);
        if (!polygons[i].patch) polygons[i].faces = cutPolygons(meshes[i], log_);
    }
    size_t next = 0;  // the first polygon not yet placed among the patches
    // Each primitive takes one id, whatever copies its level of detail makes (they never meet in a frame).
    auto patch = [&](const BilinearPatchDesc& p) {
        const uint64_t id = nextId();
        addWithDetail(p, [&](const BilinearPatchDesc& q) { addPatch(q, id, out); });
    };
    auto polygonPatchesUpTo = [&](size_t patches) {
        for (; next < meshes.size() && meshes[next].patchesBefore <= patches; ++next)
            if (polygons[next].patch) patch(*polygons[next].patch);
    };
    for (size_t i = 0; i < scene.patches.size(); ++i) {
        polygonPatchesUpTo(i);
        patch(scene.patches[i]);
    }
    polygonPatchesUpTo(scene.patches.size());
    auto each = [&](const auto& prims, const auto& addOne) {
        for (const auto& p : prims) {
            const uint64_t id = nextId();
            addWithDetail(p, [&](const auto& q) { addOne(q, id); });
        }
    };
    each(scene.procedurals, [&](const ProceduralDesc& p, uint64_t id) { addProcedural(p, id, depth, out); });
    for (const GeneratedProcedural& g : generated) {
        const uint64_t id = nextId();
        addWithDetail(g.desc, [&](const ProceduralDesc& q) { addProcedural(q, g.generator, id, depth, out); });
    }
    each(scene.patchMeshes, [&](const PatchMeshDesc& p, uint64_t id) { addPatchMesh(p, id, out, keep); });
    each(scene.subdivisionMeshes, [&](const SubdivisionMeshDesc& p, uint64_t id) { addSubdivisionMesh(p, id, out, keep); });
    each(scene.quadrics, [&](const QuadricDesc& q, uint64_t id) { addQuadric(q, id, out, keep); });
    for (size_t i = 0; i < meshes.size(); ++i)
        if (!polygons[i].patch && !polygons[i].faces.faces.empty()) {
            const uint64_t id = nextId();
            addWithDetail(meshes[i], [&](const PolygonMeshDesc& q) { addPolygonFaces(q, polygons[i].faces, id, out); });
        }
    each(scene.curves, [&](const CurvesDesc& c, uint64_t id) { addCurves(c, id, out, keep); });
    each(scene.points, [&](const PointsDesc& p, uint64_t id) { addPoints(p, id, out, keep); });
    each(scene.nuPatches, [&](const NuPatchDesc& p, uint64_t id) { addNuPatch(p, id, out, keep); });
    uint64_t bytes = 0;
    for (size_t i = first; i < out.size(); ++i) bytes += out[i]->memoryBytes();
    bodyBytes_ += bytes;
}

uint64_t childPrimitiveId(uint64_t parent, uint64_t index) {
    const uint64_t id = hashCombine(mix64(parent), index + 1);
    return id == 0 || id == UINT64_MAX ? 1 : id;
}

void BodyFactory::addChildren(const ProceduralOutput& output, uint64_t parentId, int depth, std::vector<BodyPtr>& out,
                              Keep* keep, bool count) {
    const uint64_t budget = bodyBudget_.load();
    if (budget && bodyBytes_.load() > budget)
        throw InputError("expanding the scene's procedurals for ray tracing (shadows, or --algorithm raytrace) needs "
                         "more than the memory budget of " + std::to_string(renderBudget_.load() >> 20) + " MiB (" +
                         std::to_string(bodiesMade_.load()) + " bodies so far, " + std::to_string(bodyBytes_.load() >> 20) +
                         " MiB, with " + std::to_string(budget >> 20) +
                         " MiB left for them): raise --max-memory, or turn shadows off");
    uint64_t index = 0;
    const size_t first = out.size();
    addPrimitives(output.scene, output.procedurals, depth, [&] { return childPrimitiveId(parentId, index++); }, out,
                  keep);
    if (count) return;
    // Made again after a release: take back what addPrimitives counted (the same kinds it counts).
    uint64_t bodies = 0, procedurals = 0, bytes = 0;
    for (size_t i = first; i < out.size(); ++i) {
        const Body* b = out[i].get();
        bytes += b->memoryBytes();
        if (b->expands()) ++procedurals;
        else if (dynamic_cast<const TrilinearBody*>(b) || dynamic_cast<const KeyedPatchBody*>(b) ||
                 dynamic_cast<const CurvedBody*>(b))
            ++bodies;
    }
    bodiesMade_ -= bodies;
    proceduralsMade_ -= procedurals;
    bodyBytes_ -= bytes;
    if (procedurals) {
        std::lock_guard<std::mutex> lock(mutex_);
        proceduralsByDepth_[size_t(depth)] -= procedurals;
    }
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

}  // namespace streyes
