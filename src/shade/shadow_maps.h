// The depth maps a render's shadow() calls read (RenderOptions::shadowMaps): each frame's own map
// of a name, as the passes before this render made it (streyes/passes.h), else the file on disk.
//
// shadow(name, P) in frame f looks the name up among frame f's maps; a name no pass made is read
// from the file (the working folder first, then the texture search path), once a render. A name
// that is neither warns once, naming where the scene gives it, and leaves points unshadowed, as
// PRMan and Aqsis do; a file that is there but is no depth map (or does not read whole) is an
// InputError naming the same place. P is in the frame's current (camera) space: the frame's own
// camera (Scene::frameWorldToCamera) takes it to world space, where the map's camera takes over.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "shade/shadow_map.h"
#include "streyes/error.h"
#include "streyes/scene.h"

namespace streyes {

namespace sl {
struct TextureOptions;
struct DirectionQuery;
}  // namespace sl

struct ShadowMapBinding {
    // Frame -> name -> the map that frame reads under that name (frames may share one map).
    std::map<int, std::map<std::string, std::shared_ptr<const DepthMap>>> frames;
    // Reads a map no pass made; null: none is read.
    std::function<bool(const std::string& path, DepthMap* out, std::string* error)> readFile;
    // Where the scene gives each name (a shader parameter's RIB line), for messages.
    std::map<std::string, SourceLoc> namedAt;
    // Do frames read different maps under one name? (Then what reads maps is shaded per frame.)
    bool varies() const;
};

class ShadowMaps {
  public:
    // `searchPath`: folders for names without one (after the working folder).
    ShadowMaps(std::shared_ptr<const ShadowMapBinding> binding, const Scene& scene, std::vector<std::string> searchPath,
               Log& log);
    // shadow(): the fraction of light blocked at each active point of q into out. False when
    // `name` is no map (warned once): the caller leaves the points unshadowed.
    bool shadow(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q, float* out);
    // occlusion(mapname, P, N): the map-based occlusion at each active point of q (R: P) about
    // normal[c][i] over the maps of the name's file (shade/occlusion_maps.h, which defines it).
    // False, as shadow(), when `name` is no map.
    bool occlusion(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q,
                   const float* const* normal, float* out);
    bool varies() const { return varies_; }
    // Are there maps the input's passes made frame by frame (whether or not they differ)? A
    // property of the input, not of the frames a job renders, unlike varies().
    bool perFrame() const { return binding_ && !binding_->frames.empty(); }
    // World -> the current (camera) space of the frame that time t falls in.
    Matrix4 worldToCameraAt(double t) const;
    // Do the frames' cameras differ (so "world" space moves against current space between them)?
    bool worldVaries() const { return worldVaries_; }
    // Does the camera of the frame that time t falls in move within its exposure?
    bool worldMovesAt(double t) const;

  private:
    const DepthMap* map(double time, const std::string& name);
    std::shared_ptr<const ShadowMapBinding> binding_;
    std::map<int, MotionTransform> frameWorld_;
    MotionTransform world_;
    double open_ = 0;
    double bias_ = 0;
    bool varies_ = false, worldVaries_ = false;
    std::vector<std::string> searchPath_;
    Log& log_;
    std::mutex mutex_;
    std::map<std::string, std::shared_ptr<const DepthMap>> files_;  // null: not a map on disk
};

}  // namespace streyes
