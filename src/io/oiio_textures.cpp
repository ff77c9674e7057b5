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
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <filesystem>
#include <mutex>
#include <shared_mutex>
#include <unordered_map>

#include "shade/vm/texture_source.h"

namespace streyes {

namespace {

constexpr int kBatch = OIIO::Tex::BatchWidth;

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
            handle = ts_->get_texture_handle(OIIO::ustring(resolve(name)), thread);
            std::unique_lock<std::shared_mutex> lock(mutex_);
            handles_.emplace(name, handle);
        }
        if (handle && ts_->good(handle)) return handle;
        failed(name, o, what);
        return nullptr;
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
    bool failed(const std::string& name, const sl::TextureOptions& o, const char* what) {
        std::string why = ts_->geterror();
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
};

}  // namespace

sl::TextureSource* makeOiioTextureSource(const std::vector<std::string>& searchPath, TextureWarning warn) {
    return new OiioTextures(searchPath, std::move(warn));
}

bool makeOiioTexture(const MakeTextureDesc& d, std::string* error) {
    OIIO::ImageSpec config;
    config.attribute("wrapmodes", d.swrap + "," + d.twrap);
    // Halving with bilinear resampling (OIIO's default) averages 2 x 2 texels: RenderMan's box.
    if (d.filter != "box") config.attribute("maketx:filtername", d.filter);
    const auto mode = d.latLongEnvironment ? OIIO::ImageBufAlgo::MakeTxEnvLatl : OIIO::ImageBufAlgo::MakeTxTexture;
    if (!OIIO::ImageBufAlgo::make_texture(mode, d.input, d.output, config)) {
        *error = OIIO::geterror();
        while (!error->empty() && error->back() == '\n') error->pop_back();
        if (error->empty()) *error = "maketx failed";
        return false;
    }
    return true;
}

}  // namespace streyes
