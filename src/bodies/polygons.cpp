#include "bodies/polygons.h"

#include <map>

#include "geom/triangulate.h"

namespace streyes {

std::optional<BilinearPatchDesc> polygonAsPatch(const PolygonMeshDesc& mesh) {
    if (mesh.request != "Polygon" || mesh.polygons.size() != 1 || mesh.polygons[0].size() != 1) return std::nullopt;
    const std::vector<int>& loop = mesh.polygons[0][0];
    if (loop.size() != 3 && loop.size() != 4) return std::nullopt;
    if (loop.size() == 4) {
        for (const std::vector<Vec3d>& points : mesh.P) {
            std::vector<std::array<int, 4>> faces;
            if (cutPolygon(points, {loop}, &faces) && faces.size() > 1) return std::nullopt;  // concave
        }
    }
    // Corner c takes vertex order[c].
    static const int quadOrder[4] = {0, 1, 3, 2};
    static const int triangleOrder[4] = {0, 1, 2, 2};
    const int* order = loop.size() == 4 ? quadOrder : triangleOrder;
    BilinearPatchDesc patch;
    patch.times = mesh.times;
    for (const std::vector<Vec3d>& points : mesh.P) {
        std::array<Vec3d, 4>& corners = patch.P.emplace_back();
        for (size_t c = 0; c < 4; ++c) corners[c] = points[size_t(loop[size_t(order[c])])];
    }
    patch.hasCs = mesh.Cs.given();
    if (patch.hasCs) {
        const bool perVertex = mesh.Cs.cls != ParamClass::Constant && mesh.Cs.cls != ParamClass::Uniform;
        for (size_t c = 0; c < 4; ++c) patch.Cs[c] = mesh.Cs.values[perVertex ? size_t(loop[size_t(order[c])]) : 0];
    }
    // Primitive variables: constant ones as they are, per-vertex ones at the corners.
    for (const Param& v : mesh.primvars.params) {
        Param q = v;
        if (v.cls != ParamClass::Constant) {
            const size_t w = size_t(v.componentsPerItem());
            q.nums.clear();
            for (size_t c = 0; c < 4; ++c) {
                const size_t at = size_t(loop[size_t(order[c])]) * w;
                q.nums.insert(q.nums.end(), v.nums.begin() + long(at), v.nums.begin() + long(at + w));
            }
        }
        patch.primvars.params.push_back(std::move(q));
    }
    patch.objectToWorld = mesh.objectToWorld;
    patch.attributes = mesh.attributes;
    patch.loc = mesh.loc;
    patch.life = mesh.life;
    return patch;
}

PolygonFaces cutPolygons(const PolygonMeshDesc& mesh, Log& log) {
    PolygonFaces out;
    size_t faceVertex = 0;
    for (size_t p = 0; p < mesh.polygons.size(); ++p) {
        std::vector<std::array<int, 4>> faces;
        if (!cutPolygon(mesh.P[0], mesh.polygons[p], &faces))
            log.warnOnce("polygon:degenerate", mesh.loc,
                         mesh.request + ": a polygon has no area (its points are on one line): skipped");
        // Facevarying values: the polygon's own corners, by point.
        std::map<int, size_t> cornerOf;
        for (const std::vector<int>& loop : mesh.polygons[p])
            for (int v : loop) cornerOf.emplace(v, faceVertex++);
        for (const std::array<int, 4>& f : faces) {
            out.faces.push_back(f);
            out.facePolygon.push_back(p);
            out.faceCorner.push_back({cornerOf[f[0]], cornerOf[f[1]], cornerOf[f[2]], cornerOf[f[3]]});
        }
    }
    if (mesh.Cs.given()) out.faceCs = faceCorners(out, mesh.Cs);
    return out;
}

std::vector<std::array<Color, 4>> faceCorners(const PolygonFaces& faces, const ColorPrimvar& v) {
    std::vector<std::array<Color, 4>> out(faces.faces.size());
    for (size_t f = 0; f < out.size(); ++f)
        for (size_t k = 0; k < 4; ++k) {
            switch (v.cls) {
            case ParamClass::Constant: out[f][k] = v.values[0]; break;
            case ParamClass::Uniform: out[f][k] = v.values[faces.facePolygon[f]]; break;
            case ParamClass::FaceVarying: out[f][k] = v.values[faces.faceCorner[f][k]]; break;
            default: out[f][k] = v.values[size_t(faces.faces[f][k])];
            }
        }
    return out;
}

}  // namespace streyes
