// Procedural primitives: a bound now, geometry later ("model only what a scene needs").
//
// A procedural is declared with a conservative bound. It enters the split loop as a
// ProceduralBody whose camera-space bound covers the whole animation; only when that bound
// survives view and occlusion culling in some bucket is it expanded, once for all buckets and
// threads (the children are kept and shared). Children are primitives in the procedural's object
// space and inherit its attributes; they may be procedurals themselves (nested expansion:
// forest -> cells -> trees -> parts).
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "geom/body.h"
#include "streyes/rib.h"
#include "streyes/scene.h"

namespace streyes {

class ProceduralBody;
class ProceduralGenerator;

// What expansion knows about the procedural being expanded.
struct ExpandContext {
    double detail = 0;                 // raster area of the bound in pixels (RenderMan's "detail")
    ReadDetail read;                   // what its RIB output is read with: how large it is on
                                       // screen (pixelsPerUnit: sqrt(detail) over the bound's
                                       // longest side in world units)
    MotionTransform objectToWorld;     // the procedural's transform
    Matrix4 sceneToWorld;              // the world its frame was written in (ChildBodyMaker::sceneToWorld),
                                       // where sizes in world units are measured (read.pixelsPerUnit)
    AttributesPtr attributes;          // its attribute state, inherited by the children
    SourceLoc loc;                     // where it was declared
    double windowStart = 0, windowEnd = 0;  // the render's time window, frames (for animated children)
    int depth = 0;                     // nesting: 0 for a procedural declared in the scene
    Log* log = nullptr;
};

// A procedural a generator made itself (the forest's cells and trees), with its generator: the
// description alone does not say how to expand it.
struct GeneratedProcedural {
    ProceduralDesc desc;  // bound, transform, attributes and place; kind and args for messages only
    std::shared_ptr<const ProceduralGenerator> generator;
};

// What one expansion produces: primitives (a scene fragment, whose procedurals are declared in
// RIB and made into generators like the scene's) and procedurals made by the generator.
struct ProceduralOutput {
    Scene scene;
    std::vector<GeneratedProcedural> procedurals;
};

// What an expansion made: the children, and what they point into (their meshes), which lives as
// long as they do.
struct ProceduralChildren {
    std::vector<std::shared_ptr<const void>> keep;  // first: destroyed after the bodies
    std::vector<BodyPtr> bodies;
};
// A hold on a kept expansion's children: they live while any hold does (ProceduralBody::children).
using ChildrenLease = std::shared_ptr<const ProceduralChildren>;

// The code behind a procedural: turns it into more primitives. Implementations are immutable
// and may be shared; expand may run on any thread.
class ProceduralGenerator {
  public:
    virtual ~ProceduralGenerator() = default;
    // Whether the children are kept once made, for every bucket and thread (archives, programs and
    // the forest are costly to make again). When not (an object instance: a copy of primitives the
    // scene holds), each bucket that reaches the bound expands it for itself and frees the
    // children when it is done, so memory follows the buckets at work, not the instances.
    virtual bool keepsChildren() const { return true; }
    // Appends the children to `out` (primitives and nested procedurals, with their object-to-world
    // transforms and attributes). Throws InputError naming ctx.loc when it cannot.
    virtual void expand(const ExpandContext& ctx, ProceduralOutput& out) const = 0;
    virtual std::string describe() const = 0;  // for messages: "DelayedReadArchive tree.rib"
};

// What turns an expansion's output into camera-space bodies: the render scene's BodyFactory
// (src/bodies/), which lies above this stage and is reached only through this interface.
class ChildBodyMaker {
  public:
    virtual ~ChildBodyMaker() = default;
    // The render's time window, frames.
    virtual double windowStart() const = 0;
    virtual double windowEnd() const = 0;
    // Appends a body (or several) for everything in `output`, `depth` expansions below the scene;
    // ids of the children are derived from `parentId`, so they do not depend on the thread. What
    // the bodies point into goes to `keep` when given (the children's owner frees it with them),
    // else it stays with the maker for the whole render.
    // `count`: false when the same children are made again (after ProceduralBody::release), so
    // that the counts of what was made do not depend on when the first ones were freed.
    virtual void addChildren(const ProceduralOutput& output, uint64_t parentId, int depth,
                             std::vector<std::unique_ptr<Body>>& out,
                             std::vector<std::shared_ptr<const void>>* keep = nullptr, bool count = true) = 0;
    // A procedural whose children reached outside its declared bound (rendered again).
    virtual void reportOutgrown(ProceduralBody* procedural) = 0;
    // The world a procedural living over `life` was written in, from the scene's space at time t:
    // identity, but in a frame sequence, whose frames are baked into the render camera's space
    // (scene/sequence.cpp), its frame's camera-to-world. What its output measures in world units
    // (ReadDetail::pixelsPerUnit) is measured there, as the frame written as one world measures it.
    virtual Matrix4 sceneToWorld(const Lifetime& /*life*/, double /*t*/) const { return {}; }
    // The camera-space box of an object-space box during [a, b].
    virtual Bounds3f cameraBound(const Bounds3d& objectBound, const MotionTransform& objectToWorld, double a,
                                 double b) const = 0;
};

// A procedural in the split loop.
//
// Its level of detail (RenderMan's "detail": the raster area of its bound) is decided per frame
// where the procedural moves in camera space (the camera or its transform moves): each frame
// takes the level of its own bound, rounded up to a power of two (detailLevel), and the procedural
// expands once per level it is seen at; a frame's children are those of its level. The split loop
// works on *views*: a procedural over a run of frames that share a level (restrictedTo), bounded
// over those frames only, whose children it pushes for those frames only. A still procedural has
// one level, from its bound over the shot, and is its own view.
class ProceduralBody final : public Body {
  public:
    ProceduralBody(ProceduralDesc desc, std::shared_ptr<const ProceduralGenerator> generator,
                   const Bounds3f& cameraBound, TimeSpan window, int depth, bool moving, const ChildBodyMaker* maker);

    bool expands() const override { return true; }
    LBBox3f bound() const override;
    Bounds3f boundDuring(double a, double b) const override;  // camera space, over [a, b]
    RasterMeasure measure(const Camera& camera) const override;
    CameraExtents cameraExtents() const override;
    void split(SplitAxis, std::unique_ptr<Body> out[2]) const override;  // procedurals expand instead
    // A view over [a, b] (a run of exposures) at `level` (detailLevel of its frames), bounded over
    // [a, b]; expanding it gives the children of that level.
    std::unique_ptr<Body> restrictedTo(double a, double b) const override;
    std::unique_ptr<ProceduralBody> view(double a, double b, int level) const;
    void dice(int, int, Grid&) const override;
    size_t memoryBytes() const override;  // with its description; its children are bodies of their own

    const ProceduralDesc& desc() const { return root().desc_; }
    const ProceduralGenerator& generator() const { return *root().generator_; }
    int depth() const { return root().depth_; }
    // The level of detail this body expands at (a view's own, or a still procedural's).
    int level(const Camera& camera) const;

    // Expands at this body's level (first call for the level, on any thread; the others wait)
    // and returns a hold on the children, camera-space bodies over the whole shot: they live as
    // long as a hold does. Rethrows the expansion's error on every call. *madeHere is set when
    // this call made them, and *madeAgain too when they had been made before and released (so
    // that counting expansions does not depend on timing: count the first only).
    ChildrenLease children(ChildBodyMaker& maker, const Camera& camera, Log& log, bool* madeHere = nullptr,
                           bool* madeAgain = nullptr) const;
    // Lets go of the children of `level` (of the procedural views come from): they are freed when
    // the last hold on them goes, and a later children() makes them again (the same bodies: child
    // ids depend on the parent's). The renderer calls it once no bucket left can reach them
    // (render/expansion_release.h).
    void release(int level) const;
    // The procedural views come from, and what holds it: its parent's children (null for a
    // procedural of the scene, which the render scene holds).
    const ProceduralBody& rootBody() const { return root(); }
    ChildrenLease heldBy() const { return root().heldBy_.lock(); }
    // Whether children() keeps what it makes (ProceduralGenerator::keepsChildren); when not, a
    // bucket calls expandInto and owns the children.
    bool keepsChildren() const { return root().generator_->keepsChildren(); }
    // The procedural its views come from: its identity (Body::pieceKey) names what it expands into.
    uint64_t rootKey() const { return root().pieceKey; }
    // Expands at this body's level into `out`, kept by nobody else (the caller frees them).
    void expandInto(ProceduralChildren& out, ChildBodyMaker& maker, const Camera& camera, Log& log) const;

    // Children that reach outside the declared bound: the union of everything, for the renderer to
    // render again where the declared bound was too small.
    bool outgrewBound() const { return root().outgrew_; }
    const Bounds3f& grownBound() const { return root().grown_; }
    // From then on, cull with the grown bound, and so do the procedurals this one came from
    // (their bounds were made from its declared one). Called by the renderer between passes.
    void useGrownBound();

  private:
    struct Expansion {  // the children of one level of detail, made once
        std::once_flag once;
        std::shared_ptr<ProceduralChildren> children;  // null once released
        std::exception_ptr error;
    };
    struct Level {
        std::shared_ptr<Expansion> current;  // shared: a caller may still wait on a released one
        bool madeBefore = false;             // made and released at least once
    };
    const ProceduralBody& root() const { return root_ ? *root_ : *this; }
    void expand(ProceduralChildren& out, int level, ChildBodyMaker& maker, Log& log, bool own, bool count) const;

    // The procedural itself (views point at it and share its expansions).
    const ProceduralBody* root_ = nullptr;
    ProceduralDesc desc_;
    std::shared_ptr<const ProceduralGenerator> generator_;
    const ChildBodyMaker* maker_ = nullptr;  // for bounds over part of the shot
    int depth_;
    int level_ = -1;   // a view's level; -1: from the bound
    Bounds3f bound_;   // camera space: over the whole shot (a view: over its frames)
    bool useGrown_ = false;
    mutable const ProceduralBody* parent_ = nullptr;  // the procedural that produced this one

    mutable std::mutex mutex_;  // guards expansions_ (the map, and each Expansion's children pointer)
    mutable std::map<int, Level> expansions_;
    mutable std::weak_ptr<const ProceduralChildren> heldBy_;  // the parent's children, which hold this one
    mutable std::atomic<bool> outgrew_{false};
    mutable Bounds3f grown_;  // under mutex_
};

// A raster area (pixels) as a level of detail: the power of two at or above it (0 for a pixel or
// less); kDetailUnbounded for a bound reaching the eye plane. The detail a level expands with is
// 2^level (infinite for kDetailUnbounded).
constexpr int kDetailUnbounded = 1000;
int detailLevel(double area);
double detailOfLevel(int level);

// The generator behind a declared procedural, one of those a RIB file can ask for:
//   Procedural "DelayedReadArchive" ["file.rib"] [bound]
//   Procedural "RunProgram" ["program args" "datablock"] [bound]
//   Procedural "DynamicLoad" ["forest" | "tree" | "plugin" "parameters"] [bound]  (dynamic_load.h)
//   Procedural "RiFunction" ["id"] [bound]: RiProcedural with a function (scene/ri_stream.h)
// Relative names are looked up in desc.directory first, then along the search paths. Throws InputError naming desc.loc for an
// unknown kind or name, bad arguments, a missing archive or program, or one the scene may not
// reach (SceneAccess, rib.h).
std::shared_ptr<const ProceduralGenerator> makeProceduralGenerator(const ProceduralDesc& desc);

// Limits, documented in docs/SCENE-FORMAT.md.
constexpr int kMaxProceduralDepth = 32;  // nested expansions; deeper ones warn and are dropped

}  // namespace streyes
