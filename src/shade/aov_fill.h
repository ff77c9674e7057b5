// Output variables per vertex (util/aov.h): what a shaded grid carries to the samples for the
// displays that ask for more than colour.
//
// N is the shading normal as diced (or displaced), normalised; P the position; both in camera
// space. s and t are the grid's u and v over the body's parameter rectangle, as the shaders see
// them. Ci is the shaded colour, Oi the shaded opacity (Grid::Oi). motion is the vertex's raster
// motion in pixels per frame (x right, y down): (raster(P at t1) - raster(P at t0)) / (t1 - t0)
// for a grid moving from t0 to t1 (a body moving linearly through its piece; keyed bodies one key
// interval at a time), 0 for a still one.
#pragma once

#include "geom/camera.h"
#include "geom/grid.h"
#include "util/aov.h"

namespace streyes {

// Fills grid.aov[k] for every slot the grid has, after shading (grid.aovCount == layout.count).
void fillAovs(Grid& grid, const AovLayout& layout, const Camera& camera);

}  // namespace streyes
