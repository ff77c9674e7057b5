// The environment map of indirectdiffuse() and occlusion() ("environmentmap", read in
// "environmentspace"): what a direction no surface covers sees. Shared by the ray-traced path
// (trace/shader_rays.cpp: a ray that hits nothing) and the point-based one
// (shadeops_pointbased.cpp: a microbuffer pixel no disc covers), so both read a map the same way.
#pragma once

#include <vector>

#include "shade/vm/ray_source.h"
#include "shade/vm/texture_source.h"

namespace streyes::sl {

// Looks o.environmentmap up in n unit directions d (x, y, z interleaved; current space, taken
// into the map's space by o.environmentFromCurrent), direction i filtered over a square cone of
// width[i] radians a side (all `width` when `widths` is null). Writes out (RGB interleaved) and
// returns true; false when there is no source or the map cannot be read (out left as it is; the
// texture source warns). `scratch` is the caller's, reused from call to call.
bool lookupEnvironment(TextureSource* textures, const RayOptions& o, const float* d, int n, const float* widths,
                       float width, float time, std::vector<float>& scratch, float* out);

}  // namespace streyes::sl
