// Quadrics: Sphere, Cylinder, Cone, Disk, Paraboloid, Hyperboloid, Torus, with their arguments as
// motion keys.
#include <algorithm>
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
    d->primvars = otherParams(args, list, counts, reader.log());
    return true;
}

void quadricKeys(RibParser& reader, const RibKeys& keys) {
    auto anyShape = [](const QuadricDesc&, const QuadricDesc&) { return true; };
    auto positions = [](QuadricDesc& d) -> auto& { return d.params; };
    if (auto d = mergeKeys<QuadricDesc>(reader, keys, readQuadricKey, anyShape, "", positions))
        reader.scene().quadrics.push_back(std::move(*d));
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
