// The renderer: buckets (an x-y tile times a block of frames) rendered in parallel, each with
// its own split loop, z-buffer of samples and pixel filter.
//
// Algorithm S ("spacetime"): one split loop per bucket covers every frame of the block, so a
// body that does not move is split, diced and shaded once for all of them. Algorithm C
// ("frames"): Catmull's per-frame loop, the baseline; a bucket is a tile times one frame, with the
// same samples, so the two differ only in how often geometry is processed. The "-occlusion"
// variants (C' and S with culling) process bodies near to far in depth layers and drop those a
// summed-volume table of nearer coverage says are hidden (src/cull/occlusion.h).
// Ray tracing ("raytrace", "raytrace-frames"): the same buckets and samples, traced through
// Glassner's spacetime hierarchy (one for the whole render) or a 3D hierarchy per frame
// (src/trace/trace.h).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "streyes/error.h"
#include "streyes/frame_image.h"
#include "streyes/render_options.h"
#include "streyes/scene.h"
#include "streyes/stats.h"

namespace streyes {

struct RenderScene;  // the scene in camera space (src/bodies/render_scene.h)

// Frame range, resolution and sample pattern after applying options over the scene.
struct ResolvedSettings {
    int firstFrame = 0, lastFrame = 0, width = 0, height = 0;
    int shotFirst = 0, shotLast = 0;  // RenderOptions::hasShot
    SamplePattern pattern;
    int bucketSize = kDefaultBucketSize, gridSize = kDefaultGridSize;  // options over Option "limits"
    // CropWindow in pixels: [cropX0, cropX1) x [cropY0, cropY1), rows from the top (RI Spec 3.2:
    // from ceil(xres xmin) to ceil(xres xmax) - 1, clamped to the frame). The whole frame when none.
    int cropX0 = 0, cropY0 = 0, cropX1 = 0, cropY1 = 0;
    bool cropped() const { return cropX0 > 0 || cropY0 > 0 || cropX1 < width || cropY1 < height; }
};
ResolvedSettings resolveSettings(const Scene& scene, const RenderOptions& options);

class SceneShaders;  // the Shading Language shaders of the scene (src/shade)

class Renderer {
  public:
    // A sink that keeps a frame may take its pixels, swapping in buffers of its own
    // (FrameWriter::handOver): the renderer makes the next frame in whatever the sink leaves.
    using FrameSink = std::function<void(FrameImage&)>;
    using Progress = std::function<void(uint64_t done, uint64_t total)>;

    Renderer(const Scene& scene, const RenderOptions& options, Log& log);
    ~Renderer();

    // Renders every frame, handing each to `sink` in frame order as soon as its block is done.
    RenderStats render(const FrameSink& sink, const Progress& progress = {});

    const RenderScene& renderScene() const { return *scene_; }
    const ResolvedSettings& settings() const { return settings_; }
    // The nearest and farthest camera depth of the whole shot's bodies, clipped to the clipping
    // range (--layers N and --dof-preview space their layers over it). Rendering part of the shot,
    // the render scene holds only the motion segments its frames reach (BodyFactory::setWanted):
    // the whole shot's are made for it here, so that a frame's layers do not depend on the frames
    // rendered with it.
    std::pair<float, float> shotDepthRange() const;

  private:
    std::vector<float> geometricLayerDepths() const;

    const Scene& source_;
    RenderOptions options_;
    Log& log_;
    ResolvedSettings settings_;
    std::unique_ptr<SceneShaders> shaders_;
    std::unique_ptr<RenderScene> scene_;
    double buildSeconds_ = 0;
};

// The most frames a render of `scene` with `options` keeps together (before the memory budget
// shrinks the block): --frame-block, ~4 GiB of resolved pixels, and for spacetime buckets ~16 M
// samples a bucket. A render farm's blocks longer than this gain no more coherence.
int frameBlockLimit(const Scene& scene, const RenderOptions& options);

// Splits `samples` per pixel into an sx x sy stratification as square as possible.
void factorSamples(int samples, int* sx, int* sy);

}  // namespace streyes
