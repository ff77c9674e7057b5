// The image library module (image_library.h): OpenImageIO behind a few functions (textures in
// oiio_textures.cpp). Built as its
// own shared module, libstreyes_oiio.so; nothing else in streyes links OpenImageIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <filesystem>

#include "io/image_library.h"
#include "io/image_size.h"
#include "io/oiio_textures.h"

namespace streyes {

namespace {

bool readWithOiio(const std::string& path, ImageData* out, std::string* error) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        *error = OIIO::geterror();
        return false;
    }
    const OIIO::ImageSpec& spec = in->spec();
    // The header is believed only as far as the file can hold it: the pixels are allocated next.
    std::error_code ec;
    const std::string implausible = implausibleImageSize(spec.width, spec.height, spec.nchannels,
                                                         int64_t(spec.format.size()), std::filesystem::file_size(path, ec));
    if (!implausible.empty()) {
        *error = implausible;
        return false;
    }
    ImageData img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels = spec.channelnames;
    for (int c = 0; c < spec.nchannels; ++c) img.formats.push_back(spec.channelformat(c).c_str());
    img.pixels.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
    // Some readers (TIFF's, for a truncated strip) succeed and report only through geterror.
    const bool read = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data());
    *error = in->geterror();
    if (!read || !error->empty()) {
        if (error->empty()) *error = "cannot read its pixels";
        return false;
    }
    *out = std::move(img);
    return true;
}

bool encodeWithOiio(const std::string& path, int width, int height, const std::vector<std::string>& channels,
                    const float* pixels, const char* storage, std::vector<unsigned char>* bytes, std::string* error) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        *error = "no image format for this file name (" + OIIO::geterror() + ")";
        return false;
    }
    if (!out->supports("ioproxy")) {
        *error = "this format cannot be written safely (use .exr or .png)";
        return false;
    }
    const std::string store = storage ? storage : "float";
    // Floats: the format picks what it stores; integers: what quantization made.
    const OIIO::TypeDesc type = store == "uint8"    ? OIIO::TypeDesc::UINT8
                                : store == "uint16" ? OIIO::TypeDesc::UINT16
                                                    : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(width, height, int(channels.size()), type);
    spec.channelnames = channels;
    spec.attribute("DateTime", "2000:01:01 00:00:00");  // fixed: the same pixels give the same bytes
    spec.attribute("Software", "streyes");
    OIIO::Filesystem::IOVecOutput memory(*bytes);
    OIIO::Filesystem::IOProxy* proxy = &memory;
    spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, pixels) || !out->close()) {
        *error = out->geterror();
        return false;
    }
    return true;
}

bool resizeWithOiio(const float* rgb, int w, int h, float* out, int nw, int nh, std::string* error) {
    OIIO::ImageBuf src(OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT), const_cast<float*>(rgb));
    OIIO::ImageBuf dst = OIIO::ImageBufAlgo::resize(src, "", 0.0f, OIIO::ROI(0, nw, 0, nh, 0, 1, 0, 3));
    if (dst.has_error() || !dst.get_pixels(OIIO::ROI(0, nw, 0, nh, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, out)) {
        *error = dst.geterror();
        return false;
    }
    return true;
}

const ImageLibrary kLibrary{readWithOiio,           encodeWithOiio,         resizeWithOiio,     makeOiioTextureSource,
                            makeOiioTexture,        encodeOiioDepthMap,     readOiioDepthMap};

}  // namespace

}  // namespace streyes

extern "C" __attribute__((visibility("default"))) const streyes::ImageLibrary* streyesImageLibrary() {
    return &streyes::kLibrary;
}
