#include "procedural/grass.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "procedural/number_list.h"
#include "util/sampling.h"

namespace streyes {

namespace {

// ---- Parameters -----------------------------------------------------------------------------------

std::vector<double> grassNumbers(const std::string& key, const std::string& value, size_t n, const SourceLoc& loc) {
    return parseNumberList("grass", key, value, n, loc);
}

// ---- Tiles ----------------------------------------------------------------------------------------

struct GrassTiling {
    int64_t nx = 1, nz = 1;
};

GrassTiling grassTiling(const GrassParams& g) {
    GrassTiling t;
    t.nx = std::max<int64_t>(1, int64_t(std::ceil((g.x1 - g.x0) / g.tile - 1e-9)));
    t.nz = std::max<int64_t>(1, int64_t(std::ceil((g.z1 - g.z0) / g.tile - 1e-9)));
    return t;
}

struct GrassTileRect {
    double x0, z0, x1, z1;
    double area() const { return (x1 - x0) * (z1 - z0); }
};

GrassTileRect grassTileRect(const GrassParams& g, const GrassTiling& t, int64_t k) {
    const int64_t i = k % t.nx, j = k / t.nx;
    return {g.x0 + g.tile * double(i), g.z0 + g.tile * double(j), std::min(g.x1, g.x0 + g.tile * double(i + 1)),
            std::min(g.z1, g.z0 + g.tile * double(j + 1))};
}

// Area of tiles 0..k-1: whole rows, then part of row k / nx.
double grassAreaBefore(const GrassParams& g, const GrassTiling& t, int64_t k) {
    const int64_t rows = k / t.nx, rest = k % t.nx;
    const double rowDepthFull = std::min(g.z1 - g.z0, g.tile * double(rows));
    double area = (g.x1 - g.x0) * rowDepthFull;
    if (rest > 0) {
        const double depth = std::min(g.z1, g.z0 + g.tile * double(rows + 1)) - (g.z0 + g.tile * double(rows));
        area += std::min(g.x1 - g.x0, g.tile * double(rest)) * depth;
    }
    return area;
}

// What bounds every blade: its root's box grown by the longest blade and half the widest root
// (the curve lies in its control polygon's hull, each point within its length of the root,
// however it leans or sways).
Bounds3d grassBound(const GrassParams& g, const GrassTileRect& r) {
    const double halfWidest = 0.5 * 1.3 * g.width / 0.05;  // a root 1.3 x width, widened up to 1 / 0.05 far away
    const double reach = g.heightMax + halfWidest + 1e-4;
    return Bounds3d({r.x0 - reach, -reach, r.z0 - reach}, {r.x1 + reach, reach, r.z1 + reach});
}

// ---- Blades ---------------------------------------------------------------------------------------

struct GrassBlade {
    Vec3d root;
    Vec3d leg[3];      // unit directions of the three legs, still
    double length;     // of the control polygon
    double width;      // at the root
    double phase;      // of its sway
    Color color;
};

double grassUniform(HashRng& r, double lo, double hi) { return lo + (hi - lo) * double(r.nextFloat()); }

GrassBlade grassBlade(const GrassParams& g, const GrassTileRect& t, uint64_t key) {
    HashRng r(key);
    GrassBlade b;
    b.root = {grassUniform(r, t.x0, t.x1), 0, grassUniform(r, t.z0, t.z1)};
    b.length = grassUniform(r, g.heightMin, g.heightMax);
    b.width = g.width * grassUniform(r, 0.7, 1.3);
    const double azimuth = grassUniform(r, 0, 2 * M_PI);
    const double lean = grassUniform(r, 0, g.lean) * M_PI / 180;
    const double bend = grassUniform(r, 0.3, 1) * g.bend * M_PI / 180;
    for (int i = 0; i < 3; ++i) {
        const double a = lean + bend * i / 2;
        b.leg[i] = {std::sin(a) * std::cos(azimuth), std::cos(a), std::sin(a) * std::sin(azimuth)};
    }
    b.phase = grassUniform(r, -0.5, 0.5);
    const float shade = float(grassUniform(r, 0.8, 1.2)), yellow = float(grassUniform(r, 0, 0.25));
    b.color = Color{g.color.x * shade + yellow * 0.5f, g.color.y * shade + yellow * 0.35f, g.color.z * shade};
    return b;
}

// The sway angle (radians) of a blade at time t (frames).
double grassSway(const GrassParams& g, const GrassBlade& b, double t) {
    const double along = b.root.x * g.windX + b.root.z * g.windZ;
    return g.wind * 0.35 * 0.5 * (1 + std::sin(2 * M_PI * (t / g.period - along / g.wavelength) + b.phase));
}

// Key times (frames) covering [windowStart, windowEnd]: multiples of keystep, at least two; one
// key when still.
std::vector<double> grassKeyTimes(const GrassParams& g, double windowStart, double windowEnd) {
    if (g.wind == 0) return {windowStart};
    std::vector<double> ts;
    const double first = std::floor(windowStart / g.keyStep);
    for (double n = first; ts.size() < 2 || ts.back() < windowEnd; n += 1) ts.push_back(n * g.keyStep);
    return ts;
}

// v turned about the unit axis a by angle (Rodrigues).
Vec3d grassTurn(Vec3d v, Vec3d a, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + cross(a, v) * s + a * (dot(a, v) * (1 - c));
}

class GrassTileGenerator final : public ProceduralGenerator {
  public:
    GrassTileGenerator(std::shared_ptr<const GrassParams> g, int64_t tile) : g_(std::move(g)), tile_(tile) {}
    std::string describe() const override { return "grass tile"; }

    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const GrassParams& g = *g_;
        const GrassTiling tiling = grassTiling(g);
        const GrassTileRect rect = grassTileRect(g, tiling, tile_);
        const int64_t count = grassBladesBefore(g, tile_ + 1) - grassBladesBefore(g, tile_);
        if (count <= 0) return;
        // Level of detail by the tile's projected size: at most 4 x detail blades a pixel of its
        // bound (at least 5% of them), each wider by the inverse of the share kept so that the
        // tile's cover stays; straight (linear) blades under 64 / detail pixels across.
        const double size = ctx.detail > 0 ? std::sqrt(ctx.detail) : 1e9;  // pixels across the bound
        const double share = std::clamp(4 * g.detail * size * size / double(count), 0.05, 1.0);
        const int64_t kept = std::max<int64_t>(1, int64_t(std::ceil(share * double(count))));
        const double widen = double(count) / double(kept);
        const bool cubic = size >= 64 / g.detail;

        const std::vector<double> times = grassKeyTimes(g, ctx.windowStart, ctx.windowEnd);
        const Vec3d axis{-g.windZ, 0, g.windX};  // across the wind: blades turn downwind about it
        CurvesDesc c;
        c.cubic = cubic;
        c.basis = BasisDesc{};  // Bezier, step 3
        c.times = times;
        c.P.resize(times.size());
        c.widthClass = ParamClass::Varying;
        c.width.clear();
        c.Cs.cls = ParamClass::Varying;
        const uint64_t tileKey = hashCombine(mix64(g.seed), uint64_t(tile_));
        for (int64_t j = 0; j < kept; ++j) {
            const GrassBlade b = grassBlade(g, rect, hashCombine(tileKey, uint64_t(j)));
            c.nvertices.push_back(cubic ? 4 : 2);
            for (size_t k = 0; k < times.size(); ++k) {
                const double sway = g.wind > 0 ? grassSway(g, b, times[k]) : 0;
                Vec3d p = b.root;
                std::vector<Vec3d>& key = c.P[k];
                key.push_back(p);
                for (int i = 0; i < 3; ++i) {
                    p = p + grassTurn(b.leg[i], axis, sway * (i + 1) / 3) * (b.length / 3);
                    if (cubic) key.push_back(p);
                }
                if (!cubic) key.push_back(p);
            }
            c.width.push_back(b.width * widen);
            c.width.push_back(b.width * widen * 0.1);
            c.Cs.values.push_back(b.color * 0.45f);
            c.Cs.values.push_back(b.color);
        }
        c.objectToWorld = ctx.objectToWorld;
        c.attributes = ctx.attributes;
        c.loc = ctx.loc;
        out.scene.curves.push_back(std::move(c));
    }

  private:
    std::shared_ptr<const GrassParams> g_;
    int64_t tile_;
};

class GrassGenerator final : public ProceduralGenerator {
  public:
    explicit GrassGenerator(GrassParams g) : g_(std::make_shared<const GrassParams>(g)) {}
    std::string describe() const override { return "DynamicLoad grass"; }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const GrassTiling t = grassTiling(*g_);
        for (int64_t k = 0; k < t.nx * t.nz; ++k) {
            if (grassBladesBefore(*g_, k + 1) == grassBladesBefore(*g_, k)) continue;
            GeneratedProcedural p;
            p.generator = std::make_shared<GrassTileGenerator>(g_, k);
            p.desc.kind = "DynamicLoad";
            p.desc.bound = grassBound(*g_, grassTileRect(*g_, t, k));
            p.desc.objectToWorld = ctx.objectToWorld;
            p.desc.attributes = ctx.attributes;
            p.desc.loc = ctx.loc;
            out.procedurals.push_back(std::move(p));
        }
    }

  private:
    std::shared_ptr<const GrassParams> g_;
};

}  // namespace

int64_t grassBladesBefore(const GrassParams& g, int64_t tiles) {
    return int64_t(std::floor(g.density * grassAreaBefore(g, grassTiling(g), tiles)));
}

GrassParams parseGrassParams(const std::string& datablock, const SourceLoc& loc) {
    GrassParams g;
    std::istringstream in(datablock);
    std::string item;
    while (in >> item) {
        const size_t eq = item.find('=');
        if (eq == std::string::npos || eq == 0) throw InputError(loc, "grass: expected key=value, got '" + item + "'");
        const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
        auto one = [&](double lo, double hi) {
            const double v = grassNumbers(key, value, 1, loc)[0];
            if (!(v >= lo && v <= hi))
                throw InputError(loc, "grass: " + key + " must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                          "], got " + value);
            return v;
        };
        if (key == "seed") g.seed = uint64_t(one(0, 1e15));
        else if (key == "rect") {
            const auto r = grassNumbers(key, value, 4, loc);
            if (!(r[2] > r[0] && r[3] > r[1]))
                throw InputError(loc, "grass: rect=X0,Z0,X1,Z1 needs X1 > X0 and Z1 > Z0, got '" + value + "'");
            g.x0 = r[0], g.z0 = r[1], g.x1 = r[2], g.z1 = r[3];
        } else if (key == "density") g.density = one(0, 1e7);
        else if (key == "height") {
            const auto h = grassNumbers(key, value, 2, loc);
            if (!(h[0] > 0 && h[1] >= h[0]))
                throw InputError(loc, "grass: height=MIN,MAX needs 0 < MIN <= MAX, got '" + value + "'");
            g.heightMin = h[0], g.heightMax = h[1];
        } else if (key == "width") g.width = one(1e-6, 1e3);
        else if (key == "lean") g.lean = one(0, 60);
        else if (key == "bend") g.bend = one(0, 60);
        else if (key == "wind") g.wind = one(0, 4);
        else if (key == "winddir") {
            const auto d = grassNumbers(key, value, 2, loc);
            const double l = std::hypot(d[0], d[1]);
            if (!(l > 0)) throw InputError(loc, "grass: winddir must not be zero");
            g.windX = d[0] / l, g.windZ = d[1] / l;
        } else if (key == "period") g.period = one(1e-3, 1e9);
        else if (key == "wavelength") g.wavelength = one(1e-3, 1e9);
        else if (key == "keystep") g.keyStep = one(1e-3, 1e9);
        else if (key == "detail") g.detail = one(1e-6, 1e9);
        else if (key == "tile") g.tile = one(1e-3, 1e6);
        else if (key == "color") {
            const auto c = grassNumbers(key, value, 3, loc);
            if (!(c[0] >= 0 && c[1] >= 0 && c[2] >= 0)) throw InputError(loc, "grass: color must not be negative");
            g.color = Color{float(c[0]), float(c[1]), float(c[2])};
        } else throw InputError(loc, "grass: unknown parameter '" + key + "'");
    }
    const double tiles = std::ceil((g.x1 - g.x0) / g.tile) * std::ceil((g.z1 - g.z0) / g.tile);
    if (!(tiles <= 1e7))
        throw InputError(loc, "grass: rect over tile makes " + std::to_string(tiles) +
                                  " tiles (at most 1e7): give a larger tile= or a smaller rect");
    if (!(g.density * (g.x1 - g.x0) * (g.z1 - g.z0) <= 1e9))
        throw InputError(loc, "grass: density x area is over 1e9 blades: give a smaller density or rect");
    return g;
}

std::shared_ptr<const ProceduralGenerator> makeGrassGenerator(const std::string& datablock, const SourceLoc& loc) {
    return std::make_shared<GrassGenerator>(parseGrassParams(datablock, loc));
}

}  // namespace streyes
