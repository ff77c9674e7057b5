// The Weber–Penn tree procedural: a tree expands into its trunk and one procedural per
// first-level branch (bounded by how far its subtree can reach), which grows its subtree when seen.
// Stems are generalized cylinders: bicubic patch meshes, a periodic B-spline ring around
// (round, with the trunk's lobes) swept along a Catmull-Rom curve through the stem's segment
// points (so they show the stem's curvature); leaves are outline polygons (LeafShape).
#include <algorithm>
#include <cmath>

#include "procedural/weber_penn.h"
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

// One patch mesh per path of the stem (the stem and each clone). `sides` control points around;
// `extraRings` adds rings inside the first segment (the trunk's flare).
void emitStem(ProceduralOutput& out, const ExpandContext& ctx, const WeberPennParams& p, const WeberPennStem& s,
              int sides, double zs) {
    if (s.length <= 0 || s.radius <= 0) return;
    const int res = int(s.paths[0].points.size()) - 1;
    // The B-spline ring passes inside its control polygon: at a control point's angle, by
    // (4 + 2 cos(2 pi / sides)) / 6. Scale it back so the radius is the paper's.
    const double ringScale = 6 / (4 + 2 * std::cos(2 * M_PI / sides));
    for (const WeberPennStem::Path& path : s.paths) {
        struct Ring {
            Vec3d at, x;
            double z;
        };
        std::vector<Ring> rings;
        for (size_t i = 0; i < path.points.size(); ++i) {
            const double z = double(path.firstSegment + int(i)) / res;
            if (s.level == 0 && p.flare > 0 && i == 1 && path.firstSegment == 0)
                for (double f : {0.03, 0.08, 0.16, 0.3, 0.55})  // the flare lies in the trunk's first eighth
                    rings.push_back({lerp(path.points[0], path.points[1], f), path.xAxis[0], f / res});
            rings.push_back({path.points[i], path.xAxis[i], z});
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
        std::vector<Vec3d> P;
        P.reserve(size_t(m.nu * m.nv));
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
                P.push_back(squash(rings[k].at + (x * std::cos(a) + y * std::sin(a)) * (r * lobe), zs));
            }
        };
        // The first control ring: before the first (for a clone, on its parent's path, so that the
        // clone leaves the split along the curve) or the first again.
        if (path.firstSegment == 0) {
            ring(0);
        } else {
            const size_t first = P.size();
            ring(0);
            const Vec3d shift = squash(path.before - rings[0].at, zs);
            for (size_t i = first; i < P.size(); ++i) P[i] = P[i] + shift;
        }
        for (size_t k = 0; k < n; ++k) ring(long(k));
        ring(long(n) - 1);
        m.P = {std::move(P)};
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

// All the leaves of an expansion as one PointsPolygons, a colour each (the leaf colour varied).
void emitLeaves(ProceduralOutput& out, const ExpandContext& ctx, const WeberPennParams& p,
                const std::vector<WeberPennLeaf>& leaves, double quality, uint64_t key, double zs) {
    if (leaves.empty() || p.leafScale <= 0) return;
    const auto& shape = outline(p.leafShape);
    // The paper's reduction for distant trees: fewer leaves, larger, the same area.
    const double scale = p.leafScale / std::sqrt(quality);
    const double len = scale, half = 0.5 * scale * p.leafScaleX;
    PolygonMeshDesc m;
    m.request = "PointsPolygons";
    m.times = {0.0};
    m.objectToWorld = ctx.objectToWorld;
    m.attributes = ctx.attributes;
    m.loc = ctx.loc;
    m.Cs.cls = ParamClass::Uniform;
    std::vector<Vec3d> P;
    HashRng r(hashCombine(key, 0x1ea7e5));
    const size_t every = quality >= 1 ? 1 : size_t(std::lround(1 / quality));
    for (size_t i = 0; i < leaves.size(); i += every) {
        const WeberPennLeaf& l = leaves[i];
        Vec3d across = cross(l.direction, l.normal);
        across = length(across) > 1e-9 ? normalize(across) : Vec3d{1, 0, 0};
        std::vector<int> loop;
        for (const auto& [u, w] : shape) {
            loop.push_back(int(P.size()));
            P.push_back(squash(l.position + l.direction * (u * len) + across * (w * half), zs));
        }
        m.polygons.push_back({std::move(loop)});
        m.Cs.values.push_back(p.leafColor * (0.8f + 0.4f * r.nextFloat()));
    }
    m.P = {std::move(P)};
    out.scene.polygonMeshes.push_back(std::move(m));
}

int sidesOf(int level) { return level == 0 ? 8 : level == 1 ? 6 : 4; }

// A bound of a stem's subtree: its axis (every path's points) grown by how far what grows on it
// can reach: a child is at most nLength + |nLengthV| of its parent's length and lies within its
// length of its base; leaves add their largest size (quality 0.05), radii and a tenth of the stem's
// length for the spline through the axis points.
Bounds3d subtreeBound(const WeberPennParams& p, const WeberPennStem& s, double zs) {
    double reach = 0, l = s.length;
    for (int level = s.level + 1; level < p.levels; ++level) {
        const WeberPennLevel& c = p.level[size_t(std::min(level, 3))];
        l *= c.length + std::fabs(c.lengthV);
        reach += l;
    }
    const double flare = s.level == 0 ? (1 + p.flare) * (1 + p.lobeDepth) : 1;
    reach += p.leafScale * std::max(1.0, p.leafScaleX) * std::sqrt(20.0) + 2 * s.radius * flare + 0.1 * s.length;
    Bounds3d b;
    for (const auto& path : s.paths)
        for (Vec3d q : path.points) {
            b.extend(squash(q - Vec3d{reach, reach, reach}, zs));
            b.extend(squash(q + Vec3d{reach, reach, reach}, zs));
        }
    return b;
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

// The leaves' share kept at this size on screen (the paper's LeafQuality for distant trees):
// all of them while the subtree is 300 pixels across or more (times detail=), fewer below.
double qualityAt(const WeberPennParams& p, const ExpandContext& ctx) {
    const double size = std::sqrt(std::max(0.0, ctx.detail));
    return std::clamp(size * p.detail / 300, 0.05, 1.0);
}

class SubtreeGenerator final : public ProceduralGenerator {
  public:
    SubtreeGenerator(std::shared_ptr<const WeberPennParams> p, WeberPennStem stem, double zs)
        : p_(std::move(p)), stem_(std::move(stem)), zs_(zs) {}
    std::string describe() const override { return "weberpenn branch"; }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const WeberPennParams& p = *p_;
        std::vector<WeberPennStem> stems{stem_};
        std::vector<WeberPennLeaf> leaves;
        weberPennGrowBelow(p, stems, 0, p.levels, &leaves);
        // Stems under a quarter of a pixel across are left out (their leaves stay).
        const double ppu = ctx.read.pixelsPerUnit;
        for (const WeberPennStem& s : stems)
            if (s.level <= 1 || ppu <= 0 || 2 * s.radius * ppu >= 0.25 / p.detail) emitStem(out, ctx, p, s, sidesOf(s.level), zs_);
        emitLeaves(out, ctx, p, leaves, qualityAt(p, ctx), stem_.key, zs_);
    }

  private:
    std::shared_ptr<const WeberPennParams> p_;
    WeberPennStem stem_;
    double zs_;
};

class WeberPennTreeGenerator final : public ProceduralGenerator {
  public:
    explicit WeberPennTreeGenerator(WeberPennParams p) : p_(std::make_shared<const WeberPennParams>(std::move(p))) {}
    std::string describe() const override { return "DynamicLoad tree (weberpenn " + p_->name + ")"; }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const WeberPennParams& p = *p_;
        const double zs = zScaleOf(p);
        std::vector<WeberPennStem> stems{weberPennTrunk(p, nullptr)};
        weberPennGrowBelow(p, stems, 0, 1, nullptr);
        emitStem(out, ctx, p, stems[0], sidesOf(0), zs);
        if (p.levels == 1) {
            std::vector<WeberPennLeaf> leaves;
            weberPennGrowBelow(p, stems, 0, 1, &leaves);
            emitLeaves(out, ctx, p, leaves, qualityAt(p, ctx), stems[0].key, zs);
            return;
        }
        for (size_t i = 1; i < stems.size(); ++i) {
            if (stems[i].length <= 0) continue;
            emitProcedural(out, ctx, std::make_shared<SubtreeGenerator>(p_, stems[i], zs), subtreeBound(p, stems[i], zs));
        }
    }

  private:
    std::shared_ptr<const WeberPennParams> p_;
};

}  // namespace

// The bound of what the tree procedural makes: the trunk's and its branches' subtrees.
Bounds3d weberPennBound(const WeberPennParams& p) {
    const double zs = zScaleOf(p);
    std::vector<WeberPennStem> stems{weberPennTrunk(p, nullptr)};
    weberPennGrowBelow(p, stems, 0, 1, nullptr);
    WeberPennParams trunkOnly = p;
    trunkOnly.levels = std::min(p.levels, 1);  // the trunk's own reach (its leaves when it has them)
    Bounds3d b = subtreeBound(trunkOnly, stems[0], zs);
    for (size_t i = 1; i < stems.size(); ++i) b.extend(subtreeBound(p, stems[i], zs));
    return b;
}

std::shared_ptr<const ProceduralGenerator> makeWeberPennGenerator(const std::string& datablock, const SourceLoc& loc) {
    return std::make_shared<WeberPennTreeGenerator>(parseWeberPennParams(datablock, loc));
}

}  // namespace streyes
