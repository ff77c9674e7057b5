// Scenes the pass planner (streyes/passes.h) reads or makes: the strings a frame names (the maps
// and textures it may read) and the depth frame an "autoshadows" light renders.
#pragma once

#include <map>
#include <string>

#include "streyes/scene.h"

namespace streyes {

// Every string a shader parameter of the scene gives (lights, surfaces, displacements,
// atmospheres, the imager, in objects too), with where it is first given: the names a frame may
// read maps and textures by.
void stringsOf(const Scene& s, std::map<std::string, SourceLoc>& out);

// Attribute "autoshadows" on a light (Aqsis): the depth frame rendered from it before the frame.
Scene autoShadowFrame(const Scene& picture, const LightDesc& light);

}  // namespace streyes
