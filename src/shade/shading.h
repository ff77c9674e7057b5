// Shading: the built-in surface shaders (constant, matte, plastic, defaultsurface) and lights
// (ambientlight, distantlight, pointlight), evaluated at grid vertices in camera space.
//
// REYES shades the vertices of a diced grid, not samples. A moving grid is shaded at t0 and at
// t1 and the colour is interpolated in time between them; a still grid is shaded once.
//
// Shadows: a light declared with Attribute "light" "shadows" "on" has a shadow slot. Its
// contribution is kept apart from the rest (shadePoint's `shadowed` parts; Grid::Cl per vertex)
// and added per sample where a shadow ray at the sample's own time reaches the light (trace.h),
// so shadows blur with motion even on still geometry shaded once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bodies/material.h"
#include "geom/lights.h"

namespace streyes {

struct Grid;

// The colour Ci of one surface point (position p, unnormalised normal n, surface colour cs, all
// in camera space): what shadeGrid computes at each vertex and the ray tracer at each hit.
// With `shadowed` given (room for `slots` colours), the contribution of each light that casts
// shadows goes to shadowed[its slot] instead of the result (0 where it does not reach); without
// it, every light is in the result.
Color shadePoint(const Material& m, Color cs, Vec3f p, Vec3f n, bool orthographic,
                 const std::vector<CameraLight>& lights, Color* shadowed = nullptr, int slots = 0);

// Shades grid.Ci[k] for every vertex at the grid's t0 (and t1 when moving). `orthographic`
// sets the view direction to +z instead of from the eye. With grid.shadowSlots > 0 the lights
// that cast shadows go to grid.Cl[k] instead.
void shadeGrid(Grid& grid, const LightSet& lights, bool orthographic, std::vector<CameraLight>& scratch);
// One end of a grid: Ci[k] (and Cl[k]) from P[k], N[k] at `time` (a grid diced at several keys is
// shaded a key at a time). With `need`, only the vertices where it is non-zero: the others keep
// what they held (each vertex is shaded on its own, so those shaded get the same colours).
void shadeGridSlot(Grid& grid, int k, double time, const LightSet& lights, bool orthographic,
                   std::vector<CameraLight>& scratch, const uint8_t* need = nullptr);

}  // namespace streyes
