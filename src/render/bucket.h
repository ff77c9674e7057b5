// One bucket's work: the split loop (Algorithm S or C) over a tile times a block of frames,
// then the pixel filter. A BucketWorker is one thread's reusable workspace; nothing in its hot
// path allocates once its vectors are warm.
#pragma once

#include <vector>

#include "streyes/film.h"
#include "streyes/grid.h"
#include "streyes/image_block.h"
#include "streyes/rasterizer.h"
#include "streyes/render_scene.h"
#include "streyes/renderer.h"
#include "streyes/stats.h"
#include "streyes/trace.h"

namespace streyes {

struct BucketSpec {
    PixelRect tile;       // the pixels this bucket resolves
    PixelRect rect;       // tile plus the filter's guard band, clipped to the image
    int firstFrame = 0;   // frames this bucket's split loop covers
    int frameCount = 1;
};

class BucketWorker {
  public:
    BucketWorker(const RenderScene& scene, const RenderOptions& options, const PixelFilter& filter,
                 const SamplePattern& pattern, Log& log);

    // Renders the bucket and resolves its tile into frames[f - framesFirst] for each of its frames.
    void render(const BucketSpec& bucket, std::vector<FrameImage>& frames, int framesFirst);
    // The ray tracer's scene (null when nothing is ray traced): eye rays replace the split loop
    // for --algorithm raytrace*; otherwise it traces the shadow rays of lights that cast shadows.
    void setTrace(const TraceScene* trace);

    RenderCounters counters;

  private:
    void process(const Body& body);  // one step of the split loop
    void pushSplit(const Body& body, SplitAxis axis, bool eyeSplit);
    void diceShadeSample(const Body& body, int nu, int nv);

    const RenderScene& scene_;
    const RenderOptions& options_;
    const PixelFilter& filter_;
    SamplePattern pattern_;
    Log& log_;

    BucketSpec bucket_;
    ImageBlock block_;
    Grid grid_;
    GridRasterizer rasterizer_;
    RasterCounters rasterCounters_;
    std::vector<BodyPtr> stack_;
    std::vector<CameraLight> lightScratch_;
    std::vector<float> resolveScratch_;
    const TraceScene* trace_ = nullptr;
    bool traceEyeRays_ = false;
    int shadowSlots_ = 0;  // the rasterizer's shadowed light parts per sample
    SampleTracer tracer_;
};

}  // namespace streyes
