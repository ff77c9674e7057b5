// The Weber–Penn tree procedural: a tree expands into its trunk and one procedural per
// first-level branch (bounded by how far its subtree can reach), which grows its subtree when seen.
// Stems are generalized cylinders: bicubic patch meshes, a periodic B-spline ring around
// (round, with the trunk's lobes) swept along a Catmull-Rom curve through the stem's segment
// points (so they show the stem's curvature); leaves are outline polygons (LeafShape).
#include <algorithm>
#include <cmath>

#include "procedural/weber_penn.h"
#include "procedural/weber_penn_wind.h"
#include "util/sampling.h"

namespace streyes {

namespace {

const Vec3d kUp{0, 1, 0};

// ZScale ± ZScaleV for the tree (the paper scales the tree along its vertical axis).
double zScaleOf(const WeberPennParams& p) {
    HashRng r(mix64(p.seed ^ 0x25ca1eULL));
    return std::max(1e-6, p.zScale + (2 * double(r.nextFloat()) - 1) * p.zScaleV);
}

Vec3d squash(Vec3d v, double zs) { return {v.x, v.y * zs, v.z}; }

// A still PointsPolygons in the procedural's space with a colour a face (the crown volume, the
// diamond leaves).
PolygonMeshDesc uniformPolygonsOf(const ExpandContext& ctx) {
    PolygonMeshDesc m;
    m.request = "PointsPolygons";
    m.times = {0.0};
    m.objectToWorld = ctx.objectToWorld;
    m.attributes = ctx.attributes;
    m.loc = ctx.loc;
    m.Cs.cls = ParamClass::Uniform;
    return m;
}

PatchMeshDesc meshOf(const ExpandContext& ctx, Color cs) {
    PatchMeshDesc m;
    m.times = {0.0};
    m.objectToWorld = ctx.objectToWorld;
    m.attributes = ctx.attributes;
    m.loc = ctx.loc;
    m.bicubic = true;
    m.uPeriodic = true;
    basisFromName("b-spline", &m.uBasis);
    basisFromName("catmull-rom", &m.vBasis);
    m.Cs.cls = ParamClass::Constant;
    m.Cs.values = {cs};
    return m;
}

// The key times of a windy expansion and, for each, the poses of the stems it makes (empty: still).
struct Motion {
    std::vector<double> times{0.0};
    std::vector<std::vector<WeberPennPose>> poses;  // [key][stem]
    bool moving() const { return !poses.empty(); }
};

constexpr int kHelixRings = 10;  // control rings a turn of a helical stem (nCurveV < 0)

// One patch mesh per path of the stem (the stem and each clone). `sides` control points around;
// the trunk's flare adds rings inside its first segment. Moving, each control ring is keyed by the
// motion of the segment it lies on (a joint's: the segment leaving it).
void emitStem(ProceduralOutput& out, const ExpandContext& ctx, const WeberPennParams& p, const WeberPennStem& s,
              int sides, double zs, const Motion& motion = {}, size_t stemIndex = 0) {
    if (s.length <= 0 || s.radius <= 0) return;
    const int res = int(s.paths[0].points.size()) - 1;
    // The B-spline ring passes inside its control polygon: at a control point's angle, by
    // (4 + 2 cos(2 pi / sides)) / 6. Scale it back so the radius is the paper's.
    const double ringScale = 6 / (4 + 2 * std::cos(2 * M_PI / sides));
    // nCurveV < 0: each segment one turn of a helix whose tangent leans |nCurveV| from the segment
    // (the helix's circumference is the segment's length times tan |nCurveV|).
    const double curveV = p.level[size_t(std::clamp(s.level, 0, 3))].curveV;
    const double helixRadius = curveV < 0 && curveV > -90
                                   ? std::tan(-curveV * M_PI / 180) * s.length / std::max(1, res) / (2 * M_PI)
                                   : 0;
    for (size_t pathIndex = 0; pathIndex < s.paths.size(); ++pathIndex) {
        const WeberPennStem::Path& path = s.paths[pathIndex];
        struct Ring {
            Vec3d at, x;
            double z;
            int segment;
        };
        std::vector<Ring> rings;
        // The helix's rings inside the segment from a to b: kHelixRings - 1 of them, each on the
        // segment the stem's motion moves (the one leaving a). The B-spline through control points on
        // a circle passes inside it, as the ring's does: the offsets are scaled back by the same rule.
        auto addHelixRings = [&](std::vector<Ring>& out, Vec3d a, Vec3d b, Vec3d xAxis, double radius,
                                 double segment, int segments) {
            const Vec3d d = b - a;
            const Vec3d t = normalize(d);
            Vec3d x = xAxis - t * dot(xAxis, t);
            x = length(x) > 1e-9 ? normalize(x) : normalize(std::fabs(t.y) < 0.9 ? cross(t, kUp) : cross(t, Vec3d{1, 0, 0}));
            const Vec3d y = cross(t, x);
            const double scaled = radius * 6 / (4 + 2 * std::cos(2 * M_PI / kHelixRings));
            for (int k = 1; k < kHelixRings; ++k) {
                const double f = double(k) / kHelixRings, angle = 2 * M_PI * f;
                const Vec3d at = a + d * f + (x * (std::cos(angle) - 1) + y * std::sin(angle)) * scaled;
                out.push_back({at, xAxis, (segment + f) / segments, int(segment)});
            }
        };
        for (size_t i = 0; i < path.points.size(); ++i) {
            const double z = double(path.firstSegment + int(i)) / res;
            if (s.level == 0 && p.flare > 0 && i == 1 && path.firstSegment == 0 && helixRadius == 0)
                for (double f : {0.03, 0.08, 0.16, 0.3, 0.55})  // the flare lies in the trunk's first eighth
                    rings.push_back({lerp(path.points[0], path.points[1], f), path.xAxis[0], f / res, 0});
            if (helixRadius > 0 && i > 0)
                addHelixRings(rings, path.points[i - 1], path.points[i], path.xAxis[i - 1], helixRadius,
                              double(path.firstSegment + int(i) - 1), res);
            rings.push_back({path.points[i], path.xAxis[i], z, path.firstSegment + int(i)});
        }
        if (rings.size() < 2) continue;
        const size_t n = rings.size();
        // Control rings: the point before (a clone's parent path), the rings, the last again.
        auto pointOf = [&](long i) {
            if (i < 0) return path.before;
            return rings[size_t(std::min<long>(i, long(n) - 1))].at;
        };
        PatchMeshDesc m = meshOf(ctx, p.barkColor);
        m.nu = sides;
        m.nv = int(n) + 2;
        // Each control point before ZScale, with the path and segment whose motion moves it.
        std::vector<Vec3d> rest;
        std::vector<std::pair<int, int>> on;
        rest.reserve(size_t(m.nu * m.nv));
        auto ring = [&](long i) {
            const size_t k = size_t(std::clamp<long>(i, 0, long(n) - 1));
            Vec3d tangent = pointOf(long(k) + 1) - pointOf(long(k) - 1);
            if (k == 0 && path.firstSegment == 0) tangent = rings[1].at - rings[0].at;
            if (k + 1 == n) tangent = rings[k].at - rings[k - 1].at;
            const Vec3d t = length(tangent) > 0 ? normalize(tangent) : kUp;
            Vec3d x = rings[k].x - t * dot(rings[k].x, t);
            x = length(x) > 1e-9 ? normalize(x) : normalize(std::fabs(t.y) < 0.9 ? cross(t, kUp) : cross(t, Vec3d{1, 0, 0}));
            const Vec3d y = cross(t, x);
            const double r = std::max(weberPennRadiusAt(p, s, rings[k].z), s.radius * 1e-3) * ringScale;
            for (int j = 0; j < sides; ++j) {
                const double a = 2 * M_PI * j / sides;
                const double lobe = s.level == 0 && p.lobes > 0 ? 1 + p.lobeDepth * std::sin(p.lobes * a) : 1;
                rest.push_back(rings[k].at + (x * std::cos(a) + y * std::sin(a)) * (r * lobe));
                on.emplace_back(int(pathIndex), rings[k].segment);
            }
        };
        // The first control ring: before the first (for a clone, on its parent's path, so that the
        // clone leaves the split along the curve) or the first again.
        ring(0);
        const Vec3d shift = path.before - rings[0].at;
        if (path.firstSegment > 0)
            for (auto& o : on) o = {path.from, path.firstSegment - 1};
        for (size_t k = 0; k < n; ++k) ring(long(k));
        ring(long(n) - 1);
        const size_t shifted = path.firstSegment > 0 ? size_t(sides) : 0;
        if (!motion.moving()) {
            std::vector<Vec3d> P(rest.size());
            for (size_t i = 0; i < rest.size(); ++i) P[i] = squash(rest[i], zs);
            for (size_t i = 0; i < shifted; ++i) P[i] = P[i] + squash(shift, zs);
            m.P = {std::move(P)};
        } else {
            m.times = motion.times;
            for (const auto& poses : motion.poses) {
                const WeberPennPose& pose = poses[stemIndex];
                std::vector<Vec3d> P(rest.size());
                for (size_t i = 0; i < rest.size(); ++i)
                    P[i] = squash(pose.of(on[i].first, on[i].second)(i < shifted ? rest[i] + shift : rest[i]), zs);
                m.P.push_back(std::move(P));
            }
        }
        out.scene.patchMeshes.push_back(std::move(m));
    }
}

// A leaf's outline in its own plane: (along the blade 0..1, across -1..1 times half its width).
const std::vector<std::pair<double, double>>& outline(int shape) {
    static const std::vector<std::pair<double, double>> shapes[3] = {
        // 0: ellipse
        {{0, 0}, {0.067, 0.5}, {0.25, 0.866}, {0.5, 1}, {0.75, 0.866}, {0.933, 0.5}, {1, 0},
         {0.933, -0.5}, {0.75, -0.866}, {0.5, -1}, {0.25, -0.866}, {0.067, -0.5}},
        // 1: ovate, pointed at the tip (oak, tupelo)
        {{0, 0}, {0.05, 0.55}, {0.2, 0.92}, {0.38, 1}, {0.58, 0.85}, {0.78, 0.5}, {1, 0},
         {0.78, -0.5}, {0.58, -0.85}, {0.38, -1}, {0.2, -0.92}, {0.05, -0.55}},
        // 2: lanceolate (willow)
        {{0, 0}, {0.1, 0.7}, {0.3, 1}, {0.6, 0.8}, {0.85, 0.4}, {1, 0}, {0.85, -0.4}, {0.6, -0.8},
         {0.3, -1}, {0.1, -0.7}},
    };
    return shapes[std::clamp(shape, 0, 2)];
}

// Under this many pixels long (times detail=) a leaf's outline is a diamond of its area: one
// bilinear patch instead of the outline's several, its motion keys on 4 points instead of 10-12.
constexpr double kLeafOutlinePixels = 6;

// All the leaves of an expansion as one PointsPolygons, a colour each (the leaf colour varied).
void emitLeaves(ProceduralOutput& out, const ExpandContext& ctx, const WeberPennParams& p,
                const std::vector<WeberPennLeaf>& leaves, uint64_t key, double zs,
                const Motion& motion = {}) {
    if (leaves.empty() || p.leafScale <= 0) return;
    const auto& shape = outline(p.leafShape);
    // A degraded leaf (grown: the range thinned its neighbours) or a small one is a diamond, one bilinear patch
    // instead of the outline's several, as wide as keeps the outline's area: (0,0) (0.5,w) (1,0)
    // (0.5,-w) has area w, the outline's the shoelace sum (in units of length x half width).
    double outlineArea = 0;
    for (size_t k = 0; k < shape.size(); ++k) {
        const auto& [u0, w0] = shape[k];
        const auto& [u1, w1] = shape[(k + 1) % shape.size()];
        outlineArea += 0.5 * (u0 * w1 - u1 * w0);
    }
    const std::pair<double, double> diamond[4] = {{0, 0}, {0.5, -std::fabs(outlineArea)}, {1, 0}, {0.5, std::fabs(outlineArea)}};
    const double ppu = ctx.read.pixelsPerUnit;
    const bool small = ppu > 0 && p.leafScale * std::max(1.0, p.leafScaleX) * ppu * p.detail < kLeafOutlinePixels;
    PolygonMeshDesc m = uniformPolygonsOf(ctx);
    std::vector<Vec3d> P;
    std::vector<size_t> leafOf;  // moving: the leaf each point belongs to
    HashRng r(hashCombine(key, 0x1ea7e5));
    for (size_t i = 0; i < leaves.size(); ++i) {
        const WeberPennLeaf& l = leaves[i];
        Vec3d across = cross(l.direction, l.normal);
        across = length(across) > 1e-9 ? normalize(across) : Vec3d{1, 0, 0};
        std::vector<int> loop;
        // The paper's reduction for distant trees: fewer leaves (grown so), larger, the same area.
        const double len = p.leafScale * l.grow, half = 0.5 * len * p.leafScaleX;
        auto corner = [&](double u, double w) {
            loop.push_back(int(P.size()));
            const Vec3d q = l.position + l.direction * (u * len) + across * (w * half);
            P.push_back(motion.moving() ? q : squash(q, zs));
            if (motion.moving()) leafOf.push_back(i);
        };
        if (l.grow > 1 || small)
            for (const auto& [u, w] : diamond) corner(u, w);
        else
            for (const auto& [u, w] : shape) corner(u, w);
        m.polygons.push_back({std::move(loop)});
        m.Cs.values.push_back(p.leafColor * (0.8f + 0.4f * r.nextFloat()));
    }
    if (!motion.moving()) {
        m.P = {std::move(P)};
    } else {
        // Each leaf moves with the segment of its stem it grows on.
        m.times = motion.times;
        for (const auto& poses : motion.poses) {
            std::vector<Vec3d> K(P.size());
            for (size_t i = 0; i < P.size(); ++i) {
                const WeberPennLeaf& l = leaves[leafOf[i]];
                K[i] = squash(poses[size_t(l.stem)].of(l.path, l.segment)(P[i]), zs);
            }
            m.P.push_back(std::move(K));
        }
    }
    out.scene.polygonMeshes.push_back(std::move(m));
}

int sidesOf(int level) { return level == 0 ? 8 : level == 1 ? 6 : 4; }

// A bound of a stem's subtree: its axis (every path's points) grown by how far what grows on it
// can reach: a child is at most nLength + |nLengthV| of its parent's length and lies within its
// length of its base; leaves add their largest size (quality 0.05), radii and a tenth of the stem's
// length for the spline through the axis points.
double subtreeReach(const WeberPennParams& p, const WeberPennStem& s) {
    // A helical stem (nCurveV < 0) leaves its axis by at most twice its helix's radius (scaled as
    // emitStem scales it, under 1.1).
    auto helixReach = [&](const WeberPennLevel& c, double length) {
        return c.curveV < 0 && c.curveV > -90
                   ? 2.2 * std::tan(-c.curveV * M_PI / 180) * length / std::max(1, c.curveRes) / (2 * M_PI)
                   : 0.0;
    };
    double l = s.length;
    double reach = helixReach(p.level[size_t(std::clamp(s.level, 0, 3))], l);
    for (int level = s.level + 1; level < p.levels; ++level) {
        const WeberPennLevel& c = p.level[size_t(std::min(level, 3))];
        l *= c.length + std::fabs(c.lengthV);
        reach += l + helixReach(c, l);
    }
    const double flare = s.level == 0 ? (1 + p.flare) * (1 + p.lobeDepth) : 1;
    return reach + p.leafScale * std::max(1.0, p.leafScaleX) * std::sqrt(1 / kWeberPennLeastQuality) + 2 * s.radius * flare + 0.1 * s.length;
}

// A stem's subtree before ZScale and wind: its axis (every path's points) grown by its reach.
Bounds3d restSubtreeBox(const WeberPennParams& p, const WeberPennStem& s) {
    const double reach = subtreeReach(p, s);
    Bounds3d b;
    for (const auto& path : s.paths)
        for (Vec3d q : path.points) {
            b.extend(q - Vec3d{reach, reach, reach});
            b.extend(q + Vec3d{reach, reach, reach});
        }
    return b;
}

Bounds3d squashBox(const Bounds3d& b, double zs) { return b.empty() ? b : Bounds3d(squash(b.lo, zs), squash(b.hi, zs)); }

Bounds3d subtreeBound(const WeberPennParams& p, const WeberPennStem& s, double zs) {
    return squashBox(restSubtreeBox(p, s), zs);
}

void emitProcedural(ProceduralOutput& out, const ExpandContext& ctx, std::shared_ptr<const ProceduralGenerator> g,
                    const Bounds3d& bound) {
    GeneratedProcedural gp;
    gp.generator = std::move(g);
    gp.desc.kind = "DynamicLoad";
    gp.desc.bound = bound;
    gp.desc.objectToWorld = ctx.objectToWorld;
    gp.desc.attributes = ctx.attributes;
    gp.desc.loc = ctx.loc;
    out.procedurals.push_back(std::move(gp));
}

// The leaves' share kept at this size on screen. The paper's quality for distant trees: all of them
// while the subtree is 300 pixels across or more (times detail=), below as its area: a branch's
// leaves on screen follow the pixels it covers, not its width. And a cap on detail per pixel: a
// leaf under a pixel / detail= long (its length at the procedural's pixels a unit, which its level
// sets, so that it is decided over the shot as the level is) keeps the share (its length in
// pixels times detail=)², so that the leaves kept, grown by the share left out, are about a pixel
// long and keep the leaves' area.
// `still`: what is grown, still (object space): its size on screen is that box's longest side at
// the procedural's pixels a unit, not its bound's, which the wind widens.
double qualityAt(const WeberPennParams& p, const ExpandContext& ctx, const Bounds3d& still) {
    const double ppu = ctx.read.pixelsPerUnit;
    double pixels = std::sqrt(std::max(0.0, ctx.detail));
    if (ppu > 0 && std::isfinite(ppu) && !still.empty() && !ctx.objectToWorld.keys().empty()) {
        const Vec3d d = (ctx.objectToWorld.keys().front() * ctx.sceneToWorld).box(still).diagonal();  // as ppu's
        pixels = std::min(pixels, ppu * std::max({d.x, d.y, d.z}));
    }
    const double size = pixels * p.detail / 300;
    double q = size * size;
    if (ppu > 0 && std::isfinite(ppu) && p.leaves > 0 && p.leafScale > 0) {
        const double leafPixels = p.leafScale * std::max(1.0, p.leafScaleX) * ppu * p.detail;
        q = std::min(q, leafPixels * leafPixels);
    }
    return std::clamp(q, kWeberPennLeastQuality, 1.0);
}

// A stem as lines (the paper's stems drawn as lines at range): a linear curve along each path's
// segment points, as wide as the stem there (ribbons facing the eye).
void emitLines(ProceduralOutput& out, const ExpandContext& ctx, const WeberPennParams& p, const WeberPennStem& s,
               double zs, const Motion& motion, size_t stemIndex) {
    const int res = int(s.paths[0].points.size()) - 1;
    CurvesDesc c;
    c.times = motion.times;
    c.objectToWorld = ctx.objectToWorld;
    c.attributes = ctx.attributes;
    c.loc = ctx.loc;
    c.widthClass = ParamClass::Varying;
    c.width.clear();
    c.Cs.cls = ParamClass::Constant;
    c.Cs.values = {p.barkColor};
    c.P.resize(motion.times.size());
    for (size_t pathIndex = 0; pathIndex < s.paths.size(); ++pathIndex) {
        const WeberPennStem::Path& path = s.paths[pathIndex];
        if (path.points.size() < 2) continue;
        c.nvertices.push_back(int(path.points.size()));
        for (size_t i = 0; i < path.points.size(); ++i) {
            const int segment = path.firstSegment + int(i);
            c.width.push_back(2 * weberPennRadiusAt(p, s, double(segment) / std::max(1, res)));
            for (size_t k = 0; k < motion.times.size(); ++k)
                c.P[k].push_back(squash(motion.moving() ? motion.poses[k][stemIndex].of(int(pathIndex), segment)(path.points[i])
                                                        : path.points[i],
                                        zs));
        }
    }
    if (!c.nvertices.empty()) out.scene.curves.push_back(std::move(c));
}

// A stem by its width on screen: a generalized cylinder; under a pixel / detail across, lines;
// under a quarter of a pixel / detail, nothing (what grows on it stays). The trunk and the
// first-level branches are never left out. Without a measure of the screen (ppu 0), cylinders.
void emitStemAtRange(ProceduralOutput& out, const ExpandContext& ctx, const WeberPennParams& p, const WeberPennStem& s,
                     double zs, const Motion& motion, size_t stemIndex) {
    if (s.length <= 0 || s.radius <= 0) return;
    const double ppu = ctx.read.pixelsPerUnit;
    const double across = 2 * s.radius * ppu * p.detail;  // pixels, scaled by detail=
    if (ppu <= 0 || across >= 1) emitStem(out, ctx, p, s, sidesOf(s.level), zs, motion, stemIndex);
    else if (s.level <= 1 || across >= 0.25) emitLines(out, ctx, p, s, zs, motion, stemIndex);
}

// Bounds in the wind, from what the sway angles can reach (weberPennSwayAmplitude), whatever the
// time: a pose composes turns about the rest joints (each segment's start c, by at most A about its x
// axis, then about its y), so a rest point q moves by at most the sum over the joints carrying it
// of |R q - q|. R, turns by a and b about perpendicular axes, is one turn by theta with
// cos(theta / 2) = cos(a / 2) cos(b / 2) (the product of their quaternions), and moves q by at most
// 2 sin(theta / 2) |q - c|: with |a|, |b| <= A, 2 sqrt(1 - cos^4(A / 2)) |q - c|.

// The farthest a point of `box` lies from c.
double farthestIn(const Bounds3d& box, Vec3d c) {
    const double x = std::max(std::fabs(c.x - box.lo.x), std::fabs(box.hi.x - c.x));
    const double y = std::max(std::fabs(c.y - box.lo.y), std::fabs(box.hi.y - c.y));
    const double z = std::max(std::fabs(c.z - box.lo.z), std::fabs(box.hi.z - c.z));
    return std::sqrt(x * x + y * y + z * z);
}

// How far a joint of s (the start of segment `segment`) moves a point at distance `d` from it.
double jointSway(const WeberPennParams& p, const WeberPennStem& s, int segment, double d) {
    const double a = std::min(weberPennSwayAmplitude(p, s, segment) * M_PI / 180, M_PI);
    const double c = std::cos(a / 2);
    return a > 0 ? 2 * std::sqrt(std::max(0.0, 1 - c * c * c * c)) * d : 0;
}

// The joints of s that move what grows on (path, segment), as WeberPennPose::of composes them: the
// path's segments up to that one, then those of the path it split from up to the split; `box`
// holds what they move.
double chainSway(const WeberPennParams& p, const WeberPennStem& s, int path, int segment, const Bounds3d& box) {
    double d = 0;
    size_t i = size_t(std::clamp(path, 0, int(s.paths.size()) - 1));
    for (int guard = 0; guard <= int(s.paths.size()); ++guard) {
        const WeberPennStem::Path& ph = s.paths[i];
        const int segments = int(ph.points.size()) - 1;  // (WeberPennPose::of clamps to them)
        const int last = segments < 1 ? -1 : std::clamp(segment - ph.firstSegment, 0, segments - 1);
        for (int k = 0; k <= last; ++k) d += jointSway(p, s, ph.firstSegment + k, farthestIn(box, ph.points[size_t(k)]));
        if (i == 0 || ph.firstSegment == 0) break;
        segment = ph.firstSegment - 1;
        i = size_t(std::clamp(ph.from, 0, int(s.paths.size()) - 1));
    }
    return d;
}

// The joints of s that carry a point (its path's and those of the paths it split from), each
// moving it from as far as what lies beyond that joint reaches (the path's later points, or with
// clones any point of the stem, grown by `reach`, what grows on them); the most over its paths.
double stemSway(const WeberPennParams& p, const WeberPennStem& s, double reach) {
    auto lever = [&](const WeberPennStem::Path& path, size_t k) {
        double far = 0;
        if (s.paths.size() == 1) {
            for (size_t j = k + 1; j < path.points.size(); ++j) far = std::max(far, length(path.points[j] - path.points[k]));
        } else {
            for (const auto& other : s.paths)
                for (Vec3d q : other.points) far = std::max(far, length(q - path.points[k]));
        }
        return far + reach;
    };
    double most = 0;
    for (size_t end = 0; end < s.paths.size(); ++end) {
        double d = 0;
        size_t i = end;
        int segment = s.paths[end].firstSegment + int(s.paths[end].points.size());  // all of the end path
        for (int guard = 0; guard <= int(s.paths.size()); ++guard) {
            const WeberPennStem::Path& ph = s.paths[i];
            const int last = std::min(segment - ph.firstSegment, int(ph.points.size()) - 2);
            for (int k = 0; k <= last; ++k) d += jointSway(p, s, ph.firstSegment + k, lever(ph, size_t(k)));
            if (i == 0 || ph.firstSegment == 0) break;
            segment = ph.firstSegment - 1;
            i = size_t(std::clamp(ph.from, 0, int(s.paths.size()) - 1));
        }
        most = std::max(most, d);
    }
    // However far they turn, the stem and what grows on it stay within its length and reach of its
    // base, which its own joints do not move: a point moves by at most twice that.
    return std::min(most, 2 * (s.length + reach));
}

Bounds3d grownBy(const Bounds3d& b, double d) { return {b.lo - Vec3d{d, d, d}, b.hi + Vec3d{d, d, d}}; }

Bounds3d clippedTo(const Bounds3d& b, const Bounds3d& keep) { return {vmax(b.lo, keep.lo), vmin(b.hi, keep.hi)}; }

// The cube about the trunk's foot that holds the windy tree whatever the angles (its trunk's length
// and reach, and its longest branch's: turns keep path lengths from the foot, which stays put),
// before ZScale. The bounds below are clipped to it, so that they never exceed it.
Bounds3d anyAngleCube(const WeberPennParams& p, const std::vector<WeberPennStem>& stems) {
    WeberPennParams trunkOnly = p;
    trunkOnly.levels = std::min(p.levels, 1);
    double branch = 0;
    for (size_t i = 1; i < stems.size(); ++i) branch = std::max(branch, stems[i].length + subtreeReach(p, stems[i]));
    const double r = stems[0].length + subtreeReach(trunkOnly, stems[0]) + branch;
    return {Vec3d{-r, -r, -r}, Vec3d{r, r, r}};
}

// A first-level branch's procedural in the wind. Its pose composes the trunk's joints below it (A),
// its own (B) and those of the levels below (C): a point q moves to A B C q. C keeps a child's
// subtree within its length and reach of its base, which lies on the branch's axis, so C q lies in
// the branch's still box (its axis grown by its reach, which holds that); A and B then move it by
// at most the sums of their joints' turns (chainSway, stemSway) at its distance from each.
Bounds3d swayingBound(const WeberPennParams& p, const WeberPennStem& trunk, const WeberPennStem& s, const Bounds3d& cube,
                      double zs) {
    const Bounds3d rest = restSubtreeBox(p, s);
    const double d = chainSway(p, trunk, s.parentPath, s.parentSegment, rest) + stemSway(p, s, subtreeReach(p, s));
    // Nor does it leave the ball about its base (moved by the trunk's joints) that holds it
    // whatever its own angles: its length and reach.
    const Vec3d base = s.paths[0].points[0];
    const Bounds3d ball = grownBy(Bounds3d(base, base), s.length + subtreeReach(p, s) +
                                                          chainSway(p, trunk, s.parentPath, s.parentSegment, Bounds3d(base, base)));
    return squashBox(clippedTo(clippedTo(grownBy(rest, d), ball), cube), zs);
}

// The trunk itself in the wind (with its own leaves when it has them).
Bounds3d swayingTrunkBound(const WeberPennParams& p, const WeberPennStem& trunk, const Bounds3d& cube, double zs) {
    WeberPennParams trunkOnly = p;
    trunkOnly.levels = std::min(p.levels, 1);
    const Bounds3d rest = restSubtreeBox(trunkOnly, trunk);
    return squashBox(clippedTo(grownBy(rest, stemSway(p, trunk, subtreeReach(trunkOnly, trunk))), cube), zs);
}

// The trunk's poses at the key times (its foot stays put).
std::vector<WeberPennPose> trunkPoses(const WeberPennParams& p, const WeberPennStem& trunk, const std::vector<double>& times) {
    std::vector<WeberPennPose> poses;
    for (double t : times) poses.push_back(weberPennPoseStem(p, trunk, WeberPennRigid{}, t));
    return poses;
}

class SubtreeGenerator final : public ProceduralGenerator {
  public:
    SubtreeGenerator(std::shared_ptr<const WeberPennParams> p, std::shared_ptr<const WeberPennStem> trunk,
                     WeberPennStem stem, double zs)
        : p_(std::move(p)), trunk_(std::move(trunk)), stem_(std::move(stem)), zs_(zs) {}
    std::string describe() const override { return "weberpenn branch"; }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const WeberPennParams& p = *p_;
        std::vector<WeberPennStem> stems{stem_};
        std::vector<WeberPennLeaf> leaves;
        const WeberPennReduction reduce = weberPennReduction(p, qualityAt(p, ctx, subtreeBound(p, stem_, zs_)));
        weberPennGrowBelow(p, stems, 0, p.levels, &leaves, reduce);
        Motion motion;
        if (weberPennWindy(p)) {
            // Each stem posed at each key after its parent where it grows; the branch after the trunk.
            motion.times = weberPennKeyTimes(p, ctx.windowStart, ctx.windowEnd);
            const std::vector<WeberPennPose> trunk = trunkPoses(p, *trunk_, motion.times);
            for (size_t k = 0; k < motion.times.size(); ++k) {
                std::vector<WeberPennPose> poses;
                poses.reserve(stems.size());
                for (size_t i = 0; i < stems.size(); ++i) {
                    const WeberPennStem& s = stems[i];
                    const WeberPennPose& parent = i == 0 ? trunk[k] : poses[size_t(s.parent)];
                    poses.push_back(weberPennPoseStem(p, s, parent.of(s.parentPath, s.parentSegment), motion.times[k]));
                }
                motion.poses.push_back(std::move(poses));
            }
        }
        for (size_t i = 0; i < stems.size(); ++i) emitStemAtRange(out, ctx, p, stems[i], zs_, motion, i);
        emitLeaves(out, ctx, p, leaves, stem_.key, zs_, motion);
    }

  private:
    std::shared_ptr<const WeberPennParams> p_;
    std::shared_ptr<const WeberPennStem> trunk_;
    WeberPennStem stem_;
    double zs_;
};

// The bound of the still tree: its trunk's (with its own leaves when it has them) and its
// first-level branches' subtrees'. `stems`: the trunk and its first-level branches.
Bounds3d stillTreeBound(const WeberPennParams& p, const std::vector<WeberPennStem>& stems, double zs) {
    WeberPennParams trunkOnly = p;
    trunkOnly.levels = std::min(p.levels, 1);  // the trunk's own reach (its leaves when it has them)
    Bounds3d b = subtreeBound(trunkOnly, stems[0], zs);
    for (size_t i = 1; i < stems.size(); ++i) b.extend(subtreeBound(p, stems[i], zs));
    return b;
}

// Under this many pixels / detail (the still tree's longest side on screen) a tree is the paper's
// far tree: a simple volume. As the forest's own trees lose their branches under 40.
constexpr double kVolumePixels = 40;

// The tree's size on screen: its still bound's longest side in pixels (by the procedural's pixels
// a unit), or, without that measure, the side of its bound's raster area.
double treePixels(const WeberPennParams& p, const ExpandContext& ctx, const std::vector<WeberPennStem>& stems, double zs) {
    if (!(ctx.read.pixelsPerUnit > 0)) return std::sqrt(std::max(0.0, ctx.detail));
    const Vec3d d = stillTreeBound(p, stems, zs).diagonal();
    return ctx.read.pixelsPerUnit * std::max({d.x, d.y, d.z});
}

// The paper's far tree as a simple volume: a surface of revolution about the trunk's foot, around
// the first-level branches' axes (at each of kCrownRings heights as far out as those within a
// band of it reach, and the leaves' size more), closed at the lowest and highest of their points,
// in the leaves' colour; its points kept inside the still tree's bound.
void emitCrownVolume(ProceduralOutput& out, const ExpandContext& ctx, const WeberPennParams& p,
                     const std::vector<WeberPennStem>& stems, double zs) {
    constexpr int kCrownRings = 6, kAround = 8;
    double lo = 1e300, hi = -1e300;
    for (size_t i = 1; i < stems.size(); ++i)
        for (const auto& path : stems[i].paths)
            for (Vec3d q : path.points) lo = std::min(lo, q.y), hi = std::max(hi, q.y);
    for (const auto& path : stems[0].paths)
        for (Vec3d q : path.points) hi = std::max(hi, q.y);
    if (!(hi > lo)) return;
    const double band = (hi - lo) / (kCrownRings + 1);
    std::vector<double> radius(kCrownRings, 0.0);
    for (int k = 0; k < kCrownRings; ++k) {
        const double y = lo + band * (k + 1);
        for (size_t i = 1; i < stems.size(); ++i)
            for (const auto& path : stems[i].paths)
                for (Vec3d q : path.points)
                    if (std::fabs(q.y - y) <= band) radius[size_t(k)] = std::max(radius[size_t(k)], std::hypot(q.x, q.z));
        radius[size_t(k)] += p.leafScale;
    }
    const Bounds3d keep = stillTreeBound(p, stems, zs);
    auto inside = [&](Vec3d q) {
        q = squash(q, zs);
        return Vec3d{std::clamp(q.x, keep.lo.x, keep.hi.x), std::clamp(q.y, keep.lo.y, keep.hi.y),
                     std::clamp(q.z, keep.lo.z, keep.hi.z)};
    };
    PolygonMeshDesc m = uniformPolygonsOf(ctx);
    std::vector<Vec3d> P;
    const int bottom = 0;
    P.push_back(inside({0, lo, 0}));
    for (int k = 0; k < kCrownRings; ++k)
        for (int j = 0; j < kAround; ++j) {
            const double a = 2 * M_PI * j / kAround;
            P.push_back(inside({radius[size_t(k)] * std::cos(a), lo + band * (k + 1), radius[size_t(k)] * std::sin(a)}));
        }
    const int top = int(P.size());
    P.push_back(inside({0, hi, 0}));
    auto at = [&](int k, int j) { return 1 + k * kAround + (j % kAround); };
    for (int j = 0; j < kAround; ++j) {
        m.polygons.push_back({{bottom, at(0, j + 1), at(0, j)}});
        m.Cs.values.push_back(p.leafColor * 0.7f);
        for (int k = 0; k + 1 < kCrownRings; ++k) {
            m.polygons.push_back({{at(k, j), at(k, j + 1), at(k + 1, j + 1), at(k + 1, j)}});
            m.Cs.values.push_back(p.leafColor * (0.75f + 0.05f * float(k)));
        }
        m.polygons.push_back({{at(kCrownRings - 1, j), at(kCrownRings - 1, j + 1), top}});
        m.Cs.values.push_back(p.leafColor);
    }
    m.P = {std::move(P)};
    out.scene.polygonMeshes.push_back(std::move(m));
}

class WeberPennTreeGenerator final : public ProceduralGenerator {
  public:
    explicit WeberPennTreeGenerator(WeberPennParams p) : p_(std::make_shared<const WeberPennParams>(std::move(p))) {}
    std::string describe() const override { return "DynamicLoad tree (weberpenn " + p_->name + ")"; }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const WeberPennParams& p = *p_;
        const double zs = zScaleOf(p);
        std::vector<WeberPennStem> stems{weberPennTrunk(p, nullptr)};
        weberPennGrowBelow(p, stems, 0, 1, nullptr);
        Motion motion;
        if (weberPennWindy(p)) {
            motion.times = weberPennKeyTimes(p, ctx.windowStart, ctx.windowEnd);
            for (WeberPennPose& pose : trunkPoses(p, stems[0], motion.times)) motion.poses.push_back({std::move(pose)});
        }
        if (p.levels > 1 && treePixels(p, ctx, stems, zs) < kVolumePixels / p.detail) {
            // Far: the trunk (lines, most likely) and the crown as a still volume.
            emitStemAtRange(out, ctx, p, stems[0], zs, {}, 0);
            emitCrownVolume(out, ctx, p, stems, zs);
            return;
        }
        emitStemAtRange(out, ctx, p, stems[0], zs, motion, 0);
        if (p.levels == 1) {
            std::vector<WeberPennLeaf> leaves;
            const WeberPennReduction reduce = weberPennReduction(p, qualityAt(p, ctx, stillTreeBound(p, stems, zs)));
            weberPennGrowBelow(p, stems, 0, 1, &leaves, reduce);
            emitLeaves(out, ctx, p, leaves, stems[0].key, zs, motion);
            return;
        }
        const auto trunk = std::make_shared<const WeberPennStem>(stems[0]);
        const Bounds3d cube = anyAngleCube(p, stems);
        for (size_t i = 1; i < stems.size(); ++i) {
            const WeberPennStem& s = stems[i];
            if (s.length <= 0) continue;
            const Bounds3d bound = motion.moving() ? swayingBound(p, stems[0], s, cube, zs) : subtreeBound(p, s, zs);
            emitProcedural(out, ctx, std::make_shared<SubtreeGenerator>(p_, trunk, s, zs), bound);
        }
    }

  private:
    std::shared_ptr<const WeberPennParams> p_;
};

}  // namespace

// The bound of what the tree procedural makes: the trunk's and its branches' subtrees; in the wind
// the union of the bounds its parts declare (swayingBound), which the keys never leave.
Bounds3d weberPennBound(const WeberPennParams& p) {
    const double zs = zScaleOf(p);
    std::vector<WeberPennStem> stems{weberPennTrunk(p, nullptr)};
    weberPennGrowBelow(p, stems, 0, 1, nullptr);
    Bounds3d b = stillTreeBound(p, stems, zs);
    if (weberPennWindy(p)) {
        const Bounds3d cube = anyAngleCube(p, stems);
        b.extend(swayingTrunkBound(p, stems[0], cube, zs));
        for (size_t i = 1; i < stems.size(); ++i)
            if (stems[i].length > 0) b.extend(swayingBound(p, stems[0], stems[i], cube, zs));
    }
    return b;
}

std::shared_ptr<const ProceduralGenerator> makeWeberPennGenerator(const std::string& datablock, const SourceLoc& loc) {
    return std::make_shared<WeberPennTreeGenerator>(parseWeberPennParams(datablock, loc));
}

std::shared_ptr<const ProceduralGenerator> makeWeberPennGenerator(WeberPennParams p) {
    return std::make_shared<WeberPennTreeGenerator>(std::move(p));
}

Bounds3d weberPennFootBound(const WeberPennParams& p) {
    // The longest trunk the draws allow, with the widest radius; subtreeReach adds what grows on it.
    const WeberPennLevel& c = p.level[0];
    WeberPennStem trunk;
    trunk.level = 0;
    trunk.length = (p.scale + std::fabs(p.scaleV)) * (c.length + std::fabs(c.lengthV));
    trunk.radius = trunk.length * p.ratio * (p.scale0 + std::fabs(p.scale0V));
    // weberPennBound's windy cube counts a branch's leaves, radius and spline allowance on top of
    // the trunk's: those are added here once more.
    const double branch = trunk.length * (p.level[1].length + std::fabs(p.level[1].lengthV));
    const double d = trunk.length + subtreeReach(p, trunk) + p.leafScale * std::max(1.0, p.leafScaleX) * std::sqrt(1 / kWeberPennLeastQuality) +
                     2 * trunk.radius * (1 + p.flare) * (1 + p.lobeDepth) + 0.1 * branch;
    const double zs = std::max(1e-6, p.zScale + std::fabs(p.zScaleV));
    return Bounds3d({-d, -d * zs, -d}, {d, d * zs, d});
}

}  // namespace streyes
