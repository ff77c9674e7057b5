// The ray tracer stage: spacetime hierarchies over a render's bodies, eye rays through a
// bucket's samples, and shadow rays at each sample's own time.
//
// It fills the same ImageBlock the rasterizer fills, sample for sample (the same jittered
// (x, y, t)), so the same resolveTile turns either into pixels and the two are comparable
// sample by sample. An eye ray hits the exact bilinear patch its trilinear body is at the
// sample's time (not micropolygons), and the hit is shaded by the shaders the grids use
// (shadePoint) with the bilinear Cs and the patch normal at the hit.
//
// Shadows, in both the ray tracer and the rasterizer: the contribution of each light that casts
// shadows is kept apart (shadePoint's `shadowed`), and added where a shadow ray from the hit
// point, at the sample's time, reaches the light through the hierarchy. Shadow rays start one
// pixel footprint away from the surface (the bias that keeps a surface from shadowing itself:
// the rasterizer's hit lies on a micropolygon, a hair off the exact patch).
#pragma once

#include <algorithm>
#include <deque>
#include <memory>
#include <vector>

#include "raster/image_block.h"
#include "shade/grid_shader.h"
#include "bodies/render_scene.h"
#include "procedural/procedural.h"
#include "trace/spacetime_bvh.h"
#include "trace/tessellate.h"
#include "streyes/stats.h"

namespace streyes {

// The bodies the ray tracer can intersect and the hierarchies over them, for one render.
class TraceScene {
  public:
    // Takes the scene's root bodies: trilinear bodies as they are, keyed patches as their
    // trilinear segments (cut at their keys, as the split loop cuts them), procedurals expanded
    // (all of them: rays go anywhere, shadow rays off screen too), every other kind of body
    // (curved ones) as its micropolygons, diced at the split loop's rate (trace/tessellate.h),
    // bodies in parallel. Throws what a procedural's expansion throws. Only what exists during
    // the exposures of the frames rendered (RenderScene::renderedStart, renderedEnd) is taken:
    // rays are cast at those times only, so a frame's rays meet the same bodies whatever else is
    // rendered with it (a render of one frame of a long shot builds for that frame, not the shot).
    // A displaced surface (its material has a displacement shader, and `shaders` is given) is
    // traced as its displaced micropolygons, whatever its kind; one whose displacement reads
    // `time` as its micropolygons of each frame's exposure, displaced at that exposure's ends.
    TraceScene(const RenderScene& scene, const RenderOptions& options, Log& log,
               const SceneShaders* shaders = nullptr);

    // The frames the hierarchies built from now on cover (buildSpacetime, and the moving
    // occluders' of buildShadowHierarchies): the exposures of [first, first + count) within those
    // rendered; by default every frame rendered. A renderer sets each frame block's before
    // building, so that the hierarchies of swaying leaves (cut in time, their references copied
    // into every time cell) grow with the block, not with the frames rendered (docs/ARCHITECTURE.md,
    // "Shadows"). A ray's answer does not depend on the hierarchy it goes through.
    void setFrames(int first, int count);
    // Whether a body it holds moves, or begins or ends, during the frames rendered: if not, its
    // hierarchies are the same over any of those frames.
    bool changesOverFrames() const;
    // One 4D hierarchy over the exposures of the frames set (setFrames).
    void buildSpacetime(const HierarchyOptions& options);
    // One 3D hierarchy per frame of [first, first + count) (over its exposure), replacing those
    // built before: the frame-by-frame baseline. Frames are built in parallel (TBB).
    void buildFrames(int first, int count, const HierarchyOptions& options);
    // Shadows of the rasterizer's hits (docs/ARCHITECTURE.md, "Shadows"): the bodies parted into
    // those that stand still through the whole shot (not moving, existing from the shot's first
    // exposure to its last: whether a body is one depends on the body alone, not on the frames
    // rendered) and the rest, one hierarchy over each. A still occluder blocks a ray the same at
    // every time, so it is tested once per vertex of a still grid; the moving ones per sample.
    // The still ones' hierarchy is built once (over every frame rendered), the moving ones' again
    // at each call, over the frames set (setFrames).
    void buildShadowHierarchies(const HierarchyOptions& options);
    bool hasShadowHierarchies() const { return shadowSplit_; }
    const SpacetimeBVH& stillOccluders() const { return still_; }
    const SpacetimeBVH& movingOccluders() const { return moving_; }
    bool anyMovingOccluder() const { return !movingBodies_.empty(); }
    // A box holding every moving occluder during the frames rendered: a ray that misses it
    // meets none of them (a cull that cannot change a pixel, whatever frames it is made over).
    const Bounds3f& movingBound() const { return movingBound_; }
    // Boxes holding every root body that does not stand still through the shot, frame by frame
    // over the whole shot (RenderScene::windowStart, windowEnd; frames grouped when there would be
    // more than kShotMoverBoxes): made from the scene's roots, not from the bodies rendered, so
    // they are the same whatever frames are rendered. A still grid whose rays to its lights meet
    // none of them has its shadows decided at its vertices for every frame of the shot
    // (SampleTracer::occludeStillVertices folds them into its colour).
    const std::vector<Bounds3f>& shotMoverBoxes() const { return shotMoverBoxes_; }
    static constexpr size_t kShotMoverBoxes = 4096;
    // The boxes of frame f: one for each moving root (empty where it does not exist then), at
    // shotMoverBoxes()[root * shotMoverGroups() + shotMoverGroupOf(f)]; -1 for a frame outside the shot.
    size_t shotMoverRoots() const { return shotMoverRoots_; }
    size_t shotMoverGroups() const { return shotMoverGroups_; }
    long shotMoverGroupOf(int frame) const {
        const long g = (long(frame) - shotFirstFrame_) / long(shotMoverGroup_);
        return frame < shotFirstFrame_ || g >= long(shotMoverGroups_) ? -1 : g;
    }
    // The time the still occluders' tests run at: any time of the render gives the same answer.
    double stillTime() const { return scene_.renderedStart; }

    // The hierarchy rays of frame f go through.
    const SpacetimeBVH& hierarchy(int frame) const {
        return frames_.empty() ? spacetime_ : frames_[size_t(frame - framesFirst_)];
    }

    const RenderScene& scene() const { return scene_; }
    size_t bodyCount() const { return bodies_.size(); }
    // Bytes held for ray tracing, for the memory estimate: the pieces cut at motion keys, the
    // micropolygons of curved bodies and the body list, with the hierarchies built so far (hierarchyBytes() alone: the frame-by-frame
    // ones are built again for every frame block), and each tracing thread's mailbox.
    size_t bytes() const;
    size_t hierarchyBytes() const;
    // What the hierarchies built again for each frame block (setFrames) hold, and the most their
    // builds held besides: the memory estimate's part per frame of the block.
    size_t blockHierarchyBytes() const { return spacetime_.bytes() + moving_.bytes(); }
    size_t blockBuildBytes() const { return std::max(spacetime_.buildBytes(), moving_.buildBytes()); }
    // The most a hierarchy's build held at once besides what it keeps (SpacetimeBVH::buildBytes).
    size_t buildBytes() const;
    size_t mailboxBytes() const { return bodies_.size() * sizeof(uint32_t); }
    // Shadow rays start this far (camera-space units) from a surface at depth z: one pixel.
    float shadowBias(float z, double time) const;

    // Totals over every build so far: nodes built, and CPU seconds spent building (builds run
    // in parallel, alone).
    uint64_t boundingVolumes = 0;
    double buildSeconds = 0;
    // Procedurals this expanded (first), by nesting depth, for the render's counters.
    std::vector<uint64_t> proceduralsExpandedByDepth;

  private:
    void collect(const Body& body, Log& log);
    void collectShotMovers();
    void markMovingSolids();
    bool inMovingSolid(const Body& b) const;
    bool standsStillThroughShot(const Body& root) const;
    bool displaced(const Body& body) const;

    const RenderScene& scene_;
    const SceneShaders* shaders_;
    std::vector<const TrilinearBody*> bodies_;
    std::vector<BodyPtr> pieces_;  // segments of keyed patches, frames of time-displaced bodies
    std::vector<ChildrenLease> leases_;  // the procedurals' children it holds
    // Curved bodies met by collect, and where in bodies_ their micropolygons go; then the
    // micropolygons of each (deques: bodies_ points into them).
    struct Curved {
        const Body* body;
        size_t at;
    };
    std::vector<Curved> curved_;
    std::vector<std::deque<TrilinearBody>> micropolygons_;
    size_t micropolygonCount_ = 0;
    Bounds3f include_;  // the eye and the point lights: part of the root cell, as in the paper
    SpacetimeBVH spacetime_;
    std::vector<SpacetimeBVH> frames_;
    bool shadowSplit_ = false;
    std::vector<const TrilinearBody*> stillBodies_, movingBodies_;
    SpacetimeBVH still_, moving_;
    Bounds3f movingBound_;
    std::vector<Bounds3f> shotMoverBoxes_;
    std::vector<uint8_t> movingSolids_;  // per solid node: its tree has a member that does not stand still
    size_t shotMoverRoots_ = 0, shotMoverGroups_ = 0, shotMoverGroup_ = 1;
    long shotFirstFrame_ = 0;
    int framesFirst_ = 0;
    double windowStart_ = 0, windowEnd_ = 0;  // setFrames
};

// One thread's ray tracer for buckets: its traversal scratch and light cache.
class SampleTracer {
  public:
    // Shades hits on Shading Language surfaces (the built-in shading needs none).
    void setShader(GridShader* shader) { shader_ = shader; }

    // Every sample of the block: the nearest hit at the sample's time, shaded, with shadow
    // rays. Writes the block's hits as the rasterizer would (z, colour, alpha 1).
    void traceSamples(ImageBlock& block, const TraceScene& trace, RenderCounters& counters);
    // The rasterizer's shadows: adds to each hit sample the contributions the rasterizer kept
    // apart (block.shadowed()) of the lights its shadow rays reach.
    // With the shadow hierarchies built (TraceScene::buildShadowHierarchies): a sample whose
    // parts were tested at its grid's vertices (ImageBlock::stillTested) casts rays against the
    // moving occluders only (none at all when nothing moves); the others against both.
    void shadeShadows(ImageBlock& block, const TraceScene& trace, RenderCounters& counters);
    // A still grid under still lights, after shading: scales each vertex's parts (Cl[0]) by the
    // share of its light that the still occluders leave it (0 or 1; for an area light, the share
    // of its points a ray reaches: every point tested, not one picked per sample), and sets
    // Grid::stillShadows: bit 0, and bit k + 1 for each light slot k that no moving occluder can
    // shadow anywhere on the grid (its samples then cast no ray for it). Needs the shadow
    // hierarchies. Where no moving root can come between the grid and any of its lights in any
    // frame of the shot (TraceScene::shotMoverBoxes: decided over the shot, not the block), the
    // parts are added into its colour (Ci[0]) and zeroed, and Grid::stillShadows is
    // kFoldedShadows: its samples need no shadow pass and may sit in the still layer.
    // A grid left unfolded gets, for each frame of the block [firstFrame, firstFrame + frameCount),
    // the lights no moving root's box of that frame can shadow (Grid::frameShadows): its samples
    // of that frame cast no ray for them (as the block-wide bits: a cull that cannot change a pixel).
    void occludeStillVertices(Grid& grid, const TraceScene& trace, RenderCounters& counters, int firstFrame = 0,
                              int frameCount = 0);

  private:
    const std::vector<CameraLight>& lightsAt(const LightSet& lights, double t);
    // c plus each shadowed[k] whose light a shadow ray from p at `time` reaches.
    // With `also`, a ray blocked by either hierarchy is blocked (the still and the moving
    // occluders: together what `bvh` alone would hold). Slot k with bit k of `unblocked` set is
    // added without a ray (nothing in `bvh` can block it).
    Color addVisibleLights(Color c, Vec3f p, double time, const Color* shadowed, const TraceScene& trace,
                           const SpacetimeBVH& bvh, RenderCounters& counters, const SpacetimeBVH* also = nullptr,
                           unsigned unblocked = 0);

    // Whether no moving root's box of `frame` meets a ray from the grid's box to any of its lights.
    bool frameClear(const Grid& grid, const TraceScene& trace, const std::vector<CameraLight>& lights, double lightTime,
                    int frame);
    std::vector<uint8_t> foldFrames_;  // occludeStillVertices' scratch: frameClear per frame of the block
    unsigned unblockedByMoving(Grid& grid, const TraceScene& trace, const std::vector<CameraLight>& lights,
                               double lightTime, int firstFrame, int frameCount);

    TraceContext ctx_;
    GridShader* shader_ = nullptr;
    std::vector<CameraLight> lights_;
    double lightsTime_ = 0;
    bool lightsValid_ = false;
    std::vector<Color> shadowed_;
    SolidWalk solidWalk_;  // an eye ray's crossings of solids' boundaries (geom/solid_tree.h)
};

}  // namespace streyes
