// Polygons: Polygon, GeneralPolygon, PointsPolygons and PointsGeneralPolygons. A Polygon of 3 or 4
// vertices is a bilinear patch; other polygons are cut into triangles and convex quads.
#include <map>

#include "geom/triangulate.h"
#include "scene/rib_geometry.h"

namespace streyes {

namespace {

// One key of a polygon request of any size: its points, its polygons as loops of indices into the
// points (the outline, then holes) and "Cs".
struct PolygonsKey : PrimitiveDesc {
    std::string request;
    std::vector<std::vector<Vec3d>> P;
    std::vector<std::vector<std::vector<int>>> polygons;
    ColorPrimvar Cs;
};

bool readPolygonsKey(RibParser& reader, RibArgs& args, PolygonsKey* d) {
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
    ClassCounts counts;
    counts.uniform = d->polygons.size();
    counts.varying = counts.vertex = npoints;
    counts.faceVarying = sum(loopSizes);
    d->Cs = readColors(args, params, counts);
    otherParams(args, params, counts, reader.log());
    return true;
}

// Cuts every polygon once (at the first key) into triangles and convex quads that share the points.
PolygonMeshDesc cutPolygons(Log& log, const PolygonsKey& k) {
    PolygonMeshDesc d;
    static_cast<PrimitiveDesc&>(d) = k;
    d.P = k.P;
    size_t faceVertex = 0;
    for (size_t p = 0; p < k.polygons.size(); ++p) {
        std::vector<std::array<int, 4>> faces;
        if (!cutPolygon(k.P[0], k.polygons[p], &faces))
            log.warnOnce("polygon:degenerate", k.loc,
                         k.request + ": a polygon has no area (its points are on one line): skipped");
        // Facevarying colours: the polygon's own corners, by point.
        std::map<int, size_t> cornerOf;
        for (const std::vector<int>& loop : k.polygons[p])
            for (int v : loop) cornerOf.emplace(v, faceVertex++);
        for (const std::array<int, 4>& f : faces) {
            d.faces.push_back(f);
            if (!k.Cs.given()) continue;
            std::array<Color, 4> c;
            for (size_t i = 0; i < 4; ++i) {
                const int v = f[i];
                switch (k.Cs.cls) {
                case ParamClass::Constant: c[i] = k.Cs.values[0]; break;
                case ParamClass::Uniform: c[i] = k.Cs.values[p]; break;
                case ParamClass::FaceVarying: c[i] = k.Cs.values[cornerOf[v]]; break;
                default: c[i] = k.Cs.values[size_t(v)];
                }
            }
            d.faceCs.push_back(c);
        }
    }
    return d;
}

// Any polygon request read as polygons: every key the same polygons, only the points move.
void polygonMeshKeys(RibParser& reader, const RibKeys& keys) {
    auto sameShape = [&keys](const PolygonsKey& k, const PolygonsKey& f) {
        if (k.polygons == f.polygons) return true;
        if (k.request == "Polygon")
            throw InputError(keys.requests.front().loc,
                             "the polygons in a motion block must have the same number of vertices (" +
                                 std::to_string(f.polygons[0][0].size()) + " and " +
                                 std::to_string(k.polygons[0][0].size()) + ")");
        return false;
    };
    auto positions = [](PolygonsKey& d) -> auto& { return d.P; };
    if (auto k = mergeKeys<PolygonsKey>(reader, keys, readPolygonsKey, sameShape,
                                        "polygons and vertex indices (only \"P\" may change)", positions)) {
        PolygonMeshDesc d = cutPolygons(reader.log(), *k);
        if (!d.faces.empty()) reader.scene().polygonMeshes.push_back(std::move(d));
    }
}

// A Polygon of 3 or 4 vertices as a bilinear patch. Corner c takes vertex order[c]: a quad's
// vertices go around its edge (0 1 2 3), a patch's corners row by row (0 1 / 2 3); a triangle
// repeats its last vertex as a collapsed edge.
void addPolygon(RibParser& reader, const std::vector<double>& times, const std::vector<FaceKey>& keys,
                const SourceLoc& loc) {
    static const int quadOrder[4] = {0, 1, 3, 2};
    static const int triangleOrder[4] = {0, 1, 2, 2};
    const int* order = keys.front().P.size() == 4 ? quadOrder : triangleOrder;
    BilinearPatchDesc patch;
    const bool moves = faceKeysMove(reader.log(), keys, loc);
    patch.times = moves ? times : std::vector<double>{times.front()};
    for (size_t i = 0; i < (moves ? keys.size() : 1); ++i) {
        std::array<Vec3d, 4>& corners = patch.P.emplace_back();
        for (size_t c = 0; c < 4; ++c) corners[c] = keys[i].P[size_t(order[c])];
    }
    const FaceKey& first = keys.front();
    patch.hasCs = first.Cs.given();
    if (patch.hasCs)
        for (size_t c = 0; c < 4; ++c) patch.Cs[c] = first.vertexCs[size_t(order[c])];
    patch.objectToWorld = reader.state().ctm;
    patch.attributes = reader.state().attributes;
    patch.loc = loc;
    reader.scene().patches.push_back(std::move(patch));
}

// A Polygon of 3 or 4 vertices is read as a single face, with the checks of Patch "bilinear" in
// their order; a larger one, or a concave quad, as polygons.
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
            polygonMeshKeys(reader, keys);  // more than four vertices, or concave
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
