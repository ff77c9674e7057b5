// Polygons: Polygon, GeneralPolygon, PointsPolygons and PointsGeneralPolygons, kept as written
// (loops of points, holes after the outline): the bodies stage cuts them into faces.
#include <algorithm>
#include <numeric>

#include "scene/object_st.h"
#include "scene/rib_geometry.h"

namespace streyes {

namespace {

// One key of a polygon request of any size: its points, polygons and "Cs".
bool readPolygonsKey(RibParser& reader, RibArgs& args, PolygonMeshDesc* d) {
    const std::string& name = args.name();
    d->request = name;
    std::vector<int> loopsPerPolygon, loopSizes, indices;
    if (name == "GeneralPolygon") {
        loopSizes = intArray(args, "nvertices", 3);
        loopsPerPolygon = {int(loopSizes.size())};
    } else if (name == "PointsPolygons") {
        loopSizes = intArray(args, "nvertices", 3);
        loopsPerPolygon.assign(loopSizes.size(), 1);
        indices = intArray(args, "vertices", 0);
    } else if (name == "PointsGeneralPolygons") {
        loopsPerPolygon = intArray(args, "nloops", 1);
        loopSizes = intArray(args, "nvertices", 3);
        if (loopSizes.size() != sum(loopsPerPolygon))
            args.fail("nvertices has " + plural(loopSizes.size(), "loop") + " but nloops asks for " +
                      std::to_string(sum(loopsPerPolygon)));
        indices = intArray(args, "vertices", 0);
    }
    if (!indices.empty() || name == "PointsPolygons" || name == "PointsGeneralPolygons")
        if (indices.size() != sum(loopSizes))
            args.fail("vertices has " + indexCount(indices.size()) + " but nvertices asks for " +
                      std::to_string(sum(loopSizes)));
    ParamList params = reader.readParams(args);
    const Param& pos = positionParam(args, params);
    const size_t per = size_t(pos.componentsPerItem());
    size_t npoints = 0;
    if (name == "Polygon") {
        if (pos.nums.size() % per != 0)
            args.failAt(pos.loc.line,
                        "parameter '" + pos.name + "' has " + plural(pos.nums.size(), "number") +
                            ", which is not a whole number of vertices (" + std::to_string(per) + " numbers each)",
                        false);
        npoints = pos.nums.size() / per;
        loopSizes = {int(npoints)};
        loopsPerPolygon = {1};
    } else if (name == "GeneralPolygon") {
        npoints = sum(loopSizes);
    } else {
        for (int i : indices) npoints = std::max(npoints, size_t(i) + 1);
    }
    checkCount(args, pos, npoints);
    d->P = {pointsOf(args, pos)};
    // Loops as indices into the points.
    d->polygons.clear();
    for (size_t p = 0, loop = 0, at = 0; p < loopsPerPolygon.size(); ++p) {
        std::vector<std::vector<int>> loops;
        for (int l = 0; l < loopsPerPolygon[p]; ++l, ++loop) {
            std::vector<int> ring;
            for (int k = 0; k < loopSizes[loop]; ++k, ++at) ring.push_back(indices.empty() ? int(at) : indices[at]);
            loops.push_back(std::move(ring));
        }
        d->polygons.push_back(std::move(loops));
    }
    if (emptyPrimitive(reader, args, d->polygons.size(), "polygons")) return false;
    ClassCounts counts;
    counts.uniform = d->polygons.size();
    counts.varying = counts.vertex = npoints;
    counts.faceVarying = sum(loopSizes);
    d->Cs = readColors(args, params, counts);
    d->primvars = otherParams(args, params, counts, reader.log(), false, true);  // per face of the cut polygons
    return true;
}

// Any polygon request read as polygons: every key the same polygons, only the points move.
void polygonMeshKeys(RibParser& reader, const RibKeys& keys) {
    auto sameShape = [&keys](const PolygonMeshDesc& k, const PolygonMeshDesc& f) {
        if (k.polygons == f.polygons) return true;
        if (k.request == "Polygon")
            throw InputError(keys.requests.front().loc,
                             "the polygons in a motion block must have the same number of vertices (" +
                                 std::to_string(f.polygons[0][0].size()) + " and " +
                                 std::to_string(k.polygons[0][0].size()) + ")");
        return false;
    };
    auto positions = [](PolygonMeshDesc& d) -> auto& { return d.P; };
    if (auto d = mergeKeys<PolygonMeshDesc>(reader, keys, readPolygonsKey, sameShape,
                                            "polygons and vertex indices (only \"P\" may change)", positions)) {
        d->patchesBefore = reader.scene().patches.size();
        if (!d->P.empty()) addObjectSt(d->P.front(), *d);  // the first key's: texture does not swim
        reader.scene().polygonMeshes.push_back(std::move(*d));
    }
}

// A Polygon of 3 or 4 vertices: one polygon of one loop.
void addPolygon(RibParser& reader, const std::vector<double>& times, const std::vector<FaceKey>& keys,
                const SourceLoc& loc) {
    PolygonMeshDesc d;
    const bool moves = faceKeysMove(reader.log(), keys, loc);
    placePrimitive(reader, d, moves ? times : std::vector<double>{times.front()}, loc);
    d.request = "Polygon";
    for (size_t i = 0; i < d.times.size(); ++i) d.P.push_back(keys[i].P);
    std::vector<int> loop(keys.front().P.size());
    std::iota(loop.begin(), loop.end(), 0);
    d.polygons = {{loop}};
    d.Cs = keys.front().Cs;
    d.primvars = keys.front().primvars;  // per vertex around the loop: polygonAsPatch puts them at the corners
    addObjectSt(d.P.front(), d);
    d.patchesBefore = reader.scene().patches.size();
    const std::vector<Vec3d>& v = d.P.front();  // around the edge: corners in patch order
    shapeAreaLight(reader, {v.size() == 4 ? std::array<Vec3d, 4>{v[0], v[1], v[3], v[2]} : std::array<Vec3d, 4>{v[0], v[1], v[2], v[2]}},
                   loc);
    reader.scene().polygonMeshes.push_back(std::move(d));
}

// A Polygon of 3 or 4 vertices is read as a single face, with the checks of Patch "bilinear" in
// their order; a larger one as polygons.
void polygon(RibParser& reader, RibArgs& args) {
    FaceKey key;
    if (readFaceKey(reader, args, true, &key))
        addPolygon(reader, {0.0}, {key}, args.loc());
    else
        polygonMeshKeys(reader, {{0.0}, {args.request()}, args.usage()});
}

void polygonKeys(RibParser& reader, const RibKeys& keys) {
    std::vector<FaceKey> faces(keys.requests.size());
    for (size_t i = 0; i < faces.size(); ++i) {
        RibArgs args(keys.requests[i], keys.usage);
        if (!readFaceKey(reader, args, true, &faces[i])) {
            polygonMeshKeys(reader, keys);  // more than four vertices
            return;
        }
    }
    addPolygon(reader, keys.times, faces, keys.requests.front().loc);
}

}  // namespace

void addPolygonRequests(RibRequestTable& table) {
    const RibPhase world = RibPhase::World;
    table.add("Polygon", {polygon, "Polygon \"P\" [x y z ...]", world, polygonKeys});
    table.add("GeneralPolygon", {oneKey<polygonMeshKeys>, "GeneralPolygon [nvertices per loop] \"P\" [...]", world,
                                 polygonMeshKeys});
    table.add("PointsPolygons", {oneKey<polygonMeshKeys>, "PointsPolygons [nvertices] [vertices] \"P\" [...]", world,
                                 polygonMeshKeys});
    table.add("PointsGeneralPolygons", {oneKey<polygonMeshKeys>,
                                        "PointsGeneralPolygons [nloops] [nvertices] [vertices] \"P\" [...]", world,
                                        polygonMeshKeys});
}

}  // namespace streyes
