// Wind sway of Weber–Penn trees: the paper's sway angles and the stems' poses at a time.
#include "procedural/weber_penn_wind.h"

#include <algorithm>
#include <cmath>

#include "util/sampling.h"

namespace streyes {

namespace {

constexpr double kDeg = M_PI / 180;

// The rotation by `angle` (radians) about the unit axis a, as a rigid motion about the point c.
WeberPennRigid turnAbout(Vec3d c, Vec3d a, double angle) {
    const double cs = std::cos(angle), sn = std::sin(angle);
    auto turn = [&](Vec3d v) { return v * cs + cross(a, v) * sn + a * (dot(a, v) * (1 - cs)); };
    WeberPennRigid m;
    m.x = turn({1, 0, 0});
    m.y = turn({0, 1, 0});
    m.z = turn({0, 0, 1});
    m.t = c - m.turned(c);
    return m;
}

}  // namespace

WeberPennRigid WeberPennRigid::then(const WeberPennRigid& inner) const {
    WeberPennRigid m;
    m.x = turned(inner.x);
    m.y = turned(inner.y);
    m.z = turned(inner.z);
    m.t = (*this)(inner.t);
    return m;
}

const WeberPennRigid& WeberPennPose::of(int path, int segment) const {
    const size_t i = size_t(std::clamp(path, 0, int(motion.size()) - 1));
    const int j = std::clamp(segment - firstSegment[i], 0, int(motion[i].size()) - 1);
    return motion[i][size_t(j)];
}

bool weberPennWindy(const WeberPennParams& p) { return p.windSpeed > 0 || p.windGust > 0; }

void weberPennSwayOffsets(const WeberPennStem& s, double* x, double* y) {
    HashRng r(hashCombine(s.key, 0x5a7e0ffULL));  // apart from the growth's draws: wind leaves the shape
    *x = 2 * M_PI * double(r.nextFloat());
    *y = 2 * M_PI * double(r.nextFloat());
}

namespace {

// a1 and a2 of a segment (degrees before / nCurveRes); false when it does not sway.
bool swayFactors(const WeberPennParams& p, const WeberPennStem& s, int segment, double* a1, double* a2, int* res) {
    if (!weberPennWindy(p) || s.length <= 0 || s.radius <= 0) return false;
    *res = std::max(1, int(s.paths[0].points.size()) - 1);
    const double z = double(segment) / *res;
    const double radiusZ = weberPennRadiusAt(p, s, z);
    if (!(radiusZ > 0)) return false;
    const double a0 = 4 * s.length * (1 - z) / radiusZ;
    *a1 = p.windSpeed / 50 * a0;
    *a2 = p.windGust / 50 * a0 + *a1 / 2;
    return true;
}

}  // namespace

WeberPennSwayAngles weberPennSwayAngles(const WeberPennParams& p, const WeberPennStem& s, int segment, double frame) {
    WeberPennSwayAngles a;
    double a1, a2;
    int res;
    if (!swayFactors(p, s, segment, &a1, &a2, &res)) return a;
    double offsetX, offsetY;
    weberPennSwayOffsets(s, &offsetX, &offsetY);
    const double rate = s.radius / s.length * (frame * p.windTime) / 15;
    const double bx = offsetX + rate, by = offsetY + rate;
    a.x = (a1 * std::sin(bx) + a2 * std::sin(0.7 * bx)) / res;
    a.y = (a1 * std::sin(by) + a2 * std::sin(0.7 * by)) / res;
    return a;
}

double weberPennSwayAmplitude(const WeberPennParams& p, const WeberPennStem& s, int segment) {
    double a1, a2;
    int res;
    if (!swayFactors(p, s, segment, &a1, &a2, &res)) return 0;
    return (std::fabs(a1) + std::fabs(a2)) / res;
}

WeberPennPose weberPennPoseStem(const WeberPennParams& p, const WeberPennStem& s, const WeberPennRigid& attach,
                                double frame) {
    WeberPennPose pose;
    pose.motion.resize(s.paths.size());
    for (const auto& path : s.paths) pose.firstSegment.push_back(path.firstSegment);
    // Clones split from paths before them: each path starts from its parent path's motion.
    for (size_t i = 0; i < s.paths.size(); ++i) {
        const WeberPennStem::Path& path = s.paths[i];
        WeberPennRigid m = i == 0 || path.firstSegment == 0 ? attach : pose.of(path.from, path.firstSegment - 1);
        for (size_t k = 0; k + 1 < path.points.size(); ++k) {
            const Vec3d c = path.points[k], d = path.points[k + 1] - c;
            const WeberPennSwayAngles a = weberPennSwayAngles(p, s, path.firstSegment + int(k), frame);
            if (length(d) > 0 && (a.x != 0 || a.y != 0)) {
                const Vec3d z = normalize(d);
                Vec3d x = path.xAxis[k + 1] - z * dot(path.xAxis[k + 1], z);
                x = length(x) > 1e-12 ? normalize(x) : normalize(std::fabs(z.y) < 0.9 ? cross(z, Vec3d{0, 1, 0}) : cross(z, Vec3d{1, 0, 0}));
                const Vec3d y = cross(z, x);
                m = m.then(turnAbout(c, y, a.y * kDeg).then(turnAbout(c, x, a.x * kDeg)));
            }
            pose.motion[i].push_back(m);
        }
        if (pose.motion[i].empty()) pose.motion[i].push_back(m);
    }
    return pose;
}

std::vector<double> weberPennKeyTimes(const WeberPennParams& p, double windowStart, double windowEnd) {
    if (!weberPennWindy(p)) return {windowStart};
    // From the multiple of keystep at or before the window's start to the first at or after its end
    // (two keys even for an instant, so that it is interpolated as it is within a block).
    std::vector<double> ts;
    const double first = std::floor(windowStart / p.keyStep);
    for (double n = first; ts.size() < 2 || ts.back() < windowEnd; n += 1) ts.push_back(n * p.keyStep);
    return ts;
}

}  // namespace streyes
