// Depth maps as float TIFF files through OpenImageIO (image_library.h: encodeDepthMap,
// readDepthMap). Part of libstreyes_oiio.so only.
//
// The layout is PRMan's and Aqsis's: one 32-bit float channel of light camera-space depth, and
// the light's matrices in Pixar's TIFF tags (OpenImageIO's "worldtocamera" and "worldtoscreen":
// row vectors, p * M, as RenderMan writes matrices). A shadow map (MakeShadow, Display "shadow")
// is tiled 64 x 64 and says textureformat "Shadow"; a zfile is scanlines. No MIP levels: depths
// are never averaged.
#include <unistd.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <filesystem>

#include "io/oiio_textures.h"

namespace streyes {

namespace {

void toFloats(const Matrix4& m, float* out) {
    for (int i = 0; i < 16; ++i) out[i] = float(m.m[size_t(i)]);
}

Matrix4 fromFloats(const float* f) {
    Matrix4 m;
    for (int i = 0; i < 16; ++i) m.m[size_t(i)] = double(f[i]);
    return m;
}

}  // namespace

bool encodeOiioDepthMap(const std::string& path, const DepthMap& map, bool shadow, std::vector<unsigned char>* bytes,
                        std::string* error) {
    auto out = OIIO::ImageOutput::create("tiff");
    if (!out) {
        *error = "OpenImageIO cannot write TIFF (" + OIIO::geterror() + ")";
        return false;
    }
    OIIO::ImageSpec spec(map.width, map.height, 1, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"z"};
    spec.z_channel = 0;
    float m[16];
    toFloats(map.worldToCamera, m);
    spec.attribute("worldtocamera", OIIO::TypeMatrix, m);
    toFloats(map.worldToScreen, m);
    spec.attribute("worldtoscreen", OIIO::TypeMatrix, m);
    spec.attribute("compression", "zip");
    spec.attribute("DateTime", "2000:01:01 00:00:00");  // fixed: the same depths give the same bytes
    spec.attribute("Software", "streyes");
    if (shadow) {
        spec.tile_width = spec.tile_height = 64;
        spec.attribute("textureformat", "Shadow");
    }
    if (out->supports("ioproxy")) {
        OIIO::Filesystem::IOVecOutput memory(*bytes);
        OIIO::Filesystem::IOProxy* proxy = &memory;
        spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, map.z.data()) || !out->close()) {
            *error = out->geterror();
            return false;
        }
        return true;
    }
    // Without an I/O proxy: through a scratch file, read back into memory.
    std::error_code ec;
    const std::filesystem::path scratch =
        std::filesystem::temp_directory_path(ec) / ("streyes-depth-" + std::to_string(::getpid()) + ".tif");
    const bool ok =
        out->open(scratch.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, map.z.data()) && out->close();
    if (!ok) *error = out->geterror();
    if (ok) {
        FILE* f = std::fopen(scratch.c_str(), "rb");
        if (!f) {
            *error = "cannot read back " + scratch.string();
        } else {
            unsigned char buf[1 << 16];
            for (size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) bytes->insert(bytes->end(), buf, buf + n);
            std::fclose(f);
        }
    }
    std::filesystem::remove(scratch, ec);
    return ok && error->empty();
}

bool readOiioDepthMap(const std::string& path, DepthMap* out, std::string* error) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        *error = OIIO::geterror();
        if (error->empty()) *error = "it cannot be read as an image";
        return false;
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.nchannels != 1 || spec.channelformat(0) != OIIO::TypeDesc::FLOAT) {
        *error = "it is not a depth map (" + std::to_string(spec.nchannels) + " channel" +
                 (spec.nchannels == 1 ? "" : "s") + " of " + spec.channelformat(0).c_str() +
                 "; a depth map has one channel of 32-bit floats)";
        return false;
    }
    const OIIO::ParamValue* toCamera = spec.find_attribute("worldtocamera", OIIO::TypeMatrix);
    const OIIO::ParamValue* toScreen = spec.find_attribute("worldtoscreen", OIIO::TypeMatrix);
    if (!toCamera || !toScreen) {
        *error = "it is not a depth map (no worldtocamera and worldtoscreen matrices: not made by a depth pass or "
                 "MakeShadow)";
        return false;
    }
    if (spec.width < 1 || spec.height < 1) {
        *error = "it holds no pixels";
        return false;
    }
    DepthMap m;
    m.width = spec.width;
    m.height = spec.height;
    m.worldToCamera = fromFloats(static_cast<const float*>(toCamera->data()));
    m.worldToScreen = fromFloats(static_cast<const float*>(toScreen->data()));
    m.z.resize(size_t(spec.width) * size_t(spec.height));
    if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, m.z.data())) {
        *error = in->geterror();
        if (error->empty()) *error = "its pixels do not read (truncated?)";
        return false;
    }
    *out = std::move(m);
    return true;
}

}  // namespace streyes
