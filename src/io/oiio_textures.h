// Textures in the image library module (image_library.h): OpenImageIO's TextureSystem behind
// sl::TextureSource, and maketx. Part of libstreyes_oiio.so only.
#pragma once

#include <string>
#include <vector>

#include "io/image_library.h"

namespace streyes {

sl::TextureSource* makeOiioTextureSource(const std::vector<std::string>& searchPath, TextureWarning warn);
bool makeOiioTexture(const MakeTextureDesc& desc, std::string* error);
// Depth maps as TIFF (oiio_depth_maps.cpp).
bool encodeOiioDepthMap(const std::string& path, const DepthMap& map, bool shadow, std::vector<unsigned char>* bytes,
                        std::string* error);
bool readOiioDepthMap(const std::string& path, DepthMap* out, std::string* error);

}  // namespace streyes
