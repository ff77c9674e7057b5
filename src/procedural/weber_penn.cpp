// Weber–Penn trees: parameters, the paper's presets, and growing the stems (the paper's formulas).
// The procedural that renders them is weber_penn_procedural.cpp.
#include "procedural/weber_penn.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "procedural/number_list.h"
#include "util/sampling.h"

namespace streyes {

namespace {

constexpr double kDeg = M_PI / 180;
const Vec3d kUp{0, 1, 0};

// A number in [-1, 1): the paper's "±" (x ± xV is x + xV * u).
double pm(HashRng& r) { return 2 * double(r.nextFloat()) - 1; }

// Rodrigues: v turned about the unit axis a by angle (radians).
Vec3d turn(Vec3d v, Vec3d a, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + cross(a, v) * s + a * (dot(a, v) * (1 - c));
}

const WeberPennLevel& column(const WeberPennParams& p, int n) { return p.level[size_t(std::clamp(n, 0, 3))]; }

int rounded(double x) { return x > 0 ? int(std::lround(x)) : 0; }

// ---- Presets: the paper's table ----------------------------------------------------------------

WeberPennLevel lv(double downAngle, double downAngleV, double rotate, double rotateV, double length, double lengthV,
                  double segSplits, double splitAngle, double splitAngleV, int curveRes, double curve, double curveBack,
                  double curveV, double branches) {
    WeberPennLevel l;
    l.downAngle = downAngle, l.downAngleV = downAngleV, l.rotate = rotate, l.rotateV = rotateV;
    l.length = length, l.lengthV = lengthV, l.taper = 1, l.segSplits = segSplits;
    l.splitAngle = splitAngle, l.splitAngleV = splitAngleV, l.curveRes = curveRes;
    l.curve = curve, l.curveBack = curveBack, l.curveV = curveV, l.branches = branches;
    return l;
}

std::vector<WeberPennParams> makePresets() {
    std::vector<WeberPennParams> v;
    {
        WeberPennParams p;
        p.name = "quaking_aspen";
        p.shape = 7, p.baseSize = 0.4, p.scale = 13, p.scaleV = 3, p.levels = 3, p.ratio = 0.015, p.ratioPower = 1.2;
        p.lobes = 5, p.lobeDepth = 0.07, p.flare = 0.6;
        p.level = {lv(0, 0, 0, 0, 1, 0, 0, 0, 0, 3, 0, 0, 20, 0), lv(60, -50, 140, 0, 0.3, 0, 0, 0, 0, 5, -40, 0, 50, 50),
                   lv(45, 10, 140, 0, 0.6, 0, 0, 0, 0, 3, -40, 0, 75, 30), lv(45, 10, 77, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 10)};
        p.leaves = 25, p.leafShape = 0, p.leafScale = 0.17, p.leafScaleX = 1, p.attractionUp = 0.5;
        p.barkColor = {0.55f, 0.53f, 0.45f}, p.leafColor = {0.35f, 0.52f, 0.14f};
        v.push_back(p);
    }
    {
        WeberPennParams p;
        p.name = "black_tupelo";
        p.shape = 4, p.baseSize = 0.2, p.scale = 23, p.scaleV = 5, p.levels = 4, p.ratio = 0.015, p.ratioPower = 1.3;
        p.lobes = 3, p.lobeDepth = 0.1, p.flare = 1;
        p.level = {lv(0, 0, 0, 0, 1, 0, 0, 0, 0, 10, 0, 0, 40, 0), lv(60, -40, 140, 0, 0.3, 0.05, 0, 0, 0, 10, 0, 0, 90, 50),
                   lv(30, 10, 140, 0, 0.6, 0.1, 0, 0, 0, 10, -10, 0, 150, 25), lv(45, 10, 140, 0, 0.4, 0, 0, 0, 0, 1, 0, 0, 0, 12)};
        p.leaves = 6, p.leafShape = 1, p.leafScale = 0.3, p.leafScaleX = 0.5, p.attractionUp = 0.5;
        p.barkColor = {0.3f, 0.25f, 0.22f}, p.leafColor = {0.2f, 0.4f, 0.1f};
        v.push_back(p);
    }
    {
        WeberPennParams p;
        p.name = "weeping_willow";
        p.shape = 3, p.baseSize = 0.05, p.scale = 15, p.scaleV = 5, p.levels = 4, p.ratio = 0.03, p.ratioPower = 2;
        p.lobes = 9, p.lobeDepth = 0.03, p.flare = 0.75, p.baseSplits = 2;
        p.level = {lv(0, 0, 0, 0, 0.8, 0, 0.1, 3, 0, 8, 0, 20, 120, 0), lv(20, 10, -120, 30, 0.5, 0.1, 0.1, 30, 10, 10, 40, 80, 90, 25),
                   lv(30, 10, -120, 30, 1.5, 0, 0.2, 45, 20, 6, 0, 0, 0, 10), lv(20, 10, 140, 0, 0.1, 0, 0, 0, 0, 1, 0, 0, 0, 300)};
        p.leaves = 15, p.leafShape = 2, p.leafScale = 0.12, p.leafScaleX = 0.2, p.attractionUp = -3;
        p.barkColor = {0.36f, 0.31f, 0.24f}, p.leafColor = {0.42f, 0.55f, 0.16f};
        v.push_back(p);
    }
    {
        WeberPennParams p;
        p.name = "ca_black_oak";
        p.shape = 2, p.baseSize = 0.05, p.scale = 10, p.scaleV = 10, p.levels = 3, p.ratio = 0.018, p.ratioPower = 1.3;
        p.lobes = 5, p.lobeDepth = 0.1, p.flare = 1.2, p.baseSplits = 2;
        p.level = {lv(0, 0, 0, 0, 1, 0, 0.4, 10, 0, 8, 0, 0, 90, 0), lv(30, -30, 80, 0, 0.8, 0.1, 0.2, 10, 10, 10, 40, -70, 150, 40),
                   lv(45, 10, 140, 0, 0.2, 0.05, 0.1, 10, 10, 3, 0, 0, -30, 120), lv(45, 10, 140, 0, 0.4, 0, 0, 0, 0, 1, 0, 0, 0, 0)};
        p.leaves = 25, p.leafShape = 1, p.leafScale = 0.12, p.leafScaleX = 0.66, p.attractionUp = 0.8;
        p.barkColor = {0.22f, 0.2f, 0.18f}, p.leafColor = {0.18f, 0.34f, 0.1f};
        v.push_back(p);
    }
    return v;
}

const std::vector<WeberPennParams>& presets() {
    static const std::vector<WeberPennParams> all = makePresets();
    return all;
}

// ---- Growing a stem's axis ------------------------------------------------------------------------

struct Frame {
    Vec3d x, z;  // across (the axis curvature turns about) and along
};

// The stem's segments from its base: curvature (nCurve, nCurveBack, nCurveV), AttractionUp (level
// 2 and above) and splitting into clones (0BaseSplits at the trunk's first segment, nSegSplits
// elsewhere, their fractions carried over: the paper's error diffusion).
void growAxis(const WeberPennParams& p, WeberPennStem& s, Vec3d base, Frame f0, HashRng& r) {
    const WeberPennLevel& c = column(p, s.level);
    const int res = std::max(1, c.curveRes);
    const double segLength = s.length / res;
    constexpr size_t kMaxPaths = 32;  // clones of one stem, so that nSegSplits >= 1 cannot explode
    struct Open {
        size_t path;
        int segment;
        Vec3d at;
        Frame f;
    };
    double splitError = 0;
    s.paths.assign(1, {});
    s.paths[0].before = base;
    std::vector<Open> open{{0, 0, base, f0}};
    while (!open.empty()) {
        Open o = open.back();
        open.pop_back();
        WeberPennStem::Path* path = &s.paths[o.path];
        path->firstSegment = o.segment;
        path->points.push_back(o.at);
        path->xAxis.push_back(o.f.x);
        for (int i = o.segment; i < res; ++i) {
            // Curvature of segment i, about the stem's x axis.
            double bend = c.curveBack == 0 ? c.curve / res
                                           : (i < (res + 1) / 2 ? c.curve / std::max(1, res / 2)
                                                                : c.curveBack / std::max(1, res / 2));
            if (c.curveV > 0) bend += pm(r) * c.curveV / res;  // nCurveV < 0: a helix, drawn by emitStem
            Frame& f = o.f;
            f.z = normalize(turn(f.z, f.x, bend * kDeg));
            if (s.level >= 2 && p.attractionUp != 0) {
                // The paper's curve_up_segment: declination times the share of the bend axis lying up.
                const double declination = std::acos(std::clamp(dot(f.z, kUp), -1.0, 1.0));
                const Vec3d y = cross(f.z, f.x);
                double up = p.attractionUp * declination * std::fabs(dot(y, kUp)) / res;
                up = std::clamp(up, declination - M_PI, declination);  // never past straight up or down
                const Vec3d axis = cross(f.z, kUp);
                if (length(axis) > 1e-9) {
                    const Vec3d a = normalize(axis);
                    f.z = normalize(turn(f.z, a, up));
                    f.x = normalize(turn(f.x, a, up));
                }
            }
            f.x = normalize(f.x - f.z * dot(f.x, f.z));
            o.at = o.at + f.z * segLength;
            path = &s.paths[o.path];
            path->points.push_back(o.at);
            path->xAxis.push_back(f.x);
            if (i + 1 >= res) break;
            int splits;
            if (s.level == 0 && i == 0 && p.baseSplits > 0) {
                splits = p.baseSplits;
            } else {
                splits = int(std::lround(c.segSplits + splitError));
                splitError -= splits - c.segSplits;
            }
            splits = std::min(splits, int(kMaxPaths - s.paths.size()));
            if (splits <= 0) continue;
            const double declination = std::acos(std::clamp(dot(f.z, kUp), -1.0, 1.0)) / kDeg;
            const double angleSplit = std::max(0.0, c.splitAngle + pm(r) * c.splitAngleV - declination);
            const Frame bent{f.x, normalize(turn(f.z, f.x, angleSplit * kDeg))};
            for (int k = 0; k <= splits; ++k) {
                // The stem keeps k = 0; clones spread about the vertical: evenly at the base,
                // else by the paper's 20 + 0.75 (30 + |declination - 90|) r^2, alternating sides.
                double spread = 0;
                if (k > 0) {
                    if (s.level == 0 && i == 0 && p.baseSplits > 0) {
                        spread = 360.0 * k / (splits + 1);
                    } else {
                        const double u = double(r.nextFloat());
                        spread = (20 + 0.75 * (30 + std::fabs(declination - 90)) * u * u) * (k % 2 ? 1 : -1);
                    }
                }
                const Frame g{normalize(turn(bent.x, kUp, spread * kDeg)), normalize(turn(bent.z, kUp, spread * kDeg))};
                if (k == 0) {
                    f = g;
                } else {
                    WeberPennStem::Path clone;
                    clone.before = s.paths[o.path].points[s.paths[o.path].points.size() - 2];
                    clone.from = int(o.path);
                    s.paths.push_back(clone);
                    open.push_back({s.paths.size() - 1, i + 1, o.at, g});
                    path = &s.paths[o.path];
                }
            }
        }
    }
}

// Where along the stem (path length `offset` from its base) a child sits: the point and frame of
// the segment there, on path `pick` among those that reach it.
void placeOn(const WeberPennStem& s, double offset, int pick, Vec3d* at, Frame* f, int* onPath = nullptr,
             int* onSegment = nullptr) {
    const int res = int(s.paths[0].points.size()) - 1;
    const double segLength = s.length / std::max(1, res);
    const double u = segLength > 0 ? offset / segLength : 0;
    const int k = std::clamp(int(u), 0, res - 1);
    std::vector<const WeberPennStem::Path*> reach;
    for (const auto& path : s.paths)
        if (path.firstSegment <= k) reach.push_back(&path);
    const WeberPennStem::Path& path = *reach[size_t(pick) % reach.size()];
    const size_t i = size_t(k - path.firstSegment);
    const Vec3d a = path.points[i], b = path.points[i + 1];
    *at = lerp(a, b, std::clamp(u - k, 0.0, 1.0));
    f->z = length(b - a) > 0 ? normalize(b - a) : kUp;
    f->x = normalize(path.xAxis[i] - f->z * dot(path.xAxis[i], f->z));
    if (onPath) *onPath = int(&path - s.paths.data());
    if (onSegment) *onSegment = k;
}

// The frame of a child of `parent` (frame pf) rotated `rotate` about the parent and tilted `down`
// from it (degrees).
Frame childFrame(const Frame& pf, double rotate, double down) {
    const Vec3d a = normalize(turn(pf.x, pf.z, rotate * kDeg));
    return {a, normalize(turn(pf.z, a, down * kDeg))};
}

// The paper's nDownAngle: fixed ± nDownAngleV, or (nDownAngleV < 0) varying along the parent.
double downAngle(const WeberPennLevel& c, const WeberPennStem& parent, double offset, HashRng& r) {
    if (c.downAngleV >= 0) return c.downAngle + pm(r) * c.downAngleV;
    const double span = parent.length - parent.baseLength;
    const double ratio = span > 0 ? (parent.length - offset) / span : 0;
    return c.downAngle + pm(r) * c.downAngleV * (1 - 2 * weberPennShapeRatio(0, ratio));
}

// nRotate: accumulated; negative values alternate sides.
double nextRotate(const WeberPennLevel& c, double* acc, HashRng& r) {
    if (c.rotate < 0)
        *acc = -std::copysign(std::fabs(c.rotate), *acc == 0 ? -1.0 : *acc);
    else
        *acc += c.rotate;
    return *acc + pm(r) * c.rotateV;
}

// The paper's pruning of a stem of level >= 1: with the same random draws a shorter stem is the
// same axis scaled about its base, so the largest length whose segment points all lie inside the
// envelope is searched on scaled copies (32 steps down, then bisection), and the stem regrown at
// full + (pruned - full) PruneRatio. A stem whose base lies outside prunes to nothing.
void growPruned(const WeberPennParams& p, WeberPennStem& s, Vec3d base, const Frame& f, HashRng& r) {
    const double scaleTree = weberPennScaleTree(p);
    const HashRng start = r;
    growAxis(p, s, base, f, r);
    auto fits = [&](const WeberPennStem& stem, double scale) {
        for (const auto& path : stem.paths)
            for (Vec3d q : path.points)
                if (!weberPennInsideEnvelope(p, scaleTree, base + (q - base) * scale)) return false;
        return true;
    };
    if (fits(s, 1)) return;
    const double full = s.length;
    double lo = 0, hi = 1;
    for (int k = 31; k >= 1; --k) {
        if (fits(s, k / 32.0)) {
            lo = k / 32.0;
            break;
        }
        hi = k / 32.0;
    }
    if (lo > 0 || fits(s, 0))
        for (int i = 0; i < 24; ++i) (fits(s, 0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
    double pruned = lo * full;
    for (int attempt = 0;; ++attempt) {
        s.length = full + (pruned - full) * p.pruneRatio;
        s.paths.clear();
        r = start;
        growAxis(p, s, base, f, r);
        // Regrown points differ from the scaled ones by rounding: at PruneRatio 1 shrink until they fit.
        if (p.pruneRatio < 1 || pruned <= 0 || fits(s, 1)) break;
        pruned = attempt < 8 ? pruned * (1 - 1e-9 * std::pow(10.0, attempt)) : 0;
    }
}

// Child j of n, offset `offset` along its parent.
WeberPennStem makeChild(const WeberPennParams& p, const WeberPennStem& parent, double offset, double rotate, int j) {
    WeberPennStem s;
    s.level = parent.level + 1;
    s.key = hashCombine(parent.key, uint64_t(j) + 1);
    HashRng r(s.key);
    const WeberPennLevel& c = column(p, s.level);
    s.offset = offset;
    s.parentLength = parent.length;
    s.lengthChildMax = c.length + pm(r) * c.lengthV;
    if (s.level == 1) {
        const double span = parent.length - parent.baseLength;
        s.length = parent.length * s.lengthChildMax *
                   weberPennShapeRatio(p.shape, span > 0 ? (parent.length - offset) / span : 0);
    } else {
        s.length = s.lengthChildMax * (parent.length - 0.6 * offset);
    }
    s.length = std::max(0.0, s.length);
    Vec3d at;
    Frame pf;
    placeOn(parent, offset, j, &at, &pf, &s.parentPath, &s.parentSegment);
    const Frame f = childFrame(pf, rotate, downAngle(c, parent, offset, r));
    s.direction = f.z;
    const bool pruned = p.pruneRatio > 0 && s.length > 0;
    if (pruned) growPruned(p, s, at, f, r);
    else if (s.length > 0) growAxis(p, s, at, f, r);
    if (s.length <= 0) s.paths.assign(1, WeberPennStem::Path{0, at, {at, at}, {f.x, f.x}, 0});
    // The radius and the stems it carries follow the (pruned) length.
    s.radius = parent.length > 0 ? parent.radius * std::pow(s.length / parent.length, p.ratioPower) : 0;
    s.radius = std::min(s.radius, weberPennRadiusAt(p, parent, parent.length > 0 ? offset / parent.length : 0));
    if (s.level < p.levels - 1) {
        const double most = column(p, s.level + 1).branches;
        s.children = s.level == 1
                         ? rounded(most * (0.2 + 0.8 * (s.length / parent.length) / s.lengthChildMax))
                         : rounded(most * (1.0 - 0.5 * offset / parent.length));
        if (s.lengthChildMax == 0) s.children = 0;
    } else {
        s.leaves = rounded(p.leaves * weberPennShapeRatio(4, parent.length > 0 ? offset / parent.length : 0));
    }
    if (pruned && s.length <= 0) s.children = s.leaves = 0;  // pruned away: nothing grows on it
    return s;
}

// Evenly along the stem: beyond the trunk's base_length, anywhere along the others.
double childOffset(const WeberPennStem& s, int j, int n) {
    return s.baseLength + (s.length - s.baseLength) * (j + 0.5) / n;
}

}  // namespace

double weberPennShapeRatio(int shape, double ratio) {
    switch (shape) {
    case 0: return 0.2 + 0.8 * ratio;                                   // conical
    case 1: return 0.2 + 0.8 * std::sin(M_PI * ratio);                  // spherical
    case 2: return 0.2 + 0.8 * std::sin(0.5 * M_PI * ratio);            // hemispherical
    case 3: return 1.0;                                                 // cylindrical
    case 4: return 0.5 + 0.5 * ratio;                                   // tapered cylindrical
    case 5: return ratio <= 0.7 ? ratio / 0.7 : (1 - ratio) / 0.3;      // flame
    case 6: return 1.0 - 0.8 * ratio;                                   // inverse conical
    default: return ratio <= 0.7 ? 0.5 + 0.5 * ratio / 0.7 : 0.5 + 0.5 * (1 - ratio) / 0.3;  // 7: tend flame
    }
}

double weberPennEnvelope(const WeberPennParams& p, double ratio) {
    if (!(ratio >= 0 && ratio <= 1)) return 0;
    const double peak = p.pruneWidthPeak;
    if (ratio < 1 - peak) return std::pow(ratio / (1 - peak), p.prunePowerHigh);
    return peak > 0 ? std::pow((1 - ratio) / peak, p.prunePowerLow) : 1;
}

bool weberPennInsideEnvelope(const WeberPennParams& p, double scaleTree, Vec3d q) {
    const double ratio = (scaleTree - q.y) / (scaleTree * (1 - p.baseSize));
    return std::hypot(q.x, q.z) / scaleTree < p.pruneWidth * weberPennEnvelope(p, ratio);
}

void weberPennBendLeaf(double leafBend, WeberPennLeaf* leaf) {
    WeberPennLeaf& l = *leaf;
    const Vec3d n = l.normal;
    if (std::hypot(l.position.x, l.position.z) > 0 && std::hypot(n.x, n.z) > 0) {
        // About -y: the turn that increases atan2(z, x), the azimuth in the ground plane.
        const double theta = std::remainder(std::atan2(l.position.z, l.position.x) - std::atan2(n.z, n.x), 2 * M_PI);
        const Vec3d down{0, -1, 0};
        l.direction = normalize(turn(l.direction, down, leafBend * theta));
        l.normal = normalize(turn(l.normal, down, leafBend * theta));
    }
    const Vec3d across = cross(l.direction, l.normal);
    if (length(across) < 1e-12) return;
    const Vec3d a = normalize(across);
    const double phi = std::atan2(std::hypot(l.normal.x, l.normal.z), l.normal.y);
    const double towardUp = dot(cross(a, l.normal), kUp) >= 0 ? 1 : -1;
    l.direction = normalize(turn(l.direction, a, towardUp * leafBend * phi));
    l.normal = normalize(turn(l.normal, a, towardUp * leafBend * phi));
}

double weberPennScaleTree(const WeberPennParams& p) {
    HashRng r(mix64(p.seed ^ 0x57e9be4ULL));  // the trunk's generator: its first draw
    return p.scale + pm(r) * p.scaleV;
}

const WeberPennParams* weberPennPreset(const std::string& name) {
    for (const WeberPennParams& p : presets())
        if (p.name == name) return &p;
    return nullptr;
}

std::vector<std::string> weberPennPresetNames() {
    std::vector<std::string> names;
    for (const WeberPennParams& p : presets()) names.push_back(p.name);
    return names;
}

double weberPennRadiusAt(const WeberPennParams& p, const WeberPennStem& s, double z) {
    z = std::clamp(z, 0.0, 1.0);
    const double t = column(p, s.level).taper;
    const double unit = t < 1 ? t : t < 2 ? 2 - t : 0;
    const double taperZ = s.radius * (1 - unit * z);
    double rz = taperZ;
    if (t >= 1 && taperZ > 0) {
        const double z2 = (1 - z) * s.length;
        const double depth = (t < 2 || z2 < taperZ) ? 1 : t - 2;
        const double z3 = t < 2 ? z2 : std::fabs(z2 - 2 * taperZ * std::floor(z2 / (2 * taperZ) + 0.5));
        if (!(t < 2 && z3 >= taperZ))
            rz = (1 - depth) * taperZ + depth * std::sqrt(std::max(0.0, taperZ * taperZ - (z3 - taperZ) * (z3 - taperZ)));
    }
    if (s.level == 0) {
        const double y = std::max(0.0, 1 - 8 * z);
        rz *= p.flare * (std::pow(100.0, y) - 1) / 100 + 1;
    }
    return rz;
}

WeberPennStem weberPennTrunk(const WeberPennParams& p, double* scaleTree) {
    WeberPennStem s;
    s.key = mix64(p.seed ^ 0x57e9be4ULL);
    HashRng r(s.key);
    const double scale = p.scale + pm(r) * p.scaleV;
    const WeberPennLevel& c = column(p, 0);
    s.lengthChildMax = c.length + pm(r) * c.lengthV;
    s.length = std::max(0.0, s.lengthChildMax * scale);
    s.radius = s.length * p.ratio * (p.scale0 + pm(r) * p.scale0V);
    s.baseLength = p.baseSize * scale;
    if (p.levels > 1) s.children = rounded(column(p, 1).branches);
    else s.leaves = rounded(p.leaves);
    if (s.length > 0) growAxis(p, s, {0, 0, 0}, {{1, 0, 0}, kUp}, r);
    else s.paths.assign(1, WeberPennStem::Path{0, {}, {{}, {}}, {{1, 0, 0}, {1, 0, 0}}, 0});
    if (scaleTree) *scaleTree = scale;
    return s;
}

WeberPennReduction weberPennReduction(const WeberPennParams& p, double quality) {
    WeberPennReduction r;
    const double q = std::clamp(quality, kWeberPennLeastQuality, 1.0);
    if (p.levels - 1 >= 2) r.stemStep = std::max(1, int(std::floor(1 / std::sqrt(q) + 1e-9)));
    r.leafStep = std::max(1, int(std::lround(1 / (q * r.stemStep))));
    return r;
}

void weberPennGrowBelow(const WeberPennParams& p, std::vector<WeberPennStem>& stems, size_t index, int lastLevel,
                        std::vector<WeberPennLeaf>* leaves, const WeberPennReduction& reduce) {
    const int level = stems[index].level;
    if (level >= lastLevel) return;
    if (level + 1 < p.levels) {
        double acc = 0;
        HashRng r(hashCombine(stems[index].key, 0x707a7e));
        const int n = stems[index].children;
        // The last stem level (2 or deeper) keeps every stemStep-th stem; the rotation is drawn for
        // every one, so that those kept are where the full tree has them.
        const int step = level + 1 == p.levels - 1 && level + 1 >= 2 ? reduce.stemStep : 1;
        const size_t leavesBefore = leaves ? leaves->size() : 0;
        for (int j = 0; j < n; ++j) {
            const WeberPennStem& s = stems[index];
            const double rot = nextRotate(column(p, level + 1), &acc, r);
            if (j % step != 0) continue;
            WeberPennStem child = makeChild(p, s, childOffset(s, j, n), rot, j);
            child.parent = int(index);
            stems.push_back(std::move(child));
            weberPennGrowBelow(p, stems, stems.size() - 1, lastLevel, leaves, reduce);
        }
        if (step > 1 && leaves) {
            // The leaves of the kept stems stand for those of the stems left out: their area by n / kept.
            const double share = double(n) / double((n + step - 1) / step);
            for (size_t i = leavesBefore; i < leaves->size(); ++i) (*leaves)[i].grow *= std::sqrt(share);
        }
    } else if (leaves) {
        // Leaves along the last level's stems, turned and tilted by column Levels.
        const WeberPennStem& s = stems[index];
        const WeberPennLevel& c = column(p, p.levels);
        HashRng r(hashCombine(s.key, 0x1eaf));
        double acc = 0;
        const int step = reduce.leafStep;
        const double grow = std::sqrt(double(s.leaves) / double(std::max(1, (s.leaves + step - 1) / step)));
        for (int j = 0; j < s.leaves; ++j) {
            const double rot = nextRotate(c, &acc, r);
            const double down = c.downAngle + pm(r) * std::fabs(c.downAngleV);
            if (j % step != 0) continue;  // after its draws: the next leaf is the full tree's
            Vec3d at;
            Frame pf;
            WeberPennLeaf l;
            placeOn(s, childOffset(s, j, s.leaves), j, &at, &pf, &l.path, &l.segment);
            const Frame f = childFrame(pf, rot, down);
            l.position = at;
            l.direction = f.z;
            l.normal = normalize(cross(f.z, f.x));
            if (p.leafBend != 0) weberPennBendLeaf(p.leafBend, &l);
            l.stem = int(index);
            l.grow = grow;
            leaves->push_back(l);
        }
    }
}

WeberPennTree growWeberPenn(const WeberPennParams& p, const WeberPennReduction& reduce) {
    WeberPennTree t;
    t.params = p;
    t.stems.push_back(weberPennTrunk(p, &t.scaleTree));
    weberPennGrowBelow(p, t.stems, 0, p.levels, &t.leaves, reduce);
    return t;
}

// ---- Parameters -------------------------------------------------------------------------------------

bool isWeberPennDatablock(const std::string& datablock) {
    std::istringstream in(datablock);
    std::string item;
    while (in >> item)
        if (item == "model=weberpenn" || item == "model=weber-penn") return true;
    return false;
}

WeberPennParams parseWeberPennParams(const std::string& datablock, const SourceLoc& loc) {
    // The preset first (wherever it is written), then the parameters over it.
    WeberPennParams p;
    std::vector<std::pair<std::string, std::string>> items;
    {
        std::istringstream in(datablock);
        std::string item;
        while (in >> item) {
            const size_t eq = item.find('=');
            if (eq == std::string::npos || eq == 0)
                throw InputError(loc, "tree: expected key=value, got '" + item + "'");
            items.emplace_back(item.substr(0, eq), item.substr(eq + 1));
        }
    }
    for (const auto& [key, value] : items)
        if (key == "preset") {
            const WeberPennParams* preset = weberPennPreset(value);
            if (!preset) {
                std::string names;
                for (const std::string& n : weberPennPresetNames()) names += (names.empty() ? "" : ", ") + n;
                throw InputError(loc, "tree: preset must be one of " + names + ", not '" + value + "'");
            }
            p = *preset;
        }
    auto numbers = [&](const std::string& key, const std::string& value, size_t n) {
        return parseNumberList("tree", key, value, n, loc);
    };
    for (const auto& item : items) {
        // Named copies, not a structured binding: C++17 lambdas cannot capture those (clang refuses).
        const std::string& key = item.first;
        const std::string& value = item.second;
        auto one = [&](double lo, double hi) {
            const double v = numbers(key, value, 1)[0];
            if (!(v >= lo && v <= hi))
                throw InputError(loc, "tree: " + key + " must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                          "], got " + value);
            return v;
        };
        auto color = [&]() {
            auto c = numbers(key, value, 3);
            return Color{float(c[0]), float(c[1]), float(c[2])};
        };
        if (key == "model" && value != "weberpenn" && value != "weber-penn")
            throw InputError(loc, "tree: model must be simple (the default) or weberpenn, not '" + value + "'");
        if (key == "model" || key == "preset") continue;
        if (key == "seed") p.seed = uint64_t(one(0, 1e15));
        else if (key == "Shape") p.shape = int(one(0, 7));
        else if (key == "BaseSize") p.baseSize = one(0, 1);
        else if (key == "Scale") p.scale = one(1e-6, 1e6);
        else if (key == "ScaleV") p.scaleV = one(0, 1e6);
        else if (key == "ZScale") p.zScale = one(1e-6, 1e6);
        else if (key == "ZScaleV") p.zScaleV = one(0, 1e6);
        else if (key == "Levels") p.levels = int(one(1, 4));
        else if (key == "Ratio") p.ratio = one(0, 1);
        else if (key == "RatioPower") p.ratioPower = one(0, 10);
        else if (key == "Lobes") p.lobes = int(one(0, 32));
        else if (key == "LobeDepth") p.lobeDepth = one(0, 1);
        else if (key == "Flare") p.flare = one(0, 10);
        else if (key == "0Scale") p.scale0 = one(0, 1e6);
        else if (key == "0ScaleV") p.scale0V = one(0, 1e6);
        else if (key == "0BaseSplits") p.baseSplits = int(one(0, 31));
        else if (key == "Leaves") p.leaves = one(0, 1e5);
        else if (key == "LeafShape") p.leafShape = int(one(0, 2));
        else if (key == "LeafScale") p.leafScale = one(0, 1e3);
        else if (key == "LeafScaleX") p.leafScaleX = one(0, 1e3);
        else if (key == "LeafBend") p.leafBend = one(0, 1);
        else if (key == "AttractionUp") p.attractionUp = one(-100, 100);
        else if (key == "WindSpeed") p.windSpeed = one(0, 1e4);
        else if (key == "WindGust") p.windGust = one(0, 1e4);
        else if (key == "windtime") p.windTime = one(0, 1e9);
        else if (key == "keystep") p.keyStep = one(1e-3, 1e9);
        else if (key == "PruneRatio") p.pruneRatio = one(0, 1);
        else if (key == "PruneWidth") p.pruneWidth = one(0, 1e3);
        else if (key == "PruneWidthPeak") p.pruneWidthPeak = one(0, 1);
        else if (key == "PrunePowerLow") p.prunePowerLow = one(0, 100);
        else if (key == "PrunePowerHigh") p.prunePowerHigh = one(0, 100);
        else if (key == "barkcolor") p.barkColor = color();
        else if (key == "leafcolor") p.leafColor = color();
        else if (key == "detail") p.detail = one(1e-6, 1e9);
        else if (key.size() > 1 && key[0] >= '0' && key[0] <= '3') {
            WeberPennLevel& l = p.level[size_t(key[0] - '0')];
            const std::string name = key.substr(1);
            if (name == "DownAngle") l.downAngle = one(-360, 360);
            else if (name == "DownAngleV") l.downAngleV = one(-360, 360);
            else if (name == "Rotate") l.rotate = one(-360, 360);
            else if (name == "RotateV") l.rotateV = one(-360, 360);
            else if (name == "Length") l.length = one(0, 1e3);
            else if (name == "LengthV") l.lengthV = one(0, 1e3);
            else if (name == "Taper") l.taper = one(0, 3);
            else if (name == "SegSplits") l.segSplits = one(0, 10);
            else if (name == "SplitAngle") l.splitAngle = one(-360, 360);
            else if (name == "SplitAngleV") l.splitAngleV = one(0, 360);
            else if (name == "CurveRes") l.curveRes = int(one(1, 64));
            else if (name == "Curve") l.curve = one(-3600, 3600);
            else if (name == "CurveBack") l.curveBack = one(-3600, 3600);
            else if (name == "CurveV") l.curveV = one(-3600, 3600);
            else if (name == "Branches") l.branches = one(0, 1e4);
            else throw InputError(loc, "tree: unknown parameter '" + key + "' (model=weberpenn)");
        } else {
            throw InputError(loc, "tree: unknown parameter '" + key + "' (model=weberpenn)");
        }
    }
    return p;
}

}  // namespace streyes
