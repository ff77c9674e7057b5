#include "streyes/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "render/bucket.h"
#include "render/expansion_release.h"
#include "render/grid_cache.h"
#include "streyes/memory.h"
#include "procedural/procedural.h"
#include "raster/sample_kernels.h"
#include "shade/scene_shaders.h"
#include "trace/trace.h"
#include "util/aov.h"

namespace streyes {

const char* algorithmName(Algorithm a) {
    switch (a) {
        case Algorithm::Frames: return "frames";
        case Algorithm::FramesOcclusion: return "frames-occlusion";
        case Algorithm::Spacetime: return "spacetime";
        case Algorithm::SpacetimeOcclusion: return "spacetime-occlusion";
        case Algorithm::Raytrace: return "raytrace";
        case Algorithm::RaytraceFrames: return "raytrace-frames";
    }
    return "?";
}

bool parseAlgorithm(const std::string& name, Algorithm* out) {
    for (Algorithm a : {Algorithm::Frames, Algorithm::FramesOcclusion, Algorithm::Spacetime,
                        Algorithm::SpacetimeOcclusion, Algorithm::Raytrace, Algorithm::RaytraceFrames})
        if (name == algorithmName(a)) {
            *out = a;
            return true;
        }
    return false;
}

void factorSamples(int samples, int* sx, int* sy) {
    samples = std::max(1, samples);
    int a = int(std::sqrt(double(samples)));
    while (a > 1 && samples % a != 0) --a;
    *sy = a;
    *sx = samples / a;
}

ResolvedSettings resolveSettings(const Scene& scene, const RenderOptions& o) {
    ResolvedSettings r;
    if (o.hasFrames) {
        r.firstFrame = o.firstFrame;
        r.lastFrame = o.lastFrame;
    } else if (scene.settings.hasFrames) {
        r.firstFrame = scene.settings.firstFrame;
        r.lastFrame = scene.settings.lastFrame;
    }
    if (o.hasShot) {
        r.shotFirst = o.shotFirst;
        r.shotLast = o.shotLast;
        // Bodies exist over the shot only: a frame outside it would render empty.
        if (r.firstFrame < r.shotFirst || r.lastFrame > r.shotLast)
            throw InputError("frames " + std::to_string(r.firstFrame) + "-" + std::to_string(r.lastFrame) +
                             " lie outside the shot " + std::to_string(r.shotFirst) + "-" + std::to_string(r.shotLast) +
                             " (--shot): a shot holds every frame rendered with it; widen --shot or leave it out");
    } else {
        r.shotFirst = scene.settings.hasFrames ? std::min(r.firstFrame, scene.settings.firstFrame) : r.firstFrame;
        r.shotLast = scene.settings.hasFrames ? std::max(r.lastFrame, scene.settings.lastFrame) : r.lastFrame;
        if (scene.settings.hasShot) {  // a sequence block: its runs' frames around the block's
            r.shotFirst = std::min(r.shotFirst, scene.settings.shotFirst);
            r.shotLast = std::max(r.shotLast, scene.settings.shotLast);
        }
    }
    r.width = o.xres > 0 ? o.xres : scene.camera.xres;
    r.height = o.yres > 0 ? o.yres : scene.camera.yres;
    if (o.samples > 0) {
        factorSamples(o.samples, &r.pattern.sx, &r.pattern.sy);
    } else {
        r.pattern.sx = scene.settings.pixelSamplesX;
        r.pattern.sy = scene.settings.pixelSamplesY;
    }
    r.pattern.seed = o.seed;
    r.pattern.jitter = scene.settings.jitter;
    r.bucketSize = std::max(4, o.bucketSize > 0 ? o.bucketSize : scene.settings.bucketSize > 0 ? scene.settings.bucketSize : kDefaultBucketSize);
    r.gridSize = o.maxGridSize > 0 ? o.maxGridSize : scene.settings.gridSize > 0 ? scene.settings.gridSize : kDefaultGridSize;
    // A depth pass is the whole view (a shadow map's): a crop applies to pictures.
    const Param* cw = o.depthPass ? nullptr : scene.settings.options.find("CropWindow");  // xmin xmax ymin ymax
    const double crop[4] = {cw ? cw->nums[0] : 0, cw ? cw->nums[1] : 1, cw ? cw->nums[2] : 0, cw ? cw->nums[3] : 1};
    auto first = [](int n, double f) { return std::clamp(int(std::ceil(double(n) * f)), 0, n - 1); };
    auto last = [](int n, double f) { return std::clamp(int(std::ceil(double(n) * f - 1)), 0, n - 1); };
    r.cropX0 = first(r.width, crop[0]), r.cropX1 = std::max(r.cropX0, last(r.width, crop[1])) + 1;
    r.cropY0 = first(r.height, crop[2]), r.cropY1 = std::max(r.cropY0, last(r.height, crop[3])) + 1;
    return r;
}

namespace {
// Where a display asks for motion vectors (for the warning about a closed shutter).
SourceLoc motionLoc(const Scene& scene) {
    for (const DisplayDesc& d : scene.settings.displays)
        for (const std::string& v : modeVariables(d.mode))
            if (v == "motion") return d.loc;
    return {};
}
}  // namespace

Renderer::Renderer(const Scene& scene, const RenderOptions& options, Log& log)
    : source_(scene), options_(options), log_(log) {
    settings_ = resolveSettings(scene, options);
    options_.bucketSize = settings_.bucketSize;
    options_.maxGridSize = settings_.gridSize;
    // A merged frame sequence: each frame's lights are in its own camera space, which the still
    // vertices' test (made once, at one time) does not follow yet: shadows per sample there.
    if (!scene.frameWorldToCamera.empty()) options_.shadowsPerSample = true;
    // Option "trace" "string shadowtest": where ray-traced shadows are tested (render_options.h).
    if (const Param* p = scene.settings.options.find("trace:shadowtest"); p && !p->strings.empty()) {
        const std::string& v = p->strings[0];
        if (v == "sample") options_.shadowsPerSample = true;
        else if (v == "shadingrate") options_.shadowsPerSample = false;
        else
            log_.warnOnce("trace-shadowtest", p->loc,
                          "Option \"trace\" \"shadowtest\" \"" + v +
                              "\" is not known (\"shadingrate\" or \"sample\"): using \"shadingrate\"");
    }
    // The output variables the displays name, beside any the caller asked for: built-in ones by
    // name, shader outputs as "type name" from their DisplayChannel declarations.
    auto carry = [&](const std::string& v, const SourceLoc* loc) {
        std::string entry = v;
        if (!findAovVariable(v) && v.find(' ') == std::string::npos) {
            entry.clear();
            for (const RenderSettings::ShaderOutput& o : scene.settings.shaderOutputs)
                if (o.name == v) entry = o.type + " " + o.name;
            if (entry.empty()) {
                const std::string what = "unknown output variable \"" + v + "\" (known: " + aovVariableList() +
                                         ", and shader outputs declared with DisplayChannel)";
                throw loc ? InputError(*loc, what) : InputError(what);
            }
        }
        if (std::find(options_.aovs.begin(), options_.aovs.end(), entry) == options_.aovs.end()) options_.aovs.push_back(entry);
    };
    const std::vector<std::string> asked = options_.aovs;
    options_.aovs.clear();
    for (const std::string& v : asked) carry(v, nullptr);
    for (const DisplayDesc& d : scene.settings.displays)
        for (const std::string& v : modeVariables(d.mode)) {
            // The ray tracer shades single hits: it does not carry output variables (yet).
            if (raytraces(options_.algorithm))
                throw InputError(d.loc, "display mode \"" + d.mode + "\": output variables are written by the rasterizing "
                                        "algorithms only, not by --algorithm " + std::string(algorithmName(options_.algorithm)));
            carry(v, &d.loc);
        }
    // Motion vectors come from a grid's motion over its time span: with a closed shutter every frame
    // is an instant, and a body's pieces carry no motion.
    if (std::find(options_.aovs.begin(), options_.aovs.end(), "motion") != options_.aovs.end() &&
        !(scene.settings.shutterClose > scene.settings.shutterOpen))
        log_.warnOnce("aov-motion-shutter", motionLoc(scene),
                      "motion vectors need an open shutter (Shutter 0 0.5, say): with a closed one every frame is an "
                      "instant and motion reads 0 (but where a moving piece spans several frames of the shot)");
    if (!options_.aovs.empty() && raytraces(options_.algorithm))
        throw InputError("output variables are written by the rasterizing algorithms only, not by --algorithm " +
                         std::string(algorithmName(options_.algorithm)));
    for (const LightDesc& l : scene.lights)
        if (l.area && l.areaPatches.empty())
            log_.warnOnce("arealight-empty", l.loc,
                          "AreaLightSource \"" + l.type + "\" has no shape (no bilinear patch, polygon, sphere, cylinder, "
                          "cone or disk follows it in its attribute block): it lights nothing");
    auto t = std::chrono::steady_clock::now();
    // In an arena of its own, like the render: building runs parallel work too (subdivision
    // meshes), and --threads holds for every stage.
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        shaders_ = std::make_unique<SceneShaders>(scene, log, options.textureSource, options.shadowMaps);
        shaders_->setResolution(settings_.width, settings_.height);
        scene_ = buildRenderScene(scene, settings_.shotFirst, settings_.shotLast, settings_.width, settings_.height, log,
                                  shaders_.get(), settings_.firstFrame, settings_.lastFrame);
        // Light shaders that shine along an axis (solar): their shadow rays run parallel to it.
        for (size_t i = 0; i < scene.lights.size(); ++i)
            if (const std::optional<SolarCone>& c = shaders_->solarCone(i))
                scene_->lights.setDirectional(i, c->axis, c->angle);
    });
    buildSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

Renderer::~Renderer() = default;

std::pair<float, float> Renderer::shotDepthRange() const {
    std::unique_ptr<RenderScene> whole;
    if (settings_.firstFrame > settings_.shotFirst || settings_.lastFrame < settings_.shotLast) {
        Log quiet;  // its warnings are the render scene's, given already
        quiet.setQuiet(true);
        whole = buildRenderScene(source_, settings_.shotFirst, settings_.shotLast, settings_.width, settings_.height,
                                 quiet, shaders_.get());
    }
    float zmin = std::numeric_limits<float>::infinity(), zmax = 0;
    for (const BodyPtr& b : (whole ? whole : scene_)->roots) {
        const Bounds3f box = b->bound().swept();
        zmin = std::min(zmin, box.lo.z);
        zmax = std::max(zmax, box.hi.z);
    }
    return {std::max(zmin, scene_->camera.nearClip()), std::min(zmax, scene_->camera.farClip())};
}

// Boundaries between --layers N layers, spaced geometrically over shotDepthRange. Empty in
// adaptive mode.
std::vector<float> Renderer::geometricLayerDepths() const {
    std::vector<float> depths;
    if (options_.layers <= 1) return depths;
    const auto [zmin, zmax] = shotDepthRange();
    if (!(zmax > zmin)) return depths;
    for (int i = 1; i < options_.layers; ++i)
        depths.push_back(float(double(zmin) * std::pow(double(zmax) / double(zmin), double(i) / options_.layers)));
    return depths;
}

namespace {

// Samples a spacetime bucket may span (pixels x frames x samples per pixel). A bucket keeps the
// positions and the still layer once, and a frame's record of a pixel only where something moves
// there; 16 M lets a 64-pixel bucket at 16 samples a pixel hold 64 frames. The memory plan counts
// a record of every sample (memory.cpp) and shrinks the block further where the budget needs it.
constexpr int64_t kMaxBucketSamples = int64_t(1) << 24;
// A block's resolved frames (RGBA + Z floats, 20 bytes a pixel) are held until its last bucket is
// done: at most ~4 GiB of them, so that 1920x1080 keeps the default 64 frames together and
// 3840x2160 25. Each block splits, dices, shades and samples the scene again; at 1 GiB (until
// 2026-11-28: 25 frames at 1920x1080, 6 at 3840x2160) scenes/still.rib's 64 frames at 1920x1080
// took 1.85 times the CPU of one block. The memory plan shrinks the block where the budget needs it.
constexpr double kMaxBlockPixelBytes = 4.0 * double(int64_t(1) << 30);

int frameBlockLimit(int width, int height, int samplesPerPixel, int tileSize, const PixelFilter& filter,
                    int maxFrameBlock, bool spacetime, int frames) {
    const double pixelBytes = double(width) * height * sizeof(float) * 5;
    int block = std::min(frames, std::max(1, maxFrameBlock));
    block = std::min(block, std::max(1, int(kMaxBlockPixelBytes / pixelBytes)));
    if (spacetime) {
        const double perFrame = double(tileSize + 2 * filter.guardX()) * (tileSize + 2 * filter.guardY()) * samplesPerPixel;
        block = std::min(block, std::max(1, int(double(kMaxBucketSamples) / perFrame)));
    }
    return block;
}

}  // namespace

int frameBlockLimit(const Scene& scene, const RenderOptions& options) {
    const ResolvedSettings s = resolveSettings(scene, options);
    return frameBlockLimit(s.width, s.height, s.pattern.count(), s.bucketSize,
                           PixelFilter(scene.settings.filter), options.maxFrameBlock, !perFrame(options.algorithm),
                           std::numeric_limits<int>::max());
}

RenderStats Renderer::render(const FrameSink& sink, const Progress& progress) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const ResolvedSettings& s = settings_;
    const PixelFilter filter(source_.settings.filter);
    const int W = s.width, H = s.height, S = s.pattern.count();
    // The sample patterns and the filter's weights for them: the same for every bucket and frame.
    const PatternTable patterns(s.pattern);
    DepthFilter depthFilter = DepthFilter::Min;
    depthFilterFromName(source_.settings.depthFilter, &depthFilter);  // the parser checked the name
    // "midpoint" needs every surface a sample crosses, which only a depth pass keeps: a picture's
    // Z is the nearest.
    if (depthFilter == DepthFilter::Midpoint && !options_.depthPass) depthFilter = DepthFilter::Min;
    const FilterWeights weights(filter, patterns, depthFilter);
    const int frames = s.lastFrame - s.firstFrame + 1;
    const int tileSize = settings_.bucketSize;
    const bool spacetime = !perFrame(options_.algorithm);
    const std::vector<float> layerDepths = usesOcclusion(options_.algorithm) ? geometricLayerDepths() : std::vector<float>{};

    // Frames rendered together: bounded by the option, by ~4 GiB of resolved pixels, and (for
    // spacetime buckets, which hold every frame of the block) by ~16 M samples per bucket.
    int block = frameBlockLimit(W, H, S, tileSize, filter, options_.maxFrameBlock, spacetime, frames);

    // The ray tracer's bodies and hierarchies: for eye rays, and for shadow rays when a light
    // casts shadows. Made first, in an arena of the threads asked for, because tracing expands
    // every procedural up front: the memory estimate must count it. The hierarchies are built
    // again with each frame block (raytrace-frames: a 3D one per frame; the others over the block's
    // exposures); the first frames' are built here and measured (below).
    const int threads = options_.threads > 0 ? options_.threads : tbb::this_task_arena::max_concurrency();
    const uint64_t budget = options_.maxMemoryBytes ? options_.maxMemoryBytes : defaultMemoryBudget();
    const bool traceFrames = options_.algorithm == Algorithm::RaytraceFrames;
    std::unique_ptr<TraceScene> trace;
    uint64_t traceBytesPerFrame = 0, traceBuildBytesPerFrame = 0;
    // The other algorithms' hierarchies are built again for each frame block, over its frames
    // (TraceScene::setFrames): built here over the first two frames (one exposure alone is not
    // cut in time, and holds less a frame than a block), and measured, so that the memory plan
    // chooses a block that fits before anything is built over it. Those two frames are then
    // rendered as a block of their own (a frame's pixels do not depend on its block).
    bool traceBlocks = !traceFrames && frames > 1;  // and something traced moves (below)
    bool spacetimeHierarchy = false, shadowHierarchies = false;
    int builtFirst = s.firstFrame, builtCount = std::min({block, frames, 2});  // the frames they were last built over
    auto buildBlockHierarchies = [&] {
        if (spacetimeHierarchy) trace->buildSpacetime(options_.hierarchy);
        if (shadowHierarchies) trace->buildShadowHierarchies(options_.hierarchy);
    };
    // (A depth pass runs no lights: it traces no shadows.)
    // Shaders that cast rays (occlusion(), trace(), ...) need it too.
    // Interior and Exterior run over shaders' rays only (what the camera sees through the air runs
    // Atmosphere, as in RenderMan): without a shader that casts rays they change nothing.
    if (shaders_ && shaders_->firstVolume() && !shaders_->tracesRays()) {
        const ShaderDesc& v = *shaders_->firstVolume();
        log_.warnOnce("volume-untraced", v.loc,
                      "volume shader \"" + v.name + "\" (Interior or Exterior) runs on the rays shaders cast (trace(), "
                      "transmission(), indirectdiffuse()), and no shader here casts any: it changes nothing (what the "
                      "camera sees through the air is Atmosphere's)");
    }
    if (raytraces(options_.algorithm) ||
        ((scene_->lights.shadowSlots() > 0 || (shaders_ && shaders_->tracesRays())) && !options_.depthPass)) {
        // What the bodies may take: the budget less what rendering one frame needs besides.
        const MemoryShape bare{W, H, S, tileSize, filter.guardX(), filter.guardY(), spacetime, 0,
                               usesOcclusion(options_.algorithm)};
        const uint64_t others = estimateMemory(bare, 1, 1).total();
        tbb::task_arena traceArena(threads);
        traceArena.execute([&] {
            scene_->factory->setBodyBudget(budget, budget > others ? budget - others : 1);
            trace = std::make_unique<TraceScene>(*scene_, options_, log_, shaders_.get());
            scene_->factory->setBodyBudget(0, 0);
            // The rasterizer's shadows go through their own two hierarchies (trace.h); the one
            // over every body is for eye rays and the rays shaders cast.
            shadowHierarchies =
                !raytraces(options_.algorithm) && scene_->lights.shadowSlots() > 0 && !options_.depthPass;
            if (!traceFrames) {
                spacetimeHierarchy = !shadowHierarchies || (shaders_ && shaders_->tracesRays());
                // Where nothing traced moves or comes and goes, the hierarchies are the same over
                // any frames: built once, over them all.
                traceBlocks = traceBlocks && trace->changesOverFrames();
                if (traceBlocks) trace->setFrames(builtFirst, builtCount);
                buildBlockHierarchies();
                if (traceBlocks) {
                    const uint64_t n = uint64_t(builtCount);
                    traceBytesPerFrame = (trace->blockHierarchyBytes() + n - 1) / n;
                    traceBuildBytesPerFrame = std::max<uint64_t>(1, (trace->blockBuildBytes() + n - 1) / n);
                }
            } else {
                trace->buildFrames(s.firstFrame, 1, options_.hierarchy);
                traceBytesPerFrame = trace->hierarchyBytes();
                trace->boundingVolumes = 0;  // a measurement, not the render's work: the blocks build again
                trace->buildSeconds = 0;
            }
        });
    }

    // Memory (memory.h), before anything large is allocated: the block shrinks until one worker
    // fits the budget, then as many workers run as fit; a render that does not fit one frame at
    // a time is refused (InputError: the request must change).
    MemoryShape shape{W, H, S, tileSize, filter.guardX(), filter.guardY(), spacetime, scene_->factory->bodyBytes(),
                      usesOcclusion(options_.algorithm)};
    shape.sharedBytes = scene_->factory->sharedBytes();
    shape.aovFloats = AovLayout(options_.aovs).count;
    shape.gridCacheBytes = raytraces(options_.algorithm) ? 0 : options_.gridCacheBytes;
    if (trace) {
        shape.shadowSlots = raytraces(options_.algorithm) ? 0 : scene_->lights.shadowSlots();
        shape.traceBytes = trace->bytes() - (traceFrames   ? trace->hierarchyBytes()
                                             : traceBlocks ? trace->blockHierarchyBytes()
                                                           : 0);
        shape.traceBytesPerFrame = traceBytesPerFrame;
        shape.traceBuildBytesPerFrame = traceBuildBytesPerFrame;
        shape.traceMinFrames = traceBlocks && builtCount > 1 ? 2 : 1;
        shape.traceBytesPerWorker = trace->mailboxBytes();
        shape.traceBuildBytes = trace->buildBytes();
    }
    const MemoryEstimate memory = planMemory(shape, block, threads, budget);
    block = memory.frameBlock;
    // The first block: the frames the hierarchies were measured over, when the plan allows as many.
    const int firstBlock = trace && traceBlocks && builtCount <= block ? builtCount : block;
    auto blockAt = [&](int first) { return std::min(first == s.firstFrame ? firstBlock : block, s.lastFrame - first + 1); };
    int blocks = 0;
    for (int f = s.firstFrame; f <= s.lastFrame; f += blockAt(f)) ++blocks;

    RenderStats stats;
    stats.algorithm = algorithmName(options_.algorithm);
    stats.firstFrame = s.firstFrame;
    stats.lastFrame = s.lastFrame;
    stats.width = W;
    stats.height = H;
    stats.samplesPerPixel = S;
    stats.frameBlock = block;
    stats.tolerance = options_.tolerance;
    stats.layers = options_.layers;
    stats.layerDepths = layerDepths;
    stats.bucketSize = tileSize;
    stats.timeBuild = buildSeconds_;
    stats.counters.rootBodies = scene_->roots.size();

    // Tiles in scanline order; their count and shape do not depend on the thread count.
    const TileLayout layout{W, H, tileSize, filter.guardX(), filter.guardY()};
    std::vector<BucketSpec> tiles;
    std::vector<PixelRect> tileRects;
    // A crop (CropWindow) renders the tiles that reach it, the same tiles and buckets as the whole
    // frame's: its pixels are the whole frame's, bit for bit.
    const PixelRect crop{s.cropX0, s.cropY0, s.cropX1 - 1, s.cropY1 - 1};
    for (int ty = 0; ty * tileSize < H; ++ty)
        for (int tx = 0; tx * tileSize < W; ++tx) {
            BucketSpec b;
            b.tile = layout.tile(tx, ty);
            if (b.tile.x1 < crop.x0 || b.tile.x0 > crop.x1 || b.tile.y1 < crop.y0 || b.tile.y0 > crop.y1) continue;
            b.tileIndex = tiles.size();
            tileRects.push_back(b.tile);
            b.rect = layout.bucketRect(tx, ty);
            tiles.push_back(b);
        }

    stats.memoryEstimateBytes = memory.total();
    stats.memoryBudgetBytes = budget;
    stats.memoryProgramBytes = memory.baseline;
    GridCache gridCache;  // grids shared by the buckets of a frame block
    gridCache.configure(layout, memory.gridCache);
    tbb::task_arena arena(memory.workers);
    stats.threads = arena.max_concurrency();
    stats.simd = pixelTestTarget();
    tbb::enumerable_thread_specific<std::unique_ptr<BucketWorker>> workers;
    const uint64_t totalBuckets = uint64_t(tiles.size()) * uint64_t(spacetime ? blocks : frames);
    std::atomic<uint64_t> done{0};
    double renderSeconds = 0, writeSeconds = 0;

    // Frame blocks in order. A procedural whose children reach outside its declared bound may
    // have been culled by that bound where its children are seen: then the render starts again
    // with the grown bounds (frames already handed to the sink come again; rare, and warned).
    constexpr int kMaxPasses = 8;
    TiledFrames resolved;  // the block's frames, tile by tile (film/tiled_frames.h)
    FrameImage image;      // one of them at a time, for the sink
    const std::vector<std::string> aovNames = AovLayout(options_.aovs).channelNames();
    // --resume: the frames already written, asked once before rendering (a second pass must not
    // take the frames of the first for finished ones).
    std::vector<char> written(size_t(frames), 0);
    if (options_.frameDone)
        for (int f = s.firstFrame; f <= s.lastFrame; ++f) written[size_t(f - s.firstFrame)] = options_.frameDone(f);
    auto alreadyWritten = [&](int f) { return written[size_t(f - s.firstFrame)] != 0; };
    const uint64_t bucketsPerBlock = uint64_t(tiles.size()) * uint64_t(spacetime ? 1 : block);
    // What procedurals expand into is let go once no bucket of the block can reach it: in a
    // spacetime block (a bucket a tile) that no other block follows (they would make it again),
    // and without ray tracing (its scene holds the bodies).
    ExpansionRelease release;
    std::vector<PixelRect> bucketRects;  // a tile's bucket: the tile and the filter's guard band
    for (const BucketSpec& b : tiles) bucketRects.push_back(b.rect);
    for (int pass = 1;; ++pass) {
        bool again = false;
        stats.framesSkipped = 0;
        for (int first = s.firstFrame, count = 0; first <= s.lastFrame && !again; first += count) {
            count = blockAt(first);
            {  // --resume: skip a block whose frames are all written
                int n = 0;
                for (int f = first; f < first + count; ++f) n += alreadyWritten(f);
                if (n == count) {
                    stats.framesSkipped += count;
                    uint64_t n = done += spacetime ? bucketsPerBlock : uint64_t(tiles.size()) * uint64_t(count);
                    if (progress) progress(n, totalBuckets);
                    continue;
                }
            }
            resolved.reset(W, H, tileRects, first, count, aovNames, s.cropped() ? &crop : nullptr);
            // Spacetime: one bucket per tile spans the block's frames. Frames: one per tile and frame.
            std::vector<BucketSpec> buckets;
            for (int f = 0; f < (spacetime ? 1 : count); ++f)
                for (BucketSpec b : tiles) {
                    b.firstFrame = first + f;
                    b.frameCount = spacetime ? count : 1;
                    buckets.push_back(b);
                }
            using Free = RenderOptions::FreeExpansions;
            release.start(spacetime ? bucketRects : std::vector<PixelRect>{},
                          spacetime && !trace && options_.freeExpansions != Free::Never && first + count > s.lastFrame,
                          options_.freeExpansions == Free::Always ? 0 : budget / 4,
                          [this] { return scene_->factory->bodyBytes(); });
            auto t = Clock::now();
            if (traceFrames) arena.execute([&] { trace->buildFrames(first, count, options_.hierarchy); });
            if (trace && traceBlocks && (first != builtFirst || count != builtCount)) {
                arena.execute([&] {
                    trace->setFrames(first, count);
                    buildBlockHierarchies();
                });
                builtFirst = first, builtCount = count;
            }
            // The workers take the buckets in scanline order, each the next one left: they sweep the
            // image together, so that the buckets at work are neighbours (what procedurals expand
            // into is let go behind them). Pixels do not depend on the order.
            std::atomic<size_t> nextBucket{0};
            arena.execute([&] {
                tbb::parallel_for(0, arena.max_concurrency(), [&](int) {
                    std::unique_ptr<BucketWorker>& w = workers.local();
                    if (!w) w = std::make_unique<BucketWorker>(*scene_, options_, patterns, weights, layerDepths, log_);
                    w->setTrace(trace.get());
                    w->setShaders(shaders_.get());
                    w->setGridCache(&gridCache);
                    w->setExpansionRelease(release.enabled() ? &release : nullptr);
                    for (size_t i; (i = nextBucket++) < buckets.size();) {
                        w->render(buckets[i], resolved);
                        release.bucketDone(buckets[i].tileIndex);
                        uint64_t n = ++done;
                        if (progress) progress(n, totalBuckets);
                    }
                });
            });
            renderSeconds += std::chrono::duration<double>(Clock::now() - t).count();
            gridCache.clear();  // the next block's buckets span other frames
            std::vector<ProceduralBody*> outgrown = scene_->factory->takeOutgrown();
            if (!outgrown.empty() && pass < kMaxPasses) {
                for (ProceduralBody* p : outgrown) p->useGrownBound();
                again = true;
                break;
            }
            t = Clock::now();
            for (int i = 0; i < count; ++i) {
                if (alreadyWritten(first + i)) {
                    ++stats.framesSkipped;
                    continue;
                }
                resolved.assemble(i, image);
                shaders_->runImager(image);
                applyExposure(image, source_.settings.exposureGain, source_.settings.exposureGamma);
                sink(image);
            }
            writeSeconds += std::chrono::duration<double>(Clock::now() - t).count();
        }
        if (!again) break;
        stats.passes = pass + 1;
    }
    for (const auto& w : workers)
        if (w) stats.counters += w->counters;
    stats.counters.rootBodies = scene_->roots.size();
    stats.counters.gridsEvicted = gridCache.evictions();
    if (stats.counters.shadingSanitised > 0)
        log_.warnOnce("shading:sanitised", {},
                      std::to_string(stats.counters.shadingSanitised) +
                          " shading results were NaN or infinite (a division by zero, the root or log of a negative) "
                          "and were written as 0");
    if (trace) {
        RenderCounters c;
        c.traceBodies = trace->bodyCount();
        c.boundingVolumes = trace->boundingVolumes;
        c.timeHierarchy = trace->buildSeconds;
        c.proceduralsExpandedByDepth = trace->proceduralsExpandedByDepth;  // expanded for rays first
        for (uint64_t n : c.proceduralsExpandedByDepth) c.proceduralsExpanded += n;
        stats.counters += c;
    }
    stats.procedurals = scene_->factory->proceduralsMade();
    stats.proceduralsByDepth = scene_->factory->proceduralsMadeByDepth();
    stats.bodiesGenerated = scene_->factory->bodiesMade();
    stats.timeRender = renderSeconds;
    stats.timeWrite = writeSeconds;
    stats.timeTotal = std::chrono::duration<double>(Clock::now() - start).count();
    stats.peakMemoryBytes = peakResidentBytes();
    stats.memoryBodiesBytes = scene_->factory->bodyBytes();
    stats.counters.proceduralsReleased = release.released();
    // The estimate the budget is held to counts the bodies made before rendering, not what
    // procedurals expand into as buckets reach them (kept while a bucket left can reach it, or to
    // the end). Say so when the render went over the budget (by more than the program's own size
    // varies), rather than leave the figure in --stats for the user to find.
    if (budget > 0 && stats.peakMemoryBytes > budget + budget / 20) {
        std::string why;
        if (stats.counters.proceduralsExpanded > 0)
            why = ": procedurals expanded into bodies during the render (" + std::to_string(stats.bodiesGenerated) +
                  " bodies made, " + formatBytes(stats.memoryBodiesBytes) + " in all" +
                  (stats.counters.proceduralsReleased > 0 ? ", freed once no bucket left could reach them" : "") +
                  "), which the estimate cannot know beforehand; raise --max-memory";
        log_.warnOnce("memory:over-budget", {},
                      "the render peaked at " + formatBytes(stats.peakMemoryBytes) + " of memory, over the budget of " +
                          formatBytes(budget) + why);
    }
    // What bake3d() and bake() gathered, once every frame is shaded (point_clouds.h).
    if (shaders_) shaders_->pointClouds()->write();
    // Displacement that went past its bound (may have lost pieces): said once the moves are all seen.
    if (shaders_) shaders_->displacementReach().report(log_);
    return stats;
}

}  // namespace streyes
