// The spacetime hierarchy: nearest hits and shadow tests equal brute force over every body,
// bounds are clipped to non-overlapping cells, and time is cut only where things move.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "trace/spacetime_bvh.h"
#include "util/sampling.h"

namespace streyes {
namespace {

using Corners = TrilinearBody::Corners;

// A random scene: small patches scattered in a box, a third of them moving (some fast), some
// existing only for part of the window [0, 8], and one large floor under everything.
struct RandomScene {
    std::vector<std::unique_ptr<TrilinearBody>> owned;
    std::vector<const TrilinearBody*> bodies;
    explicit RandomScene(int n, uint64_t seed = 1) {
        HashRng rng(seed);
        auto r = [&](float a, float b) { return a + (b - a) * rng.nextFloat(); };
        auto add = [&](TimeSpan span, const Corners& a, const Corners& b) {
            owned.push_back(std::make_unique<TrilinearBody>(span, a, b, std::array<Color, 4>{}, nullptr));
            bodies.push_back(owned.back().get());
        };
        add({0, 8}, Corners{{{-20, -6, 0}, {20, -6, 0}, {-20, -6, 40}, {20, -6, 40}}},
            Corners{{{-20, -6, 0}, {20, -6, 0}, {-20, -6, 40}, {20, -6, 40}}});
        for (int i = 0; i < n; ++i) {
            const Vec3f c{r(-10, 10), r(-5, 5), r(5, 30)};
            Corners a;
            for (Vec3f& p : a) p = c + Vec3f{r(-1, 1), r(-1, 1), r(-1, 1)};
            Corners b = a;
            const int kind = i % 3;
            if (kind == 1) {
                const Vec3f move{r(-6, 6), r(-2, 2), r(-4, 4)};
                for (Vec3f& p : b) p = p + move;
            }
            TimeSpan span{0, 8};
            if (i % 5 == 4) span = {r(0, 4), r(4, 8)};
            add(span, a, b);
        }
    }
};

bool bruteNearest(const std::vector<const TrilinearBody*>& bodies, const Ray& ray, double time, float tMax,
                  PatchHit* best, const TrilinearBody** which) {
    bool found = false;
    float limit = tMax;
    for (const TrilinearBody* b : bodies) {
        if (time < b->time().t0 || time > b->time().t1) continue;
        PatchHit h;
        if (intersectBilinearPatch(b->cornersAt(time), ray, 1e-3f, limit, &h)) {
            limit = h.t;
            *best = h;
            *which = b;
            found = true;
        }
    }
    return found;
}

void expectSameAsBruteForce(const SpacetimeBVH& bvh, const RandomScene& scene, double t0, double t1, uint64_t seed) {
    HashRng rng(seed);
    auto r = [&](float a, float b) { return a + (b - a) * rng.nextFloat(); };
    TraceContext ctx;
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
        const double time = t0 + (t1 - t0) * rng.nextFloat();
        const Ray ray{{r(-2, 2), r(-2, 2), r(-2, 2)}, normalize(Vec3f{r(-0.5f, 0.5f), r(-0.4f, 0.3f), 1})};
        PatchHit ref;
        const TrilinearBody* refBody = nullptr;
        const bool refFound = bruteNearest(scene.bodies, ray, time, 1e30f, &ref, &refBody);
        TraceHit h;
        const bool found = bvh.intersect(ray, time, 1e-3f, 1e30f, &h, ctx);
        ASSERT_EQ(found, refFound) << "ray " << i;
        EXPECT_EQ(bvh.occluded(ray, time, 1e-3f, 1e30f, ctx), refFound) << "ray " << i;
        if (!found) continue;
        ++hits;
        EXPECT_EQ(h.t, ref.t) << "ray " << i;
        EXPECT_EQ(bvh.bodies()[h.body], refBody) << "ray " << i;
        // Shadow rays stop short of the nearest hit: nothing in between.
        EXPECT_FALSE(bvh.occluded(ray, time, 1e-3f, h.t * 0.999f, ctx)) << "ray " << i;
    }
    EXPECT_GT(hits, 2000);
    // The mailbox tests each body at most once per ray; the hierarchy tests far fewer.
    EXPECT_LT(ctx.bodyTests, uint64_t(3 * 4000) * scene.bodies.size() / 10);
}

TEST(SpacetimeBVH, NearestHitsEqualBruteForce) {
    RandomScene scene(400);
    SpacetimeBVH bvh;
    bvh.build(scene.bodies, 0, 8, Bounds3f{}, HierarchyOptions{});
    ASSERT_GT(bvh.nodeCount(), 10u);
    expectSameAsBruteForce(bvh, scene, 0, 8, 11);
}

TEST(SpacetimeBVH, GlassnersAlwaysSplitTimeRuleAgreesToo) {
    RandomScene scene(300, 2);
    HierarchyOptions o;
    o.alwaysSplitTime = true;
    SpacetimeBVH bvh;
    bvh.build(scene.bodies, 0, 8, Bounds3f{}, o);
    expectSameAsBruteForce(bvh, scene, 0, 8, 12);
}

TEST(SpacetimeBVH, FrameHierarchyCoversItsFrameOnly) {
    RandomScene scene(300, 3);
    HierarchyOptions o;
    o.splitTime = false;
    SpacetimeBVH frame;
    frame.build(scene.bodies, 5, 5.5, Bounds3f{}, o);
    expectSameAsBruteForce(frame, scene, 5, 5.5, 13);
    for (const SpacetimeBVH::Node& n : frame.nodes()) {  // every node spans at most the frame
        EXPECT_GE(n.ta, 5.0f);
        EXPECT_LE(n.tb, 5.5f);
    }
    EXPECT_LT(frame.bodies().size(), scene.bodies.size());  // bodies gone by t = 5 are left out
}

// Children lie inside their parent, siblings do not overlap in spacetime (beyond the few ulps
// of padding), and no node has a single child.
TEST(SpacetimeBVH, BoundsAreNestedClippedAndDisjoint) {
    RandomScene scene(400, 4);
    SpacetimeBVH bvh;
    bvh.build(scene.bodies, 0, 8, Bounds3f{}, HierarchyOptions{});
    const auto& nodes = bvh.nodes();
    const float pad = 1e-3f;
    int interior = 0, timeCuts = 0;
    for (const SpacetimeBVH::Node& n : nodes) {
        if (n.leaf) continue;
        ++interior;
        timeCuts += n.timeCut;
        EXPECT_GE(n.count, 2u);
        for (uint32_t i = n.first; i < n.first + n.count; ++i) {
            const SpacetimeBVH::Node& a = nodes[i];
            for (int k = 0; k < 3; ++k) {
                EXPECT_GE(a.box.lo[k], n.box.lo[k]);
                EXPECT_LE(a.box.hi[k], n.box.hi[k]);
            }
            EXPECT_GE(a.ta, n.ta);
            EXPECT_LE(a.tb, n.tb);
            if (n.timeCut) {  // the halves a ray chooses between by its time
                if (i < n.first + n.before) EXPECT_LE(a.tb, n.tSplitHi);
                else EXPECT_GE(a.ta, n.tSplitLo);
            }
            for (uint32_t j = i + 1; j < n.first + n.count; ++j) {
                const SpacetimeBVH::Node& b = nodes[j];
                bool apart = a.tb <= b.ta + 1e-5f || b.tb <= a.ta + 1e-5f;
                for (int k = 0; k < 3; ++k)
                    apart = apart || a.box.hi[k] <= b.box.lo[k] + pad || b.box.hi[k] <= a.box.lo[k] + pad;
                EXPECT_TRUE(apart) << "siblings " << i << " and " << j;
            }
        }
    }
    EXPECT_GT(interior, 5);
    EXPECT_GT(timeCuts, 0);
}

TEST(SpacetimeBVH, StillSceneIsCutInSpaceOnly) {
    // Still bodies spanning the window: cutting time cannot tighten anything, so the spacetime
    // hierarchy is the 3D one.
    std::vector<std::unique_ptr<TrilinearBody>> owned;
    std::vector<const TrilinearBody*> bodies;
    for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j) {
            const float x = float(i), y = float(j);
            Corners c{{{x, y, 10}, {x + 0.9f, y, 10}, {x, y + 0.9f, 10.5f}, {x + 0.9f, y + 0.9f, 10}}};
            owned.push_back(std::make_unique<TrilinearBody>(TimeSpan{0, 64}, c, c, std::array<Color, 4>{}, nullptr));
            bodies.push_back(owned.back().get());
        }
    HierarchyOptions space;
    space.splitTime = false;
    SpacetimeBVH st, s3, glassner;
    st.build(bodies, 0, 64, Bounds3f{}, HierarchyOptions{});
    s3.build(bodies, 0, 64, Bounds3f{}, space);
    EXPECT_EQ(st.nodeCount(), s3.nodeCount());
    EXPECT_EQ(st.leafReferences(), s3.leafReferences());
    for (const SpacetimeBVH::Node& n : st.nodes()) EXPECT_EQ(n.tb - n.ta, 64.0f);
    // Glassner's rule halves t anyway and builds more for the same tests.
    HierarchyOptions always;
    always.alwaysSplitTime = true;
    glassner.build(bodies, 0, 64, Bounds3f{}, always);
    EXPECT_GT(glassner.nodeCount(), st.nodeCount());
}

TEST(SpacetimeBVH, FastMotionIsBoundedPiecewiseInTime) {
    // A column of patches crossing 60 units in 64 frames: each cell asks them for their bound
    // during the time they can be inside it, so a ray at frame 50 where they were at frame 5
    // never tests them.
    Corners a{{{-30, -1, 10}, {-28, -1, 10}, {-30, 1, 10}, {-28, 1, 10}}}, b = a;
    for (Vec3f& p : b) p.x += 60;
    std::vector<std::unique_ptr<TrilinearBody>> owned;
    std::vector<const TrilinearBody*> bodies;
    for (int i = 0; i < 8; ++i) {
        Corners ai = a, bi = b;
        for (Vec3f& p : ai) p.y += 3 * float(i);
        for (Vec3f& p : bi) p.y += 3 * float(i);
        owned.push_back(std::make_unique<TrilinearBody>(TimeSpan{0, 64}, ai, bi, std::array<Color, 4>{}, nullptr));
        bodies.push_back(owned.back().get());
    }
    SpacetimeBVH bvh;
    HierarchyOptions o;
    o.maxLeafBodies = 1;
    bvh.build(bodies, 0, 64, Bounds3f{}, o);
    float shortest = 64;
    for (const SpacetimeBVH::Node& n : bvh.nodes()) shortest = std::min(shortest, n.tb - n.ta);
    EXPECT_LT(shortest, 16.0f);
    TraceContext ctx;
    TraceHit h;
    // At frame 50 the patches are near x = 17; a ray at x = -25 (where they were at frame 5).
    EXPECT_FALSE(bvh.intersect(Ray{{-25, 0, 0}, {0, 0, 1}}, 50, 0, 100, &h, ctx));
    EXPECT_EQ(ctx.bodyTests, 0u);
    EXPECT_TRUE(bvh.intersect(Ray{{-25, 0, 0}, {0, 0, 1}}, 4.5, 0, 100, &h, ctx));
}

// Rays lying in the planes the hierarchy cut its cells at (a child's box face, not padded) with a
// zero direction component: the nearest hits equal brute force whatever the zero's sign. With -0,
// 1/d was -inf and the slab test's 0 * inf NaN rejected both children meeting at the plane (a lit
// row through a hard sun's shadow).
TEST(SpacetimeBVH, RaysInTheCellsPlanesHitWhateverTheSignOfTheirZeroDirection) {
    RandomScene scene(400, 5);
    SpacetimeBVH bvh;
    bvh.build(scene.bodies, 0, 8, Bounds3f{}, HierarchyOptions{});
    std::vector<float> planes;  // the x faces of the nodes' boxes inside the scene
    for (const SpacetimeBVH::Node& n : bvh.nodes())
        for (const float x : {n.box.lo.x, n.box.hi.x})
            if (x > -2 && x < 2 && std::find(planes.begin(), planes.end(), x) == planes.end()) planes.push_back(x);
    ASSERT_GT(planes.size(), 4u);
    HashRng rng(21);
    auto r = [&](float a, float b) { return a + (b - a) * rng.nextFloat(); };
    TraceContext ctx;
    int hits = 0;
    for (const float x : planes) {
        for (int i = 0; i < 40; ++i) {
            const Vec3f d = normalize(Vec3f{0, r(-0.4f, 0.3f), 1});
            for (const float zero : {0.0f, -0.0f}) {
                const Ray ray{{x, r(-2, 2), r(-2, 2)}, Vec3f{zero, d.y, d.z}};
                const double time = r(0, 8);
                PatchHit ref;
                const TrilinearBody* refBody = nullptr;
                const bool refFound = bruteNearest(scene.bodies, ray, time, 1e30f, &ref, &refBody);
                TraceHit h;
                ASSERT_EQ(bvh.intersect(ray, time, 1e-3f, 1e30f, &h, ctx), refFound) << "x " << x << " zero " << zero;
                EXPECT_EQ(bvh.occluded(ray, time, 1e-3f, 1e30f, ctx), refFound) << "x " << x << " zero " << zero;
                if (refFound) {
                    ++hits;
                    EXPECT_EQ(h.t, ref.t);
                }
            }
        }
    }
    EXPECT_GT(hits, int(planes.size()) * 40);
}

TEST(SpacetimeBVH, EmptySceneMissesEverything) {
    SpacetimeBVH bvh;
    bvh.build({}, 0, 1, Bounds3f{}, HierarchyOptions{});
    TraceContext ctx;
    TraceHit h;
    EXPECT_EQ(bvh.nodeCount(), 0u);
    EXPECT_FALSE(bvh.intersect(Ray{{0, 0, 0}, {0, 0, 1}}, 0.5, 0, 100, &h, ctx));
    EXPECT_FALSE(bvh.occluded(Ray{{0, 0, 0}, {0, 0, 1}}, 0.5, 0, 100, ctx));
}

}  // namespace
}  // namespace streyes
