// The body factory's curves and points (body_factory.h): ribbons as Bezier meshes, points as
// clouds of discs grouped into bodies that split spatially.
#include <cmath>

#include "bodies/body_factory.h"
#include "bodies/motion_segments.h"
#include "geom/curves.h"
#include "geom/patch_mesh.h"
#include "geom/points.h"

namespace streyes {

namespace {

// How a transform scales lengths across it (the cube root of its volume scale): widths are given
// in object space.
double meanScale(const Matrix4& m) {
    const double det = m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
                       m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
    return std::cbrt(std::fabs(det));
}

}  // namespace

void BodyFactory::addCurves(const CurvesDesc& c, uint64_t primitiveId, std::vector<BodyPtr>& out, Keep* keep) {
    std::vector<double> ts;
    std::vector<std::vector<Vec3d>> points;
    if (!keyedPoints(c, c.P, &ts, &points)) return;
    const Material* mat = material(c.attributes, c.objectToWorld, c.N.empty(), &c.primvars, primitiveId);  // ribbons facing the camera: no sides
    const CurveRibbons ribbons(c);
    const std::vector<std::array<Color, 4>> colors = ribbons.colors(mat->Cs);
    const SourceLoc* src = source(c.loc);
    const bool lastOpen = windowOf(c.life).openEnd;
    const MotionTransform toCamera = c.objectToWorld.then(worldToCamera_);
    const bool perspective = camera_->perspective();
    // Camera-facing ribbons turn with the view: made per key, in camera space.
    std::vector<std::vector<BezierPatch>> keys(ts.size());
    auto key = [&](size_t i) {
        if (keys[i].empty()) keys[i] = ribbons.patches(points[i], toCamera.at(ts[i]), perspective);
        return keys[i];
    };
    forEachSegment(ts, points, [&](double t0, double t1, size_t i, size_t j) {
        std::vector<BezierPatch> k1;
        if (j != i) k1 = key(j);
        addSurface(std::make_unique<BezierMesh>(ribbons.topology(), segmentSpan(t0, t1, ts, lastOpen), mat, cameraOf(c.life),
                                                key(i), std::move(k1), colors),
                   src, primitiveId, out, keep);
    }, wantedStart_, wantedEnd_);
}

void BodyFactory::addPoints(const PointsDesc& p, uint64_t primitiveId, std::vector<BodyPtr>& out, Keep* keep) {
    std::vector<double> ts;
    std::vector<std::vector<Vec3d>> centres;
    if (!keyedPoints(p, p.P, &ts, &centres)) return;
    const Material* mat = material(p.attributes, p.objectToWorld, true, &p.primvars, primitiveId);  // discs face the camera
    const size_t n = centres[0].size();
    std::vector<Color> colors(n, mat->Cs);
    if (p.Cs.given())
        for (size_t i = 0; i < n; ++i) colors[i] = p.Cs.values[p.Cs.values.size() == n ? i : 0];
    const MotionTransform toCamera = p.objectToWorld.then(worldToCamera_);
    auto asFloat = [](const std::vector<Vec3d>& v) { return std::vector<Vec3f>(v.begin(), v.end()); };
    auto radii = [&](size_t i) {
        const double scale = 0.5 * meanScale(toCamera.at(ts[i]));
        std::vector<float> r(n);
        for (size_t k = 0; k < n; ++k) r[k] = float(scale * p.width[p.width.size() == n ? k : 0]);
        return r;
    };
    const SourceLoc* src = source(p.loc);
    const bool lastOpen = windowOf(p.life).openEnd;
    forEachSegment(ts, centres, [&](double t0, double t1, size_t i, size_t j) {
        std::vector<Vec3f> c1;
        std::vector<float> r1;
        if (j != i) {
            c1 = asFloat(centres[j]);
            r1 = radii(j);
        }
        auto cloud = std::make_shared<const PointCloud>(segmentSpan(t0, t1, ts, lastOpen), asFloat(centres[i]),
                                                        std::move(c1), radii(i), std::move(r1), colors);
        BodyPtr body = cloud->root(mat);
        body->setSource(src);
        body->setPrimitiveId(primitiveId);
        out.push_back(std::move(body));
        ++bodiesMade_;
        sharedBytes_ += cloud->bytes();
        if (keep) {
            keep->push_back(std::move(cloud));
            return;
        }
        std::lock_guard<std::mutex> lock(mutex_);
        clouds_.push_back(std::move(cloud));
    }, wantedStart_, wantedEnd_);
}

}  // namespace streyes
