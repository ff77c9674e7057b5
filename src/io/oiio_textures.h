// Textures in the image library module (image_library.h): OpenImageIO's TextureSystem behind
// sl::TextureSource, and maketx. Part of libstreyes_oiio.so only.
#pragma once

#include <string>
#include <vector>

#include "io/image_library.h"

namespace streyes {

sl::TextureSource* makeOiioTextureSource(const std::vector<std::string>& searchPath, TextureWarning warn);
bool makeOiioTexture(const MakeTextureDesc& desc, std::string* error);
// Why the picture at `path` cannot be read whole ("" when it can): it does not open, its header
// claims more than the file holds, or its pixels do not all read.
std::string pictureProblem(const std::string& path);

// MakeCubeFaceEnvironment's six faces resampled into a picture in OpenImageIO's lat-long layout
// (oiio_cube_faces.cpp), which makeOiioTexture makes a lat-long environment map of.
struct CubeFaceLatLong {
    int width = 0, height = 0;
    std::vector<std::string> channels;  // the faces' channel names
    int alphaChannel = -1;
    std::string format;                 // the faces' pixel type ("uint8", "half", "float", ...)
    std::vector<float> pixels;          // interleaved, top row first
};
// False, with *error naming the face, when a face cannot be read whole or the faces differ in size
// or channels.
bool resampleCubeFaces(const MakeTextureDesc& desc, CubeFaceLatLong* out, std::string* error);
// Depth maps as TIFF (oiio_depth_maps.cpp).
bool encodeOiioDepthMap(const std::string& path, const DepthMap& map, bool shadow, std::vector<unsigned char>* bytes,
                        std::string* error);
bool readOiioDepthMap(const std::string& path, DepthMap* out, std::string* error);

}  // namespace streyes
