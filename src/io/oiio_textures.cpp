// texture() and environment() through OpenImageIO's TextureSystem, and MakeTexture through
// maketx (ImageBufAlgo::make_texture).
//
// One TextureSystem per render (not OIIO's shared one: a render's cache is its own), used from
// every bucket thread: lookups take the calling thread's Perthread record and the map's handle
// once per call, i.e. once per grid and call site, then go through OIIO's batch interface 16
// points a call.
//
// Texture space is OIIO's and RenderMan's alike: s runs left to right, t top to bottom, (0, 0)
// is the image's top-left corner and texel (x, y)'s centre is ((x + .5) / w, (y + .5) / h).
// The footprint is the change of s and t across one micropolygon along u and v (the grid's
// derivatives), given as OIIO's d/dx and d/dy. Wrap modes are the file's (MakeTexture's swrap
// and twrap; black for files that say none). Within a MIP level texels are interpolated
// bilinearly, so a lookup at a texel's centre gives the texel; "filter" "closest" takes the
// nearest texel and "filter" "bicubic" OIIO's smart bicubic.
#include "io/oiio_textures.h"

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <filesystem>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>
#include <vector>

#include "io/image_size.h"
#include "shade/vm/texture_source.h"

namespace streyes {

namespace {

constexpr int kBatch = OIIO::Tex::BatchWidth;

// "" when every pixel of the open image can be read, else why not: it is read through a band of rows
// at a time (memory for 64 rows). OpenImageIO's TIFF reader reports a truncated strip only through
// geterror, and succeeds; its texture lookups and maketx then see zeros, silently.
std::string unreadablePixels(OIIO::ImageInput& in) {
    const OIIO::ImageSpec& spec = in.spec();
    if (spec.tile_width > 0) {  // tiled: a tile at a time
        std::vector<float> tile(size_t(spec.tile_width) * size_t(spec.tile_height) * size_t(std::max(1, spec.tile_depth)) *
                                size_t(spec.nchannels));
        for (int y = spec.y; y < spec.y + spec.height; y += spec.tile_height)
            for (int x = spec.x; x < spec.x + spec.width; x += spec.tile_width) {
                const bool read = in.read_tile(x, y, spec.z, OIIO::TypeDesc::FLOAT, tile.data());
                std::string why = in.geterror();
                if (!read && why.empty()) why = "cannot read its pixels";
                if (!why.empty()) return why;
            }
        return "";
    }
    const int band = 64;
    std::vector<float> rows(size_t(spec.width) * size_t(spec.nchannels) * band);
    for (int y = spec.y; y < spec.y + spec.height; y += band) {
        const int end = std::min(y + band, spec.y + spec.height);
        const bool read = in.read_scanlines(0, 0, y, end, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, rows.data());
        std::string why = in.geterror();  // some readers report a short read only here, and succeed
        if (!read && why.empty()) why = "cannot read its pixels";
        if (!why.empty()) return why;
    }
    return "";
}

class OiioTextures final : public sl::TextureSource {
  public:
    OiioTextures(const std::vector<std::string>& searchPath, TextureWarning warn)
        : ts_(OIIO::TextureSystem::create(true)), warn_(std::move(warn)) {
        // OpenImageIO's shared TextureSystem: 2.4's TextureSystem::destroy deletes through a
        // mismatched type (AddressSanitizer: new-delete-type-mismatch), so the process keeps the
        // shared one and a render starts by forgetting what an earlier render of the process
        // read (files may have changed since).
        ts_->invalidate_all(true);
        for (const std::string& f : searchPath) path_ += (path_.empty() ? "" : ":") + f;
        folders_ = searchPath;
        // Images without MIP levels (a plain .exr or .png) get them made in memory, so that
        // large footprints are filtered rather than aliased.
        ts_->attribute("automip", 1);
    }
    ~OiioTextures() override = default;  // the shared TextureSystem stays with the process

    bool texture(const std::string& name, const sl::TextureOptions& o, const sl::TextureQuery& q,
                 float* const* out) override {
        OIIO::TextureSystem::Perthread* thread = ts_->get_perthread_info();
        OIIO::TextureSystem::TextureHandle* handle = open(name, thread, o, "texture");
        if (!handle) return false;
        OIIO::TextureOptBatch opt = batchOptions(o);
        alignas(64) float s[kBatch], t[kBatch], dsdx[kBatch], dtdx[kBatch], dsdy[kBatch], dtdy[kBatch];
        alignas(64) float result[3 * kBatch];
        const int channels = std::clamp(o.channels, 1, 3);
        for (int base = 0; base < q.n; base += kBatch) {
            const int w = std::min(kBatch, q.n - base);
            OIIO::Tex::RunMask mask = 0;
            for (int j = 0; j < kBatch; ++j) {
                const int i = base + j;
                const bool on = j < w && (!q.active || q.active[i]);
                if (on) mask |= OIIO::Tex::RunMask(1) << j;
                s[j] = on ? q.s[i] : 0;
                t[j] = on ? q.t[i] : 0;
                dsdx[j] = on ? q.dsdu[i] : 0;
                dtdx[j] = on ? q.dtdu[i] : 0;
                dsdy[j] = on ? q.dsdv[i] : 0;
                dtdy[j] = on ? q.dtdv[i] : 0;
            }
            if (!mask) continue;
            if (!ts_->texture(handle, thread, opt, mask, s, t, dsdx, dtdx, dsdy, dtdy, channels, result))
                return failed(name, o, "texture");
            copyOut(result, mask, base, channels, out);
        }
        return true;
    }

    bool environment(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q,
                     float* const* out) override {
        OIIO::TextureSystem::Perthread* thread = ts_->get_perthread_info();
        OIIO::TextureSystem::TextureHandle* handle = open(name, thread, o, "environment");
        if (!handle) return false;
        OIIO::TextureOptBatch opt = batchOptions(o);
        alignas(64) float R[3 * kBatch], dRdx[3 * kBatch], dRdy[3 * kBatch], result[3 * kBatch];
        const int channels = std::clamp(o.channels, 1, 3);
        for (int base = 0; base < q.n; base += kBatch) {
            const int w = std::min(kBatch, q.n - base);
            OIIO::Tex::RunMask mask = 0;
            for (int j = 0; j < kBatch; ++j) {
                const int i = base + j;
                const bool on = j < w && (!q.active || q.active[i]);
                if (on) mask |= OIIO::Tex::RunMask(1) << j;
                for (int c = 0; c < 3; ++c) {
                    R[c * kBatch + j] = on ? q.R[c][i] : (c == 2 ? 1.0f : 0.0f);
                    dRdx[c * kBatch + j] = on ? q.dRdu[c][i] : 0;
                    dRdy[c * kBatch + j] = on ? q.dRdv[c][i] : 0;
                }
            }
            if (!mask) continue;
            if (!ts_->environment(handle, thread, opt, mask, R, dRdx, dRdy, channels, result))
                return failed(name, o, "environment");
            copyOut(result, mask, base, channels, out);
        }
        return true;
    }

    // Shadow maps are not read: streyes ray traces shadows per sample instead (a light with
    // "shadowname" "raytrace"; shadow("raytrace") itself never reaches a source). shadow() of a
    // map leaves points unoccluded, with a warning once a name.
    bool shadow(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery&, float* const*) override {
        warn_("shadowmap:" + name, "shadow(\"" + name + "\")" + (o.shader ? " in shader \"" + *o.shader + "\"" : std::string()) +
                                       ": shadow maps are not read; give the light \"string shadowname\" [\"raytrace\"] "
                                       "(or Attribute \"light\" \"shadows\" \"on\") for ray-traced shadows: unoccluded");
        return false;
    }

    // textureinfo(): OIIO's names for RenderMan's ("type" is OIIO's "texturetype").
    bool textureInfo(const std::string& name, const std::string& field, sl::QueryValue& out) override {
        const OIIO::ustring file(resolve(name));
        if (field == "resolution") {
            int res[2] = {0, 0};
            if (!ts_->get_texture_info(file, 0, OIIO::ustring("resolution"), OIIO::TypeDesc(OIIO::TypeDesc::INT, 2), res))
                return false;
            out = sl::QueryValue::numbers({float(res[0]), float(res[1])});
            return true;
        }
        if (field == "channels") {
            int channels = 0;
            if (!ts_->get_texture_info(file, 0, OIIO::ustring("channels"), OIIO::TypeInt, &channels)) return false;
            out = sl::QueryValue::numbers({float(channels)});
            return true;
        }
        if (field == "type") {
            OIIO::ustring type;
            if (!ts_->get_texture_info(file, 0, OIIO::ustring("texturetype"), OIIO::TypeString, &type)) return false;
            const std::string t = type.string();
            out = sl::QueryValue::string(t == "Shadow" ? "shadow" : t == "Environment" ? "environment" : "texture");
            return true;
        }
        if (field == "viewingmatrix" || field == "projectionmatrix") {  // OIIO: worldtocamera, worldtoscreen
            float m[16];
            const OIIO::ustring key(field == "viewingmatrix" ? "worldtocamera" : "worldtoscreen");
            if (!ts_->get_texture_info(file, 0, key, OIIO::TypeMatrix, m)) return false;
            out.type = sl::BaseType::Matrix;
            out.count = 1;
            out.floats.assign(m, m + 16);
            return true;
        }
        return false;
    }

  private:
    static OIIO::TextureOptBatch batchOptions(const sl::TextureOptions& o) {
        OIIO::TextureOptBatch opt;
        for (int j = 0; j < kBatch; ++j) {
            opt.sblur[j] = o.sblur;
            opt.tblur[j] = o.tblur;
            opt.swidth[j] = o.swidth;
            opt.twidth[j] = o.twidth;
        }
        opt.fill = o.fill;
        opt.firstchannel = o.firstChannel;
        opt.missingcolor = nullptr;  // a missing map is an error (the caller fills and warns)
        if (o.filter == "closest") opt.interpmode = OIIO::Tex::InterpMode::Closest;
        else if (o.filter == "bicubic") opt.interpmode = OIIO::Tex::InterpMode::SmartBicubic;
        else opt.interpmode = OIIO::Tex::InterpMode::Bilinear;
        return opt;
    }

    static void copyOut(const float* result, OIIO::Tex::RunMask mask, int base, int channels, float* const* out) {
        for (int c = 0; c < channels; ++c)
            for (int j = 0; j < kBatch; ++j)
                if (mask & (OIIO::Tex::RunMask(1) << j)) out[c][base + j] = result[c * kBatch + j];
    }

    // A name without a folder is looked for along the search path, then in the working folder
    // (OIIO's own "searchpath" would try the working folder first). Handles are kept by name:
    // the search happens once a map, and each later lookup costs one shared lock and a hash.
    OIIO::TextureSystem::TextureHandle* open(const std::string& name, OIIO::TextureSystem::Perthread* thread,
                                             const sl::TextureOptions& o, const char* what) {
        OIIO::TextureSystem::TextureHandle* handle = nullptr;
        {
            std::shared_lock<std::shared_mutex> lock(mutex_);
            const auto it = handles_.find(name);
            if (it != handles_.end()) handle = it->second;
        }
        if (!handle) {
            const std::string path = resolve(name);
            handle = ts_->get_texture_handle(OIIO::ustring(path), thread);
            // A map whose header claims more than its file can hold, or an untiled one whose
            // pixels cannot all be read, is never looked up (validate).
            std::string implausible;
            if (handle && ts_->good(handle)) implausible = validate(handle, thread, path);
            std::unique_lock<std::shared_mutex> lock(mutex_);
            handles_.emplace(name, handle);
            if (!implausible.empty()) refused_.emplace(name, implausible);
        }
        {
            std::shared_lock<std::shared_mutex> lock(mutex_);
            const auto it = refused_.find(name);
            if (it != refused_.end()) return failed(name, o, what, it->second), nullptr;
        }
        if (handle && ts_->good(handle)) return handle;
        failed(name, o, what);
        return nullptr;
    }

    // Why the map at `path` cannot be read as its header says, or "": a size the file cannot hold
    // (implausibleImageSize), or, for an untiled map (which OpenImageIO reads whole on the first
    // lookup, on whichever thread comes first), pixels that cannot be read. OpenImageIO's TIFF reader
    // reports a truncated strip only through geterror, and its texture lookups not at all: the map
    // is read through once here, a band of rows at a time, so that every lookup gives the same
    // answer whatever the order of the buckets.
    std::string validate(OIIO::TextureSystem::TextureHandle* handle, OIIO::TextureSystem::Perthread* thread,
                         const std::string& path) {
        const OIIO::ImageSpec* spec = ts_->imagespec(handle, thread, 0);
        std::error_code ec;
        const uint64_t bytes = std::filesystem::file_size(path, ec);
        if (!spec || ec) return "";
        std::string why =
            implausibleImageSize(spec->width, spec->height, spec->nchannels, int64_t(spec->format.size()), bytes);
        if (!why.empty()) return why;
        auto in = OIIO::ImageInput::open(path);  // the file's own spec: the cache's calls an untiled image one tile
        if (!in) return OIIO::geterror();
        if (in->spec().tile_width > 0) return "";
        return unreadablePixels(*in);
    }

    std::string resolve(const std::string& name) const {
        namespace fs = std::filesystem;
        if (name.empty() || fs::path(name).is_absolute()) return name;
        std::error_code ec;
        for (const std::string& folder : folders_) {
            const fs::path p = fs::path(folder) / name;
            if (fs::is_regular_file(p, ec)) return p.string();
        }
        return name;
    }

    // Reports the map once (the warning's key is its name) and gives false: the caller fills.
    bool failed(const std::string& name, const sl::TextureOptions& o, const char* what, std::string why = "") {
        if (why.empty()) why = ts_->geterror();
        if (why.empty()) why = "cannot be read";
        while (!why.empty() && why.back() == '\n') why.pop_back();
        warn_("texture:" + name, std::string(what) + "(\"" + name + "\")" +
                                     (o.shader ? " in shader \"" + *o.shader + "\"" : std::string()) + ": " + why +
                                     " (texture searchpath " + path_ + "): using the fill value");
        return false;
    }

    OIIO::TextureSystem* ts_;
    TextureWarning warn_;
    std::vector<std::string> folders_;
    std::string path_;  // the folders, for messages
    std::shared_mutex mutex_;
    std::unordered_map<std::string, OIIO::TextureSystem::TextureHandle*> handles_;
    std::unordered_map<std::string, std::string> refused_;  // maps never read, and why
};

}  // namespace

sl::TextureSource* makeOiioTextureSource(const std::vector<std::string>& searchPath, TextureWarning warn) {
    return new OiioTextures(searchPath, std::move(warn));
}

std::string pictureProblem(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        std::string why = OIIO::geterror();
        while (!why.empty() && why.back() == '\n') why.pop_back();
        return why.empty() ? "cannot be read" : why;
    }
    const OIIO::ImageSpec& spec = in->spec();
    std::error_code ec;
    std::string why = implausibleImageSize(spec.width, spec.height, spec.nchannels, int64_t(spec.format.size()),
                                           std::filesystem::file_size(path, ec));
    if (why.empty()) why = unreadablePixels(*in);
    while (!why.empty() && why.back() == '\n') why.pop_back();
    return why;
}

bool makeOiioTexture(const MakeTextureDesc& d, std::string* error) {
    // MakeCubeFaceEnvironment: the faces resampled into a lat-long picture in memory (checked there).
    OIIO::ImageBuf latLong;
    if (!d.cubeFaces.empty()) {
        CubeFaceLatLong picture;
        if (!resampleCubeFaces(d, &picture, error)) return false;
        OIIO::ImageSpec spec(picture.width, picture.height, int(picture.channels.size()),
                             OIIO::TypeDesc(picture.format.c_str()));
        spec.channelnames = picture.channels;
        spec.alpha_channel = picture.alphaChannel;
        latLong.reset(spec);
        latLong.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, picture.pixels.data());
    } else if (auto in = OIIO::ImageInput::open(d.input)) {
        // maketx reads the picture whole: its header is believed only as far as the file can hold
        // it, and its pixels are read through first (a truncated TIFF would make a map of zeros, silently).
        in.reset();
        *error = pictureProblem(d.input);
        if (!error->empty()) {
            *error = "the picture '" + d.input + "': " + *error;
            return false;
        }
    }
    OIIO::ImageSpec config;
    config.attribute("wrapmodes", d.swrap + "," + d.twrap);
    // Halving with bilinear resampling (OIIO's default) averages 2 x 2 texels: RenderMan's box.
    if (d.filter != "box") config.attribute("maketx:filtername", d.filter);
    // A tiled, MIP-mapped TIFF whatever the name's extension (".tex", ".tx", ".env", as RenderMan
    // files name maps): OpenImageIO would otherwise pick the writer by the extension, and has none
    // for ".tex".
    config.attribute("maketx:fileformatname", "tiff");
    const auto mode = d.latLongEnvironment ? OIIO::ImageBufAlgo::MakeTxEnvLatl : OIIO::ImageBufAlgo::MakeTxTexture;
    const bool made = d.cubeFaces.empty() ? OIIO::ImageBufAlgo::make_texture(mode, d.input, d.output, config)
                                          : OIIO::ImageBufAlgo::make_texture(mode, latLong, d.output, config);
    if (!made) {
        *error = OIIO::geterror();
        while (!error->empty() && error->back() == '\n') error->pop_back();
        if (error->empty()) *error = "maketx failed";
        return false;
    }
    return true;
}

}  // namespace streyes
