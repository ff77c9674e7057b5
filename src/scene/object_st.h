// Texture coordinates of polygons given none: the RI Spec (3.2, "Polygons") makes a polygon's
// surface parameters its object-space (x, y) and its texture coordinates (s, t) those, unless
// "s", "t" or "st" are given per vertex; Aqsis 1.8.4 does the same. Polygon, GeneralPolygon,
// PointsPolygons, PointsGeneralPolygons and the Blobby (drawn as a polygon mesh) take them, as
// read and, in an object's instances, under the instance's attributes.
#pragma once

#include <vector>

#include "streyes/scene.h"

namespace streyes {

// Adds "s" and "t" as vertex primitive variables of `d` from the x and y of its object-space
// points P (one per vertex), unless `d` gives "s", "t" or "st", or no shader of its attributes
// may read them (the built-in surfaces read neither, and a primitive variable would take the
// primitive off the built-in shading).
void addObjectSt(const std::vector<Vec3d>& P, PolygonMeshDesc& d);

}  // namespace streyes
