// Depth maps as files (shade/shadow_map.h): what a depth pass's Display "zfile" or "shadow" and
// MakeShadow write, and what shadow() reads when no pass of the render makes a map. Float TIFF
// through the image library module (image_library.h: the layout PRMan's and Aqsis's maps have).
#pragma once

#include <string>

#include "shade/shadow_map.h"

namespace streyes {

// Writes `map` to `path` as a shadow map (`shadow`: tiled, textureformat "Shadow") or a zfile,
// atomically (a temporary file renamed into place), with the maps before it (map.previous) as
// the file's first directories. Throws RenderError when it cannot.
void writeDepthMapFile(const std::string& path, const DepthMap& map, bool shadow);

// Reads a depth map (a file of several: the last, the others chained as its `previous`): false,
// with *error saying why (missing, not a depth map, truncated).
bool readDepthMapFile(const std::string& path, DepthMap* out, std::string* error);

}  // namespace streyes
