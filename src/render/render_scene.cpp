#include "streyes/render_scene.h"

#include <algorithm>
#include <map>

#include "streyes/curved_body.h"
#include "streyes/patch_mesh.h"
#include "streyes/quadric.h"
#include "streyes/subdivision.h"

namespace streyes {

namespace {

// ---- Motion segments, for every kind of primitive --------------------------------------------------
// Where time t falls among a primitive's keys: between key i and i + 1 at fraction s (held
// before the first key and after the last, where s = 0).
void keyInterval(const std::vector<double>& times, size_t keys, double t, size_t* i, double* s) {
    *s = 0;
    if (keys == 1 || t <= times.front()) {
        *i = 0;
    } else if (t >= times.back()) {
        *i = keys - 1;
    } else {
        *i = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
        *s = (t - times[*i]) / (times[*i + 1] - times[*i]);
    }
}

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

// Key times of everything that moves the primitive in camera space, inside (a, b), plus a and b.
std::vector<double> segmentTimes(const std::vector<double>& ownTimes, bool ownMoves,
                                 const MotionTransform& objectToCamera, double a, double b) {
    std::vector<double> keys = objectToCamera.isStatic() ? std::vector<double>{} : objectToCamera.times();
    if (ownMoves) keys = unionTimes(keys, ownTimes);
    std::vector<double> ts{a};
    for (double t : keys)
        if (t > a && t < b) ts.push_back(t);
    if (b > a) ts.push_back(b);
    return ts;
}

// Calls add(t0, t1, i, j) for each segment between consecutive times, with i and j the indices
// of its keys in `keys`; a run of segments over which the keys do not change is one still
// segment; a single time (one frame, no shutter) is a segment of length zero.
template <typename Key, typename Add>
void forEachSegment(const std::vector<double>& ts, const std::vector<Key>& keys, Add add) {
    if (ts.size() == 1) {
        add(ts[0], ts[0], size_t(0), size_t(0));
        return;
    }
    for (size_t i = 0; i + 1 < ts.size();) {
        size_t j = i + 1;
        if (keys[j] == keys[i])
            while (j + 1 < ts.size() && keys[j + 1] == keys[i]) ++j;
        add(ts[i], ts[j], i, j);
        i = j;
    }
}

// Camera-space points of a primitive at each time; false (with a warning) when any is not finite.
bool cameraPoints(const std::vector<double>& ts, const PrimitiveDesc& p, const std::vector<std::vector<Vec3d>>& P,
                  const MotionTransform& objectToCamera, std::vector<std::vector<Vec3d>>* out, Log& log) {
    out->resize(ts.size());
    for (size_t i = 0; i < ts.size(); ++i) {
        const Matrix4 m = objectToCamera.at(ts[i]);
        std::vector<Vec3d>& pts = (*out)[i];
        pts = pointsAt(p.times, P, ts[i]);
        for (Vec3d& q : pts) {
            q = m.point(q);
            if (!isFinite(Vec3f(q))) {
                log.warn(p.loc, "primitive has non-finite coordinates in camera space: skipped");
                return false;
            }
        }
    }
    return true;
}

// One TrilinearBody per segment of a bilinear patch whose camera-space corners are given per time.
void addBilinearBodies(const std::vector<double>& ts, const std::vector<TrilinearBody::Corners>& corners,
                       const std::array<Color, 4>& cs, const Material* material, const SourceLoc* source,
                       RenderScene& rs) {
    forEachSegment(ts, corners, [&](double t0, double t1, size_t i, size_t j) {
        auto body = std::make_unique<TrilinearBody>(TimeSpan{t0, t1}, corners[i], corners[j], cs, material);
        body->setSource(source);
        rs.roots.push_back(std::move(body));
    });
}

// The bodies of a segment's surface mesh: one per face, the mesh kept alive by the scene.
void addSurface(std::unique_ptr<SurfaceMesh> mesh, const SourceLoc* source, RenderScene& rs) {
    mesh->setSource(source);
    for (int f = 0; f < mesh->faceCount(); ++f) rs.roots.push_back(std::make_unique<CurvedBody>(mesh.get(), f));
    rs.surfaces.push_back(std::move(mesh));
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
    const double ws = rs->windowStart, we = rs->windowEnd;

    static const Attributes kDefault;
    std::map<const Attributes*, const Material*> materialOf;
    auto attributesOf = [&](const AttributesPtr& a) -> const Attributes& { return a ? *a : kDefault; };
    auto materialFor = [&](const AttributesPtr& a) {
        const Attributes* attr = &attributesOf(a);
        auto it = materialOf.find(attr);
        if (it == materialOf.end()) {
            rs->materials.push_back(makeMaterial(*attr));
            it = materialOf.emplace(attr, &rs->materials.back()).first;
        }
        return it->second;
    };
    auto sourceFor = [&](const SourceLoc& loc) {
        rs->sources.push_back(loc);
        return &rs->sources.back();
    };
    // What every primitive given by points needs: its material, the times of its motion
    // segments and its camera-space points at each (false, with a warning, when not finite).
    struct Keyed {
        const Material* material;
        std::vector<double> ts;
        std::vector<std::vector<Vec3d>> points;
    };
    auto keyed = [&](const PrimitiveDesc& p, const std::vector<std::vector<Vec3d>>& P, Keyed* k) {
        k->material = materialFor(p.attributes);
        const MotionTransform objectToCamera = p.objectToWorld.then(cam.worldToCamera);
        k->ts = segmentTimes(p.times, P.size() > 1, objectToCamera, ws, we);
        return cameraPoints(k->ts, p, P, objectToCamera, &k->points, log);
    };

    // Bilinear patches and small polygons: a TrilinearBody per segment.
    for (const BilinearPatchDesc& p : scene.patches) {
        std::array<Color, 4> cs;
        for (int c = 0; c < 4; ++c) cs[size_t(c)] = p.hasCs ? p.Cs[size_t(c)] : attributesOf(p.attributes).color;
        std::vector<std::vector<Vec3d>> P;
        for (const auto& key : p.P) P.emplace_back(key.begin(), key.end());
        Keyed k;
        if (!keyed(PrimitiveDesc{p.times, p.objectToWorld, p.attributes, p.loc}, P, &k)) continue;
        std::vector<TrilinearBody::Corners> corners(k.ts.size());
        for (size_t i = 0; i < k.ts.size(); ++i)
            for (size_t c = 0; c < 4; ++c) corners[i][c] = Vec3f(k.points[i][c]);
        addBilinearBodies(k.ts, corners, cs, k.material, sourceFor(p.loc), *rs);
    }

    // Polygon meshes: each face (a triangle or a convex quad) like a bilinear patch.
    for (const PolygonMeshDesc& p : scene.polygonMeshes) {
        Keyed k;
        if (!keyed(p, p.P, &k)) continue;
        const SourceLoc* source = sourceFor(p.loc);
        std::vector<TrilinearBody::Corners> corners(k.ts.size());
        for (size_t f = 0; f < p.faces.size(); ++f) {
            for (size_t i = 0; i < k.ts.size(); ++i)
                for (size_t c = 0; c < 4; ++c) corners[i][c] = Vec3f(k.points[i][size_t(p.faces[f][c])]);
            std::array<Color, 4> cs;
            cs.fill(attributesOf(p.attributes).color);
            if (!p.faceCs.empty()) cs = p.faceCs[f];
            addBilinearBodies(k.ts, corners, cs, k.material, source, *rs);
        }
    }

    // Patch meshes: a BezierMesh per segment.
    for (const PatchMeshDesc& p : scene.patchMeshes) {
        Keyed k;
        if (!keyed(p, p.P, &k)) continue;
        const PatchMeshShape shape(p);
        const std::vector<std::array<Color, 4>> colors = shape.colors(p.Cs, attributesOf(p.attributes).color);
        const SourceLoc* source = sourceFor(p.loc);
        forEachSegment(k.ts, k.points, [&](double t0, double t1, size_t i, size_t j) {
            std::vector<BezierPatch> k1;
            if (j != i) k1 = shape.patches(k.points[j]);
            addSurface(std::make_unique<BezierMesh>(shape.topology(), TimeSpan{t0, t1}, k.material, &rs->camera,
                                                    shape.patches(k.points[i]), std::move(k1), colors),
                       source, *rs);
        });
    }

    // Subdivision meshes: the topology once, the limit surface per key, a SubdivisionMesh per segment.
    for (const SubdivisionMeshDesc& p : scene.subdivisionMeshes) {
        Keyed k;
        if (!keyed(p, p.P, &k)) continue;
        auto shape = std::make_shared<const SubdivisionShape>(p);
        if (shape->faceCount() == 0) {
            log.warn(p.loc, "SubdivisionMesh has no face with a limit surface (is it all boundary? see "
                            "\"interpolateboundary\"): skipped");
            continue;
        }
        const std::vector<std::array<Color, 4>> colors = shape->colors(p.Cs, attributesOf(p.attributes).color);
        const SourceLoc* source = sourceFor(p.loc);
        std::vector<std::shared_ptr<const SubdivisionKey>> keys(k.ts.size());
        auto keyAt = [&](size_t i) {
            if (!keys[i]) keys[i] = shape->key(k.points[i]);
            return keys[i];
        };
        forEachSegment(k.ts, k.points, [&](double t0, double t1, size_t i, size_t j) {
            addSurface(std::make_unique<SubdivisionMesh>(shape, keyAt(i), keyAt(j), TimeSpan{t0, t1}, k.material,
                                                         &rs->camera, colors),
                       source, *rs);
        });
    }

    // Quadrics: a QuadricMesh per segment (its shape and transform at both ends).
    for (const QuadricDesc& q : scene.quadrics) {
        const Material* material = materialFor(q.attributes);
        const MotionTransform objectToCamera = q.objectToWorld.then(cam.worldToCamera);
        const std::vector<double> ts = segmentTimes(q.times, q.params.size() > 1, objectToCamera, ws, we);
        struct Key {
            QuadricMesh::Params params;
            Matrix4 toCamera;
            bool operator==(const Key& o) const { return params == o.params && toCamera == o.toCamera; }
        };
        std::vector<Key> keys(ts.size());
        bool finite = true;
        for (size_t i = 0; i < ts.size(); ++i) {
            size_t k;
            double s;
            keyInterval(q.times, q.params.size(), ts[i], &k, &s);
            for (size_t a = 0; a < 7; ++a)
                keys[i].params[a] = s == 0 ? q.params[k][a] : (1 - s) * q.params[k][a] + s * q.params[k + 1][a];
            keys[i].toCamera = objectToCamera.at(ts[i]);
            finite = finite && keys[i].toCamera.isFinite();
        }
        if (!finite) {
            log.warn(q.loc, "primitive has non-finite coordinates in camera space: skipped");
            continue;
        }
        std::array<Color, 4> colors;
        colors.fill(attributesOf(q.attributes).color);
        if (q.Cs.given())
            for (size_t c = 0; c < 4; ++c) colors[c] = q.Cs.values[q.Cs.values.size() == 4 ? c : 0];
        const SourceLoc* source = sourceFor(q.loc);
        forEachSegment(ts, keys, [&](double t0, double t1, size_t i, size_t j) {
            const QuadricMesh::Params params[2] = {keys[i].params, keys[j].params};
            const Matrix4 toCamera[2] = {keys[i].toCamera, keys[j].toCamera};
            addSurface(std::make_unique<QuadricMesh>(q.kind, params, toCamera, TimeSpan{t0, t1}, material,
                                                     &rs->camera, colors),
                       source, *rs);
        });
    }
    return rs;
}

}  // namespace streyes
