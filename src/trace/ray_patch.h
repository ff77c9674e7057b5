// Rays and the exact ray/bilinear-patch intersection.
//
// The ray tracer intersects the patches themselves, not micropolygons: a trilinear body at time
// t is a bilinear patch P(u, v) = lerp(lerp(p0, p1, u), lerp(p2, p3, u), v) (corners in
// RenderMan order). The intersection follows the idea of Reshetov's "Cool Patches" (Ray Tracing
// Gems, 2019): the ray meets the segment from P(u, 0) to P(u, 1) exactly when that segment's line
// and the ray are coplanar, which is a quadratic in u; v and the ray parameter follow from the
// two lines. The quadratic's leading coefficient is computed from the patch's edges alone (not
// from differences of positions relative to the ray origin), which keeps near-planar patches and
// grazing rays accurate; everything runs in double.
#pragma once

#include <array>

#include "streyes/vecmath.h"

namespace streyes {

// Points o + t d. d need not be unit length; t is in units of d.
struct Ray {
    Vec3f o, d;
};

struct PatchHit {
    float t = 0;     // ray parameter
    float u = 0, v = 0;  // patch parameters in [0, 1]
};

// The nearest intersection with tMin < t < tMax of the ray and the bilinear patch with corners
// p (p[0] = (0,0), p[1] = (1,0), p[2] = (0,1), p[3] = (1,1)). Zero-area patches and rays lying
// in the plane of a planar patch are missed. Hits on an edge shared by two patches are found in
// both (u and v are accepted a hair outside [0, 1] and clamped), so rays never slip through.
bool intersectBilinearPatch(const std::array<Vec3f, 4>& p, const Ray& ray, float tMin, float tMax, PatchHit* hit);

}  // namespace streyes
