// Ray/bilinear-patch intersection: exact answers on planar patches, agreement with the patch
// equation on random twisted patches, grazing rays, near-degenerate patches and shared edges.
#include <gtest/gtest.h>

#include <cmath>

#include "geom/body.h"
#include "trace/ray_patch.h"
#include "util/sampling.h"

namespace streyes {
namespace {

using Corners = std::array<Vec3f, 4>;

float distance(Vec3f a, Vec3f b) { return length(a - b); }

TEST(RayPatch, PlanarSquareHitIsExact) {
    const Corners sq{{{0, 0, 5}, {4, 0, 5}, {0, 2, 5}, {4, 2, 5}}};
    PatchHit h;
    ASSERT_TRUE(intersectBilinearPatch(sq, Ray{{1, 0.5f, 0}, {0, 0, 1}}, 0, 100, &h));
    EXPECT_FLOAT_EQ(h.t, 5);
    EXPECT_FLOAT_EQ(h.u, 0.25f);
    EXPECT_FLOAT_EQ(h.v, 0.25f);
    // A slanted ray from the eye, direction with z = 1: t is the hit's depth.
    ASSERT_TRUE(intersectBilinearPatch(sq, Ray{{0, 0, 0}, {0.6f, 0.3f, 1}}, 0, 100, &h));
    EXPECT_FLOAT_EQ(h.t, 5);
    EXPECT_NEAR(h.u, 0.75f, 1e-6f);
    EXPECT_NEAR(h.v, 0.75f, 1e-6f);
    // The interval (tMin, tMax) is open at both ends and limits the hit.
    EXPECT_FALSE(intersectBilinearPatch(sq, Ray{{1, 0.5f, 0}, {0, 0, 1}}, 0, 5, &h));
    EXPECT_FALSE(intersectBilinearPatch(sq, Ray{{1, 0.5f, 0}, {0, 0, 1}}, 5, 100, &h));
    // Beside the square, and behind the origin.
    EXPECT_FALSE(intersectBilinearPatch(sq, Ray{{4.01f, 0.5f, 0}, {0, 0, 1}}, 0, 100, &h));
    EXPECT_FALSE(intersectBilinearPatch(sq, Ray{{1, 0.5f, 6}, {0, 0, 1}}, 0, 100, &h));
}

// Random twisted patches: a ray aimed at P(u0, v0) hits there, or at a nearer point of the patch.
TEST(RayPatch, RandomTwistedPatchesHitWhereAimed) {
    HashRng rng(7);
    auto r = [&](float a, float b) { return a + (b - a) * rng.nextFloat(); };
    int exact = 0;
    for (int i = 0; i < 20000; ++i) {
        Corners p;
        for (Vec3f& c : p) c = {r(-1, 1), r(-1, 1), r(-1, 1)};
        const float u0 = r(0.02f, 0.98f), v0 = r(0.02f, 0.98f);
        const Vec3f target = bilerp(p, u0, v0);
        const Vec3f o{r(-4, 4), r(-4, 4), r(-4, 4)};
        const Ray ray{o, target - o};  // t = 1 at the target
        PatchHit h;
        ASSERT_TRUE(intersectBilinearPatch(p, ray, 0, 2, &h)) << "patch " << i;
        ASSERT_LE(h.t, 1 + 1e-4f) << "patch " << i;
        const Vec3f onRay = o + ray.d * h.t, onPatch = bilerp(p, h.u, h.v);
        EXPECT_LT(distance(onRay, onPatch), 2e-4f * (1 + length(ray.d))) << "patch " << i;
        if (h.t > 1 - 1e-4f) {
            ++exact;
            EXPECT_LT(distance(onPatch, target), 2e-4f * (1 + length(ray.d))) << "patch " << i;
        }
    }
    EXPECT_GT(exact, 15000);  // most rays see their target first; the rest hit a fold in front
}

// Grazing rays: nearly in the plane of a planar patch, they must still hit where they cross it.
TEST(RayPatch, GrazingRaysHitAccurately) {
    const Corners sq{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}};
    for (float eps : {1e-1f, 1e-2f, 1e-3f, 1e-4f, 1e-5f}) {
        // Crosses z = 0 at (0.5, 0.3) after travelling 10 along x.
        const Ray ray{{0.5f - 10, 0.3f, 10 * eps}, {1, 0, -eps}};
        PatchHit h;
        ASSERT_TRUE(intersectBilinearPatch(sq, ray, 0, 100, &h)) << eps;
        EXPECT_NEAR(h.t, 10, 1e-4) << eps;
        EXPECT_NEAR(h.u, 0.5, 1e-5) << eps;
        EXPECT_NEAR(h.v, 0.3, 1e-5) << eps;
    }
    // In the plane itself: edge-on, no hit, no NaN.
    PatchHit h;
    EXPECT_FALSE(intersectBilinearPatch(sq, Ray{{-1, 0.5f, 0}, {1, 0, 0}}, 0, 100, &h));
    // A twisted patch seen almost edge-on along its mean plane still agrees with its equation.
    const Corners twisted{{{0, 0, 0}, {1, 0, 0.01f}, {0, 1, 0.01f}, {1, 1, 0}}};
    const Vec3f target = bilerp(twisted, 0.4f, 0.7f);
    const Vec3f o = target + Vec3f{-10, 0.001f, 0.002f};
    ASSERT_TRUE(intersectBilinearPatch(twisted, Ray{o, target - o}, 0, 2, &h));
    EXPECT_LT(distance(o + (target - o) * h.t, bilerp(twisted, h.u, h.v)), 1e-5f);
}

TEST(RayPatch, DegenerateAndNearDegeneratePatches) {
    PatchHit h;
    // A triangle (P3 = P2, as Polygon makes them): hits inside, misses the other half of the square.
    const Corners tri{{{0, 0, 5}, {1, 0, 5}, {0, 1, 5}, {0, 1, 5}}};
    EXPECT_TRUE(intersectBilinearPatch(tri, Ray{{0.2f, 0.2f, 0}, {0, 0, 1}}, 0, 100, &h));
    EXPECT_FLOAT_EQ(h.t, 5);
    EXPECT_FALSE(intersectBilinearPatch(tri, Ray{{0.8f, 0.8f, 0}, {0, 0, 1}}, 0, 100, &h));
    // A sliver 1e-4 wide: hit inside it, missed beside it.
    const Corners sliver{{{0, 0, 5}, {1e-4f, 0, 5}, {0, 10, 5}, {1e-4f, 10, 5}}};
    EXPECT_TRUE(intersectBilinearPatch(sliver, Ray{{5e-5f, 3, 0}, {0, 0, 1}}, 0, 100, &h));
    EXPECT_NEAR(h.u, 0.5f, 1e-3f);
    EXPECT_NEAR(h.v, 0.3f, 1e-6f);
    EXPECT_FALSE(intersectBilinearPatch(sliver, Ray{{3e-4f, 3, 0}, {0, 0, 1}}, 0, 100, &h));
    // Zero area: all corners in one point, or on one line.
    const Corners point{{{1, 1, 5}, {1, 1, 5}, {1, 1, 5}, {1, 1, 5}}};
    EXPECT_FALSE(intersectBilinearPatch(point, Ray{{1, 1, 0}, {0, 0, 1}}, 0, 100, &h));
    const Corners line{{{0, 0, 5}, {1, 0, 5}, {0, 0, 5}, {1, 0, 5}}};
    EXPECT_FALSE(intersectBilinearPatch(line, Ray{{0.5f, 0, 0}, {0, 0, 1}}, 0, 100, &h));
}

// Two halves of a twisted patch share their edge bit for bit: no ray slips between them.
TEST(RayPatch, SharedEdgesAreWatertight) {
    const TrilinearBody::Corners c{{{-1, -1, 4}, {1, -1, 5}, {-1, 1, 5.5f}, {1, 1, 4}}};
    TrilinearBody body({0, 0}, c, c, {}, nullptr);
    BodyPtr halves[2];
    body.split(SplitAxis::U, halves);
    const auto& a = static_cast<const TrilinearBody&>(*halves[0]).corners(0);
    const auto& b = static_cast<const TrilinearBody&>(*halves[1]).corners(0);
    int misses = 0;
    HashRng rng(3);
    for (int i = 0; i < 20000; ++i) {
        // Points on the shared edge u = 1/2 of the whole patch, seen from the eye.
        const Vec3f target = bilerp(c, 0.5f, rng.nextFloat());
        const Ray ray{{0, 0, 0}, target * (1.0f / target.z)};
        PatchHit h;
        if (!intersectBilinearPatch(a, ray, 0, 100, &h) && !intersectBilinearPatch(b, ray, 0, 100, &h)) ++misses;
    }
    EXPECT_EQ(misses, 0);
}

}  // namespace
}  // namespace streyes
