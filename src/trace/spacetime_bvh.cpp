#include "trace/spacetime_bvh.h"

#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <limits>

#include "bodies/material.h"

namespace streyes {

namespace {

// ---- Bound requests -------------------------------------------------------------------------------

// Widens a box by a few float ulps of its size, so that points computed at a time inside the
// box's interval (a lerp, rounded) stay inside it.
Bounds3f padded(Bounds3f b) {
    for (int k = 0; k < 3; ++k) {
        const float m = std::max({std::fabs(b.lo[k]), std::fabs(b.hi[k]), b.hi[k] - b.lo[k]});
        const float e = m * 4e-6f + std::numeric_limits<float>::min();
        b.lo[k] -= e;
        b.hi[k] += e;
    }
    return b;
}

Bounds3f intersection(const Bounds3f& a, const Bounds3f& b) { return {vmax(a.lo, b.lo), vmin(a.hi, b.hi)}; }

double surfaceArea(const Bounds3f& b) {
    if (b.empty()) return 0;
    const Vec3f d = b.diagonal();
    return 2.0 * (double(d.x) * d.y + double(d.y) * d.z + double(d.z) * d.x);
}

// A body's share of one spacetime cell: its bound inside the cell's box, and the part of the
// cell's time during which it can be inside that box.
struct CellItem {
    uint32_t body;
    Bounds3f box;
    double ta, tb;
};

// The bound of a cell's items: a box and a time interval.
struct ItemsBound {
    Bounds3f box;
    double ta = std::numeric_limits<double>::infinity(), tb = -std::numeric_limits<double>::infinity();
    explicit ItemsBound(const std::vector<CellItem>& items) {
        for (const CellItem& it : items) {
            box.extend(it.box);
            ta = std::min(ta, it.ta);
            tb = std::max(tb, it.tb);
        }
    }
    // How likely a ray that meets this 4D volume (at a uniform time within it) is to meet `inner`
    // inside it: the ratio of box surface areas times the ratio of time lengths.
    double chanceOf(const ItemsBound& inner) const {
        const double sa = surfaceArea(box), len = tb - ta;
        const double ps = sa > 0 ? surfaceArea(inner.box) / sa : 1.0;
        const double pt = len > 0 ? (inner.tb - inner.ta) / len : 1.0;
        return ps * pt;
    }
};

// Subtrees above this depth are built as parallel tasks.
constexpr int kParallelDepth = 3;

// Cost of visiting a node's children, in ray/body tests (a body test and the slab tests of a
// node's children cost about the same).
constexpr double kTraversalCost = 1.0;

// What the build asks of a body again and again, asked once.
struct BodyInfo {
    const TrilinearBody* body;
    double t0, t1;
    bool moving;
    LBBox3f lb;        // its bound at t0 and t1 (lerped: a bound at any time between)
    Bounds3f still;    // a still body's bound (the same over any interval), padded
    explicit BodyInfo(const TrilinearBody* b)
        : body(b), t0(b->time().t0), t1(b->time().t1), moving(b->moving()), lb(b->bound()) {
        if (!moving) still = padded(b->boundDuring(t0, t1));
    }
};

// Asks body b for its bound inside the cell `cell` x [ca, cb]; false when it is not there.
// A moving body's linear bound (its LBBox, lerped) meets the cell's box during one interval of
// time, found from the six linear inequalities; the body is asked for its bound over that
// interval only, and the answer is clipped to the cell.
bool clipToCell(const BodyInfo& b, uint32_t index, const Bounds3f& cell, double ca, double cb, CellItem* out) {
    double a = std::max(ca, b.t0), e = std::min(cb, b.t1);
    if (a > e) return false;
    if (!b.moving) {
        const Bounds3f box = intersection(b.still, cell);
        if (box.empty()) return false;
        *out = {index, box, a, e};
        return true;
    }
    {
        const LBBox3f& lb = b.lb;
        const double t0 = b.t0, span = b.t1 - t0;
        double sa = (a - t0) / span, se = (e - t0) / span;
        // f0 + s (f1 - f0) <= limit, or >= limit when `atLeast`.
        auto restrict = [&](double f0, double f1, double limit, bool atLeast) {
            double slope = f1 - f0, rhs = limit - f0;
            if (atLeast) slope = -slope, rhs = -rhs;
            if (slope == 0) {
                if (rhs < 0) se = -1;  // never
            } else if (slope > 0) {
                se = std::min(se, rhs / slope);
            } else {
                sa = std::max(sa, rhs / slope);
            }
        };
        for (int k = 0; k < 3; ++k) {
            restrict(lb.b0.lo[k], lb.b1.lo[k], cell.hi[k], false);
            restrict(lb.b0.hi[k], lb.b1.hi[k], cell.lo[k], true);
        }
        const double slack = 1e-7;  // rounding of the lerps above and in cornersAt
        if (sa > se + slack) return false;
        a = std::max(a, t0 + (sa - slack) * span);
        e = std::min(e, t0 + (se + slack) * span);
        if (a > e) a = e = 0.5 * (a + e);  // the slack crossed over: one instant
    }
    const Bounds3f box = intersection(padded(b.body->boundDuring(a, e)), cell);
    if (box.empty()) return false;
    *out = {index, box, a, e};
    return true;
}

// ---- Build ------------------------------------------------------------------------------------------

// Float time bounds that contain the double ones (so float(t) of any t inside tests inside).
float roundDown(double t) {
    float f = float(t);
    return double(f) > t ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float roundUp(double t) {
    float f = float(t);
    return double(f) < t ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

struct BuildNode {
    Bounds3f box;
    double ta = 0, tb = 0;
    bool leaf = true;
    std::vector<SpacetimeBVH::Reference> bodies;  // leaf
    std::vector<BuildNode> children;   // interior
    bool timeCut = false;              // children before `before` lie before tSplit, the rest after
    uint16_t before = 0;
    double tSplit = 0;
};

// One way of cutting a cell: its children (8 in space, or 16 in space and time), the bodies
// in each, and what a ray can expect to test below it.
struct Cut {
    int n = 0;
    std::vector<std::vector<CellItem>> items;
    std::vector<Bounds3f> cells;
    std::vector<double> ta, tb;
    double cost = 0;        // expected ray/body tests: traversal plus, per child, its bodies
                            // times the chance that a ray through the cell's bound meets the child's
    size_t held = 0;        // the children's lists' capacities, in items
};

class Builder {
  public:
    Builder(const std::vector<BodyInfo>& bodies, const HierarchyOptions& o) : bodies_(bodies), o_(o) {}

    // Subdivision down, bounding volumes up, for one cell and the bodies in it.
    BuildNode build(const Bounds3f& cell, double ca, double cb, std::vector<CellItem>& items, int depth) {
        for (int seen = maxDepth.load(); seen < depth && !maxDepth.compare_exchange_weak(seen, depth);) {
        }
        if (int(items.size()) <= o_.maxLeafBodies || depth >= o_.maxDepth) return leaf(items);

        // Cut in space; cut time as well (Glassner's 16 children) where that pays: where bodies
        // move or begin or end inside the cell, and the expected tests drop by a fifth. A time
        // cut copies every body that lasts across it, so still geometry is cut in space only.
        Cut cut = cutCell(cell, ca, cb, items, 8);
        if (o_.splitTime && cb - ca > o_.minTimeCut && (o_.alwaysSplitTime || timeMatters(ca, cb, items))) {
            constexpr double kTimeCutGain = 0.8;
            Cut timeCut = cutCell(cell, ca, cb, items, 16);
            if (o_.alwaysSplitTime || timeCut.cost < kTimeCutGain * cut.cost) std::swap(cut, timeCut);
            release(timeCut.held);  // the cut not taken
        }
        // Cut only when it pays against a leaf. Without that, cells keep splitting along the
        // faces of overlapping boxes (a sphere's pole, where thin patches meet) to the depth
        // limit; and where every body reaches every child, the children cost more than the cell.
        if (cut.cost >= double(items.size())) {
            release(cut.held);
            return leaf(items);
        }
        // The cell's own list is not read again: let it go before the children's subtrees are
        // built, or every level of a path down the tree holds its list and its children's at once.
        std::vector<CellItem>().swap(items);

        // The children's subtrees are independent: near the root they are built in parallel
        // (the tree does not depend on the order they finish in).
        std::vector<BuildNode> children(size_t(cut.n));
        std::vector<char> occupied(size_t(cut.n));
        for (int c = 0; c < cut.n; ++c) occupied[size_t(c)] = !cut.items[size_t(c)].empty();
        auto buildChild = [&](int c) {
            std::vector<CellItem>& ci = cut.items[size_t(c)];
            const size_t capacity = ci.capacity();
            children[size_t(c)] = build(cut.cells[size_t(c)], cut.ta[size_t(c)], cut.tb[size_t(c)], ci, depth + 1);
            std::vector<CellItem>().swap(ci);
            release(capacity);
        };
        tbb::task_group group;
        for (int c = 0; c < cut.n; ++c) {
            if (!occupied[size_t(c)]) continue;
            if (depth < kParallelDepth) group.run([&buildChild, c] { buildChild(c); });
            else buildChild(c);
        }
        group.wait();

        BuildNode node;
        node.leaf = false;
        node.ta = std::numeric_limits<double>::infinity();
        node.tb = -node.ta;
        node.timeCut = cut.n == 16;
        node.tSplit = 0.5 * (ca + cb);
        // Exactly as many as there are (the whole build tree is held until it is flattened).
        node.children.reserve(size_t(std::count(occupied.begin(), occupied.end(), char(1))));
        for (int c = 0; c < cut.n; ++c) {
            if (!occupied[size_t(c)]) continue;
            if (c < 8) ++node.before;  // children 0-7 hold the first half of the time
            BuildNode& child = children[size_t(c)];
            node.box.extend(child.box);
            node.ta = std::min(node.ta, child.ta);
            node.tb = std::max(node.tb, child.tb);
            node.children.push_back(std::move(child));
        }
        if (node.children.size() == 1) return std::move(node.children.front());  // one child replaces its parent
        return node;
    }

    std::atomic<int> maxDepth{0};
    // Items the cuts' lists held at once, at most (over every path in flight): part of what a
    // build holds besides what it keeps.
    mutable std::atomic<size_t> peakHeld{0};

  private:
    // Halving x, y and z (n = 8), and t (n = 16); each child asks the bodies for their bounds.
    Cut cutCell(const Bounds3f& cell, double ca, double cb, const std::vector<CellItem>& items, int n) const {
        Cut cut;
        cut.n = n;
        cut.items.resize(size_t(n));
        cut.cells.resize(size_t(n));
        cut.ta.resize(size_t(n));
        cut.tb.resize(size_t(n));
        const Vec3f mid = (cell.lo + cell.hi) * 0.5f;
        const double tm = 0.5 * (ca + cb);
        for (int c = 0; c < n; ++c) {
            Bounds3f cc = cell;
            for (int k = 0; k < 3; ++k) {
                if (c & (1 << k)) cc.lo[k] = mid[k];
                else cc.hi[k] = mid[k];
            }
            const size_t i = size_t(c);
            cut.cells[i] = cc;
            cut.ta[i] = c & 8 ? tm : ca;
            cut.tb[i] = n == 16 && !(c & 8) ? tm : cb;
        }
        // Each body is asked only by the children its bound in this cell reaches (on which side
        // of each halving plane it lies); children keep the cell's order of bodies.
        for (const CellItem& it : items) {
            int lo[4], hi[4];
            for (int k = 0; k < 3; ++k) {
                lo[k] = it.box.lo[k] <= mid[k] ? 0 : 1;
                hi[k] = it.box.hi[k] >= mid[k] ? 1 : 0;
            }
            lo[3] = n == 16 && it.ta > tm ? 1 : 0;
            hi[3] = n == 16 && it.tb >= tm ? 1 : 0;
            for (int t = lo[3]; t <= hi[3]; ++t)
                for (int z = lo[2]; z <= hi[2]; ++z)
                    for (int y = lo[1]; y <= hi[1]; ++y)
                        for (int x = lo[0]; x <= hi[0]; ++x) {
                            const size_t i = size_t(x | y << 1 | z << 2 | t << 3);
                            CellItem out;
                            if (clipToCell(bodies_[it.body], it.body, cut.cells[i], cut.ta[i], cut.tb[i], &out))
                                cut.items[i].push_back(out);
                        }
        }
        for (const std::vector<CellItem>& ci : cut.items) cut.held += ci.capacity();
        const size_t now = held_ += cut.held;
        for (size_t seen = peakHeld.load(); seen < now && !peakHeld.compare_exchange_weak(seen, now);) {
        }
        const ItemsBound parent(items);
        cut.cost = kTraversalCost;
        for (const std::vector<CellItem>& ci : cut.items)
            if (!ci.empty()) cut.cost += parent.chanceOf(ItemsBound(ci)) * double(ci.size());
        return cut;
    }

    // Whether anything in the cell changes over its time span: a moving body, or one that
    // begins or ends inside it.
    bool timeMatters(double ca, double cb, const std::vector<CellItem>& items) const {
        for (const CellItem& it : items) {
            const BodyInfo& b = bodies_[it.body];
            if (b.moving || b.t0 > ca || b.t1 < cb) return true;
        }
        return false;
    }

    static BuildNode leaf(const std::vector<CellItem>& items) {
        const ItemsBound bound(items);
        BuildNode node;
        node.box = bound.box;
        node.ta = bound.ta;
        node.tb = bound.tb;
        node.bodies.reserve(items.size());
        for (const CellItem& it : items) node.bodies.push_back({it.body, roundDown(it.ta), roundUp(it.tb)});
        return node;
    }

    void release(size_t items) { held_ -= items; }

    const std::vector<BodyInfo>& bodies_;
    const HierarchyOptions& o_;
    mutable std::atomic<size_t> held_{0};
};


// What a build tree holds below its root (vectors' capacities: what was allocated).
size_t buildTreeBytes(const BuildNode& n) {
    size_t b = n.bodies.capacity() * sizeof(SpacetimeBVH::Reference) + n.children.capacity() * sizeof(BuildNode);
    for (const BuildNode& c : n.children) b += buildTreeBytes(c);
    return b;
}

}  // namespace

void SpacetimeBVH::build(const std::vector<const TrilinearBody*>& all, double ta, double tb, const Bounds3f& include,
                         const HierarchyOptions& options, const SolidTree* solids) {
    bodies_.clear();
    solids_ = nullptr;
    nodes_.clear();
    refs_.clear();
    depth_ = 0;
    buildBytes_ = 0;
    // The root cell: every body over the window, the eye and the lights.
    Bounds3f root = include;
    for (const TrilinearBody* b : all) {
        if (!b->time().overlaps(ta, tb)) continue;
        root.extend(b->boundDuring(std::max(ta, b->time().t0), std::min(tb, b->time().t1)));
        bodies_.push_back(b);
        if (solids && !solids->empty() && b->material() && b->material()->solid >= 0) solids_ = solids;
    }
    if (bodies_.empty()) return;
    root = padded(root);
    std::vector<CellItem> items;
    items.reserve(bodies_.size());
    std::vector<BodyInfo> info;
    info.reserve(bodies_.size());
    for (uint32_t i = 0; i < uint32_t(bodies_.size()); ++i) {
        info.emplace_back(bodies_[i]);
        CellItem it;
        if (clipToCell(info.back(), i, root, ta, tb, &it)) items.push_back(it);
    }
    if (items.empty()) return;
    const size_t listBytes = info.capacity() * sizeof(BodyInfo) + items.capacity() * sizeof(CellItem);
    Builder builder(info, options);
    BuildNode tree = builder.build(root, ta, tb, items, 0);
    depth_ = builder.maxDepth.load();
    buildBytes_ = listBytes + builder.peakHeld.load() * sizeof(CellItem) + sizeof(BuildNode) + buildTreeBytes(tree);

    // Flatten breadth first, so that each node's children are contiguous.
    std::deque<std::pair<const BuildNode*, uint32_t>> queue{{&tree, 0}};
    nodes_.push_back({});
    while (!queue.empty()) {
        auto [b, index] = queue.front();
        queue.pop_front();
        Node n;
        n.box = b->box;
        n.ta = roundDown(b->ta);
        n.tb = roundUp(b->tb);
        n.leaf = b->leaf;
        n.timeCut = b->timeCut;
        n.before = b->before;
        n.tSplitLo = roundDown(b->tSplit);
        n.tSplitHi = roundUp(b->tSplit);
        if (b->leaf) {
            n.first = uint32_t(refs_.size());
            n.count = uint32_t(b->bodies.size());
            refs_.insert(refs_.end(), b->bodies.begin(), b->bodies.end());
        } else {
            n.first = uint32_t(nodes_.size());
            n.count = uint32_t(b->children.size());
            for (const BuildNode& c : b->children) {
                queue.emplace_back(&c, uint32_t(nodes_.size()));
                nodes_.push_back({});
            }
        }
        nodes_[index] = n;
    }
}

// ---- Traversal ----------------------------------------------------------------------------------------

namespace {

// Slab test of the ray against a box within [t0, t1]; NaN from 0 * inf (a ray in a slab's plane)
// leaves the interval alone. The far distance is widened by a few ulps (as in pbrt) so that
// rounding never rejects a box the ray grazes.
inline bool enterBox(const Bounds3f& b, const Ray& r, const Vec3f& inv, float t0, float t1, float* tEnter) {
    for (int k = 0; k < 3; ++k) {
        float tNear = (b.lo[k] - r.o[k]) * inv[k];
        float tFar = (b.hi[k] - r.o[k]) * inv[k];
        if (tNear > tFar) std::swap(tNear, tFar);
        tFar *= 1 + 4 * std::numeric_limits<float>::epsilon();
        t0 = tNear > t0 ? tNear : t0;
        t1 = tFar < t1 ? tFar : t1;
        if (t0 > t1) return false;
    }
    *tEnter = t0;
    return true;
}

// A body another sample's share of a level of detail's dissolve sees (TraceContext::dissolve).
inline bool dissolvedAway(const TrilinearBody& b, const TraceContext::DissolveSample& s) {
    const Material* m = b.material();
    return m && (m->dissolveLo > 0 || m->dissolveHi < 1) &&
           !s.block->dissolveKeeps(s.frame, s.pixel, s.sample, m->dissolveLo, m->dissolveHi);
}

// Just above t: a hit at exactly the nearest distance so far still comes back (for ties).
inline float tieLimit(float t) { return std::nextafter(t, std::numeric_limits<float>::infinity()); }

}  // namespace

template <SpacetimeBVH::Mode M>
bool SpacetimeBVH::traverse(const Ray& ray, double time, float tMin, float tMax, TraceHit* hit,
                            TraceContext& ctx) const {
    if (nodes_.empty()) return false;
    if (ctx.mailbox.size() < bodies_.size()) ctx.mailbox.resize(bodies_.size(), 0);
    if (++ctx.rayId == 0) {  // wrapped: forget every mark
        std::fill(ctx.mailbox.begin(), ctx.mailbox.end(), 0u);
        ctx.rayId = 1;
    }
    const uint32_t rayId = ctx.rayId;
    const float tf = float(time);
    // + 0.0f makes a -0 component +0: 1/-0 = -inf turned a ray in a box face's plane into a miss
    // (enterBox's 0 * inf NaN keeps the interval only for +inf).
    const Vec3f inv{1.0f / (ray.d.x + 0.0f), 1.0f / (ray.d.y + 0.0f), 1.0f / (ray.d.z + 0.0f)};
    constexpr bool AnyHit = M != Mode::Nearest;
    // Through solids, boxes are culled at no distance: a solid's crossings beyond tMax tell
    // which of its leaves the ray starts in.
    constexpr bool ThroughSolids = M == Mode::AnyThroughSolids || M == Mode::NearestThroughSolids;
    float best = ThroughSolids ? std::numeric_limits<float>::infinity() : tMax;
    // The nearest plain surface's distance so far: `best` itself but through solids.
    float plainNearest = tMax;
    float& nearest = M == Mode::NearestThroughSolids ? plainNearest : best;
    bool found = false;

    if (ctx.stack.size() < size_t(16 * (depth_ + 2))) ctx.stack.resize(size_t(16 * (depth_ + 2)));
    TraceContext::Entry* stack = ctx.stack.data();
    int top = 0;
    float tEnter;
    const Node& root = nodes_[0];
    if (tf < root.ta || tf > root.tb || !enterBox(root.box, ray, inv, tMin, best, &tEnter)) return false;
    stack[top++] = {0, tEnter};
    while (top > 0) {
        const TraceContext::Entry e = stack[--top];
        if (e.tEnter > best) continue;  // a nearer hit was found since it was pushed
        const Node& n = nodes_[e.node];
        if (n.leaf) {
            for (uint32_t r = n.first; r < n.first + n.count; ++r) {
                const Reference& ref = refs_[r];
                if (tf < ref.ta || tf > ref.tb) continue;  // the body is elsewhere at this time
                const uint32_t bi = ref.body;
                if (ctx.mailbox[bi] == rayId) continue;
                ctx.mailbox[bi] = rayId;
                const TrilinearBody& b = *bodies_[bi];
                if (time < b.time().t0 || time > b.time().t1) continue;
                ++ctx.bodyTests;
                PatchHit h;
                if constexpr (M == Mode::Any) {
                    if (intersectBilinearPatch(b.cornersAt(time), ray, tMin, best, &h)) return true;
                } else if constexpr (M == Mode::AnyThroughSolids) {
                    const Material* m = b.material();
                    if (!m || m->solid < 0) {
                        if (intersectBilinearPatch(b.cornersAt(time), ray, tMin, tMax, &h)) return true;
                        continue;
                    }
                    if (!intersectBilinearPatch(b.cornersAt(time), ray, tMin, best, &h)) continue;
                    // Entering where its outside faces the ray, as an eye ray's crossing (sample_tracer.cpp).
                    const Vec3f n = bilinearNormal(b.cornersAt(time), h.u, h.v);
                    ctx.crossings.push_back({h.t, solidTag(m->solid, dot(m->flipNormals ? -n : n, ray.d) < 0), h.u, h.v, bi});
                } else {
                    if constexpr (M == Mode::NearestThroughSolids) {
                        // A solid's crossing, at any distance (as a shadow ray's): the walk decides.
                        if (const Material* m = b.material(); m && m->solid >= 0) {
                            if (!intersectBilinearPatch(b.cornersAt(time), ray, tMin, best, &h)) continue;
                            const Vec3f n = bilinearNormal(b.cornersAt(time), h.u, h.v);
                            ctx.crossings.push_back(
                                {h.t, solidTag(m->solid, dot(m->flipNormals ? -n : n, ray.d) < 0), h.u, h.v, bi});
                            continue;
                        }
                    }
                    // At equal distance the primitive declared first wins, as in the rasterizer
                    // (SampleHit::beatenBy), and between pieces of one primitive (micropolygons
                    // meeting at a vertex a ray grazes) the first in the scene's body order: the
                    // result does not depend on traversal order, which depends on the hierarchy
                    // and so on the frames it was built over.
                    if (!intersectBilinearPatch(b.cornersAt(time), ray, tMin, tieLimit(nearest), &h)) continue;
                    if (found && h.t == nearest) {
                        const uint64_t id = b.primitiveId(), bestId = bodies_[hit->body]->primitiveId();
                        if (id > bestId || (id == bestId && bi > hit->body)) continue;
                    }
                    if (facesAway(b, time, h, ray)) continue;  // Sides 1 (shadow rays still stop at it)
                    if (ctx.dissolve.block && dissolvedAway(b, ctx.dissolve)) continue;
                    nearest = h.t;
                    *hit = {h.t, h.u, h.v, bi};
                    found = true;
                }
            }
            continue;
        }
        // Children the ray enters at this time, pushed farthest first so the nearest comes next
        // (a shadow ray takes any hit: no order).
        TraceContext::Entry* kids = stack + top;
        int k = 0;
        uint32_t c0 = n.first, c1 = n.first + n.count;
        if (n.timeCut) {  // only the half of the children that holds this time
            if (tf < n.tSplitLo) c1 = n.first + n.before;
            else if (tf > n.tSplitHi) c0 = n.first + n.before;
        }
        for (uint32_t c = c0; c < c1; ++c) {
            const Node& cn = nodes_[c];
            ++ctx.boxTests;
            if (tf < cn.ta || tf > cn.tb || !enterBox(cn.box, ray, inv, tMin, best, &tEnter)) continue;
            const TraceContext::Entry entry{c, tEnter};
            int j = k++;
            if constexpr (!AnyHit)
                for (; j > 0 && kids[j - 1].tEnter < entry.tEnter; --j) kids[j] = kids[j - 1];
            kids[j] = entry;
        }
        top += k;
    }
    return found;
}

bool SpacetimeBVH::facesAway(const TrilinearBody& b, double time, const PatchHit& h, const Ray& ray) {
    const Material* m = b.material();
    if (!m || !m->oneSided) return false;
    const Vec3f n = bilinearNormal(b.cornersAt(time), h.u, h.v);
    return dot(m->flipNormals ? -n : n, ray.d) > 0;
}

bool SpacetimeBVH::intersect(const Ray& ray, double time, float tMin, float tMax, TraceHit* hit,
                             TraceContext& ctx) const {
    return traverse<Mode::Nearest>(ray, time, tMin, tMax, hit, ctx);
}

bool SpacetimeBVH::occluded(const Ray& ray, double time, float tMin, float tMax, TraceContext& ctx) const {
    if (!solids_) return traverse<Mode::Any>(ray, time, tMin, tMax, nullptr, ctx);
    return occludedThroughSolids(ray, time, tMin, tMax, ctx);
}

// Out of line: inlined into occluded, it cost the plain any-hit traversal 7.7% more instructions
// (callgrind, scenes/atom.rib frames 1-2 at 160x90: 214.3 M -> 230.8 M in occluded).
__attribute__((noinline)) bool SpacetimeBVH::occludedThroughSolids(const Ray& ray, double time, float tMin, float tMax,
                                                                   TraceContext& ctx) const {
    std::vector<TraceContext::SolidCrossing>& cs = ctx.crossings;
    cs.clear();
    if (traverse<Mode::AnyThroughSolids>(ray, time, tMin, tMax, nullptr, ctx)) return true;  // a plain surface
    if (cs.empty()) return false;
    startWalk(ctx, ctx.solidWalk, false);
    for (const TraceContext::SolidCrossing& c : cs) {
        if (!(c.t < tMax)) break;
        if (ctx.solidWalk.cross(solidLeafOf(c.tag), solidEnters(c.tag))) return true;  // the result's surface
    }
    return false;
}

bool SpacetimeBVH::intersectResult(const Ray& ray, double time, float tMin, float tMax, TraceHit* hit,
                                   TraceContext& ctx, bool resume) const {
    if (!solids_) return traverse<Mode::Nearest>(ray, time, tMin, tMax, hit, ctx);
    return intersectThroughSolids(ray, time, tMin, tMax, hit, ctx, resume);
}

// Out of line, as occludedThroughSolids: the plain nearest-hit traversal keeps its code.
__attribute__((noinline)) bool SpacetimeBVH::intersectThroughSolids(const Ray& ray, double time, float tMin,
                                                                    float tMax, TraceHit* hit, TraceContext& ctx,
                                                                    bool resume) const {
    std::vector<TraceContext::SolidCrossing>& cs = ctx.crossings;
    cs.clear();
    const bool found = traverse<Mode::NearestThroughSolids>(ray, time, tMin, tMax, hit, ctx);  // plain surfaces
    if (cs.empty()) return found;
    startWalk(ctx, ctx.resultWalk, resume);
    for (const TraceContext::SolidCrossing& c : cs) {
        if (!(c.t < tMax)) break;
        if (found) {  // past the nearest plain surface (at a tie, the order intersect gives them)
            if (c.t > hit->t) break;
            if (c.t == hit->t) {
                const uint64_t id = bodies_[c.body]->primitiveId(), plainId = bodies_[hit->body]->primitiveId();
                if (id > plainId || (id == plainId && c.body > hit->body)) break;
            }
        }
        if (ctx.resultWalk.cross(solidLeafOf(c.tag), solidEnters(c.tag))) {  // the result's surface
            *hit = {c.t, c.u, c.v, c.body};
            return true;
        }
    }
    return found;
}

void SpacetimeBVH::startWalk(TraceContext& ctx, SolidWalk& walk, bool resume) const {
    std::vector<TraceContext::SolidCrossing>& cs = ctx.crossings;
    // Nearest first, ties by leaf and facing, then body: the order, and so the answer, does not
    // depend on the traversal's (which depends on the frames the hierarchy was built over; the
    // bodies' order is the scene's in every hierarchy).
    std::sort(cs.begin(), cs.end(), [](const TraceContext::SolidCrossing& a, const TraceContext::SolidCrossing& b) {
        return a.t < b.t || (a.t == b.t && (a.tag < b.tag || (a.tag == b.tag && a.body < b.body)));
    });
    if (resume) return;  // each leaf is on the side the last call's walk left it
    walk.reset(*solids_);
    // Where the ray starts, each leaf it crosses is on the side its nearest crossing leaves
    // (set farthest first, so the nearest crossing's state stays).
    for (size_t i = cs.size(); i-- > 0;) walk.start(solidLeafOf(cs[i].tag), !solidEnters(cs[i].tag));
}

}  // namespace streyes
