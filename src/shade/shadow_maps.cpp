#include "shade/shadow_maps.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "shade/vm/texture_source.h"

namespace streyes {

bool ShadowMapBinding::varies() const {
    std::map<std::string, const DepthMap*> first;
    for (const auto& [frame, maps] : frames)
        for (const auto& [name, map] : maps) {
            auto [it, isNew] = first.emplace(name, map.get());
            if (!isNew && it->second != map.get()) return true;
        }
    // A name some frames read and others do not is a change too.
    for (const auto& [frame, maps] : frames)
        if (maps.size() != first.size()) return true;
    return false;
}

ShadowMaps::ShadowMaps(std::shared_ptr<const ShadowMapBinding> binding, const Scene& scene,
                       std::vector<std::string> searchPath, Log& log)
    : binding_(std::move(binding)),
      frameWorld_(scene.frameWorldToCamera),
      world_(scene.camera.worldToCamera),
      open_(scene.settings.shutterOpen),
      bias_(scene.settings.shadowBias),
      searchPath_(std::move(searchPath)),
      log_(log) {
    varies_ = binding_ && binding_->varies();
    for (const auto& [frame, m] : frameWorld_)
        if (m.times() != frameWorld_.begin()->second.times() || m.keys() != frameWorld_.begin()->second.keys())
            worldVaries_ = true;
}

Matrix4 ShadowMaps::worldToCameraAt(double t) const {
    if (frameWorld_.empty()) return world_.at(t);
    const int f = int(std::floor(t - open_ + 1e-6));
    auto it = frameWorld_.upper_bound(f);  // the frame's own, else the nearest before it
    if (it != frameWorld_.begin()) --it;
    return it->second.at(t);
}

bool ShadowMaps::worldMovesAt(double t) const {
    if (frameWorld_.empty()) return !world_.isStatic();
    const int f = int(std::floor(t - open_ + 1e-6));
    auto it = frameWorld_.upper_bound(f);
    if (it != frameWorld_.begin()) --it;
    return !it->second.isStatic();
}

const DepthMap* ShadowMaps::map(double time, const std::string& name) {
    static const DepthMap kGap;  // a frame of the render no pass gave this map: nothing to read
    bool anyFrame = false;
    if (binding_ && !binding_->frames.empty()) {
        // A time before or after the frames rendered (a body living over frames around them, a
        // sequence's run): no sample is there, but its shading is, once for a still body (when
        // the maps do not vary, any frame's map is every frame's) or at a piece's ends. The
        // nearest frame rendered answers.
        const int first = binding_->frames.begin()->first, last = binding_->frames.rbegin()->first;
        const int f = varies_ ? std::clamp(int(std::floor(time - open_ + 1e-6)), first, last) : first;
        auto frame = binding_->frames.find(f);
        if (frame != binding_->frames.end()) {
            auto it = frame->second.find(name);
            if (it != frame->second.end()) return it->second.get();
        }
        for (const auto& [g, maps] : binding_->frames) anyFrame = anyFrame || maps.count(name);
    }
    if (anyFrame) return &kGap;
    std::lock_guard<std::mutex> lock(mutex_);
    auto cached = files_.find(name);
    if (cached != files_.end()) return cached->second.get();
    const SourceLoc where = binding_ && binding_->namedAt.count(name) ? binding_->namedAt.at(name) : SourceLoc{};
    namespace fs = std::filesystem;
    std::string path;
    std::error_code ec;
    if (fs::path(name).is_absolute() || fs::is_regular_file(name, ec)) {
        path = name;
    } else {
        for (const std::string& folder : searchPath_)
            if (fs::is_regular_file(fs::path(folder) / name, ec)) {
                path = (fs::path(folder) / name).string();
                break;
            }
    }
    std::shared_ptr<DepthMap> map;
    if (!path.empty() && fs::is_regular_file(path, ec) && binding_ && binding_->readFile) {
        auto m = std::make_shared<DepthMap>();
        std::string error;
        if (!binding_->readFile(path, m.get(), &error))
            throw InputError(where, "shadow map \"" + name + "\" ('" + path + "'): " + error +
                                        ": give the name of a map a depth pass (Display \"zfile\" | \"shadow\") or "
                                        "MakeShadow wrote");
        ShadowLookup check;
        if (!check.set(*m, Matrix4(), &error))
            throw InputError(where, "shadow map \"" + name + "\" ('" + path + "'): " + error);
        map = std::move(m);
    } else {
        std::string folders = "the working folder";
        for (const std::string& f : searchPath_) folders += ", " + f;
        log_.warnOnce("shadowmap:" + name, where,
                      "shadow map \"" + name + "\" is written by no pass of this render and is not a file (looked in " +
                          folders + "): unshadowed");
    }
    return files_.emplace(name, std::move(map)).first->second.get();
}

bool ShadowMaps::shadow(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q, float* out) {
    const DepthMap* m = map(q.time, name);
    if (!m) return false;
    if (m->width == 0) {  // this frame has no map of the name (another pass's frame): unshadowed
        for (int i = 0; i < q.n; ++i) out[i] = 0;
        return true;
    }
    Matrix4 currentToWorld;
    if (!invert(worldToCameraAt(q.time), &currentToWorld)) return false;
    ShadowLookup look;
    std::string error;
    if (!look.set(*m, currentToWorld, &error)) {
        const SourceLoc where = binding_ && binding_->namedAt.count(name) ? binding_->namedAt.at(name) : SourceLoc{};
        throw InputError(where, "shadow map \"" + name + "\": " + error);
    }
    ShadowFilter f;
    f.sblur = o.sblur, f.tblur = o.tblur, f.swidth = o.swidth, f.twidth = o.twidth;
    f.bias = o.bias > 0 ? o.bias : float(bias_);
    f.samples = o.samples > 0 ? int(o.samples) : 16;
    look.lookup(q, f, out);
    return true;
}

}  // namespace streyes
