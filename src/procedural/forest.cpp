#include "procedural/forest.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>

#include "procedural/weber_penn.h"
#include "procedural/number_list.h"
#include "util/sampling.h"

namespace streyes {

// The attribute states of shaders=' bark and leaves, made once per parent state (a procedural's),
// so that every tree shares them and the renderer binds each shader once.
struct ForestLooks {
    AttributesPtr of(const AttributesPtr& parent, bool leaf, const ForestParams& f) {
        std::lock_guard<std::mutex> lock(mutex);
        Entry& e = made[parent.get()];
        AttributesPtr& slot = leaf ? e.leaf : e.bark;
        if (!slot) {
            e.parent = parent;
            auto a = std::make_shared<Attributes>(parent ? *parent : Attributes{});
            auto color = [&](const char* name, Color c) {
                Param p;
                p.name = name;
                p.type = ParamType::Color;
                p.nums = {c.x, c.y, c.z};
                p.loc = a->surface.loc;
                return p;
            };
            ShaderDesc s;
            s.name = leaf ? f.leafShader : f.barkShader;
            s.loc = a->surface.loc;
            s.shaderToWorld = a->surface.shaderToWorld;
            // White bases: the tree's colour (Cs) tints them.
            if (leaf && s.name == "leaf")
                s.params.params = {color("leafcolor", {1, 1, 1}), color("veincolor", {1.6f, 1.5f, 1.1f})};
            if (!leaf && s.name == "bark")
                s.params.params = {color("lightbark", {1.5f, 1.5f, 1.5f}), color("darkbark", {0.45f, 0.45f, 0.45f})};
            a->surface = std::move(s);
            slot = std::move(a);
        }
        return slot;
    }

  private:
    struct Entry {
        AttributesPtr parent, bark, leaf;  // the parent kept alive: its address is the key
    };
    std::mutex mutex;
    std::map<const Attributes*, Entry> made;
};

namespace {

// ---- Species ------------------------------------------------------------------------------------

// What a species is, in numbers. Beyond them a species is its crown's shape: a cone of tiered
// branches carrying needle sprays, or a round crown whose branches reach for its outer part and
// carry leaves there.
struct Species {
    const char* name;               // tree's kind=, and the order of forest's species= shares
    bool cone;                      // a cone of tiers and needles; otherwise a round crown
    double height[2];               // uniform in this range, metres
    double crownBase[2];            // share of the height, uniform in this range
    double crownRadius[2];          // share of the height, uniform in this range
    double trunkTop;                // share of the height; 0: the trunk ends at the crown base
    double trunkRadius;             // share of the height
    Color bark;
    Color leaf, leafVariation;      // leaf + leafVariation * v, v uniform in [0, 1)
    // Round crowns: branches + nextBelow(branchesSpread) branches, from the trunk's top or from
    // anywhere in the crown's lower part, each with leavesPerBranch leaves.
    int branches, branchesSpread;
    bool branchesFromTrunkTop;
    int leavesPerBranch;
};

const Species kSpecies[] = {
    {"conifer", true, {8, 22}, {0.15, 0.3}, {0.17, 0.25}, 0.97, 0.018, {0.22f, 0.16f, 0.11f},
     {0.08f, 0.22f, 0.07f}, {0.08f, 0.12f, 0.06f}, 0, 0, false, 0},
    {"broadleaf", false, {8, 18}, {0.35, 0.5}, {0.25, 0.33}, 0, 0.018, {0.3f, 0.22f, 0.15f},
     {0.18f, 0.4f, 0.08f}, {0.15f, 0.18f, 0.1f}, 4, 3, true, 110},
    {"birch", false, {10, 20}, {0.35, 0.5}, {0.13, 0.18}, 0.85, 0.012, {0.82f, 0.82f, 0.78f},
     {0.42f, 0.58f, 0.14f}, {0.15f, 0.1f, 0.1f}, 6, 4, false, 49},
};
constexpr int kSpeciesCount = int(sizeof kSpecies / sizeof kSpecies[0]);
static_assert(kSpeciesCount == int(sizeof ForestParams::mix / sizeof ForestParams::mix[0]),
              "forest's species= takes a share per species");

std::string speciesNames(const std::string& separator) {
    std::string names;
    for (const Species& sp : kSpecies) names += (names.empty() ? "" : separator) + sp.name;
    return names;
}

// ---- Parameters ---------------------------------------------------------------------------------

std::vector<double> numbersOf(const std::string& key, const std::string& value, size_t n, const SourceLoc& loc) {
    return parseNumberList("forest", key, value, n, loc);
}

// Reads key=value pairs; `extra` handles keys only a single tree takes.
template <typename Extra>
ForestParams parseParams(const std::string& datablock, const SourceLoc& loc, Extra extra) {
    ForestParams f;
    std::istringstream in(datablock);
    std::string item;
    while (in >> item) {
        size_t eq = item.find('=');
        if (eq == std::string::npos || eq == 0)
            throw InputError(loc, "forest: expected key=value, got '" + item + "'");
        const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
        auto one = [&](double lo, double hi) {
            double v = numbersOf(key, value, 1, loc)[0];
            if (!(v >= lo && v <= hi))
                throw InputError(loc, "forest: " + key + " must lie in [" + std::to_string(lo) + ", " +
                                          std::to_string(hi) + "], got " + value);
            return v;
        };
        if (key == "count") f.count = int(one(0, 1e8));
        else if (key == "seed") f.seed = uint64_t(one(0, 1e15));
        else if (key == "area") {
            auto a = numbersOf(key, value, 2, loc);
            if (!(a[0] > 0 && a[1] > 0)) throw InputError(loc, "forest: area must be positive");
            f.areaX = a[0], f.areaZ = a[1];
        } else if (key == "species") {
            auto m = numbersOf(key, value, size_t(kSpeciesCount), loc);
            double sum = 0;
            bool valid = true;
            for (double share : m) sum += share, valid = valid && share >= 0;
            if (!(valid && sum > 0))
                throw InputError(loc, "forest: species takes " + std::to_string(kSpeciesCount) +
                                          " non-negative shares (" + speciesNames(",") + ")");
            for (int i = 0; i < kSpeciesCount; ++i) f.mix[i] = m[size_t(i)] / sum;
        } else if (key == "leafsize") f.leafSize = one(1e-4, 100);
        else if (key == "wind") f.wind = one(0, 10);
        else if (key == "winddir") {
            auto d = numbersOf(key, value, 2, loc);
            double l = std::hypot(d[0], d[1]);
            if (!(l > 0)) throw InputError(loc, "forest: winddir must not be zero");
            f.windX = d[0] / l, f.windZ = d[1] / l;
        } else if (key == "period") f.period = one(1e-3, 1e9);
        else if (key == "keystep") f.keyStep = one(1e-3, 1e9);
        else if (key == "detail") f.detail = one(1e-6, 1e9);
        else if (key == "cell") f.treesPerCell = int(one(1, 1e6));
        else if (key == "shaders") {
            const size_t comma = value.find(',');
            if (comma == std::string::npos || comma == 0 || comma + 1 == value.size() ||
                value.find(',', comma + 1) != std::string::npos)
                throw InputError(loc, "forest: shaders takes two surface names, BARK,LEAF (e.g. shaders=bark,leaf), got '" +
                                          value + "'");
            f.barkShader = value.substr(0, comma);
            f.leafShader = value.substr(comma + 1);
            f.looks = std::make_shared<ForestLooks>();
        }
        else if (key == "model") {
            if (value == "weberpenn") {
                if (f.weberPennPresets.empty()) f.weberPennPresets = weberPennPresetNames();
            } else if (value != "simple") {
                throw InputError(loc, "forest: model must be simple (the default) or weberpenn, not '" + value + "'");
            }
        } else if (key == "presets") {
            std::vector<std::string> names;
            std::stringstream list(value);
            std::string name;
            while (std::getline(list, name, ','))
                if (!weberPennPreset(name))
                    throw InputError(loc, "forest: presets takes names of Weber-Penn presets (" +
                                              [] {
                                                  std::string all;
                                                  for (const auto& n : weberPennPresetNames()) all += (all.empty() ? "" : ", ") + n;
                                                  return all;
                                              }() +
                                              "), not '" + name + "'");
                else
                    names.push_back(name);
            if (names.empty()) throw InputError(loc, "forest: presets names no preset");
            f.weberPennPresets = names;
        }
        else if (!extra(key, value)) throw InputError(loc, "forest: unknown parameter '" + key + "'");
    }
    return f;
}

// ---- Trees ----------------------------------------------------------------------------------------

struct Tree {
    const Species* species = &kSpecies[0];
    double x = 0, z = 0;
    double height = 10;
    double crownBase = 3, crownRadius = 2.5;
    double trunkRadius = 0.2, trunkTop = 9;
    Color bark, leaf;
    double phase = 0;
    double bushRadius = 1.5, bushHeight = 1.2;  // the undergrowth at the tree's foot
    Color bush;
    uint64_t key = 0;   // seeds everything random about this tree
};

double uniform(HashRng& r, double lo, double hi) { return lo + (hi - lo) * double(r.nextFloat()); }

// forceSpecies: an index into kSpecies, or -1 to draw one by the forest's mix.
Tree makeTree(const ForestParams& f, uint64_t key, double x, double z, int forceSpecies, double forceHeight) {
    HashRng r(key);
    Tree t;
    t.key = key;
    t.x = x;
    t.z = z;
    const double s = double(r.nextFloat());
    int species = kSpeciesCount - 1;
    double share = 0;
    for (int i = 0; i < kSpeciesCount - 1; ++i)
        if (s < (share += f.mix[i])) {
            species = i;
            break;
        }
    t.species = &kSpecies[forceSpecies >= 0 ? forceSpecies : species];
    const Species& sp = *t.species;
    t.phase = uniform(r, 0, 2 * M_PI);
    const float v = r.nextFloat();  // colour variation
    t.height = uniform(r, sp.height[0], sp.height[1]);
    t.crownBase = t.height * uniform(r, sp.crownBase[0], sp.crownBase[1]);
    t.crownRadius = t.height * uniform(r, sp.crownRadius[0], sp.crownRadius[1]);
    t.trunkTop = sp.trunkTop > 0 ? t.height * sp.trunkTop : t.crownBase;
    t.bark = sp.bark;
    t.leaf = sp.leaf + sp.leafVariation * v;
    if (forceHeight > 0) {
        const double k = forceHeight / t.height;
        t.height = forceHeight;
        t.crownBase *= k, t.crownRadius *= k, t.trunkTop *= k;
    }
    t.trunkRadius = t.height * sp.trunkRadius;
    t.bushRadius = uniform(r, 1.2, 2.6);
    t.bushHeight = uniform(r, 0.8, 1.8);
    t.bush = Color{0.12f, 0.22f, 0.08f} * (0.8f + 0.4f * r.nextFloat());
    return t;
}

// Sway: a branch leans and swings about its base by up to swayAngle; leaves flutter about their
// stems by up to flutterAngle. Points r from the base move at most r * angle (an arc's chord).
double swayAngle(const ForestParams& f) { return f.wind * 0.12; }
double flutterAngle(const ForestParams& f) { return f.wind * 0.35; }

// Crown centre and half-sizes: everything of the crown lies within it (branches and leaves).
Vec3d crownCentre(const Tree& t) {
    return {t.x, t.species->cone ? (t.crownBase + t.height) / 2 : t.crownBase + 0.55 * (t.height - t.crownBase), t.z};
}

Bounds3d treeBound(const ForestParams& f, const Tree& t) {
    const double reach = std::max(1.15 * t.crownRadius + 2 * f.leafSize, t.bushRadius);
    const double margin = (t.height + reach) * swayAngle(f) + f.leafSize * flutterAngle(f) + 1e-3;
    const double top = std::max(t.height, crownCentre(t).y + reach) + margin;
    return Bounds3d({t.x - reach - margin, -margin, t.z - reach - margin}, {t.x + reach + margin, top, t.z + reach + margin});
}

// Times of the sway keys covering the render window.
std::vector<double> swayTimes(const ForestParams& f, const ExpandContext& ctx) {
    if (f.wind == 0 || !(ctx.windowEnd > ctx.windowStart)) return {ctx.windowStart};
    std::vector<double> ts;
    for (double t = std::floor(ctx.windowStart / f.keyStep) * f.keyStep; t < ctx.windowEnd + f.keyStep; t += f.keyStep)
        ts.push_back(t);
    return ts;
}

// A rotation about the axis `a` (unit) through `c` by an angle, its cosine and sine taken once for
// every point it turns (Rodrigues).
struct Rotation {
    Vec3d c, a;
    double cs, sn;
    Rotation(Vec3d centre, Vec3d axis, double angle) : c(centre), a(axis), cs(std::cos(angle)), sn(std::sin(angle)) {}
    Vec3d operator()(Vec3d p) const {
        const Vec3d v = p - c;
        return c + v * cs + cross(a, v) * sn + a * (dot(a, v) * (1 - cs));
    }
};

// ---- Geometry output --------------------------------------------------------------------------------

using Quad = std::array<Vec3d, 4>;  // RenderMan patch corner order

// What a part of a tree is shaded with: the procedural's own surface, or shaders=' bark or leaf.
enum class Part { Own, Bark, Leaf };

void emit(ProceduralOutput& out, const ExpandContext& ctx, std::vector<double> times, std::vector<Quad> keys, Color cs,
          Part part = Part::Own, const ForestParams* f = nullptr) {
    BilinearPatchDesc p;
    p.times = std::move(times);
    p.P = std::move(keys);
    p.hasCs = true;
    p.Cs = {cs, cs, cs, cs};
    p.objectToWorld = ctx.objectToWorld;
    p.attributes = part != Part::Own && f && f->looks ? f->looks->of(ctx.attributes, part == Part::Leaf, *f) : ctx.attributes;
    p.loc = ctx.loc;
    out.scene.patches.push_back(std::move(p));
}

void emitStill(ProceduralOutput& out, const ExpandContext& ctx, const Quad& q, Color cs, Part part = Part::Own,
               const ForestParams* f = nullptr) {
    emit(out, ctx, {0.0}, {q}, cs, part, f);
}

// A nested procedural under the expanding one's transform and attributes.
void emitProcedural(ProceduralOutput& out, const ExpandContext& ctx, std::shared_ptr<const ProceduralGenerator> generator,
                    const Bounds3d& bound) {
    GeneratedProcedural g;
    g.generator = std::move(generator);
    ProceduralDesc& p = g.desc;
    p.kind = "DynamicLoad";
    p.bound = bound;
    p.objectToWorld = ctx.objectToWorld;
    p.attributes = ctx.attributes;
    p.loc = ctx.loc;
    out.procedurals.push_back(std::move(g));
}

// Two unit vectors perpendicular to `d` and to each other.
void basis(Vec3d d, Vec3d& u, Vec3d& v) {
    u = normalize(std::fabs(d.y) < 0.9 ? cross(d, Vec3d{0, 1, 0}) : cross(d, Vec3d{1, 0, 0}));
    v = cross(d, u);
}

// A tube (prism frustum) of `sides` bilinear strips around the axis p0 -> p1.
std::vector<Quad> tube(Vec3d p0, Vec3d p1, double r0, double r1, int sides) {
    Vec3d u, v;
    basis(normalize(p1 - p0), u, v);
    std::vector<Quad> qs;
    for (int k = 0; k < sides; ++k) {
        double a0 = 2 * M_PI * k / sides, a1 = 2 * M_PI * (k + 1) / sides;
        Vec3d d0 = u * std::cos(a0) + v * std::sin(a0), d1 = u * std::cos(a1) + v * std::sin(a1);
        qs.push_back({p0 + d0 * r0, p0 + d1 * r0, p1 + d0 * r1, p1 + d1 * r1});
    }
    return qs;
}

// ---- A branch with its leaves ------------------------------------------------------------------------

struct Branch {
    Vec3d base, dir;
    double length = 1, radius = 0.05;
    double spread = 0.3;  // how far leaves sit from the branch
    int leaves = 10;
    double phase = 0;
    uint64_t key = 0;
};

std::vector<Branch> branchesOf(const ForestParams& f, const Tree& t) {
    HashRng r(hashCombine(t.key, 0xb5a9c4));
    std::vector<Branch> bs;
    const Vec3d trunk{t.x, 0, t.z};
    auto add = [&](Vec3d base, Vec3d dir, double length, double spread, int leaves) {
        Branch b;
        b.base = base;
        b.dir = normalize(dir);
        b.length = length;
        b.radius = std::max(0.01, t.trunkRadius * 0.35 * std::min(1.0, length / t.crownRadius));
        b.spread = spread;
        b.leaves = leaves;
        b.phase = t.phase + uniform(r, -0.8, 0.8);
        b.key = hashCombine(t.key, bs.size() + 1);
        bs.push_back(b);
    };
    const Species& sp = *t.species;
    if (sp.cone) {
        const int tiers = 6 + int(t.height / 3);
        for (int i = 0; i < tiers; ++i) {
            const double y = t.crownBase + (t.height * 0.95 - t.crownBase) * i / tiers;
            const double reach = t.crownRadius * (1 - (y - t.crownBase) / (t.height - t.crownBase)) + 0.2;
            const int n = 5 + int(r.nextBelow(3));
            const double off = uniform(r, 0, 2 * M_PI);
            for (int k = 0; k < n; ++k) {
                const double a = off + 2 * M_PI * k / n;
                const double len = std::min(reach * uniform(r, 0.8, 1.05), t.crownRadius);
                add(trunk + Vec3d{0, y, 0}, {std::cos(a), -0.25, std::sin(a)}, len, f.leafSize,
                    std::max(2, int(len / (f.leafSize * 0.7))) * 2);
            }
        }
    } else {
        const Vec3d c = crownCentre(t);
        const int n = sp.branches + int(r.nextBelow(uint32_t(sp.branchesSpread)));
        for (int k = 0; k < n; ++k) {
            // Towards a point in the outer crown; leaves cluster around the outer part.
            const double a = 2 * M_PI * (k + uniform(r, -0.3, 0.3)) / n;
            const double up = uniform(r, -0.2, 0.8);
            const Vec3d target = c + Vec3d{std::cos(a) * std::sqrt(1 - up * up), up, std::sin(a) * std::sqrt(1 - up * up)} *
                                         (t.crownRadius * 0.7);
            const Vec3d base = sp.branchesFromTrunkTop
                                   ? trunk + Vec3d{0, t.trunkTop, 0}
                                   : trunk + Vec3d{0, t.crownBase + (t.trunkTop - t.crownBase) * uniform(r, 0, 0.8), 0};
            const Vec3d d = target - base;
            add(base, d, length(d), t.crownRadius * 0.35, sp.leavesPerBranch);
        }
    }
    return bs;
}

Bounds3d branchBound(const ForestParams& f, const Branch& b) {
    Bounds3d box;
    box.extend(b.base);
    box.extend(b.base + b.dir * b.length);
    const double reach = b.length + b.spread + f.leafSize;
    const double grow = b.spread + f.leafSize + reach * swayAngle(f) + f.leafSize * flutterAngle(f) + 1e-3;
    return {box.lo - Vec3d{grow, grow, grow}, box.hi + Vec3d{grow, grow, grow}};
}

class BranchGenerator final : public ProceduralGenerator {
  public:
    BranchGenerator(std::shared_ptr<const ForestParams> f, const Tree& tree, const Branch& b)
        : f_(std::move(f)), tree_(tree), branch_(b) {}

    std::string describe() const override { return "forest branch"; }

    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const ForestParams& f = *f_;
        const Branch& b = branch_;
        const std::vector<double> times = swayTimes(f, ctx);
        // The sway axis: horizontal, across the wind, so branches swing along it.
        const Vec3d axis = normalize(Vec3d{-f.windZ, 0, f.windX});
        std::vector<Rotation> sway;
        sway.reserve(times.size());
        for (double t : times) sway.emplace_back(b.base, axis, swayAngle(f) * 0.5 * (1 + std::sin(2 * M_PI * t / f.period + b.phase)));
        // A quad's keys: turned by `local` at key k (a leaf's flutter), then swayed with the branch.
        auto swaying = [&](const Quad& q, auto&& local) {
            std::vector<Quad> keys(times.size());
            for (size_t k = 0; k < times.size(); ++k) {
                const Quad lq = local(q, k);
                for (int c = 0; c < 4; ++c) keys[k][size_t(c)] = sway[k](lq[size_t(c)]);
            }
            return keys;
        };
        for (const Quad& q : tube(b.base, b.base + b.dir * b.length, b.radius, b.radius * 0.4, 3))
            emit(out, ctx, times, swaying(q, [](const Quad& quad, size_t) { return quad; }), tree_.bark, Part::Bark, &f);

        HashRng r(b.key);
        Vec3d u, v;
        basis(b.dir, u, v);
        const double s = f.leafSize;
        for (int i = 0; i < b.leaves; ++i) {
            Vec3d attach, along, across;
            if (tree_.species->cone) {
                // Needle sprays on both sides along the branch.
                const double at = b.length * (0.15 + 0.85 * double(i / 2) / std::max(1, b.leaves / 2));
                const double side = (i % 2) ? 1 : -1;
                attach = b.base + b.dir * at;
                along = normalize(u * side + b.dir * 0.6 + Vec3d{0, -0.2, 0});
                across = normalize(cross(along, v)) * (s * 0.5);
            } else {
                const double at = b.length * uniform(r, 0.45, 1.0);
                Vec3d off{uniform(r, -1, 1), uniform(r, -1, 1), uniform(r, -1, 1)};
                if (length(off) > 1) off = normalize(off);
                attach = b.base + b.dir * at + off * b.spread;
                along = normalize(Vec3d{uniform(r, -1, 1), uniform(r, -0.6, 1), uniform(r, -1, 1)});
                Vec3d pu, pv;
                basis(along, pu, pv);
                across = pu * (s * 0.6);
            }
            const Quad leaf{attach - across * 0.5, attach + across * 0.5, attach + along * s - across * 0.5,
                            attach + along * s + across * 0.5};
            const Vec3d stem = along;
            const double phase = uniform(r, 0, 2 * M_PI);
            const float shade = 0.85f + 0.3f * r.nextFloat();
            auto flutter = [&](const Quad& q, size_t k) {
                const Rotation turn(attach, stem, flutterAngle(f) * std::sin(2 * M_PI * 3 * times[k] / f.period + phase));
                Quad o;
                for (int c = 0; c < 4; ++c) o[size_t(c)] = turn(q[size_t(c)]);
                return o;
            };
            emit(out, ctx, times, swaying(leaf, flutter), tree_.leaf * shade, Part::Leaf, &f);
        }
    }

  private:
    std::shared_ptr<const ForestParams> f_;
    Tree tree_;
    Branch branch_;
};

// ---- A tree, by level of detail ---------------------------------------------------------------------

class TreeGenerator final : public ProceduralGenerator {
  public:
    TreeGenerator(std::shared_ptr<const ForestParams> f, const Tree& t) : f_(std::move(f)), tree_(t) {}
    std::string describe() const override { return "forest tree"; }

    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const ForestParams& f = *f_;
        const Tree& t = tree_;
        const double size = std::sqrt(std::max(0.0, ctx.detail));  // pixels across the bound
        const Vec3d trunk{t.x, 0, t.z};
        const Vec3d c = crownCentre(t);
        const double R = t.crownRadius;
        if (size < 4 / f.detail) {
            // Far: two crossed quads the size of the crown.
            const double y0 = t.crownBase * 0.6, y1 = t.height;
            emitStill(out, ctx, {Vec3d{t.x - R, y0, t.z}, Vec3d{t.x + R, y0, t.z}, Vec3d{t.x - R, y1, t.z}, Vec3d{t.x + R, y1, t.z}}, t.leaf);
            emitStill(out, ctx, {Vec3d{t.x, y0, t.z - R}, Vec3d{t.x, y0, t.z + R}, Vec3d{t.x, y1, t.z - R}, Vec3d{t.x, y1, t.z + R}}, t.leaf);
            return;
        }
        const bool near = size >= 40 / f.detail;
        // Undergrowth: a still, solid half-ellipsoid at the tree's foot.
        for (int k = 0; k < 8; ++k)
            for (int j = 0; j < 3; ++j) {
                const double a0 = 2 * M_PI * k / 8, a1 = 2 * M_PI * (k + 1) / 8;
                const double b0 = 0.5 * M_PI * j / 3, b1 = 0.5 * M_PI * (j + 1) / 3;
                auto p = [&](double a, double b) {
                    return trunk + Vec3d{t.bushRadius * std::cos(b) * std::cos(a), t.bushHeight * std::sin(b),
                                         t.bushRadius * std::cos(b) * std::sin(a)};
                };
                emitStill(out, ctx, {p(a0, b0), p(a1, b0), p(a0, b1), p(a1, b1)}, t.bush * (0.8f + 0.15f * float(j)));
            }
        for (const Quad& q : tube(trunk, trunk + Vec3d{0, near ? t.trunkTop : t.crownBase, 0}, t.trunkRadius,
                                  t.trunkRadius * 0.6, near ? 6 : 4))
            emitStill(out, ctx, q, t.bark, Part::Bark, &f);
        if (!near) {
            // Middle: a still crown proxy.
            const int n = 8;
            for (int k = 0; k < n; ++k) {
                const double a0 = 2 * M_PI * k / n, a1 = 2 * M_PI * (k + 1) / n;
                if (t.species->cone) {
                    const Vec3d apex{t.x, t.height, t.z};
                    emitStill(out, ctx, {trunk + Vec3d{R * std::cos(a0), t.crownBase, R * std::sin(a0)},
                                         trunk + Vec3d{R * std::cos(a1), t.crownBase, R * std::sin(a1)}, apex, apex},
                              t.leaf);
                } else {
                    const double ry = (t.height - t.crownBase) * 0.5;
                    for (int j = 0; j < 4; ++j) {
                        const double b0 = M_PI * j / 4 - M_PI / 2, b1 = M_PI * (j + 1) / 4 - M_PI / 2;
                        auto p = [&](double a, double b) {
                            return c + Vec3d{R * std::cos(b) * std::cos(a), ry * std::sin(b), R * std::cos(b) * std::sin(a)};
                        };
                        emitStill(out, ctx, {p(a0, b0), p(a1, b0), p(a0, b1), p(a1, b1)}, t.leaf * (0.8f + 0.1f * float(j)));
                    }
                }
            }
            return;
        }
        // Near: every branch a procedural of its own, so unseen branches never grow leaves.
        for (const Branch& b : branchesOf(f, t))
            emitProcedural(out, ctx, std::make_shared<BranchGenerator>(f_, t, b), branchBound(f, b));
    }

  private:
    std::shared_ptr<const ForestParams> f_;
    Tree tree_;
};

// ---- Cells and the forest ------------------------------------------------------------------------------

struct CellGrid {
    int nx = 1, nz = 1;
    double sx = 1, sz = 1;  // cell size
};

CellGrid cellGrid(const ForestParams& f) {
    const double cells = std::max(1.0, std::ceil(double(f.count) / f.treesPerCell));
    CellGrid g;
    // Between 1 and the number of cells, in double first: a very long, thin area would overflow an
    // int (the fuzzer found area=1e50,1000).
    double nx = std::ceil(std::sqrt(cells * f.areaX / f.areaZ));
    if (!(nx >= 1)) nx = 1;
    g.nx = int(std::min(nx, cells));
    g.nz = std::max(1, int(std::ceil(cells / g.nx)));
    g.sx = f.areaX / g.nx;
    g.sz = f.areaZ / g.nz;
    return g;
}

// Trees j with j % cells == cell, placed uniformly in the cell.
template <typename Fn>
void forEachTreeInCell(const ForestParams& f, const CellGrid& g, int cell, Fn fn) {
    const int cells = g.nx * g.nz;
    const int cx = cell % g.nx, cz = cell / g.nx;
    for (int j = cell; j < f.count; j += cells) {
        const uint64_t key = hashCombine(mix64(f.seed), uint64_t(j));
        HashRng r(hashCombine(key, 0x9e37));
        const double x = -f.areaX / 2 + g.sx * (cx + double(r.nextFloat()));
        const double z = -f.areaZ / 2 + g.sz * (cz + double(r.nextFloat()));
        fn(makeTree(f, key, x, z, -1, 0));
    }
}

// model=weberpenn: the forest's tree `t` as a Weber-Penn tree of a preset drawn from presets=,
// with its own seed, turned about its foot by a drawn angle and standing where `t` stands; the
// forest's wind (wind w: WindSpeed 4w, WindGust 2w, its keystep) and detail.
struct WeberPennPlacement {
    WeberPennParams params;
    Matrix4 local;  // tree space to the forest's
};

WeberPennPlacement weberPennTreeOf(const ForestParams& f, const Tree& t) {
    HashRng r(hashCombine(t.key, 0x57e6b1ULL));
    const size_t n = f.weberPennPresets.size();
    const size_t pick = std::min(n - 1, size_t(double(r.nextFloat()) * double(n)));
    WeberPennPlacement w{*weberPennPreset(f.weberPennPresets[pick]), {}};
    w.params.seed = t.key % uint64_t(1e15);
    w.params.windSpeed = 4 * f.wind, w.params.windGust = 2 * f.wind, w.params.keyStep = f.keyStep;
    w.params.detail = f.detail;
    w.local = Matrix4::rotate(360.0 * double(r.nextFloat()), {0, 1, 0}) * Matrix4::translate({t.x, 0, t.z});
    return w;
}

class CellGenerator final : public ProceduralGenerator {
  public:
    CellGenerator(std::shared_ptr<const ForestParams> f, int cell) : f_(std::move(f)), cell_(cell) {}
    std::string describe() const override { return "forest cell"; }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        forEachTreeInCell(*f_, cellGrid(*f_), cell_, [&](const Tree& t) {
            if (f_->weberPennPresets.empty()) {
                emitProcedural(out, ctx, std::make_shared<TreeGenerator>(f_, t), treeBound(*f_, t));
                return;
            }
            WeberPennPlacement w = weberPennTreeOf(*f_, t);
            GeneratedProcedural g;
            g.desc.kind = "DynamicLoad";
            g.desc.bound = weberPennBound(w.params);  // in the tree's own space
            g.desc.objectToWorld = MotionTransform(w.local).then(ctx.objectToWorld);
            g.desc.attributes = ctx.attributes;
            g.desc.loc = ctx.loc;
            g.generator = makeWeberPennGenerator(std::move(w.params));
            out.procedurals.push_back(std::move(g));
        });
    }

  private:
    std::shared_ptr<const ForestParams> f_;
    int cell_;
};

class ForestGenerator final : public ProceduralGenerator {
  public:
    explicit ForestGenerator(ForestParams f) : f_(std::make_shared<const ForestParams>(f)) {}
    std::string describe() const override { return "DynamicLoad forest"; }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const CellGrid g = cellGrid(*f_);
        std::map<std::string, Bounds3d> footBounds;  // model=weberpenn: each preset's, about its foot
        for (const std::string& name : f_->weberPennPresets) footBounds[name] = weberPennFootBound(*weberPennPreset(name));
        for (int cell = 0; cell < g.nx * g.nz; ++cell) {
            Bounds3d bound;
            forEachTreeInCell(*f_, g, cell, [&](const Tree& t) {
                if (f_->weberPennPresets.empty()) {
                    bound.extend(treeBound(*f_, t));
                    return;
                }
                const WeberPennPlacement w = weberPennTreeOf(*f_, t);
                bound.extend(w.local.box(footBounds.at(w.params.name)));
            });
            if (bound.empty()) continue;
            emitProcedural(out, ctx, std::make_shared<CellGenerator>(f_, cell), bound);
        }
    }

  private:
    std::shared_ptr<const ForestParams> f_;
};

}  // namespace

ForestParams parseForestParams(const std::string& datablock, const SourceLoc& loc) {
    return parseParams(datablock, loc, [](const std::string&, const std::string&) { return false; });
}

std::shared_ptr<const ProceduralGenerator> makeForestGenerator(const std::string& datablock, const SourceLoc& loc) {
    return std::make_shared<ForestGenerator>(parseForestParams(datablock, loc));
}

std::shared_ptr<const ProceduralGenerator> makeTreeGenerator(const std::string& datablock, const SourceLoc& loc) {
    // model=weberpenn: the paper's trees (weber_penn.h); the default, model=simple, is this file's.
    if (isWeberPennDatablock(datablock)) return makeWeberPennGenerator(datablock, loc);
    int species = -1;
    double height = 0;
    ForestParams f = parseParams(datablock, loc, [&](const std::string& key, const std::string& value) {
        if (key == "kind") {
            for (int i = 0; i < kSpeciesCount; ++i)
                if (value == kSpecies[i].name) species = i;
            if (species < 0)
                throw InputError(loc, "tree: kind must be one of " + speciesNames(", ") + ", not '" + value + "'");
            return true;
        }
        if (key == "height") {
            height = numbersOf(key, value, 1, loc)[0];
            if (!(height > 0)) throw InputError(loc, "tree: height must be positive");
            return true;
        }
        return false;
    });
    Tree t = makeTree(f, hashCombine(mix64(f.seed), 0), 0, 0, species, height);
    return std::make_shared<TreeGenerator>(std::make_shared<const ForestParams>(f), t);
}

}  // namespace streyes
