// Glassner's spacetime hierarchy (1988): adaptive subdivision of spacetime down, tight
// bounding volumes up.
//
// Down: the 4D box of the scene (x, y, z and the time window; the eye and the lights included)
// is cut into 16 children by halving x, y, z and t, while a cell holds more than a few bodies
// and a depth limit is not reached. Each body goes into every child it reaches, and each child
// asks the body for its bound within the child's spacetime region (Body::boundDuring over the
// part of the child's time the body can be inside the child's box).
// Up: each node's bounding volume is the union of what it holds, clipped to its cell: a 3D box
// and a time interval. Cells do not overlap, so neither do the bounding volumes of siblings. A
// node with one child is replaced by the child.
//
// Time is cut only where it separates something: a cell whose bodies are all still and exist
// over the cell's whole time span is cut in x, y and z only (8 children). Glassner cuts t
// everywhere; for still geometry that builds the same 3D subdivision again for each time half
// without removing a single intersection test (see docs/ARCHITECTURE.md).
//
// The frame-by-frame baseline builds the same structure over one frame's exposure with t never
// cut: a 3D hierarchy (octree-like cells, tight boxes) per frame.
//
// Traversal visits the children a ray enters in order of entry distance and skips those that
// start beyond the nearest hit found so far. A body held by several cells is tested once per ray
// (a mailbox). Hot loop: no allocation, no virtual call (bodies are TrilinearBodies, read through
// inline accessors).
#pragma once

#include <cstdint>
#include <vector>

#include "geom/body.h"
#include "geom/solid_tree.h"
#include "raster/image_block.h"
#include "streyes/render_options.h"
#include "trace/ray_patch.h"

namespace streyes {

struct TraceHit {
    float t = 0, u = 0, v = 0;
    uint32_t body = 0;  // index into the hierarchy's bodies
};

// Per-thread scratch of the traversal, and what it counts.
struct TraceContext {
    std::vector<uint32_t> mailbox;  // per body: the last ray that tested it
    uint32_t rayId = 0;
    struct Entry {
        uint32_t node;
        float tEnter;
    };
    std::vector<Entry> stack;  // sized once: 16 a level
    uint64_t bodyTests = 0;  // ray/body intersection tests (the paper's "intersections")
    uint64_t boxTests = 0;   // ray/bounding-volume tests (time and box)
    // An eye ray's sample, while one is traced: nearest hits skip a body whose material a level of
    // detail dissolves (Material::dissolveLo/Hi) where the sample is outside its share
    // (ImageBlock::dissolveKeeps), as the rasterizer does; the other representation, which may
    // coincide with it, is then found. Null block: no such test.
    struct DissolveSample {
        const ImageBlock* block = nullptr;
        int frame = 0;  // in the block
        size_t pixel = 0;
        int sample = 0;
    } dissolve;
    // A ray's crossings of solids' boundaries (t and solidTag; where on which body, for nearest
    // hits), and the walk through them.
    struct SolidCrossing {
        float t;
        int32_t tag;
        float u, v;
        uint32_t body;
    };
    std::vector<SolidCrossing> crossings;
    SolidWalk solidWalk;
    // A nearest-hit ray's walk (intersectResult), kept apart: it goes on from where the last call
    // left it, past shadow rays the hit's shading casts.
    SolidWalk resultWalk;
};

class SpacetimeBVH {
  public:
    SpacetimeBVH() = default;

    // Builds over the bodies that exist during [ta, tb]. `include` widens the root cell (the eye
    // and the lights, as in the paper). The bodies must outlive the hierarchy; it keeps pointers
    // to those it holds, and TraceHit::body indexes them (bodies()).
    // `solids`: the scene's solids' trees, where some of the bodies bound solids (Material::solid).
    void build(const std::vector<const TrilinearBody*>& bodies, double ta, double tb, const Bounds3f& include,
               const HierarchyOptions& options, const SolidTree* solids = nullptr);

    // Nearest hit with tMin < t < tMax at time `time`; false when none. A solid's members are hit
    // as any surface: eye rays walk their crossings from the eye (SampleTracer::traceSamples).
    bool intersect(const Ray& ray, double time, float tMin, float tMax, TraceHit* hit, TraceContext& ctx) const;
    // The nearest hit that is a surface of what the scene shows (shaders' rays: trace(), gather(),
    // transmission(), ...): as intersect, but a solid's boundary is hit only where the ray goes in
    // or out of the solid's result, the leaves' states where the ray starts told by their crossings
    // as occluded() tells them. Without solids, intersect. `resume`: the ray of the last call with
    // ctx, gone on past its hit (tMin beyond it): the leaves are where that call left them, so
    // that a second crossing of a surface it already crossed (a ray through an edge two
    // micropolygons share) is not one of the result's again.
    bool intersectResult(const Ray& ray, double time, float tMin, float tMax, TraceHit* hit, TraceContext& ctx,
                         bool resume = false) const;
    // Whether anything is hit with tMin < t < tMax at time `time` (shadow rays). A solid's boundary
    // blocks only where the ray goes in or out of the solid's result (geom/solid_tree.h): the ray
    // is walked through every crossing of the solids it meets, beyond tMax too, since where it
    // starts (on a surface, maybe inside a solid) each leaf's state is the opposite of what its
    // nearest crossing after tMin sets (a solid is closed).
    bool occluded(const Ray& ray, double time, float tMin, float tMax, TraceContext& ctx) const;
    bool holdsSolids() const { return solids_ != nullptr; }

    // Bounding volumes built: the nodes of the final tree, leaves included.
    size_t nodeCount() const { return nodes_.size(); }
    size_t leafReferences() const { return refs_.size(); }  // body references held by leaves
    // Bytes its last build held besides what it keeps (the build tree before flattening, the
    // bodies' bounds and the root's list), let go when build returns: the memory estimate's
    // build-time part (memory.h).
    size_t buildBytes() const { return buildBytes_; }
    // Bytes the hierarchy holds (for the memory estimate, memory.h).
    size_t bytes() const {
        return bodies_.capacity() * sizeof(bodies_[0]) + nodes_.capacity() * sizeof(Node) +
               refs_.capacity() * sizeof(Reference);
    }
    int depth() const { return depth_; }
    const std::vector<const TrilinearBody*>& bodies() const { return bodies_; }

    // A leaf's reference to a body, with the time the body spends in the leaf's cell: rays at
    // other times skip it without reading the body.
    struct Reference {
        uint32_t body;
        float ta, tb;
    };
    // The node layout, for tests: a 4D box; children (or leaf bodies) are a contiguous range.
    struct Node {
        Bounds3f box;
        float ta, tb;          // time interval, rounded outwards
        uint32_t first;        // first child in nodes_, or first reference in refs_
        uint32_t count;        // children or references
        bool leaf;
        // A cut in time: the first `before` children end by tSplitLo, the others begin at
        // tSplitHi or later (tSplit rounded down and up), so a ray visits one half.
        bool timeCut;
        uint16_t before;
        float tSplitLo, tSplitHi;
    };
    const std::vector<Node>& nodes() const { return nodes_; }
    const std::vector<Reference>& references() const { return refs_; }

  private:
    // Whether an eye ray's hit is on the inside of a one-sided surface (Sides 1): passed through.
    static bool facesAway(const TrilinearBody& b, double time, const PatchHit& h, const Ray& ray);
    enum class Mode { Nearest, Any, AnyThroughSolids, NearestThroughSolids };
    bool occludedThroughSolids(const Ray& ray, double time, float tMin, float tMax, TraceContext& ctx) const;
    bool intersectThroughSolids(const Ray& ray, double time, float tMin, float tMax, TraceHit* hit,
                                TraceContext& ctx, bool resume) const;
    // Sorts ctx.crossings (nearest first, ties by tag and body) and, unless resuming, sets `walk`
    // to each leaf's state where the ray starts.
    void startWalk(TraceContext& ctx, SolidWalk& walk, bool resume) const;
    template <Mode M>
    bool traverse(const Ray& ray, double time, float tMin, float tMax, TraceHit* hit, TraceContext& ctx) const;

    std::vector<const TrilinearBody*> bodies_;
    std::vector<Node> nodes_;   // nodes_[0] is the root (when there is one)
    std::vector<Reference> refs_;
    int depth_ = 0;
    size_t buildBytes_ = 0;
    const SolidTree* solids_ = nullptr;  // set when a body it holds bounds a solid
};

}  // namespace streyes
