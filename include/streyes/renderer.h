// The renderer: buckets (an x-y tile times a block of frames) rendered in parallel, each with
// its own split loop, z-buffer of samples and pixel filter.
//
// Algorithm S ("spacetime"): one split loop per bucket covers every frame of the block, so a
// body that does not move is split, diced and shaded once for all of them. Algorithm C
// ("frames"): Catmull's per-frame loop, the baseline; a bucket is a tile times one frame, with the
// same samples, so the two differ only in how often geometry is processed. The "-occlusion"
// variants (C' and S with culling) process bodies near to far in depth layers and drop those a
// summed-volume table of nearer coverage says are hidden (occlusion.h).
// Ray tracing ("raytrace", "raytrace-frames"): the same buckets and samples, traced through
// Glassner's spacetime hierarchy (one for the whole render) or a 3D hierarchy per frame (trace.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "streyes/film.h"
#include "streyes/render_scene.h"
#include "streyes/scene.h"
#include "streyes/spacetime_bvh.h"
#include "streyes/stats.h"

namespace streyes {

enum class Algorithm { Frames, FramesOcclusion, Spacetime, SpacetimeOcclusion, Raytrace, RaytraceFrames };
inline bool usesOcclusion(Algorithm a) { return a == Algorithm::FramesOcclusion || a == Algorithm::SpacetimeOcclusion; }
inline bool perFrame(Algorithm a) {
    return a == Algorithm::Frames || a == Algorithm::FramesOcclusion || a == Algorithm::RaytraceFrames;
}
inline bool raytraces(Algorithm a) { return a == Algorithm::Raytrace || a == Algorithm::RaytraceFrames; }
const char* algorithmName(Algorithm a);
bool parseAlgorithm(const std::string& name, Algorithm* out);

struct RenderOptions {
    Algorithm algorithm = Algorithm::SpacetimeOcclusion;
    bool hasFrames = false;          // --frames; otherwise the scene's, otherwise frame 0
    int firstFrame = 0, lastFrame = 0;
    int xres = 0, yres = 0;          // --res; 0: the scene's Format
    int samples = 0;                 // --samples per pixel per frame; 0: the scene's PixelSamples
    int threads = 0;                 // 0: every core
    uint64_t seed = 0;
    int bucketSize = 32;             // tile side in pixels
    int maxFrameBlock = 64;          // frames rendered (and held in memory) together
    uint64_t maxMemoryBytes = 0;     // --max-memory; 0: defaultMemoryBudget() (memory.h)
    // --resume: frames already written completely. A block whose frames all are is not rendered
    // again; the others are rendered whole, so that their pixels are an uninterrupted render's,
    // and only their missing frames go to the sink.
    std::function<bool(int frame)> frameDone;

    // Occlusion culling (the -occlusion algorithms).
    double tolerance = 0;            // epsilon: drop a body when uncovered <= epsilon * its block
    int layers = 0;                  // depth layers with geometric spacing; 0: adaptive
    double adaptiveLayerHits = 0.05; // adaptive: a layer ends once this share of samples got a first hit

    // Split loop (see docs/ARCHITECTURE.md).
    int maxGridSize = 256;           // micropolygons per grid (RenderMan's "limits" "gridsize")
    int maxSplitDepth = 60;          // a body split this often and still too large is dropped
    int maxEyeSplits = 40;           // the same for splits at the eye plane
    int maxSplitsPerPrimitive = 1 << 20;  // splits of one primitive in one bucket (bounds the work)
    float timeSplitRatio = 2.0f;     // split t when motion > ratio * size ...
    float timeSplitMinMotion = 16.0f;  // ... and motion > this many pixels

    // Ray tracing and shadows (see spacetime_bvh.h).
    HierarchyOptions hierarchy;
    // For tests and tools: sees each bucket's samples (hits before the filter) and the tile it
    // resolves. Called from worker threads, one bucket at a time each.
    std::function<void(const ImageBlock& block, const PixelRect& tile)> sampleObserver;
};

// Frame range, resolution and sample pattern after applying options over the scene.
struct ResolvedSettings {
    int firstFrame = 0, lastFrame = 0, width = 0, height = 0;
    SamplePattern pattern;
};
ResolvedSettings resolveSettings(const Scene& scene, const RenderOptions& options);

class Renderer {
  public:
    using FrameSink = std::function<void(const FrameImage&)>;
    using Progress = std::function<void(uint64_t done, uint64_t total)>;

    Renderer(const Scene& scene, const RenderOptions& options, Log& log);
    ~Renderer();

    // Renders every frame, handing each to `sink` in frame order as soon as its block is done.
    RenderStats render(const FrameSink& sink, const Progress& progress = {});

    const RenderScene& renderScene() const { return *scene_; }
    const ResolvedSettings& settings() const { return settings_; }

  private:
    std::vector<float> geometricLayerDepths() const;

    const Scene& source_;
    RenderOptions options_;
    Log& log_;
    ResolvedSettings settings_;
    std::unique_ptr<RenderScene> scene_;
    double buildSeconds_ = 0;
};

// Splits `samples` per pixel into an sx x sy stratification as square as possible.
void factorSamples(int samples, int* sx, int* sy);

}  // namespace streyes
