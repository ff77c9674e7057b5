#include "bodies/level_of_detail.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bodies/body_factory.h"

namespace streyes {

double detailArea(const LevelOfDetail& lod, const MotionTransform& worldToCamera, const Camera& camera, double t) {
    constexpr double kInfinite = std::numeric_limits<double>::infinity();
    if (!lod.hasBound) return kInfinite;
    const Matrix4 m = lod.boundToWorld.then(worldToCamera).at(t);
    const Bounds3d& b = lod.bound;
    double x0 = kInfinite, x1 = -kInfinite, y0 = kInfinite, y1 = -kInfinite;
    for (int i = 0; i < 8; ++i) {
        const Vec3d c = m.point({(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z});
        if (!isFinite(c) || (camera.perspective() && !(c.z >= double(camera.eyePlane())))) return kInfinite;
        const double sx = camera.perspective() ? c.x / c.z : c.x, sy = camera.perspective() ? c.y / c.z : c.y;
        const double x = double(camera.ax()) * sx, y = double(camera.ay()) * sy;
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    return (x1 - x0) * (y1 - y0);
}

DetailShare detailShare(const std::array<double, 4>& r, double area) {
    auto clamp01 = [](double v) { return std::clamp(v, 0.0, 1.0); };
    // Ramps of zero width are steps; an infinite area is past every finite end.
    const double lo = r[1] == r[0] ? (area < r[1] ? 1 : 0) : clamp01((r[1] - area) / (r[1] - r[0]));
    const double hi = r[2] == r[3] ? (area < r[2] ? 1 : 0) : clamp01((r[3] - area) / (r[3] - r[2]));
    return {float(lo), float(hi)};
}

std::vector<DetailRun> detailRuns(const LevelOfDetail& lod, int first, int last, const Shutter& shutter,
                                  const MotionTransform& worldToCamera, const Camera& camera, double relativeDetail,
                                  const FrameCameras* cameras) {
    std::vector<DetailRun> runs;
    for (int f = first; f <= last; ++f) {
        const double t = f + 0.5 * (shutter.open + shutter.close);
        const double area = detailArea(lod, worldToCamera, cameras ? cameras->ofFrame(f) : camera, t) * relativeDetail;
        const DetailShare share = detailShare(lod.range, std::isnan(area) ? 0 : area);
        if (share.none()) continue;
        if (!runs.empty() && runs.back().last == f - 1 && runs.back().share == share) runs.back().last = f;
        else runs.push_back({f, f, share});
    }
    return runs;
}

Lifetime runLifetime(const Lifetime& life, int a, int b, const Shutter& shutter) {
    const double t0 = a + shutter.open, t1 = b + shutter.close;
    Lifetime out;
    out.t0 = std::max(life.t0, t0);
    // The next frame's exposure starts where this run's ends: it is that frame's instant.
    const bool openHere = t1 >= (b + 1) + shutter.open;
    if (life.t1 < t1) {
        out.t1 = life.t1;
        out.openEnd = life.openEnd;
    } else if (life.t1 > t1) {
        out.t1 = t1;
        out.openEnd = openHere;
    } else {
        out.t1 = t1;
        out.openEnd = life.openEnd || openHere;
    }
    return out;
}

// A sequence's procedural lives over the exposures of the frames it was matched across (its
// children too), whose cameras are its frame's: the first frame's, its camera at time t, inverted.
Matrix4 BodyFactory::sceneToWorld(const Lifetime& life, double t) const {
    if (frameWorlds_.empty() || !std::isfinite(life.t0)) return {};
    auto it = frameWorlds_.upper_bound(int(std::floor(life.t0 - frameOpen_ + 1e-6)));  // the frame's, else the one before
    if (it != frameWorlds_.begin()) --it;
    Matrix4 cameraToWorld;
    return invert(it->second.at(t), &cameraToWorld) ? cameraToWorld : Matrix4{};
}

// A copy of an attribute state whose material a share of each frame's samples sees
// (BodyFactory::material reads dissolveOf_), made once per state and share.
AttributesPtr BodyFactory::dissolving(const AttributesPtr& attributes, float lo, float hi) {
    std::lock_guard<std::mutex> lock(mutex_);
    AttributesPtr& made = dissolving_[{attributes.get(), lo, hi}];
    if (!made) {
        made = std::make_shared<const Attributes>(*attributes);
        dissolveOf_[made.get()] = {lo, hi};
        keepAlive_.push_back(attributes);  // its address keys dissolving_
    }
    return made;
}

}  // namespace streyes
