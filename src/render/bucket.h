// One bucket's work: the split loop (Algorithm S or C, with or without occlusion culling) over a
// tile times a block of frames, then the pixel filter. A BucketWorker is one thread's reusable
// workspace: its vectors (samples, grid, stack) are reused from bucket to bucket. The pieces a
// split or an exposure cut makes are allocated one by one (docs/ARCHITECTURE.md, "The split loop").
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <unordered_map>
#include <vector>

#include "bodies/render_scene.h"
#include "cull/occlusion.h"
#include "film/film.h"
#include "geom/grid.h"
#include "procedural/procedural.h"
#include "raster/image_block.h"
#include "raster/rasterizer.h"
#include "shade/grid_shader.h"
#include "streyes/render_options.h"
#include "streyes/stats.h"
#include "trace/shader_rays.h"
#include "trace/trace.h"
#include "util/aov.h"

namespace streyes {

class ExpansionRelease;
class GridCache;

struct BucketSpec {
    PixelRect tile;       // the pixels this bucket resolves: tile `tileIndex` of the frames
    size_t tileIndex = 0;
    PixelRect rect;       // tile plus the filter's guard band, clipped to the image
    int firstFrame = 0;   // frames this bucket's split loop covers
    int frameCount = 1;
};

// Absolute frames [lo, hi] a moving root's pieces may span: the whole shot, or for a moving
// procedural's child the run of frames at its view's level of detail around the view.
struct FrameRun {
    int lo = INT32_MIN, hi = INT32_MAX;
    bool whole() const { return lo == INT32_MIN && hi == INT32_MAX; }
};

class BucketWorker {
  public:
    // layerDepths: boundaries between the geometric depth layers of --layers N (unused when
    // options.layers == 0: adaptive layers).
    BucketWorker(const RenderScene& scene, const RenderOptions& options, const PatternTable& patterns,
                 const FilterWeights& filter, const std::vector<float>& layerDepths, Log& log);

    // Renders the bucket and resolves its tile into `frames` for each of its frames.
    void render(const BucketSpec& bucket, TiledFrames& frames);
    // The ray tracer's scene (null when nothing is ray traced): eye rays replace the split loop
    // for --algorithm raytrace*; otherwise it traces the shadow rays of lights that cast shadows.
    void setTrace(const TraceScene* trace);
    // The scene's Shading Language shaders (null: built-in shading only). Before render().
    void setShaders(const SceneShaders* shaders) {
        shaders_ = shaders;
        shader_.setShaders(shaders);
        updateShaderRays();
    }
    // Grids shared with the other buckets of the frame block (null or disabled: none).
    void setGridCache(GridCache* cache) { gridCache_ = cache; }
    // Where the expansions this worker makes are registered, to be let go once no bucket can reach
    // them (null: kept to the end). The bucket's index there is its tile's.
    void setExpansionRelease(ExpansionRelease* release) { release_ = release; }

    RenderCounters counters;

  private:
    // A body waiting in the split loop: a root (not owned) or a piece (owned).
    struct WorkItem {
        float zmin;           // nearest camera depth over its time span: the heap's key
        uint64_t order;       // arrival order: makes the heap deterministic on equal depths
        const Body* body;
        BodyPtr owned;
    };

    void runDepthFirst();     // Algorithms S and C: a stack, no layers
    void runNearToFar();      // with occlusion: a heap by depth, tables between layers
    void push(BodyPtr body);
    // A root (or a procedural's child) for the bucket's frames [fa, fb] (indices in the block; -1:
    // to the last).
    void pushRoot(const Body& body, int fa = 0, int fb = -1, FrameRun run = {});
    void pushProceduralViews(const ProceduralBody& procedural, int fa, int fb);
    void collectLevels(const ProceduralBody& procedural, int fa, int fb);
    // The level of detail of a moving procedural in an absolute frame (a property of the frame,
    // whatever the block), and the run of frames at a view's level around the view's frames.
    int levelInFrame(const ProceduralBody& procedural, int frame) const;
    bool sameLevelBetween(const ProceduralBody& procedural, int fa, int fb, int level) const;
    FrameRun levelRun(const ProceduralBody& view, int first, int last) const;
    int chunkFrames(const Body& root) const;
    void pushChunks(const Body& root, int chunk, int ca, int cb, FrameRun run);
    void process(const Body& body);  // one step of the split loop
    bool withinSplitBudget(const Body& body);  // counts a split of the body's primitive
    void expand(const ProceduralBody& procedural);
    // The raster bound of `procedural` as process() culls it (every bucket takes the same), or
    // *everywhere when it reaches the eye plane (culled against the frustum instead).
    Bounds3f reach(const ProceduralBody& procedural, bool* everywhere) const;
    bool occluded(const Body& body, const Bounds3f& raster) const;
    bool hiddenBehindHits(const Body& body, const Bounds3f& raster, float zmin) const;
    void endLayer(float boundary);
    void split(const Body& body, SplitAxis axis, bool eyeSplit);
    // `raster`: the body's raster bound as the view cull took it (the buckets it reaches).
    void diceShadeSample(const Body& body, int nu, int nv, const Bounds3f& raster);
    // Shared when it reaches at least three buckets: a grid on the border of two is mostly hidden
    // in one of them in dense scenes, and keeping it costs more than dicing it again. On the
    // flyover (frames 1-2) sharing from two buckets on cost 7% more CPU than none, from three on
    // 0.6% (2-4% over frames 1-8); the moving sphere's micropolygons are 1.33x the still
    // sphere's from three on, 1.67x from two (docs/ARCHITECTURE.md, "Grids shared between buckets").
    static constexpr int kMinBucketsShared = 3;
    // Dices and shades the body into grid_; false when nothing of it is left to sample.
    bool diceShade(const Body& body, int nu, int nv);
    void sample(const Grid& grid);
    void diceShadeSampleKeys(const KeyedPatchBody& body, int nu, int nv);
    // Small keyed grids wait to be shaded together with others of their material (at each key
    // time) and are sampled when the batch is flushed, in the order they came (bucket_batch.cpp).
    // False: the body cannot wait (shade it now).
    bool batchKeys(const KeyedPatchBody& body, int nu, int nv, const Bounds3f& raster);
    // The same for a small grid diced over its span (shaded at t0, and t1 when it moves) that no
    // other bucket shares.
    bool batchGrid(const Body& body, int nu, int nv, const Bounds3f& raster);
    // diceShade's dicing: the body into grid_, oriented, ready to shade; false when every
    // micropolygon faces away (nothing to shade or sample).
    bool diceForShading(const Body& body, int nu, int nv);
    Grid& spareGrid();  // the next grid of the pool
    // Shades and samples every waiting body. Called before anything else is sampled or anything
    // reads the samples (a table, the hits behind a body whose bound meets the waiting ones'), at
    // the end of the split loop, and when the batch is full.
    void flushPending();
    struct PendingBody {
        bool keyed = false;             // a keyed body's keys, or one grid (keys == 1)
        size_t firstKey = 0, keys = 0;  // its grids: keyGrids_[firstKey, firstKey + keys)
        const Camera* camera = nullptr;
        const Material* material = nullptr;
        size_t firstInterval = 0;  // its key intervals in pendingIntervals_ (keys - 1 of them)
        Bounds3f raster;           // its raster bound as the view cull took it
        uint64_t primitive = 0;    // its primitive (Body::primitiveId)
    };
    // Does a waiting body's raster bound meet `raster` (of primitive `*primitive` only, when given)?
    // Hits at equal depth are ordered by primitive: only grids of one primitive depend on the
    // order they are sampled in.
    bool pendingMeets(const Bounds3f& raster, const uint64_t* primitive) const;
    struct PendingInterval {
        double t0 = 0, t1 = 0;
        bool openEnd = false, moving = false;
    };
    std::vector<PendingBody> pending_;
    std::vector<PendingInterval> pendingIntervals_;
    std::vector<std::unique_ptr<Grid>> keyGrids_;  // a pool: [0, keyGridsUsed_) wait
    size_t keyGridsUsed_ = 0;
    int pendingPoints_ = 0;
    std::vector<GridShader::Slot> pendingSlots_;
    bool batching_ = false;  // options_.shadeBatching where it is sound
    // Bodies still in world space under a moving camera (Body::stillInWorld; bucket_world.cpp).
    // Is the root's chunk of frames measured by the still-in-world rule (geom/root_chunks.h)?
    bool worldChunks(const Body& root) const;
    // Does the piece span several exposures by that rule: diced once, then shaded once or per frame?
    bool dicedForFrames(const Body& body) const;
    // The camera a body or grid is projected by: its frames' (a zoom's projection per frame; a
    // body lives under one, see FrameCameras).
    const Camera& cameraOf(const Body& body) const { return scene_.cameras.during(body.time().t0, body.time().t1); }
    const Camera& gridCamera(const Grid& grid) const { return scene_.cameras.during(grid.t0, grid.t1); }
    void diceShadeSampleFrames(const Body& body, int nu, int nv, const Bounds3f& raster);
    // Dices the piece into `grid` (normals oriented, not shaded).
    void diceOnly(const Body& body, int nu, int nv, Grid& grid);
    // Can the piece's diced grid be shaded once for every frame it spans (what its shading reads
    // of the view is the same from every camera of its span)?
    bool shadesOnceForFrames(const Body& body, const Grid& diced) const;
    // Shades and samples `diced` as it is (once), or cut to each of the bucket's frames.
    void shadeSampleOnce(const Grid& diced, bool dicedHere);
    // The vertices of grid_ (one frame's cut) whose quads this bucket's samples can reach over the
    // frame's exposure, in seenHere_; false (and nothing marked) where that cannot be bounded.
    bool markSeenHere(const Camera& cam);
    void shadeSampleFrames(const Body& body, const Grid& diced, bool dicedHere);

    const RenderScene& scene_;
    const RenderOptions& options_;
    const PatternTable& patterns_;
    const FilterWeights& filter_;
    const std::vector<float>& layerDepths_;
    Log& log_;
    const bool occlusion_;
    const bool shadingVaries_;  // some light moves: still geometry it lights is shaded per exposure
    const SceneShaders* shaders_ = nullptr;
    // Does anything the body's shading reads change over time, while its grid may stand still in
    // camera space: a light it reads moving, its shader reading `time`, or the world moving
    // against the camera under a Shading Language surface (world-space noise, say)?
    // Or do the shadow maps it reads differ between frames (constant within each)?
    bool shadingVaries(const Body& body) const {
        const Material* m = body.material();
        // A shader casting rays sees what moves anywhere: shaded per exposure (to begin with, always).
        return shadingMovesWithin(body) || (m && m->readsMaps && shaders_ && shaders_->mapsVary()) ||
               (m && m->surface && shaders_ && shaders_->worldVaries()) || (m && m->tracesRays);
    }
    // What changes within an exposure (a still grid is then shaded at both ends of its piece and
    // its colour interpolated between them): all of the above but the maps, and the world only
    // where the camera of the frame at `time` (a time in the piece) moves within its exposure: a
    // frame whose camera stands still is shaded once, as it is when rendered alone.
    bool shadingMovesWithin(const Body& body, double time) const {
        const Material* m = body.material();
        if (!m) return false;
        return (shadingVaries_ && scene_.lights.anyMoves(m->lights)) || m->readsTime ||
               (m->surface && (!scene_.camera.worldToCamera().isStatic() || (shaders_ && shaders_->worldMovesAt(time))));
    }
    bool shadingMovesWithin(const Body& body) const {  // anywhere in the shot
        const Material* m = body.material();
        if (!m) return false;
        return (shadingVaries_ && scene_.lights.anyMoves(m->lights)) || m->readsTime ||
               (m->surface && (!scene_.camera.worldToCamera().isStatic() || (shaders_ && shaders_->worldVaries())));
    }

    BucketSpec bucket_;
    double windowStart_ = 0, windowEnd_ = 0;  // the bucket's frames' exposures
    ImageBlock block_;
    Grid grid_;
    Grid diced_;  // a still-in-world piece diced for several frames (diceShadeSampleFrames)
    std::vector<uint8_t> seenHere_;  // its vertices a frame's grid shows in this bucket (markSeenHere)
    std::vector<std::array<float, 4>> seenBox_;  // each vertex's raster box over the frame (x0 x1 y0 y1)
    GridRasterizer rasterizer_;
    RasterCounters rasterCounters_;
    std::vector<BodyPtr> stack_;
    std::deque<ProceduralChildren> ownChildren_;  // expansions this bucket made for itself (deque: stable)
    std::vector<ChildrenLease> leases_;            // holds on the kept expansions it took children from
    ExpansionRelease* release_ = nullptr;
    // Splits per primitive (and per frame, for pieces cut to one exposure) in this bucket: a
    // frame's budget does not depend on the other frames in its block.
    struct PieceKeyHash {
        size_t operator()(const std::pair<uint64_t, int32_t>& k) const {
            return std::hash<uint64_t>()(k.first * 0x9e3779b97f4a7c15ull ^ uint64_t(uint32_t(k.second)));
        }
    };
    std::unordered_map<std::pair<uint64_t, int32_t>, uint32_t, PieceKeyHash> splitsOf_;
    std::vector<WorkItem> heap_;
    uint64_t arrivals_ = 0;
    // Each root's raster bound as the view cull takes it (its displaced camera bound, projected and
    // grown by the circle of confusion), made once per worker: a bucket passes over the roots it
    // cannot see at the cost of a rectangle test, where each went through the heap and the split
    // loop's cull (a Blobby's or a big mesh's million triangles in each of a thousand buckets).
    // An infinite box: a procedural (its bound may grow) or a root reaching the eye plane.
    std::vector<Bounds3f> rootRaster_;
    const BodyPtr* rootRasterOf_ = nullptr;  // scene_.roots.data() they were made for
    bool rootOutside(size_t i);
    GridShader shader_;
    std::vector<std::pair<int, int>> levels_;  // (frame index, level of detail) of a moving procedural
    ResolveScratch resolveScratch_;

    // Occlusion state of the current bucket.
    int layer_ = 0;                   // tables built so far in this bucket
    size_t nextDepth_ = 0;            // next geometric boundary in layerDepths_
    uint64_t firstHitsAtTable_ = 0;   // rasterCounters_.firstHits when the last table was built
    bool haveTable_ = false;
    int tableFrames_ = 1;             // frames the table has: 1 while every frame sees the still layer
    std::vector<uint8_t> coverage_;
    std::vector<float> farthest_;     // per cell: the farthest hit at the last table (hiddenBehindHits)
    SummedVolumeTable<uint32_t> table_;

    GridCache* gridCache_ = nullptr;
    const TraceScene* trace_ = nullptr;
    bool traceEyeRays_ = false;
    int shadowSlots_ = 0;  // the rasterizer's shadowed light parts per sample
    bool stillShadows_ = false;  // still grids test still occluders at their vertices (testStillShadows)
    void testStillShadows(Grid& grid);
    SampleTracer tracer_;
    // The rays shaders cast (occlusion(), trace(), ...): made when the scene has such shaders.
    std::unique_ptr<ShaderRays> shaderRays_;
    void updateShaderRays();
    AovLayout aovs_;  // output variables per sample (options_.aovs); count 0: none
};

}  // namespace streyes
