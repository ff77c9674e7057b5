// What `streyes render` does with the jobs of a multi-pass input (streyes/passes.h) besides
// rendering pictures: depth jobs rendered into depth maps (kept in memory per version and frame,
// and written to their Display names), MakeShadow and MakeTexture run between them, and each
// picture's maps handed to its render (RenderOptions::shadowMaps).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/frame_writer.h"
#include "shade/shadow_maps.h"
#include "streyes/frame_image.h"
#include "streyes/passes.h"
#include "streyes/renderer.h"

namespace streyes::cli {

class PassRunner {
  public:
    explicit PassRunner(Log& log) : log_(log) {}

    // Renders a depth job with `opts` (its frames' own Format and PixelSamples, a rasterizing
    // algorithm), keeping and writing each frame's maps. Returns the render's stats.
    RenderStats renderDepth(PassJob& job, const RenderOptions& opts);
    // Keeps frame `frame`'s depth maps (its depth displays) from a rendered image, and writes their
    // files (the latest version of a file in input order wins).
    void keep(const PassFrame& frame, const FrameImage& image, double shutterOpen);
    // MakeShadow: the depth map of its input (this render's, else the file) kept as its output's
    // version and written as a shadow map. InputError at the request's line when the input is
    // neither, or is not a depth map.
    void makeShadow(const PassJob& job);
    // MakeTexture, MakeLatLongEnvironment and MakeCubeFaceEnvironment, once the frames before them are written.
    void makeTexture(const PassJob& job, FrameWriter& writer);
    // The maps each frame of a render job reads, and how others are read from disk.
    std::shared_ptr<const ShadowMapBinding> binding(const PassJob& job) const;
    void release(const std::vector<FileVersion>& versions);
    // Cuts the job's Blobbies whose repelling planes read depth maps (ReadDetail::deferRepellingMaps):
    // each frame's maps as binding() gives them, else the files (named from the working folder).
    void cutBlobbies(PassJob& job);

    int mapsWritten() const { return mapsWritten_; }

  private:
    std::shared_ptr<const DepthMap> mapOf(FileVersion v, int frame) const;
    void writeMap(const std::string& path, FileVersion v, const DepthMap& map, bool shadow);

    Log& log_;
    // Per version, per frame (kAnyFrame: one map for every frame, read from a file).
    std::map<FileVersion, std::map<int, std::shared_ptr<const DepthMap>>> maps_;
    std::map<std::string, std::shared_ptr<const DepthMap>> lastOfName_;  // equal maps shared
    std::map<std::string, FileVersion> fileVersion_;                      // the version each file holds
    int mapsWritten_ = 0;
};

}  // namespace streyes::cli
