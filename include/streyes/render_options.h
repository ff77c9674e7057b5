// What a render is asked to do: the algorithm, frames, resolution, samples, threads, memory and
// the knobs of culling, splitting and ray tracing. Plain data, read by every stage that needs it.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "streyes/vecmath.h"

namespace streyes {

class ImageBlock;  // a bucket's samples (src/raster/image_block.h), for sampleObserver
class Log;
struct ShadowMapBinding;  // the depth maps shadow() reads (src/shade/shadow_maps.h)
namespace sl {
class TextureSource;  // where texture() and environment() read maps (src/shade/vm/texture_source.h)
}

// Makes a render's texture source from the texture search path's folders: see
// RenderOptions::textureSource.
using TextureSourceFactory =
    std::function<std::shared_ptr<sl::TextureSource>(const std::vector<std::string>& searchPath, Log& log)>;

// The sample pattern: sx x sy strata per pixel per frame, and the seed of their jitter.
struct SamplePattern {
    int sx = 2, sy = 2;      // strata per pixel in x and y; sx * sy time slices
    uint64_t seed = 0;
    bool jitter = true;      // false (Hider "hidden" "jitter" 0): samples at their strata's centres
    int count() const { return sx * sy; }
};

// The ray tracer's spacetime hierarchy (src/trace/spacetime_bvh.h; docs/ARCHITECTURE.md).
struct HierarchyOptions {
    int maxLeafBodies = 4;    // a cell with more bodies is subdivided ...
    int maxDepth = 12;        // ... unless it is this deep
    bool splitTime = true;    // false: 3D hierarchy (cells keep the whole time span)
    // Cells this short in time (frames) are cut in space only: by default one frame, the time
    // resolution of the frame-by-frame hierarchies. Finer cuts save some tests for many more
    // bounding volumes (docs/results/raytrace.md).
    double minTimeCut = 1.0;
    bool alwaysSplitTime = false;  // Glassner's rule: halve t in every subdivision (for comparison)
};

enum class Algorithm { Frames, FramesOcclusion, Spacetime, SpacetimeOcclusion, Raytrace, RaytraceFrames };
inline bool usesOcclusion(Algorithm a) { return a == Algorithm::FramesOcclusion || a == Algorithm::SpacetimeOcclusion; }
inline bool perFrame(Algorithm a) {
    return a == Algorithm::Frames || a == Algorithm::FramesOcclusion || a == Algorithm::RaytraceFrames;
}
inline bool raytraces(Algorithm a) { return a == Algorithm::Raytrace || a == Algorithm::RaytraceFrames; }
const char* algorithmName(Algorithm a);
bool parseAlgorithm(const std::string& name, Algorithm* out);

constexpr int kDefaultBucketSize = 64, kDefaultGridSize = 256;

struct RenderOptions {
    Algorithm algorithm = Algorithm::SpacetimeOcclusion;
    bool hasFrames = false;          // --frames; otherwise the scene's, otherwise frame 0
    int firstFrame = 0, lastFrame = 0;
    // --shot: the whole animation the frames belong to. What is decided once for the animation
    // (motion segments, procedural level of detail and sway keys) is decided over the shot, so that
    // a frame's pixels do not depend on which frames are rendered with it. By default the
    // scene's frames (Option "streyes" "int frames") joined with those rendered. A shot given must
    // hold the frames rendered (else resolveSettings throws InputError).
    bool hasShot = false;
    int shotFirst = 0, shotLast = 0;
    int xres = 0, yres = 0;          // --res; 0: the scene's Format
    int samples = 0;                 // --samples per pixel per frame; 0: the scene's PixelSamples
    int threads = 0;                 // 0: every core
    uint64_t seed = 0;
    // Tile side in pixels (--bucket); 0: the scene's Option "limits" "bucketsize", else 64 (a
    // moving grid is diced again in fewer buckets than with smaller tiles).
    int bucketSize = 0;
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
    // Micropolygons per grid; 0: the scene's Option "limits" "gridsize", else 256.
    int maxGridSize = 0;
    int maxSplitDepth = 60;          // a body split this often and still too large is dropped
    int maxEyeSplits = 40;           // the same for splits at the eye plane
    int maxSplitsPerPrimitive = 1 << 20;  // splits of one primitive in one bucket (bounds the work)
    // Small grids of one material at one key time (a keyed body's keys: leaves) shaded together in
    // one interpreter run each batch (GridShader::shadeSlots); the pixels are the same either way.
    // Off: one run a grid. Only with tolerance 0 (the batch is sampled later, which moves layers).
    bool shadeBatching = true;
    // Split t when motion > ratio * size and > this many pixels. Off by default: a moving grid is
    // diced once an exposure (as RenderMan dices it) and its micropolygons move; cutting in time
    // only adds dicing (every piece is diced in each bucket it reaches) for tighter sampling
    // bounds the rasterizer's time slices already give (docs/ARCHITECTURE.md, the split loop).
    float timeSplitRatio = 2.0f;
    float timeSplitMinMotion = std::numeric_limits<float>::infinity();
    // Grids whose bound reaches several buckets are diced and shaded once and shared by them
    // (render/grid_cache.h), in at most this many bytes (less when the memory budget is short);
    // 0: every bucket dices its own. Pixels do not depend on it.
    uint64_t gridCacheBytes = uint64_t(128) << 20;
    // When what procedurals expand into is freed once no bucket left can reach it
    // (render/expansion_release.h): once the bodies made hold more than a quarter of the memory
    // budget (under glibc's malloc freeing costs 4–7% of a forest's CPU when all is freed),
    // always (what the streyes command asks for when it is linked with jemalloc, where freeing
    // costs nothing), or never (kept to the end of the render). Pixels do not depend on it.
    enum class FreeExpansions { UnderPressure, Always, Never };
    FreeExpansions freeExpansions = FreeExpansions::UnderPressure;

    // Ray tracing and shadows (see spacetime_bvh.h).
    HierarchyOptions hierarchy;
    // Ray-traced shadows of the rasterizer: false (the default) tests occluders that stand still
    // through the shot once per vertex of a still grid under still lights, at the shading rate as
    // RenderMan shades shadows, and only moving occluders per sample; true tests every occluder
    // per sample (Option "trace" "string shadowtest" "sample"; docs/SCENE-FORMAT.md).
    bool shadowsPerSample = false;
    // For tests and tools: sees each bucket's samples (hits before the filter) and the tile it
    // resolves. Called from worker threads, one bucket at a time each.
    std::function<void(const ImageBlock& block, const PixelRect& tile)> sampleObserver;
    // --dof-preview N: DepthOfField as N pinhole depth layers, each blurred by its circle of
    // confusion (src/render/dof_preview.h); 0: lens samples.
    int dofPreviewLayers = 0;
    // Output variables the frames carry beyond RGBA and Z ("N", "P", ...: util/aov.h); the
    // renderer adds those its scene's displays name.
    std::vector<std::string> aovs;
    // Textures: called once a render, the first time a shader looks a map up (a render without
    // lookups never calls it), and the source it gives serves every thread. streyes::io gives
    // OpenImageIO's (streyes/textures.h): the core does not link it. Empty, or a null source:
    // every lookup gives its "fill" value.
    TextureSourceFactory textureSource;
    // Shadow maps: each frame's depth maps by name, as the passes before this render made them,
    // and how a map no pass made is read from disk (streyes/passes.h; src/shade/shadow_maps.h).
    // Null: shadow() of a map name reads 0 (unshadowed), with a warning.
    std::shared_ptr<const ShadowMapBinding> shadowMaps;
    // Depth maps only (a depth pass: Display "zfile" | "shadow"): with depthfilter "midpoint"
    // every opaque surface a sample crosses is kept, for the two nearest depths; colours are not
    // written.
    bool depthPass = false;
};

}  // namespace streyes
