// Polygons as bilinear patches, the flat faces the renderer draws.
//
// The scene keeps polygons as RIB wrote them (PolygonMeshDesc). A Polygon of 3 vertices, or of 4
// that stays one face at every key, is one bilinear patch, as RenderMan dices it: a quad v0 v1 v2
// v3 (in order around its edge) has the corners v0 v1 v3 v2, a triangle v0 v1 v2 the corners
// v0 v1 v2 v2 (one collapsed edge), and "Cs" goes with the vertices. Any other polygon is cut at
// its first key (geom/triangulate.h) into triangles and convex quads that share the points of
// every key; a concave quad would fold as a patch, so it is cut too.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "streyes/scene.h"

namespace streyes {

// The bilinear patch a polygon mesh is: nothing unless it is one Polygon of 3 or 4 vertices that
// is convex at every key.
std::optional<BilinearPatchDesc> polygonAsPatch(const PolygonMeshDesc& mesh);

// The faces of a polygon mesh, cut at its first key. A polygon without area (its points on one
// line) warns (once) and has none.
struct PolygonFaces {
    std::vector<std::array<int, 4>> faces;     // indices into the points, in patch order (a b c c)
    std::vector<std::array<Color, 4>> faceCs;  // per face corner; empty: the attribute Color
    std::vector<size_t> facePolygon;           // per face: the polygon it was cut from
    std::vector<std::array<size_t, 4>> faceCorner;  // per face corner: its loop vertex in the mesh (facevarying)
};
PolygonFaces cutPolygons(const PolygonMeshDesc& mesh, Log& log);
// A colour-like primitive variable at each face's corners, by its class: uniform per polygon,
// facevarying by the polygon's own corner, varying and vertex by point.
std::vector<std::array<Color, 4>> faceCorners(const PolygonFaces& faces, const ColorPrimvar& v);

}  // namespace streyes
