// The image library module: what streyes needs of OpenImageIO (images other than EXR frames, a
// filtered resize for contact sheets, textures), in a shared module (libstreyes_oiio.so, built
// from oiio_library.cpp and oiio_textures.cpp) that is loaded the first time one of these is
// asked for. Rendering asks only when a shader looks a texture up or the scene makes one: other
// renders load OpenEXR, not the ~260 libraries OpenImageIO brings.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "shade/shadow_map.h"
#include "streyes/image_io.h"
#include "streyes/scene.h"

namespace streyes {

namespace sl {
class TextureSource;
}

// How the module reports a map it cannot read: `key` names the map (warn once per key).
using TextureWarning = std::function<void(const std::string& key, const std::string& message)>;

struct ImageLibrary {
    // Reads any image OpenImageIO reads, every channel as float. False, with *error, on failure.
    bool (*read)(const std::string& path, ImageData* out, std::string* error);
    // Encodes interleaved float pixels (channel names given) into the format that `path`'s
    // extension names, in memory, stored as `storage` ("float": what the format stores; "uint8" or
    // "uint16": pixels in [0, 1] become integers, as OpenImageIO converts). False, with *error,
    // when the format cannot be written.
    bool (*encode)(const std::string& path, int width, int height, const std::vector<std::string>& channels,
                   const float* pixels, const char* storage, std::vector<unsigned char>* bytes, std::string* error);
    // Scales interleaved float RGB pixels from w x h to nw x nh with a filtered resize.
    bool (*resize)(const float* rgb, int w, int h, float* out, int nw, int nh, std::string* error);
    // A texture source on a TextureSystem of its own (one per render; safe from every thread),
    // looking for maps named without a folder in `searchPath`. Delete it when the render is done.
    sl::TextureSource* (*makeTextureSource)(const std::vector<std::string>& searchPath, TextureWarning warn);
    // Makes a tiled, MIP-mapped texture or lat-long environment map (maketx). False, with *error.
    bool (*makeTexture)(const MakeTextureDesc& desc, std::string* error);
    // Depth maps (shade/shadow_map.h) as float TIFF files: one channel "z", the light camera's
    // matrices as "worldtocamera" and "worldtoscreen" (Pixar's TIFF tags, as PRMan's and Aqsis's
    // shadow maps carry them). `shadow`: tiled and marked textureformat "Shadow" (MakeShadow's
    // output, Display "shadow"); else scanlines (Display "zfile"). Encoded in memory.
    bool (*encodeDepthMap)(const std::string& path, const DepthMap& map, bool shadow, std::vector<unsigned char>* bytes,
                           std::string* error);
    // Reads one: false, with *error saying why, when it is not a depth map or does not read whole.
    bool (*readDepthMap)(const std::string& path, DepthMap* out, std::string* error);
};

// The module, loaded on first use (beside the executable, then from the installed library
// folder). Throws RenderError naming where it looked when it cannot be loaded.
const ImageLibrary& imageLibrary();

}  // namespace streyes

// The module's one entry point.
extern "C" const streyes::ImageLibrary* streyesImageLibrary();
