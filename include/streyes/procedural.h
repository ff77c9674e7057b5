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
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "streyes/body.h"
#include "streyes/scene.h"

namespace streyes {

class BodyFactory;

// What expansion knows about the procedural being expanded.
struct ExpandContext {
    double detail = 0;                 // raster area of the bound in pixels (RenderMan's "detail")
    double detailScale = 1;            // --detail: multiplies the generators' level-of-detail thresholds
    MotionTransform objectToWorld;     // the procedural's transform
    AttributesPtr attributes;          // its attribute state, inherited by the children
    SourceLoc loc;                     // where it was declared
    double windowStart = 0, windowEnd = 0;  // the render's time window, frames (for animated children)
    int depth = 0;                     // nesting: 0 for a procedural declared in the scene
    Log* log = nullptr;
};

// The code behind a procedural: turns it into more primitives. Implementations are immutable
// and may be shared; expand may run on any thread.
class ProceduralGenerator {
  public:
    virtual ~ProceduralGenerator() = default;
    // Appends the children to `out` (patches and nested procedurals, with their object-to-world
    // transforms and attributes). Throws InputError naming ctx.loc when it cannot.
    virtual void expand(const ExpandContext& ctx, Scene& out) const = 0;
    virtual std::string describe() const = 0;  // for messages: "DelayedReadArchive tree.rib"
};

// A procedural in the split loop.
class ProceduralBody final : public Body {
  public:
    ProceduralBody(ProceduralDesc desc, const Bounds3f& cameraBound, TimeSpan window, int depth);

    const ProceduralBody* asProcedural() const override { return this; }
    LBBox3f bound() const override;
    RasterMeasure measure(const Camera& camera) const override;
    CameraExtents cameraExtents() const override;
    void split(SplitAxis, std::unique_ptr<Body> out[2]) const override;  // procedurals expand instead
    std::unique_ptr<Body> restrictedTo(double a, double b) const override;
    void dice(int, int, Grid&) const override;

    const ProceduralDesc& desc() const { return desc_; }
    int depth() const { return depth_; }

    // Expands (first call, on any thread; the others wait) and returns the children as
    // camera-space bodies. Rethrows the expansion's error on every call. *expandedHere is set
    // when this call did the expansion (so that counting expansions does not depend on timing).
    const std::vector<BodyPtr>& children(BodyFactory& factory, const Camera& camera, Log& log,
                                         bool* expandedHere = nullptr) const;
    bool expanded() const { return expanded_.load(std::memory_order_acquire); }

    // Children that reach outside the declared bound: the union of everything, for the renderer to
    // render again where the declared bound was too small.
    bool outgrewBound() const { return outgrew_; }
    const Bounds3f& grownBound() const { return grown_; }
    // From then on, cull with the grown bound, and so do the procedurals this one came from
    // (their bounds were made from its declared one). Called by the renderer between passes.
    void useGrownBound();

  private:
    void expand(BodyFactory& factory, const Camera& camera, Log& log) const;

    ProceduralDesc desc_;
    Bounds3f bound_;   // camera space, over the whole animation
    int depth_;
    bool useGrown_ = false;
    mutable const ProceduralBody* parent_ = nullptr;  // the procedural that produced this one

    mutable std::once_flag once_;
    mutable std::atomic<bool> expanded_{false};
    mutable std::vector<BodyPtr> children_;
    mutable std::exception_ptr error_;
    mutable bool outgrew_ = false;
    mutable Bounds3f grown_;
};

// The generators a RIB file can ask for.
//   Procedural "DelayedReadArchive" ["file.rib"] [bound]
//   Procedural "RunProgram" ["program args" "datablock"] [bound]
//   Procedural "DynamicLoad" ["forest" | "tree" "key=value ..."] [bound]
// `directory` is the folder of the file that declares it (relative paths are looked up there
// first). Throws InputError for an unknown DynamicLoad name or bad arguments.
std::shared_ptr<const ProceduralGenerator> makeProceduralGenerator(const std::string& kind,
                                                                    const std::vector<std::string>& args,
                                                                    const std::string& directory,
                                                                    const SourceLoc& loc);

// Limits, documented in docs/SCENE-FORMAT.md.
constexpr int kMaxProceduralDepth = 32;  // nested expansions; deeper ones warn and are dropped

}  // namespace streyes
