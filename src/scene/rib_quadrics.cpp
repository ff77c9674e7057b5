// Quadrics: Sphere, Cylinder, Cone, Disk, Paraboloid, Hyperboloid, Torus, with their arguments as
// motion keys.
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "scene/rib_geometry.h"

namespace streyes {

namespace {

// One key: the arguments, in the order RenderMan gives them, and "Cs" at the domain's corners.
bool readQuadricKey(RibParser& reader, RibArgs& args, QuadricDesc* d) {
    struct Kind {
        QuadricKind kind;
        size_t count;
        const char* what;
    };
    static const std::map<std::string, Kind> kinds = {
        {"Sphere", {QuadricKind::Sphere, 4, "radius zmin zmax thetamax"}},
        {"Cylinder", {QuadricKind::Cylinder, 4, "radius zmin zmax thetamax"}},
        {"Cone", {QuadricKind::Cone, 3, "height radius thetamax"}},
        {"Disk", {QuadricKind::Disk, 3, "height radius thetamax"}},
        {"Paraboloid", {QuadricKind::Paraboloid, 4, "rmax zmin zmax thetamax"}},
        {"Hyperboloid", {QuadricKind::Hyperboloid, 7, "x1 y1 z1 x2 y2 z2 thetamax"}},
        {"Torus", {QuadricKind::Torus, 5, "majorradius minorradius phimin phimax thetamax"}}};
    const Kind& k = kinds.at(args.name());
    std::vector<double> v = args.numbers(k.count, k.what);
    // thetamax is the last argument; RenderMan clamps it to a full turn.
    v.back() = std::max(-360.0, std::min(360.0, v.back()));
    if (k.kind == QuadricKind::Paraboloid && !(v[2] > 0 && v[1] >= 0 && v[1] <= v[2]))
        args.fail("needs 0 <= zmin <= zmax and zmax > 0, got zmin " + formatNumber(v[1]) + " and zmax " +
                  formatNumber(v[2]));
    d->kind = k.kind;
    std::array<double, 7> params{};
    std::copy(v.begin(), v.end(), params.begin());
    d->params = {params};
    ParamList list = reader.readParams(args);
    ClassCounts counts;
    counts.varying = counts.vertex = counts.faceVarying = 4;
    d->Cs = readColors(args, list, counts);
    d->primvars = otherParams(args, list, counts, reader.log(), true);  // one face: corners over (u, v)
    return true;
}

// A quadric's facets (8 around, 4 along), for an area light's shape: spheres, cylinders, cones and
// disks (none for the others).
std::vector<std::array<Vec3d, 4>> quadricFacets(const QuadricDesc& d) {
    const std::array<double, 7>& a = d.params.front();
    std::function<Vec3d(double, double)> at;  // (u, v) in [0, 1]^2 -> object space
    const double pi = 3.14159265358979323846;
    switch (d.kind) {
        case QuadricKind::Sphere: {
            const double r = a[0], zmin = std::max(-r, std::min(a[1], a[2])), zmax = std::min(r, std::max(a[1], a[2]));
            const double p0 = std::asin(zmin / r), p1 = std::asin(zmax / r), tmax = a[3] * pi / 180;
            at = [=](double u, double v) {
                const double phi = p0 + v * (p1 - p0), t = u * tmax;
                return Vec3d{r * std::cos(phi) * std::cos(t), r * std::cos(phi) * std::sin(t), r * std::sin(phi)};
            };
            break;
        }
        case QuadricKind::Cylinder:
            at = [=](double u, double v) {
                const double t = u * a[3] * pi / 180;
                return Vec3d{a[0] * std::cos(t), a[0] * std::sin(t), a[1] + v * (a[2] - a[1])};
            };
            break;
        case QuadricKind::Cone:
            at = [=](double u, double v) {
                const double t = u * a[2] * pi / 180, r = a[1] * (1 - v);
                return Vec3d{r * std::cos(t), r * std::sin(t), v * a[0]};
            };
            break;
        case QuadricKind::Disk:
            at = [=](double u, double v) {
                const double t = u * a[2] * pi / 180, r = a[1] * (1 - v);
                return Vec3d{r * std::cos(t), r * std::sin(t), a[0]};
            };
            break;
        default: return {};
    }
    std::vector<std::array<Vec3d, 4>> out;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 8; ++i) {
            const double u0 = i / 8.0, u1 = (i + 1) / 8.0, v0 = j / 4.0, v1 = (j + 1) / 4.0;
            out.push_back({at(u0, v0), at(u1, v0), at(u0, v1), at(u1, v1)});
        }
    return out;
}

void quadricKeys(RibParser& reader, const RibKeys& keys) {
    auto anyShape = [](const QuadricDesc&, const QuadricDesc&) { return true; };
    auto positions = [](QuadricDesc& d) -> auto& { return d.params; };
    if (auto d = mergeKeys<QuadricDesc>(reader, keys, readQuadricKey, anyShape, "", positions)) {
        shapeAreaLight(reader, quadricFacets(*d), d->loc, keys.requests.front().name);
        reader.scene().quadrics.push_back(std::move(*d));
    }
}

}  // namespace

void addQuadricRequests(RibRequestTable& table) {
    const RibPhase world = RibPhase::World;
    table.add("Sphere", {oneKey<quadricKeys>, "Sphere radius zmin zmax thetamax", world, quadricKeys});
    table.add("Cylinder", {oneKey<quadricKeys>, "Cylinder radius zmin zmax thetamax", world, quadricKeys});
    table.add("Cone", {oneKey<quadricKeys>, "Cone height radius thetamax", world, quadricKeys});
    table.add("Disk", {oneKey<quadricKeys>, "Disk height radius thetamax", world, quadricKeys});
    table.add("Paraboloid", {oneKey<quadricKeys>, "Paraboloid rmax zmin zmax thetamax", world, quadricKeys});
    table.add("Hyperboloid", {oneKey<quadricKeys>, "Hyperboloid x1 y1 z1 x2 y2 z2 thetamax", world, quadricKeys});
    table.add("Torus",
              {oneKey<quadricKeys>, "Torus majorradius minorradius phimin phimax thetamax", world, quadricKeys});
}

}  // namespace streyes
