#include "render/bucket.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "cull/view_cull.h"
#include "geom/root_chunks.h"
#include "procedural/procedural.h"
#include "raster/coverage.h"
#include "render/bucket_bounds.h"
#include "render/bucket_grid_ops.h"
#include "render/expansion_release.h"
#include "render/grid_cache.h"
#include "render/split_decision.h"
#include "shade/aov_fill.h"
#include "shade/shading.h"
#include "util/sampling.h"

namespace streyes {

using namespace bucket;

namespace {
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Heap order: nearest first; equal depths in arrival order (deterministic).
struct FartherFirst {
    template <typename T>
    bool operator()(const T& a, const T& b) const {
        return a.zmin != b.zmin ? a.zmin > b.zmin : a.order > b.order;
    }
};

constexpr size_t kMaxLayerStats = 64;  // per-layer counters beyond this go to the last entry
constexpr float kAdaptiveDepthGrowth = 1.25f;  // adaptive layers: at most this depth ratio apart
}  // namespace

namespace bucket {

// Sides and Orientation on a diced grid (slot k: the positions and normals at t0 or t1): turns
// the normals to the side Orientation calls outside.
void orientNormals(Grid& grid, int k, const Material* m) {
    if (m && m->flipNormals)
        for (Vec3f& n : grid.N[k]) n = -n;
}

// A solid's boundary (Material::solid): which way round a micropolygon runs in raster space where
// its outside (its oriented normals) faces the eye, from every quad of slot 0, each weighed by its
// raster area: a quad seen edge-on, or whose normals disagree with its corners, barely counts.
void setSolid(Grid& grid, const Material* m, const Camera& cam) {
    grid.solid = m ? m->solid : -1;
    if (grid.solid < 0) return;
    const int nu = grid.nu, nv = grid.nv, stride = nu + 1;
    double sum = 0;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
            Vec3f n{0, 0, 0}, c{0, 0, 0}, r[4];
            for (int k = 0; k < 4; ++k) {
                const Vec3f& p = grid.P[0][size_t(idx[k])];
                n = n + grid.N[0][size_t(idx[k])], c = c + p;
                r[k] = cam.toRaster(p);
            }
            const float facing = -dot(n, cam.perspective() ? c : Vec3f{0, 0, 1});
            const double area = double(r[2].x - r[0].x) * double(r[3].y - r[1].y) -
                                double(r[2].y - r[0].y) * double(r[3].x - r[1].x);
            if (std::isfinite(area)) sum += facing > 0 ? area : facing < 0 ? -area : 0.0;
        }
    grid.frontWinding = sum < 0 ? -1 : 1;
}

// Sides 1: marks in grid.hole the micropolygons whose outside faces away from the eye at every
// end of the grid's span (their corners' normals summed, against the direction from the eye).
// False when none is left to draw.
bool cullBackFacing(Grid& grid, const Camera& cam) {
    const int nu = grid.nu, nv = grid.nv, stride = nu + 1;
    if (grid.hole.empty()) grid.hole.assign(size_t(nu) * size_t(nv), 0);
    bool any = false;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            uint8_t& h = grid.hole[size_t(j * nu + i)];
            if (h) continue;
            const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
            bool back = true;
            for (int k = 0; k < (grid.moving ? 2 : 1) && back; ++k) {
                Vec3f n{0, 0, 0}, c{0, 0, 0};
                for (int v : idx) n = n + grid.N[k][size_t(v)], c = c + grid.P[k][size_t(v)];
                const Vec3f eyeToQuad = cam.perspective() ? c : Vec3f{0, 0, 1};
                back = dot(n, eyeToQuad) > 0;
            }
            h = back;
            any = any || !back;
        }
    return any;
}

}  // namespace bucket

BucketWorker::BucketWorker(const RenderScene& scene, const RenderOptions& options, const PatternTable& patterns,
                           const FilterWeights& filter, const std::vector<float>& layerDepths, Log& log)
    : scene_(scene),
      options_(options),
      patterns_(patterns),
      filter_(filter),
      layerDepths_(layerDepths),
      log_(log),
      occlusion_(usesOcclusion(options.algorithm)),
      shadingVaries_(!scene.lights.isStatic()),
      shader_(nullptr, scene.camera, scene.lights),
      aovs_(options.aovs) {
    tracer_.setShader(&shader_);
    grid_.aovCount = aovs_.count;
    shader_.setAovs(&aovs_);
    shader_.setDepthLayers(options.depthPass && filter.depthFilter() == DepthFilter::Midpoint);
    shader_.setDepthOnly(options.depthPass);
}

void BucketWorker::setTrace(const TraceScene* trace) {
    trace_ = trace;
    traceEyeRays_ = trace && raytraces(options_.algorithm);
    shadowSlots_ = trace && !traceEyeRays_ ? scene_.lights.shadowSlots() : 0;
    grid_.shadowSlots = shadowSlots_;
    // Still grids test the still occluders at their vertices where lights and camera stand still
    // (a zoom's pixel, which sets the shadow bias, changes from frame to frame).
    stillShadows_ = shadowSlots_ > 0 && trace->hasShadowHierarchies() && !options_.shadowsPerSample &&
                    scene_.lights.isStatic() && !scene_.cameras.zooms();
    updateShaderRays();
}

void BucketWorker::updateShaderRays() {
    const bool wanted = trace_ && shaders_ && shaders_->tracesRays();
    if (wanted && shaderRays_ && shaderRays_->scene() == trace_ && shaderRays_->shaders() == shaders_) return;
    const int maxDepth = shaders_ && shaders_->traceMaxDepth() >= 0 ? shaders_->traceMaxDepth() : ShaderRays::kDefaultMaxDepth;
    shaderRays_ = wanted ? std::make_unique<ShaderRays>(*trace_, shaders_, 1, maxDepth) : nullptr;
    shader_.setRaySource(shaderRays_.get());
}

void BucketWorker::render(const BucketSpec& bucket, TiledFrames& frames) {
    bucket_ = bucket;
    ++counters.buckets;
    splitsOf_.clear();
    auto t = Clock::now();
    // Dense (every frame its own samples from the start) when rays leave every sample at its own
    // time: eye rays, and shadow rays tested per sample. Shadows tested at still grids' vertices
    // keep it sparse: still grids whose shadows are folded into their colour share the still
    // layer across frames (SampleTracer::occludeStillVertices), the rest write records.
    block_.setAovCount(aovs_.count);
    block_.reset(bucket.rect, bucket.firstFrame, bucket.frameCount, patterns_,
                 traceEyeRays_ || (shadowSlots_ > 0 && !stillShadows_),
                 shadowSlots_, scene_.camera.depthOfField());
    block_.setSolids(scene_.solids.empty() ? nullptr : &scene_.solids);
    counters.timeSampleGen += secondsSince(t);

    windowStart_ = bucket.firstFrame + scene_.shutter.open;
    windowEnd_ = bucket.firstFrame + bucket.frameCount - 1 + scene_.shutter.close;
    t = Clock::now();
    const double before =
        counters.timeDice + counters.timeShade + counters.timeSample + counters.timeOcclusion + counters.timeTrace;
    // Small keyed grids shaded in batches (bucket_batch.cpp): only where the culling is exact,
    // since the batch is sampled later (tables may come at other depths).
    batching_ = options_.shadeBatching && options_.tolerance == 0 && aovs_.count == 0;
    pending_.clear();
    pendingIntervals_.clear();
    keyGridsUsed_ = 0;
    pendingPoints_ = 0;
    if (!traceEyeRays_) {  // the ray tracer traces the samples instead (below)
        if (occlusion_) runNearToFar();
        else runDepthFirst();
        flushPending();
    }
    ownChildren_.clear();  // nothing holds them now: the split loop is done
    // Nor the kept expansions: let go of them, but for a procedural that outgrew its bound, which
    // the renderer keeps (with the procedurals it came from) for the next pass.
    if (release_ && !leases_.empty() && scene_.factory->anyOutgrown()) release_->keepEverything(std::move(leases_));
    leases_.clear();
    counters.timeSplit +=
        secondsSince(t) - (counters.timeDice + counters.timeShade + counters.timeSample + counters.timeOcclusion +
                           counters.timeTrace - before);

    if (trace_) {  // eye rays (raytrace*), or the shadow rays of the rasterizer's hits
        t = Clock::now();
        if (traceEyeRays_) tracer_.traceSamples(block_, *trace_, counters);
        else if (shadowSlots_) tracer_.shadeShadows(block_, *trace_, counters);
        counters.timeTrace += secondsSince(t);
    }
    if (options_.sampleObserver) options_.sampleObserver(block_, bucket.tile);

    t = Clock::now();
    resolveTile(block_, filter_, frames, bucket.tileIndex, resolveScratch_);
    counters.timeResolve += secondsSince(t);
    counters.micropolygons += rasterCounters_.micropolygons;
    counters.sampleTests += rasterCounters_.sampleTests;
    counters.sampleHits += rasterCounters_.sampleHits;
    counters.samplesBehind += rasterCounters_.samplesBehind;
    counters.gridGroupsBehind += rasterCounters_.gridGroupsBehind;
    counters.patchGroupsBehind += rasterCounters_.patchGroupsBehind;
    counters.patchGroupsOutside += rasterCounters_.patchGroupsOutside;
    counters.sampleFragments += rasterCounters_.fragments;
    rasterCounters_ = {};
    shader_.takeCounters(counters);
    if (shaderRays_) shaderRays_->takeCounters(counters);
}

// ---- Drivers ---------------------------------------------------------------------------------------


// Each root whose time span meets the bucket's frames enters the loop. A moving root (or any
// root, while the lights move) is cut at each frame's exposure first, from the root itself: a
// frame's pieces, and so its pixels, are the same whatever block of frames it is rendered in.
void BucketWorker::pushRoot(const Body& root, int fa, int fb, FrameRun run) {
    if (fb < 0) fb = bucket_.frameCount - 1;
    const TimeSpan& span = root.time();
    const double a = bucket_.firstFrame + fa + scene_.shutter.open, b = bucket_.firstFrame + fb + scene_.shutter.close;
    if (!reachesSamples(span, a, b, scene_.shutter.open == scene_.shutter.close)) return;
    if (root.expands() && root.moving()) {
        pushProceduralViews(static_cast<const ProceduralBody&>(root), fa, fb);
    } else if (root.moving() || (!root.expands() && shadingVaries(root))) {
        // Its bound over the whole shot (made once) misses the bucket: nothing to cut.
        const PixelRect& R = bucket_.rect;
        if (boxOutside(cameraOf(root), displaced(root, root.bound().swept()), {R.x0 - 1, R.y0 - 1, R.x1 + 1, R.y1 + 1})) {
            ++counters.culledView;
            return;
        }
        const int chunk = chunkFrames(root);
        auto chunkOf = [&](int frame) { return frame >= 0 ? frame / chunk : -((-frame + chunk - 1) / chunk); };
        pushChunks(root, chunk, chunkOf(bucket_.firstFrame + fa), chunkOf(bucket_.firstFrame + fb), run);
    } else if (fa > 0 || fb < bucket_.frameCount - 1) {
        // Still, but wanted in some of the bucket's frames only (a moving procedural's children at
        // one level of detail): the piece over those frames.
        BodyPtr piece = root.restrictedTo(std::max(span.t0, a), std::min(span.t1, b));
        piece->pieceKey = hashCombine(root.pieceKey, 0x200000000ull + uint64_t(uint32_t(bucket_.firstFrame + fa)));  // span in GridKey
        push(std::move(piece));
    } else if (occlusion_) {
        heap_.push_back({displaced(root, root.bound().swept()).lo.z, arrivals_++, &root, nullptr});
        std::push_heap(heap_.begin(), heap_.end(), FartherFirst());
    } else {
        process(root);
    }
}

// Frames a moving root's pieces span (geom/root_chunks.h); one where it reads maps made frame by
// frame, so that each frame is shaded with its own maps in every block (docs/ARCHITECTURE.md, Passes).
int BucketWorker::chunkFrames(const Body& root) const {
    const Material* m = root.material();
    if (m && m->readsMaps && shaders_ && shaders_->mapsPerFrame()) return 1;
    return rootChunkFrames(root, cameraOf(root), worldChunks(root));
}

// A moving root's pieces for the bucket's frames [fa, fb]: one a chunk of `chunk` frames aligned
// to multiples of `chunk` (absolute frame numbers), cut from the root, and within `run` (the
// frames a procedural's view stands for, as its level of detail has them: see levelRun). The
// chunks whose time its bound reaches the bucket in are found by halving the range of chunks.
void BucketWorker::pushChunks(const Body& root, int chunk, int ca, int cb, FrameRun run) {
    const TimeSpan& span = root.time();
    const double open = scene_.shutter.open, close = scene_.shutter.close;
    const double first = std::max(double(ca) * chunk, double(run.lo)), last = std::min(double(cb + 1) * chunk - 1, double(run.hi));
    const double a = std::max(span.t0, first + open), b = std::min(span.t1, last + close);
    if (a > b || !reachesSamples(span, a, b, scene_.shutter.open == scene_.shutter.close)) return;
    // Not one piece of these chunks can reach the bucket (the margin keeps this conservative to
    // float rounding: the pieces' own bounds decide, as always, in process()).
    const PixelRect& R = bucket_.rect;
    if (boxOutside(cameraOf(root), displaced(root, root.boundDuring(a, b)), {R.x0 - 1, R.y0 - 1, R.x1 + 1, R.y1 + 1})) {
        ++counters.culledView;
        return;
    }
    if (ca < cb) {
        const int mid = ca + (cb - ca) / 2;
        pushChunks(root, chunk, ca, mid, run);
        pushChunks(root, chunk, mid + 1, cb, run);
        return;
    }
    BodyPtr piece = root.restrictedTo(a, b);
    piece->exposure = int(first);
    uint64_t key = 0x100000000ull + uint64_t(uint32_t(ca)) * 16 + uint64_t(chunk);
    if (!run.whole()) key = hashCombine(key, uint64_t(uint32_t(int(first))));  // two runs of one level in a chunk
    piece->pieceKey = hashCombine(root.pieceKey, key);
    push(std::move(piece));
}

void BucketWorker::push(BodyPtr body) {
    if (!occlusion_) {
        stack_.push_back(std::move(body));
        return;
    }
    const float zmin = displaced(*body, body->bound().swept()).lo.z;
    const Body* raw = body.get();
    heap_.push_back({zmin, arrivals_++, raw, std::move(body)});
    std::push_heap(heap_.begin(), heap_.end(), FartherFirst());
}

// Whether root i surely misses the bucket: the test pushRoot makes for a moving root
// (boxOutside, with a pixel to spare), on a raster bound made once per worker. What it skips the
// split loop would have culled by view; the others keep their order (occlusion tables may come at
// other depths, which exact culling does not show).
bool BucketWorker::rootOutside(size_t i) {
    const std::vector<BodyPtr>& roots = scene_.roots;
    if (rootRasterOf_ != roots.data() || rootRaster_.size() != roots.size()) {
        constexpr float kInf = std::numeric_limits<float>::infinity();
        rootRaster_.resize(roots.size());
        for (size_t r = 0; r < roots.size(); ++r) {
            const Camera& cam = cameraOf(*roots[r]);
            const Bounds3f box = displaced(*roots[r], roots[r]->bound().swept());
            // A procedural's bound grows when its children outgrow it (the renderer then renders
            // again): it takes the split loop's test every time.
            if (roots[r]->expands() || (cam.perspective() && !(box.lo.z >= cam.eyePlane()))) {
                rootRaster_[r] = Bounds3f(Vec3f{-kInf, -kInf, -kInf}, Vec3f{kInf, kInf, kInf});
                continue;
            }
            const Bounds3f raster = rasterOfBox(cam, box);
            rootRaster_[r] = cam.grownByCoc(raster, box.lo.z, box.hi.z);
        }
        rootRasterOf_ = roots.data();
    }
    const PixelRect& R = bucket_.rect;
    return rasterOutside(rootRaster_[i], {R.x0 - 1, R.y0 - 1, R.x1 + 1, R.y1 + 1});
}

// Algorithms S and C: depth first from a stack, root by root.
void BucketWorker::runDepthFirst() {
    for (size_t i = 0; i < scene_.roots.size(); ++i) {
        if (rootOutside(i)) {
            ++counters.culledView;
            continue;
        }
        pushRoot(*scene_.roots[i]);
        while (!stack_.empty()) {
            BodyPtr b = std::move(stack_.back());
            stack_.pop_back();
            process(*b);
        }
    }
}

// With occlusion: every body in one heap, nearest depth first (a piece is never nearer than the
// body it was cut from). A depth layer ends when the next body lies beyond the next geometric
// boundary (--layers N), or, adaptively, once enough samples have had their first hit; then the
// coverage of everything drawn so far, nearer than the next body, becomes the table that later
// (farther) bodies are tested against.
void BucketWorker::runNearToFar() {
    layer_ = 0;
    nextDepth_ = 0;
    haveTable_ = false;
    tableFrames_ = 1;
    arrivals_ = 0;
    firstHitsAtTable_ = 0;
    coverage_.assign(size_t(bucket_.rect.area()) * size_t(bucket_.frameCount), 0);
    // An empty pixel's farthest hit: what a new block (nothing touched yet) stands for.
    farthest_.assign(coverage_.size(), std::numeric_limits<float>::infinity());
    const uint64_t samples = uint64_t(block_.pixelCount()) * uint64_t(block_.frameCount()) * uint64_t(block_.samplesPerPixel());
    const uint64_t adaptiveHits = uint64_t(options_.adaptiveLayerHits * double(samples)) + 1;
    for (size_t i = 0; i < scene_.roots.size(); ++i) {
        if (rootOutside(i)) ++counters.culledView;
        else pushRoot(*scene_.roots[i]);
    }
    float lastZmin = -std::numeric_limits<float>::infinity();
    float lastBoundary = 0;  // of the last table
    const Camera& cam = scene_.camera;
    while (!heap_.empty()) {
        const float zmin = heap_.front().zmin;
        bool layerEnds;
        if (options_.layers > 0) {
            layerEnds = nextDepth_ < layerDepths_.size() && zmin >= layerDepths_[nextDepth_];
            while (nextDepth_ < layerDepths_.size() && zmin >= layerDepths_[nextDepth_]) ++nextDepth_;
        } else {
            // Adaptive: once enough samples got their first hit since the last table, or once
            // depth has grown by kAdaptiveDepthGrowth (surfaces already drawn may now lie nearer
            // than the boundary, which adds coverage without new first hits). Only when depth
            // has moved on from the bodies just drawn: a boundary equal to their depth would
            // cover none of their samples (coverage needs z < boundary).
            const bool newHits = rasterCounters_.firstHits - firstHitsAtTable_ >= adaptiveHits;
            const bool deeper = zmin >= std::max(lastBoundary, cam.nearClip()) * kAdaptiveDepthGrowth;
            layerEnds = zmin > lastZmin && (newHits || deeper);
        }
        if (layerEnds) lastBoundary = zmin;
        if (layerEnds) endLayer(zmin);
        std::pop_heap(heap_.begin(), heap_.end(), FartherFirst());
        WorkItem item = std::move(heap_.back());
        heap_.pop_back();
        lastZmin = item.zmin;
        process(*item.body);
    }
}

// Cells covered by hits nearer than `boundary` join the coverage volume; its summed-volume table
// replaces the last. Every body still to come has zmin >= boundary: strictly farther than what
// covers those cells, so culling against the table never hides a surface that would be seen.
void BucketWorker::endLayer(float boundary) {
    flushPending();  // the table is made of everything sampled so far
    auto t = Clock::now();
    // While nothing in the bucket has a frame's record, every frame sees the still layer: one
    // frame's coverage and a summed-area table stand for all of them (a block of n frames covers
    // n times what one does, so the culling rule decides the same). Once records appear, the
    // first frame's coverage is copied to the others and the volume is kept whole.
    const int F = bucket_.frameCount;
    const int frames = block_.recordCount() == 0 ? 1 : F;
    const size_t cells = size_t(bucket_.rect.area());
    if (frames == F && tableFrames_ == 1 && F > 1) {
        coverage_.resize(cells * size_t(F), 0);
        farthest_.resize(cells * size_t(F), std::numeric_limits<float>::infinity());
        for (int fi = 1; fi < F; ++fi) {
            std::copy(coverage_.begin(), coverage_.begin() + long(cells), coverage_.begin() + long(cells * size_t(fi)));
            std::copy(farthest_.begin(), farthest_.begin() + long(cells), farthest_.begin() + long(cells * size_t(fi)));
        }
    }
    const uint64_t added = updateCoverage(block_, boundary, coverage_, frames, &farthest_) * uint64_t(F / frames);
    block_.untouchAll();  // farthest_ holds what was measured
    const size_t li = std::min<size_t>(size_t(layer_), kMaxLayerStats - 1);
    if (counters.cellsCoveredByLayer.size() <= li) counters.cellsCoveredByLayer.resize(li + 1, 0);
    counters.cellsCoveredByLayer[li] += added;
    if (added > 0 || !haveTable_ || frames != tableFrames_) {
        table_.build(coverage_.data(), bucket_.rect.width(), bucket_.rect.height(), frames);
        ++counters.occlusionTables;
        haveTable_ = true;
    }
    tableFrames_ = frames;
    ++layer_;
    firstHitsAtTable_ = rasterCounters_.firstHits;
    counters.timeOcclusion += secondsSince(t);
}

// ---- The split loop ----------------------------------------------------------------------------------

// The body's raster-spacetime block (pixels containing its bound, frames whose exposure meets its
// time span) against the table of nearer coverage: B - A <= epsilon * B drops it.
bool BucketWorker::occluded(const Body& body, const Bounds3f& raster) const {
    const PixelRect& R = bucket_.rect;
    CellBlock b;
    b.x0 = floorClamped(raster.lo.x, R.x0, R.x1 + 1) - R.x0;
    b.x1 = floorClamped(raster.hi.x, R.x0 - 1, R.x1) - R.x0;
    b.y0 = floorClamped(raster.lo.y, R.y0, R.y1 + 1) - R.y0;
    b.y1 = floorClamped(raster.hi.y, R.y0 - 1, R.y1) - R.y0;
    const double open = scene_.shutter.open, close = scene_.shutter.close;
    const TimeSpan& span = body.time();
    // Frames f with [f + open, f + close] meeting [t0, t1]: f in [t0 - close, t1 - open].
    b.f0 = std::max(0, int(std::ceil(span.t0 - close)) - bucket_.firstFrame);
    b.f1 = std::min(bucket_.frameCount - 1, int(std::floor(span.t1 - open)) - bucket_.firstFrame);
    if (b.x0 > b.x1 || b.y0 > b.y1 || b.f0 > b.f1) return false;
    if (tableFrames_ == 1) {  // every frame the same so far: the first frame's table, times the frames
        CellBlock first = b;
        first.f0 = first.f1 = 0;
        const uint64_t n = uint64_t(b.f1 - b.f0 + 1);
        return occludedWithin(b.volume(), uint64_t(table_.sum(first)) * n, options_.tolerance);
    }
    return occludedWithin(b.volume(), table_.sum(b), options_.tolerance);
}

// Finer than the table, and exact: a body whose nearest depth lies beyond the farthest hit of every
// pixel-frame cell it can reach (as of the last table: depths only decrease since) cannot change
// a sample, so it is dropped before it is split, expanded, diced, shaded or sampled. A hit passes
// the z-test at equal depth (then primitive ids decide), and a micropolygon's interpolated depth
// may round a hair below its vertices' least: hence strictly behind, by a relative 1e-6. Blocks
// of more than kMaxCells cells are not scanned (a large body is split first; its pieces are).
// Hits are opaque today; a transparent one (a < 1) never hides what lies behind it.
bool BucketWorker::hiddenBehindHits(const Body& body, const Bounds3f& raster, float zmin) const {
    constexpr uint64_t kMaxCells = 1 << 14, kLiveSamples = 1024;
    if (!(zmin > 0)) return false;
    const float limit = zmin - zmin * 1e-6f;
    const PixelRect& R = bucket_.rect;
    const int x0 = floorClamped(raster.lo.x, R.x0, R.x1 + 1) - R.x0, x1 = floorClamped(raster.hi.x, R.x0 - 1, R.x1) - R.x0;
    const int y0 = floorClamped(raster.lo.y, R.y0, R.y1 + 1) - R.y0, y1 = floorClamped(raster.hi.y, R.y0 - 1, R.y1) - R.y0;
    const double open = scene_.shutter.open, close = scene_.shutter.close;
    const TimeSpan& span = body.time();
    int f0 = std::max(0, int(std::ceil(span.t0 - close)) - bucket_.firstFrame);
    int f1 = std::min(bucket_.frameCount - 1, int(std::floor(span.t1 - open)) - bucket_.firstFrame);
    if (x0 > x1 || y0 > y1 || f0 > f1) return false;
    const uint64_t cells = uint64_t(x1 - x0 + 1) * uint64_t(y1 - y0 + 1);
    // Small blocks are tested against the samples themselves, as they are now; larger ones
    // against the cells' farthest hits at the last table.
    const int S = block_.samplesPerPixel();
    if (cells * uint64_t(f1 - f0 + 1) * uint64_t(S) <= kLiveSamples) {
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const size_t pi = block_.pixelIndex(R.x0 + x, R.y0 + y);
                const bool records = block_.recordsOf(pi) > 0;
                for (int fi = f0; fi <= f1; ++fi) {
                    const SampleHit* h = records ? block_.hits(fi, pi) : block_.still(pi);
                    for (int k = 0; k < S; ++k)
                        if (!(h[k].z < limit)) return false;
                    if (!records) break;  // every frame sees the still layer
                }
            }
        return true;
    }
    if (tableFrames_ == 1) f0 = f1 = 0;  // every frame sees the still layer: the first stands for all
    if (cells * uint64_t(f1 - f0 + 1) > kMaxCells) return false;
    const size_t W = size_t(R.width()), area = size_t(R.area());
    for (int fi = f0; fi <= f1; ++fi)
        for (int y = y0; y <= y1; ++y) {
            const float* row = &farthest_[size_t(fi) * area + size_t(y) * W];
            for (int x = x0; x <= x1; ++x)
                if (!(row[x] < limit)) return false;
        }
    return true;
}

// One body: cull against the bucket's spacetime block and the nearer coverage, then dice it if
// it is small enough or split it along its longest direction in raster spacetime (u, v or t).
void BucketWorker::process(const Body& body) {
    const Camera& cam = cameraOf(body);
    const Bounds3f swept = displaced(body, body.bound().swept());
    if (!(swept.hi.z >= cam.nearClip() && swept.lo.z <= cam.farClip())) {
        ++counters.culledClip;  // wholly in front of the near plane or beyond the far plane (or NaN)
        return;
    }

    // Bodies reaching the eye plane cannot be projected: cull them against the frustum in camera
    // space, or split them until the pieces lie in front of the plane or behind the near plane.
    // (A procedural that reaches it is expanded instead.)
    if (cam.perspective() && swept.lo.z < cam.eyePlane()) {
        if (outsideFrustum(cam, swept, bucket_.rect)) {
            ++counters.culledView;
            return;
        }
        if (body.expands()) {
            expand(static_cast<const ProceduralBody&>(body));
            return;
        }
        if (body.eyeSplitDepth >= options_.maxEyeSplits) {
            ++counters.culledEyeLimit;
            log_.warnOnce("eyesplit", body.source() ? *body.source() : SourceLoc{},
                          "geometry crossing the eye plane still straddles it after " +
                              std::to_string(options_.maxEyeSplits) +
                              " eye splits: a piece was dropped (move the near clipping plane out, see Clipping)");
            return;
        }
        CameraExtents e = body.cameraExtents();
        SplitAxis axis = e.u >= e.v ? SplitAxis::U : SplitAxis::V;
        if ((body.moving() && e.t > std::max(e.u, e.v)) || !body.diceableInTime()) axis = SplitAxis::T;
        if (!withinSplitBudget(body)) return;
        ++counters.eyeSplits;
        split(body, axis, true);
        return;
    }

    const RasterMeasure m = body.measure(cam);
    // Every cull below (view, occlusion table, hits) takes the bound grown by the circle of
    // confusion, so none drops a body the lens blurs into the bucket.
    const Bounds3f raster = cullRaster(cam, body, m, swept);
    if (rasterOutside(raster, bucket_.rect)) {
        ++counters.culledView;
        return;
    }
    const Material* cullMat = body.material();
    const bool mayCullHidden = !cullMat || !cullMat->shadeHidden;  // Attribute "cull" "hidden"
    if (mayCullHidden && haveTable_ && occluded(body, raster)) {
        ++counters.culledOcclusion;
        const size_t li = std::min<size_t>(size_t(layer_), kMaxLayerStats - 1);
        if (counters.culledOcclusionByLayer.size() <= li) counters.culledOcclusionByLayer.resize(li + 1, 0);
        ++counters.culledOcclusionByLayer[li];
        return;
    }
    // The test reads the samples under the body's bound without the waiting batch's: it culls
    // only bodies strictly behind opaque hits, so a stale sample culls less, never more, and a
    // body it lets through is sampled behind those hits, which changes no pixel.
    if (mayCullHidden && occlusion_ && hiddenBehindHits(body, raster, swept.lo.z)) {
        ++counters.culledHidden;
        return;
    }
    if (body.expands()) {
        expand(static_cast<const ProceduralBody&>(body));  // its bound survived culling: now its children are needed
        return;
    }

    const SplitDecision decision = decideSplit(body, m, options_, scene_.shutter.close - scene_.shutter.open);
    if (decision.dice) {
        diceShadeSample(body, decision.nu, decision.nv, raster);
        return;
    }
    const SplitAxis axis = decision.axis;
    if (body.splitDepth >= options_.maxSplitDepth) {
        ++counters.culledSplitLimit;
        log_.warnOnce("splitlimit", body.source() ? *body.source() : SourceLoc{},
                      "a body is still too large to dice after " + std::to_string(options_.maxSplitDepth) +
                          " splits (degenerate or huge geometry): dropped");
        return;
    }
    if (!withinSplitBudget(body)) return;
    (axis == SplitAxis::U ? counters.splitsU : axis == SplitAxis::V ? counters.splitsV : counters.splitsT)++;
    split(body, axis, false);
}

// The split limits bound how deeply a body is split, not how many pieces it makes: a body whose
// pieces all keep overlapping the bucket without getting small doubles with every split (the
// fuzzer found a moving sliver reaching 5e22 pixels whose bucket never finished). So a primitive
// is split at most maxSplitsPerPrimitive times in one bucket; past that its pieces are dropped,
// with one warning. The split loop's order is fixed, so which pieces go does not depend on threads.
bool BucketWorker::withinSplitBudget(const Body& body) {
    uint32_t& n = splitsOf_[{body.primitiveId(), body.exposure}];
    if (n < uint32_t(options_.maxSplitsPerPrimitive)) {
        ++n;
        return true;
    }
    ++counters.culledSplitLimit;
    log_.warnOnce("splitbudget", body.source() ? *body.source() : SourceLoc{},
                  "geometry needed more than " + std::to_string(options_.maxSplitsPerPrimitive) +
                      " splits in one bucket without getting small enough to dice (degenerate or huge moving "
                      "geometry): the rest of it was dropped");
    return false;
}

void BucketWorker::split(const Body& body, SplitAxis axis, bool eyeSplit) {
    BodyPtr halves[2];
    body.split(axis, halves);
    if (axis != SplitAxis::T) {  // halves of the parameter rectangle, low half first (Body::split)
        const int lo = axis == SplitAxis::U ? 0 : 2;
        const float mid = 0.5f * (body.uv[size_t(lo)] + body.uv[size_t(lo + 1)]);
        halves[0]->uv[size_t(lo + 1)] = mid;
        halves[1]->uv[size_t(lo)] = mid;
    }
    // Second half first: on the stack, the first half is processed next (depth first).
    for (int i = 1; i >= 0; --i) {
        if (eyeSplit) halves[i]->eyeSplitDepth = static_cast<unsigned char>(body.eyeSplitDepth + 1);
        else halves[i]->splitDepth = static_cast<unsigned char>(body.splitDepth + 1);
        halves[i]->pieceKey = hashCombine(body.pieceKey, uint64_t(axis) * 4 + uint64_t(i) * 2 + (eyeSplit ? 1 : 0));
        push(std::move(halves[i]));
    }
}

// A body with several motion keys (a leaf swaying frame by frame): diced and shaded once at each
// key, and sampled one key interval at a time as a grid moving linearly between two keys. The
// grid's two slots take turns: the end of one interval is the start of the next.
void BucketWorker::diceShadeSampleKeys(const KeyedPatchBody& body, int nu, int nv) {
    auto t = Clock::now();
    body.startKeyGrid(nu, nv, grid_);
    grid_.stillShadows = 0;
    grid_.frameShadows.clear();
    ++counters.gridsDiced;
    // The key intervals that meet the bucket's frames (a piece spans a whole chunk of frames, which
    // may reach beyond the block).
    const double a = bucket_.firstFrame + scene_.shutter.open, b = bucket_.firstFrame + bucket_.frameCount - 1 + scene_.shutter.close;
    size_t k0 = 0, keys = body.keyCount();
    while (k0 + 2 < keys && body.keyTime(k0 + 1) <= a) ++k0;
    while (keys > k0 + 2 && body.keyTime(keys - 2) >= b) --keys;
    body.diceKey(k0, grid_, 0);
    const Material* mat = body.material();
    grid_.flatShading = mat && !mat->smoothShading;
    grid_.matte = mat && mat->matte;
    grid_.dissolveLo = mat ? mat->dissolveLo : 0;
    grid_.dissolveHi = mat ? mat->dissolveHi : 1;
    orientNormals(grid_, 0, mat);
    setSolid(grid_, mat, cameraOf(body));
    auto t1 = Clock::now();
    counters.timeDice += std::chrono::duration<double>(t1 - t).count();
    shader_.shadeSlot(grid_, 0, body.keyTime(k0));
    counters.timeShade += secondsSince(t1);
    for (size_t k = k0; k + 1 < keys; ++k) {
        auto ta = Clock::now();
        body.diceKey(k + 1, grid_, 1);
        orientNormals(grid_, 1, mat);
        auto tb = Clock::now();
        counters.timeDice += std::chrono::duration<double>(tb - ta).count();
        shader_.shadeSlot(grid_, 1, body.keyTime(k + 1));
        auto tc = Clock::now();
        counters.timeShade += std::chrono::duration<double>(tc - tb).count();
        grid_.t0 = body.keyTime(k);
        grid_.t1 = body.keyTime(k + 1);
        grid_.openEnd = k + 2 < body.keyCount() || body.time().openEnd;  // pieces meet at keys (TimeSpan)
        grid_.moving = body.keyMoves(k) || shadingMovesWithin(body, 0.5 * (grid_.t0 + grid_.t1));
        grid_.hole.clear();
        if (aovs_.count) fillAovs(grid_, aovs_, cameraOf(body));
        if (!mat || !mat->oneSided || cullBackFacing(grid_, cameraOf(body)))
            rasterizer_.rasterize(grid_, cameraOf(body), scene_.shutter, block_, rasterCounters_);
        counters.timeSample += secondsSince(tc);
        if (k + 2 < keys) {
            std::swap(grid_.P[0], grid_.P[1]);
            std::swap(grid_.N[0], grid_.N[1]);
            std::swap(grid_.Ci[0], grid_.Ci[1]);
            std::swap(grid_.Oi[0], grid_.Oi[1]);
            std::swap(grid_.Cl[0], grid_.Cl[1]);
            std::swap(grid_.aov[0], grid_.aov[1]);  // the shader's outputs; fillAovs writes the rest again
        }
    }
}

// A grid whose bound reaches other buckets of the block is made once, by the first bucket that
// needs it, and left in the grid cache for the others (grid_cache.h); the rest are made here.
void BucketWorker::diceShadeSample(const Body& body, int nu, int nv, const Bounds3f& raster) {
    if (body.dicesAtKeys() ? batchKeys(static_cast<const KeyedPatchBody&>(body), nu, nv, raster)
                           : !dicedForFrames(body) && batchGrid(body, nu, nv, raster))
        return;
    // What waits of this primitive where this grid may fall is sampled before it, as it came
    // before it; other primitives' hits do not depend on the order (pendingMeets).
    const uint64_t primitive = body.primitiveId();
    if (!pending_.empty() && pendingMeets(raster, &primitive)) flushPending();
    if (body.dicesAtKeys()) {
        diceShadeSampleKeys(static_cast<const KeyedPatchBody&>(body), nu, nv);
        return;
    }
    if (dicedForFrames(body)) {
        diceShadeSampleFrames(body, nu, nv, raster);
        return;
    }
    const int reached = gridCache_ && gridCache_->enabled() ? gridCache_->layout().bucketsReached(raster) : 0;
    const int others = reached - 1;
    const GridKey key{body.pieceKey, body.uv, body.time().t0, body.time().t1, nu, nv, bucket_.firstFrame,
                      bucket_.frameCount};
    GridCache::Lease lease;  // make unset: made here and kept (not shared, or being made further up this stack)
    if (reached >= kMinBucketsShared) lease = gridCache_->acquire(key);
    if (lease.grid) {
        ++counters.gridsShared;
        if (lease.grid->nu > 0) {
            const uint64_t n = uint64_t(lease.grid->nu) * uint64_t(lease.grid->nv);
            sample(*lease.grid);
            rasterCounters_.micropolygons -= n;  // counted where it was diced
            counters.micropolygonsShared += n;
        }
        gridCache_->recycle(std::move(lease.grid));
        return;
    }
    if (!lease.make) {
        if (diceShade(body, nu, nv)) sample(grid_);
        return;
    }
    // Abandoned if dicing or shading throws, so that no bucket waits for it forever.
    struct Abandon {
        GridCache* cache;
        const GridKey& key;
        bool armed = true;
        ~Abandon() {
            if (armed) cache->abandon(key);
        }
    } abandon{gridCache_, key};
    static const std::shared_ptr<const Grid> kNothing = std::make_shared<const Grid>();  // nu == 0
    if (!diceShade(body, nu, nv)) {
        gridCache_->publish(key, kNothing, others);
        abandon.armed = false;
        return;
    }
    // The made grid goes to the cache as it is: the worker dices into a spare one next.
    std::shared_ptr<Grid> made = gridCache_->spare();
    std::swap(*made, grid_);
    grid_.shadowSlots = shadowSlots_;  // what every grid of this worker is set up with
    grid_.aovCount = aovs_.count;
    // Sampling reads neither normals nor surface colour: the worker keeps those buffers.
    for (int k = 0; k < 2; ++k) std::swap(made->N[k], grid_.N[k]);
    std::swap(made->Cs, grid_.Cs);
    gridCache_->publish(key, made, others);
    abandon.armed = false;
    sample(*made);
    gridCache_->recycle(std::move(made));  // when every other bucket took it meanwhile
}

bool BucketWorker::diceShade(const Body& body, int nu, int nv) {
    if (!diceForShading(body, nu, nv)) return false;
    auto t1 = Clock::now();
    shader_.shade(grid_);
    if (aovs_.count) fillAovs(grid_, aovs_, cameraOf(body));
    counters.timeShade += secondsSince(t1);
    testStillShadows(grid_);
    return true;
}

bool BucketWorker::diceForShading(const Body& body, int nu, int nv) {
    auto t = Clock::now();
    body.dice(nu, nv, grid_);
    ++counters.gridsDiced;
    const Material* mat = body.material();
    grid_.flatShading = mat && !mat->smoothShading;
    grid_.matte = mat && mat->matte;
    grid_.dissolveLo = mat ? mat->dissolveLo : 0;
    grid_.dissolveHi = mat ? mat->dissolveHi : 1;
    for (int k = 0; k < (grid_.moving ? 2 : 1); ++k) orientNormals(grid_, k, mat);
    setSolid(grid_, mat, cameraOf(body));
    if (mat && mat->oneSided && !cullBackFacing(grid_, cameraOf(body)) && !mat->shadeBackFacing) {
        counters.timeDice += secondsSince(t);
        return false;  // every micropolygon faces away
    }
    if (!grid_.moving && grid_.t1 > grid_.t0 && shadingMovesWithin(body, 0.5 * (grid_.t0 + grid_.t1))) {
        // Still geometry under moving lights: shaded at both ends of its span like a moving grid,
        // so that its colour follows the lights through the exposure.
        grid_.resize(grid_.nu, grid_.nv, true);
        grid_.P[1] = grid_.P[0];
        grid_.N[1] = grid_.N[0];
    }
    counters.timeDice += secondsSince(t);
    return true;
}

// A still grid's vertices, once, against the occluders that stand still through the shot; its
// samples then test only the moving ones (trace.h). The vertices are the still body's dicing,
// which does not depend on the frames rendered with it (its colours do not either).
void BucketWorker::testStillShadows(Grid& grid) {
    grid.stillShadows = 0;
    grid.frameShadows.clear();
    if (!stillShadows_ || grid.moving || grid.shadowSlots == 0) return;
    auto t = Clock::now();
    tracer_.occludeStillVertices(grid, *trace_, counters, bucket_.firstFrame, bucket_.frameCount);
    counters.timeTrace += secondsSince(t);
}

void BucketWorker::sample(const Grid& grid) {
    auto t = Clock::now();
    rasterizer_.rasterize(grid, gridCamera(grid), scene_.shutter, block_, rasterCounters_);
    counters.timeSample += secondsSince(t);
}

}  // namespace streyes
