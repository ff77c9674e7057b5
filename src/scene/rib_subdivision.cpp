// SubdivisionMesh "catmull-clark": faces as vertex loops, with RenderMan's tags (crease, corner,
// interpolateboundary, hole).
#include <algorithm>
#include <set>

#include "scene/rib_geometry.h"

namespace streyes {

namespace {

// One key; false for the schemes outside the subset ("loop", "bilinear": warned and skipped).
bool readSubdivisionKey(RibParser& reader, RibArgs& args, SubdivisionMeshDesc* d) {
    const RibValue* schemeValue = args.peek();
    const std::string scheme = args.string("scheme");
    if (scheme != "catmull-clark") {
        if (scheme == "loop" || scheme == "bilinear") {
            reader.log().warnOnce(
                "subdivision:" + scheme, args.loc(),
                "SubdivisionMesh \"" + scheme + "\" is not supported (only \"catmull-clark\"): skipped");
            args.skipRest();
            return false;
        }
        args.fail(*schemeValue, "unknown subdivision scheme \"" + scheme + "\" (use \"catmull-clark\")");
    }
    d->faceSizes = intArray(args, "nvertices", 3);
    if (d->faceSizes.empty()) {
        args.skipRest();
        emptyPrimitive(reader, args, 0, "faces");
        return false;
    }
    d->faceVertices = intArray(args, "vertices", 0);
    if (d->faceVertices.size() != sum(d->faceSizes))
        args.fail("vertices has " + indexCount(d->faceVertices.size()) + " but the faces in nvertices need " +
                  std::to_string(sum(d->faceSizes)));
    d->vertexCount = 0;
    for (int v : d->faceVertices) d->vertexCount = std::max(d->vertexCount, v + 1);
    // A face that names a vertex twice has no sensible limit surface.
    std::set<std::pair<int, int>> edges;
    for (size_t f = 0, at = 0; f < d->faceSizes.size(); at += size_t(d->faceSizes[f]), ++f) {
        const int n = d->faceSizes[f];
        for (int i = 0; i < n; ++i) {
            const int a = d->faceVertices[at + size_t(i)], b = d->faceVertices[at + size_t((i + 1) % n)];
            for (int j = i + 1; j < n; ++j)
                if (d->faceVertices[at + size_t(j)] == a)
                    args.fail("face " + std::to_string(f) + " uses vertex " + std::to_string(a) + " twice");
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    }

    // Tags, if any: [tags] [nargs] [intargs] [floatargs] (and [stringargs] with 3 counts per tag).
    if (!args.done() && args.peek()->kind == RibValue::Kind::Array) {
        const std::vector<std::string> tags = takeArray(args, "tags", true).strings;
        const std::vector<int> nargs = intArray(args, "nargs", 0);
        const std::vector<double> ints = takeArray(args, "intargs", false).nums;
        const std::vector<double> floats = takeArray(args, "floatargs", false).nums;
        const size_t per = tags.empty() ? 2 : nargs.size() / tags.size();
        if ((per != 2 && per != 3) || nargs.size() != per * tags.size())
            args.fail("nargs must hold 2 (or 3) counts per tag: " + plural(tags.size(), "tag") + " and " +
                      plural(nargs.size(), "count"));
        if (per == 3) takeArray(args, "stringargs", true);
        size_t ii = 0, fi = 0;
        for (size_t t = 0; t < tags.size(); ++t) {
            const size_t ni = size_t(nargs[t * per]), nf = size_t(nargs[t * per + 1]);
            if (ii + ni > ints.size() || fi + nf > floats.size())
                args.fail("the tag \"" + tags[t] + "\" (tag " + std::to_string(t) +
                          ") asks for more intargs or floatargs than given");
            std::vector<int> iv;
            for (size_t k = 0; k < ni; ++k) {
                const double x = ints[ii + k];
                if (!isWholeInt(x)) args.fail("intargs must be whole numbers, got " + formatNumber(x));
                iv.push_back(int(x));
            }
            const std::vector<double> fv(floats.begin() + long(fi), floats.begin() + long(fi + nf));
            ii += ni, fi += nf;
            const std::string& tag = tags[t];
            auto fail = [&](const std::string& what) { args.fail("tag \"" + tag + "\": " + what); };
            auto checkVertex = [&](int v) {
                if (v < 0 || v >= d->vertexCount)
                    fail("vertex " + std::to_string(v) + " is not in the mesh (vertices 0 to " +
                         std::to_string(d->vertexCount - 1) + ")");
            };
            for (double s : fv)
                if (!(s >= 0)) fail("sharpness must not be negative, got " + formatNumber(s));
            if (tag == "crease") {
                // A chain of vertices, each consecutive pair an edge, with one sharpness for the chain
                // or one per edge (as USD and OpenSubdiv's RenderMan readers take them).
                if (iv.size() < 2 || (fv.size() != 1 && fv.size() != iv.size() - 1))
                    fail("give a chain of at least 2 vertices in intargs and one sharpness (or one per edge) in "
                         "floatargs");
                for (size_t k = 0; k + 1 < iv.size(); ++k) {
                    checkVertex(iv[k]);
                    checkVertex(iv[k + 1]);
                    if (!edges.count({std::min(iv[k], iv[k + 1]), std::max(iv[k], iv[k + 1])}))
                        fail("vertices " + std::to_string(iv[k]) + " and " + std::to_string(iv[k + 1]) +
                             " are not joined by an edge of the mesh");
                    d->creaseEdges.push_back(iv[k]);
                    d->creaseEdges.push_back(iv[k + 1]);
                    d->creaseSharpness.push_back(float(fv[fv.size() == 1 ? 0 : k]));
                }
            } else if (tag == "corner") {
                if (iv.empty() || (fv.size() != 1 && fv.size() != iv.size()))
                    fail("give the vertices in intargs and one sharpness (or one per vertex) in floatargs");
                for (size_t k = 0; k < iv.size(); ++k) {
                    checkVertex(iv[k]);
                    d->corners.push_back(iv[k]);
                    d->cornerSharpness.push_back(float(fv[fv.size() == 1 ? 0 : k]));
                }
            } else if (tag == "interpolateboundary") {
                if (iv.size() > 1 || !fv.empty()) fail("takes at most one integer (0, 1 or 2)");
                const int mode = iv.empty() ? 1 : iv[0];
                if (mode < 0 || mode > 2) fail("the mode must be 0, 1 or 2, got " + std::to_string(mode));
                d->interpolateBoundary = mode;
            } else if (tag == "hole") {
                for (int f : iv) {
                    if (f < 0 || size_t(f) >= d->faceSizes.size())
                        fail("face " + std::to_string(f) + " is not in the mesh (" +
                             plural(d->faceSizes.size(), "face") + ")");
                    d->holes.push_back(f);
                }
            } else {
                reader.log().warnOnce("subdivision-tag:" + tag, args.loc(),
                                      "SubdivisionMesh tag \"" + tag + "\" is not supported: ignored");
            }
        }
    }
    ParamList params = reader.readParams(args);
    const Param& pos = positionParam(args, params);
    checkCount(args, pos, size_t(d->vertexCount));
    ClassCounts counts;
    counts.uniform = d->faceSizes.size();
    counts.varying = counts.vertex = size_t(d->vertexCount);
    counts.faceVarying = d->faceVertices.size();
    d->P = {pointsOf(args, pos)};
    d->Cs = readColors(args, params, counts);
    // Per face (uniform), per vertex (varying: bilinear over each face; vertex: subdivided like P)
    // and per face vertex (facevarying: bilinear over each face, discontinuous between faces).
    d->primvars = otherParams(args, params, counts, reader.log(), false, true);
    return true;
}

void subdivisionKeys(RibParser& reader, const RibKeys& keys) {
    auto sameShape = [](const SubdivisionMeshDesc& k, const SubdivisionMeshDesc& f) {
        return k.faceSizes == f.faceSizes && k.faceVertices == f.faceVertices && k.creaseEdges == f.creaseEdges &&
               k.creaseSharpness == f.creaseSharpness && k.corners == f.corners &&
               k.cornerSharpness == f.cornerSharpness && k.holes == f.holes &&
               k.interpolateBoundary == f.interpolateBoundary;
    };
    auto positions = [](SubdivisionMeshDesc& d) -> auto& { return d.P; };
    if (auto d = mergeKeys<SubdivisionMeshDesc>(reader, keys, readSubdivisionKey, sameShape,
                                                "topology and tags (only \"P\" may change)", positions))
        reader.scene().subdivisionMeshes.push_back(std::move(*d));
}

}  // namespace

void addSubdivisionRequests(RibRequestTable& table) {
    table.add("SubdivisionMesh", {oneKey<subdivisionKeys>,
                                  "SubdivisionMesh \"catmull-clark\" [nvertices] [vertices] [tags] [nargs] "
                                  "[intargs] [floatargs] \"P\" [...]",
                                  RibPhase::World, subdivisionKeys});
}

}  // namespace streyes
