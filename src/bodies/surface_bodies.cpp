// The body factory's curved surfaces (body_factory.h): patch meshes, subdivision meshes
// (OpenSubdiv), quadrics and NURBS, each a SurfaceMesh kept by the factory and a CurvedBody per face.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "bodies/body_factory.h"
#include "bodies/motion_segments.h"
#include "geom/curved_body.h"
#include "geom/nurbs_mesh.h"
#include "geom/patch_mesh.h"
#include "geom/quadric.h"
#include "geom/subdivision.h"

namespace streyes {

namespace {

// The pixels a moving mesh moves in one exposure, largest over each face's corners and centre
// between its two keys: its whole lattice is diced at one rate (GeometricApproximation
// "motionfactor"), so neighbouring faces meet. 0 (no coarsening) for a still mesh, a closed
// shutter, or a mesh reaching the eye plane, which cannot be measured.
double meshBlur(const SurfaceMesh& mesh, double exposure) {
    const double span = mesh.keys().t1 - mesh.keys().t0;
    if (!mesh.moving() || !(exposure > 0) || !(span > 0)) return 0;
    const Camera& camera = mesh.camera();
    constexpr double kPoints[5][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0.5}};
    double most = 0;
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (const auto& p : kPoints) {
            Vec3f a, b, n;
            mesh.evaluatePoint(f, p[0], p[1], 0, &a, &n);
            mesh.evaluatePoint(f, p[0], p[1], 1, &b, &n);
            if (!(a.z >= camera.eyePlane() && b.z >= camera.eyePlane())) return 0;
            const Vec3f ra = camera.toRaster(a), rb = camera.toRaster(b);
            most = std::max(most, std::hypot(double(rb.x - ra.x), double(rb.y - ra.y)));
        }
    return most * exposure / span;
}

}  // namespace

void BodyFactory::addSurface(std::unique_ptr<SurfaceMesh> mesh, const SourceLoc* src, uint64_t primitiveId,
                             std::vector<BodyPtr>& out, Keep* keep, const float* primvarBlock, size_t primvarWidth) {
    mesh->setSource(src);
    if (const Material* m = mesh->material()) {
        const double blur = m->motionFactor > 0 ? meshBlur(*mesh, exposure_) : 0.0;  // measured only when asked
        mesh->setShadingRate(motionDicingRate(m->shadingRate, m->motionFactor, blur));
    }
    for (int f = 0; f < mesh->faceCount(); ++f) {
        auto body = std::make_unique<CurvedBody>(mesh.get(), f);
        body->setPrimitiveId(primitiveId);
        if (primvarBlock) body->primvarCorners = primvarBlock + size_t(f) * primvarWidth;
        out.push_back(std::move(body));
        ++bodiesMade_;
    }
    if (keep) {
        keep->push_back(std::shared_ptr<const SurfaceMesh>(std::move(mesh)));
        return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    surfaces_.push_back(std::move(mesh));
}

void BodyFactory::addPatchMesh(const PatchMeshDesc& p, uint64_t primitiveId, std::vector<BodyPtr>& out, Keep* keep) {
    const MarkStillInWorld still(out, p.objectToWorld, p.P.size());
    std::vector<double> ts;
    std::vector<std::vector<Vec3d>> points;
    if (!keyedPoints(p, p.P, &ts, &points)) return;
    // A bicubic mesh's vertex "Cs" follows its basis as P does: carried as a primitive variable
    // (its 16 Bezier controls a patch), which the shading stage binds to Cs. The corner colours
    // below stay what the body holds (built-in shading of a grid without a shader run).
    const ParamList* primvars = &p.primvars;
    ParamList withCs;
    if (p.bicubic && p.Cs.given() && p.Cs.cls == ParamClass::Vertex) {
        withCs = p.primvars;
        Param cs;
        cs.name = "Cs";
        cs.type = ParamType::Color;
        cs.cls = ParamClass::Vertex;
        cs.loc = p.loc;
        for (const Color& c : p.Cs.values) cs.nums.insert(cs.nums.end(), {double(c.x), double(c.y), double(c.z)});
        withCs.params.push_back(std::move(cs));
        primvars = &withCs;
    }
    const Material* mat = material(p.attributes, p.objectToWorld, false, primvars, primitiveId, p.bicubic);
    const PatchMeshShape shape(p);
    const std::vector<std::array<Color, 4>> colors = shape.colors(p.Cs, mat->Cs);
    size_t width = 0;
    std::function<std::vector<BezierPatch>(const std::vector<Vec3d>&)> bezierOf;
    if (p.bicubic) bezierOf = [&](const std::vector<Vec3d>& values) { return shape.patches(values); };
    const float* block = meshPrimvars(*primvars, colors.size(), [&](const ColorPrimvar& v) { return shape.colors(v, {0, 0, 0}); },
                                      keep, &width, bezierOf);
    const SourceLoc* src = source(p.loc);
    const bool lastOpen = windowOf(p.life).openEnd;
    forEachSegment(ts, points, [&](double t0, double t1, size_t i, size_t j) {
        std::vector<BezierPatch> k1;
        if (j != i) k1 = shape.patches(points[j]);
        addSurface(std::make_unique<BezierMesh>(shape.topology(), segmentSpan(t0, t1, ts, lastOpen), mat, cameraOf(p.life),
                                                shape.patches(points[i]), std::move(k1), colors),
                   src, primitiveId, out, keep, block, width);
    }, wantedStart_, wantedEnd_);
}

// The topology once, the limit surface per key, a SubdivisionMesh per segment.
std::shared_ptr<const SubdivisionShape> BodyFactory::subdivisionShape(const SubdivisionMeshDesc& p) {
    // The key: every input of the shape, as bytes.
    std::string key;
    auto add = [&key](const auto& v) {
        const size_t n = v.size();
        key.append(reinterpret_cast<const char*>(&n), sizeof n);
        key.append(reinterpret_cast<const char*>(v.data()), n * sizeof(v[0]));
    };
    const int header[2] = {p.vertexCount, p.interpolateBoundary};
    key.append(reinterpret_cast<const char*>(header), sizeof header);
    add(p.faceSizes);
    add(p.faceVertices);
    add(p.creaseEdges);
    add(p.creaseSharpness);
    add(p.corners);
    add(p.cornerSharpness);
    add(p.holes);
    bool faceVarying = p.Cs.given() && p.Cs.cls == ParamClass::FaceVarying;  // the shape then has a channel
    for (const Param& v : p.primvars.params) faceVarying = faceVarying || v.cls == ParamClass::FaceVarying;
    key.push_back(faceVarying ? 'f' : '-');
    {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = shapes_.find(key);
        if (it != shapes_.end()) return it->second;
    }
    // Built outside the lock (building refines in parallel); a mesh built twice at once keeps the first.
    auto shape = std::make_shared<const SubdivisionShape>(p);
    std::lock_guard<std::mutex> lock(mutex_);
    return shapes_.emplace(std::move(key), std::move(shape)).first->second;
}

void BodyFactory::addSubdivisionMesh(const SubdivisionMeshDesc& p, uint64_t primitiveId, std::vector<BodyPtr>& out,
                                     Keep* keep) {
    const MarkStillInWorld still(out, p.objectToWorld, p.P.size());
    std::vector<double> ts;
    std::vector<std::vector<Vec3d>> points;
    if (!keyedPoints(p, p.P, &ts, &points)) return;
    const std::shared_ptr<const SubdivisionShape> shape = subdivisionShape(p);
    if (shape->faceCount() == 0) {
        log_.warnOnce("subdiv-nolimit", p.loc,
                      "SubdivisionMesh has no face with a limit surface (is it all boundary? see "
                      "\"interpolateboundary\"): skipped");
        return;
    }
    const Material* mat = material(p.attributes, p.objectToWorld, false, &p.primvars, primitiveId);
    const std::vector<std::array<Color, 4>> colors = shape->colors(p.Cs, mat->Cs);
    size_t width = 0;
    const float* block = meshPrimvars(p.primvars, colors.size(), [&](const ColorPrimvar& v) { return shape->colors(v, {0, 0, 0}); },
                                      keep, &width);
    const SourceLoc* src = source(p.loc);
    std::vector<std::shared_ptr<const SubdivisionKey>> keys(ts.size());
    auto keyAt = [&](size_t i) {
        if (!keys[i]) keys[i] = shape->key(points[i]);
        return keys[i];
    };
    const bool lastOpen = windowOf(p.life).openEnd;
    forEachSegment(ts, points, [&](double t0, double t1, size_t i, size_t j) {
        addSurface(std::make_unique<SubdivisionMesh>(shape, keyAt(i), keyAt(j), segmentSpan(t0, t1, ts, lastOpen), mat,
                                                     cameraOf(p.life), colors),
                   src, primitiveId, out, keep, block, width);
    }, wantedStart_, wantedEnd_);
}

// A QuadricMesh per segment: the quadric's arguments and transform at both ends.
void BodyFactory::addQuadric(const QuadricDesc& q, uint64_t primitiveId, std::vector<BodyPtr>& out, Keep* keep) {
    const MarkStillInWorld still(out, q.objectToWorld, q.params.size());
    const MotionTransform objectToCamera = q.objectToWorld.then(worldToCamera_);
    std::vector<double> keyTimes = keysOf(objectToCamera);
    if (q.params.size() > 1) keyTimes = unionTimes(keyTimes, q.times);
    const Window w = windowOf(q.life);
    if (w.empty()) return;
    const std::vector<double> ts = segmentTimes(keyTimes, w.a, w.b);
    struct Key {
        QuadricMesh::Params params;
        Matrix4 toCamera;
        bool operator==(const Key& o) const { return params == o.params && toCamera == o.toCamera; }
    };
    std::vector<Key> keys(ts.size());
    for (size_t i = 0; i < ts.size(); ++i) {
        size_t k;
        double s;
        keyInterval(q.times, q.params.size(), ts[i], &k, &s);
        for (size_t a = 0; a < 7; ++a)
            keys[i].params[a] = s == 0 ? q.params[k][a] : (1 - s) * q.params[k][a] + s * q.params[k + 1][a];
        keys[i].toCamera = objectToCamera.at(ts[i]);
        if (!keys[i].toCamera.isFinite()) {
            log_.warnOnce("nonfinite", q.loc, kNonFiniteWarning);
            return;
        }
    }
    const Material* mat = material(q.attributes, q.objectToWorld, false, &q.primvars, primitiveId);
    std::array<Color, 4> colors;
    colors.fill(mat->Cs);
    if (q.Cs.given())
        for (size_t c = 0; c < 4; ++c) colors[c] = q.Cs.values[q.Cs.values.size() == 4 ? c : 0];
    const SourceLoc* src = source(q.loc);
    forEachSegment(ts, keys, [&](double t0, double t1, size_t i, size_t j) {
        const QuadricMesh::Params params[2] = {keys[i].params, keys[j].params};
        const Matrix4 toCamera[2] = {keys[i].toCamera, keys[j].toCamera};
        addSurface(std::make_unique<QuadricMesh>(q.kind, params, toCamera, segmentSpan(t0, t1, ts, w.openEnd), mat, cameraOf(q.life),
                                                 colors),
                   src, primitiveId, out, keep);
    }, wantedStart_, wantedEnd_);
}

// A NurbsMesh per segment over the patch's shape (knots, weights, trim), shared by the segments.
void BodyFactory::addNuPatch(const NuPatchDesc& p, uint64_t primitiveId, std::vector<BodyPtr>& out, Keep* keep) {
    const MarkStillInWorld still(out, p.objectToWorld, p.P.size());
    std::vector<double> ts;
    std::vector<std::vector<Vec3d>> points;
    if (!keyedPoints(p, p.P, &ts, &points)) return;
    auto shape = std::make_shared<NurbsShape>();
    shape->nu = p.nu, shape->uorder = p.uorder, shape->nv = p.nv, shape->vorder = p.vorder;
    shape->uknot = p.uknot, shape->vknot = p.vknot, shape->w = p.w;
    shape->umin = p.umin, shape->umax = p.umax, shape->vmin = p.vmin, shape->vmax = p.vmax;
    if (p.trim) shape->trim = std::make_shared<const NurbsTrim>(*p.trim);
    const Material* mat = material(p.attributes, p.objectToWorld, false, &p.primvars, primitiveId);
    // Varying Cs is bilinear between the knots (a lattice over the patch); constant Cs fills the
    // corners; uniform (per span) and vertex (per control point) colour over several spans are
    // taken from the first span and from the corner points, with a warning.
    std::array<Color, 4> colors;
    colors.fill(mat->Cs);
    std::vector<Color> varying;
    if (p.Cs.given()) {
        const std::vector<Color>& c = p.Cs.values;
        const size_t n = c.size();
        const bool vertex = p.Cs.cls == ParamClass::Vertex;
        const size_t cols = vertex ? size_t(p.nu) : size_t(p.uSpans() + 1);
        if (n == 1 || p.Cs.cls == ParamClass::Uniform || p.Cs.cls == ParamClass::Constant)
            colors.fill(c[0]);
        else
            colors = {c[0], c[cols - 1], c[n - cols], c[n - 1]};
        if (!vertex && (p.Cs.cls == ParamClass::Varying || p.Cs.cls == ParamClass::FaceVarying) && n > 4) varying = c;
        if (n > 1 && (p.Cs.cls == ParamClass::Uniform || (vertex && n > 4)))
            log_.warnOnce("nupatch-cs", p.loc,
                          "NuPatch \"Cs\" per span (uniform) or per control point (vertex) is taken from the first "
                          "span or the corner points");
    }
    const SourceLoc* src = source(p.loc);
    const bool lastOpen = windowOf(p.life).openEnd;
    std::shared_ptr<const NurbsShape> shared = std::move(shape);
    const size_t first = out.size();
    forEachSegment(ts, points, [&](double t0, double t1, size_t i, size_t j) {
        addSurface(std::make_unique<NurbsMesh>(shared, points[i], j != i ? points[j] : std::vector<Vec3d>{},
                                               segmentSpan(t0, t1, ts, lastOpen), mat, cameraOf(p.life), colors, varying),
                   src, primitiveId, out, keep);
    }, wantedStart_, wantedEnd_);
    // Shaders see a NuPatch's own parameters, [umin, umax] x [vmin, vmax] (RenderMan's rule for NURBS).
    for (size_t b = first; b < out.size(); ++b)
        out[b]->uv = {float(p.umin), float(p.umax), float(p.vmin), float(p.vmax)};
}

// Each face (a triangle or a convex quad) as the bilinear patch it is.
}  // namespace streyes
