// Finite differences over a grid of (nu + 1) x (nv + 1) points, u fastest (internal to shade/vm).
#pragma once

#include "shade/vm/shading_grid.h"

namespace streyes::sl {

// The change of f across one micropolygon along u (Du(f) du) at each of the grid's points:
// central differences inside, one-sided on the first and last column. 0 without a shape.
void diffU(const ShadingGrid& g, const float* f, float* out);
void diffV(const ShadingGrid& g, const float* f, float* out);
// du and dv at point i (the grid's values, or 1/nu and 1/nv).
float duAt(const ShadingGrid& g, int i);
float dvAt(const ShadingGrid& g, int i);

}  // namespace streyes::sl
