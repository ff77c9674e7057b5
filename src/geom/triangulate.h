// Cutting polygons into faces the renderer takes: triangles, and quads that are convex.
//
// RenderMan's polygons are planar, may be concave and (GeneralPolygon) may have holes. They are
// projected onto the plane of their largest area (Newell's normal), holes are joined to the
// outer loop by bridges to a mutually visible vertex (Eberly, "Triangulation by ear clipping"),
// and the result is cut by ear clipping. The faces keep the polygon's winding.
#pragma once

#include <array>
#include <vector>

#include "streyes/vecmath.h"

namespace streyes {

// Faces of a polygon as corner indices into `points` in patch order: a convex quad v0 v1 v2 v3
// as {v0, v1, v3, v2}, a triangle a b c as {a, b, c, c}. loops[0] is the outer boundary, the
// others are holes. False when the polygon has no area (all points on a line, or repeated).
bool cutPolygon(const std::vector<Vec3d>& points, const std::vector<std::vector<int>>& loops,
                std::vector<std::array<int, 4>>* faces);

}  // namespace streyes
