// Depth maps as float TIFF files through OpenImageIO (image_library.h: encodeDepthMap,
// readDepthMap). Part of libstreyes_oiio.so only.
//
// The layout is PRMan's and Aqsis's: one 32-bit float channel of light camera-space depth, and
// the light's matrices in Pixar's TIFF tags (OpenImageIO's "worldtocamera" and "worldtoscreen":
// row vectors, p * M, as RenderMan writes matrices). A shadow map (MakeShadow, Display "shadow")
// is tiled 64 x 64 and says textureformat "Shadow"; a zfile is scanlines. No MIP levels: depths
// are never averaged. A multi-map file (Display "append": DepthMap::previous) is one TIFF
// directory a map, as Aqsis writes its occlusion maps.
#include <unistd.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <set>
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

// The worldtocamera (33306) and worldtoscreen (33305) tags of every directory of a classic TIFF
// file, in order; false when the file is no classic TIFF, or a directory lacks either.
bool readTiffMatrices(const std::string& path, std::vector<std::pair<Matrix4, Matrix4>>* out) {
    std::ifstream f(path, std::ios::binary);
    std::vector<unsigned char> d((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (d.size() < 8 || !((d[0] == 'I' && d[1] == 'I') || (d[0] == 'M' && d[1] == 'M'))) return false;
    const bool little = d[0] == 'I';
    auto u = [&](size_t at, int bytes, uint64_t* v) {
        if (at + size_t(bytes) > d.size()) return false;
        *v = 0;
        for (int i = 0; i < bytes; ++i) *v |= uint64_t(d[at + size_t(little ? i : bytes - 1 - i)]) << (8 * i);
        return true;
    };
    uint64_t magic = 0, ifd = 0;
    if (!u(2, 2, &magic) || magic != 42 || !u(4, 4, &ifd)) return false;
    std::set<uint64_t> seen;
    while (ifd != 0) {
        if (!seen.insert(ifd).second || seen.size() > 65536) return false;  // a loop
        uint64_t count = 0;
        if (!u(size_t(ifd), 2, &count)) return false;
        Matrix4 toCamera, toScreen;
        int found = 0;
        for (uint64_t e = 0; e < count; ++e) {
            const size_t at = size_t(ifd) + 2 + 12 * size_t(e);
            uint64_t tag = 0, type = 0, n = 0, offset = 0;
            if (!u(at, 2, &tag) || !u(at + 2, 2, &type) || !u(at + 4, 4, &n) || !u(at + 8, 4, &offset)) return false;
            if ((tag != 33305 && tag != 33306) || n != 16 || (type != 11 && type != 12)) continue;
            Matrix4& m = tag == 33306 ? toCamera : toScreen;
            const int size = type == 11 ? 4 : 8;
            for (size_t k = 0; k < 16; ++k) {
                uint64_t bits = 0;
                if (!u(size_t(offset) + k * size_t(size), size, &bits)) return false;
                if (size == 4) {
                    const uint32_t b32 = uint32_t(bits);
                    float v;
                    std::memcpy(&v, &b32, sizeof v);
                    m.m[k] = double(v);
                } else {
                    double v;
                    std::memcpy(&v, &bits, sizeof v);
                    m.m[k] = v;
                }
            }
            found |= tag == 33306 ? 1 : 2;
        }
        if (found != 3) return false;
        out->push_back({toCamera, toScreen});
        if (!u(size_t(ifd) + 2 + 12 * size_t(count), 4, &ifd)) return false;
    }
    return true;
}

}  // namespace

bool encodeOiioDepthMap(const std::string& path, const DepthMap& map, bool shadow, std::vector<unsigned char>* bytes,
                        std::string* error) {
    auto out = OIIO::ImageOutput::create("tiff");
    if (!out) {
        *error = "OpenImageIO cannot write TIFF (" + OIIO::geterror() + ")";
        return false;
    }
    // The file's maps in order (Display "append": one TIFF directory a map, as Aqsis writes them).
    std::vector<const DepthMap*> maps;
    for (const DepthMap* m = &map; m; m = m->previous.get()) maps.insert(maps.begin(), m);
    std::vector<OIIO::ImageSpec> specs;
    for (const DepthMap* d : maps) {
        OIIO::ImageSpec spec(d->width, d->height, 1, OIIO::TypeDesc::FLOAT);
        spec.channelnames = {"z"};
        spec.z_channel = 0;
        float m[16];
        toFloats(d->worldToCamera, m);
        spec.attribute("worldtocamera", OIIO::TypeMatrix, m);
        toFloats(d->worldToScreen, m);
        spec.attribute("worldtoscreen", OIIO::TypeMatrix, m);
        spec.attribute("compression", "zip");
        spec.attribute("DateTime", "2000:01:01 00:00:00");  // fixed: the same depths give the same bytes
        spec.attribute("Software", "streyes");
        if (shadow) {
            spec.tile_width = spec.tile_height = 64;
            spec.attribute("textureformat", "Shadow");
        }
        specs.push_back(spec);
    }
    if (maps.size() > 1 && !out->supports("multiimage")) {
        *error = "OpenImageIO's TIFF writer cannot write several images to one file";
        return false;
    }
    auto writeAll = [&](const std::string& target, OIIO::Filesystem::IOProxy* proxy) {
        if (proxy)
            for (OIIO::ImageSpec& spec : specs) spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        if (!out->open(target, int(specs.size()), specs.data())) return false;
        for (size_t i = 0; i < maps.size(); ++i) {
            if (i > 0 && !out->open(target, specs[i], OIIO::ImageOutput::AppendSubimage)) return false;
            if (!out->write_image(OIIO::TypeDesc::FLOAT, maps[i]->z.data())) return false;
        }
        return out->close();
    };
    // (OpenImageIO 2.4's TIFF writer keeps only the first of several images through a proxy.)
    if (maps.size() == 1 && out->supports("ioproxy")) {
        OIIO::Filesystem::IOVecOutput memory(*bytes);
        if (!writeAll(path, &memory)) {
            *error = out->geterror();
            return false;
        }
        return true;
    }
    // Otherwise through a scratch file, read back into memory.
    std::error_code ec;
    const std::filesystem::path scratch =
        std::filesystem::temp_directory_path(ec) / ("streyes-depth-" + std::to_string(::getpid()) + ".tif");
    const bool ok = writeAll(scratch.string(), nullptr);
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
    // Every TIFF directory is a map (Display "append"). OpenImageIO shows a texture file's
    // directories as MIP levels (Aqsis's occlusion maps) and others as subimages: both, in order.
    std::vector<std::pair<int, int>> dirs;
    for (int s = 0; in->seek_subimage(s, 0); ++s)
        for (int m = 0; in->seek_subimage(s, m); ++m) dirs.push_back({s, m});
    if (dirs.empty()) {
        *error = "it holds no image";
        return false;
    }
    // Several: each directory's matrices from its own TIFF tags, which OpenImageIO gives only for
    // the first of a texture's levels.
    std::vector<std::pair<Matrix4, Matrix4>> tagged;
    if (dirs.size() > 1 && !readTiffMatrices(path, &tagged)) {
        *error = "it holds " + std::to_string(dirs.size()) +
                 " images, but their worldtocamera and worldtoscreen tags do not read (a multi-map file is a TIFF "
                 "whose every directory is a depth map)";
        return false;
    }
    if (!tagged.empty() && tagged.size() != dirs.size()) {
        *error = "it holds " + std::to_string(dirs.size()) + " images, and " + std::to_string(tagged.size()) +
                 " with both worldtocamera and worldtoscreen: each must be a depth map";
        return false;
    }
    std::shared_ptr<DepthMap> chain;
    for (size_t i = 0; i < dirs.size(); ++i) {
        const std::string which = dirs.size() > 1 ? "image " + std::to_string(i + 1) + " of its " +
                                                        std::to_string(dirs.size()) + ": "
                                                  : std::string();
        if (!in->seek_subimage(dirs[i].first, dirs[i].second)) {
            *error = which + in->geterror();
            return false;
        }
        const OIIO::ImageSpec spec = in->spec();
        if (spec.nchannels != 1 || spec.channelformat(0) != OIIO::TypeDesc::FLOAT) {
            *error = which + "it is not a depth map (" + std::to_string(spec.nchannels) + " channel" +
                     (spec.nchannels == 1 ? "" : "s") + " of " + spec.channelformat(0).c_str() +
                     "; a depth map has one channel of 32-bit floats)";
            return false;
        }
        auto m = std::make_shared<DepthMap>();
        if (tagged.empty()) {
            const OIIO::ParamValue* toCamera = spec.find_attribute("worldtocamera", OIIO::TypeMatrix);
            const OIIO::ParamValue* toScreen = spec.find_attribute("worldtoscreen", OIIO::TypeMatrix);
            if (!toCamera || !toScreen) {
                *error = "it is not a depth map (no worldtocamera and worldtoscreen matrices: not made by a depth pass "
                         "or MakeShadow)";
                return false;
            }
            m->worldToCamera = fromFloats(static_cast<const float*>(toCamera->data()));
            m->worldToScreen = fromFloats(static_cast<const float*>(toScreen->data()));
        } else {
            m->worldToCamera = tagged[i].first;
            m->worldToScreen = tagged[i].second;
        }
        if (spec.width < 1 || spec.height < 1) {
            *error = which + "it holds no pixels";
            return false;
        }
        m->width = spec.width;
        m->height = spec.height;
        m->z.resize(size_t(spec.width) * size_t(spec.height));
        if (!in->read_image(dirs[i].first, dirs[i].second, 0, 1, OIIO::TypeDesc::FLOAT, m->z.data())) {
            *error = which + in->geterror();
            if (error->size() == which.size()) *error += "its pixels do not read (truncated?)";
            return false;
        }
        m->previous = std::move(chain);
        chain = std::move(m);
    }
    *out = std::move(*chain);
    return true;
}

}  // namespace streyes
