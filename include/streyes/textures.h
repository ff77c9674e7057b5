// Textures for renders (streyes::io): the texture source RenderOptions::textureSource takes, and
// the maps MakeTexture, MakeLatLongEnvironment and MakeCubeFaceEnvironment ask for. All go through
// the image library module (src/io/image_library.h), loaded only when a shader first looks a map
// up or a scene makes one:
//   makeSceneTextures(scene);
//   options.textureSource = streyes::openImageTextures;
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "streyes/error.h"
#include "streyes/scene.h"

namespace streyes {

namespace sl {
class TextureSource;
}

// OpenImageIO's TextureSystem for one render, looking in `searchPath` for maps named without a
// folder. A map that cannot be read is warned about once on `log`, naming it and the shader.
// Fits RenderOptions::textureSource. Throws RenderError when the module cannot be loaded.
std::shared_ptr<sl::TextureSource> openImageTextures(const std::vector<std::string>& searchPath, Log& log);

// Makes the scene's MakeTexture, MakeLatLongEnvironment and MakeCubeFaceEnvironment maps, in order.
// A map that cannot be made (its picture missing among them) is an InputError at its request's
// line. `done` (may be null) holds the outputs already made by this process: a sequence's blocks
// make each map once.
void makeSceneTextures(const Scene& scene, std::vector<std::string>* done = nullptr);

}  // namespace streyes
