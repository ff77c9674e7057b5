#include "trace/ray_patch.h"

#include <cmath>

namespace streyes {

namespace {
// How far outside [0, 1] a parameter may fall and still count: pieces of one patch share their
// edges bit for bit, and a ray through a shared edge must hit at least one of them.
constexpr double kParamSlack = 1e-6;
// Relative size of the rounding errors in the quadratic's coefficients (float input).
constexpr double kTangentSlack = 1e-6;
}  // namespace

// Write P(u, v) = A(u) + v E(u) with A(u) = lerp(p00, p10, u) the v = 0 edge and
// E(u) = lerp(p01 - p00, p11 - p10, u). The ray o + t d meets the line A(u) + v E(u) when
// g(u) = det[A(u) - o, E(u), d] = 0, a quadratic a u^2 + b u + c. Its coefficients:
//   c = g(0) = det[p00 - o, p01 - p00, d],   a + b + c = g(1) = det[p10 - o, p11 - p10, d],
//   a = det[p10 - p00, (p11 - p10) - (p01 - p00), d] = det[p10 - p00, p11 - p01, d],
// a from edges only: exactly 0 for a parallelogram, whatever the ray.
bool intersectBilinearPatch(const std::array<Vec3f, 4>& pf, const Ray& ray, float tMin, float tMax, PatchHit* hit) {
    const Vec3d o(ray.o), d(ray.d);
    const Vec3d p00(pf[0]), p10(pf[1]), p01(pf[2]), p11(pf[3]);
    const Vec3d q00 = p00 - o, q10 = p10 - o;
    const Vec3d e0 = p01 - p00, e1 = p11 - p10;
    const double a = dot(cross(p10 - p00, p11 - p01), d);
    const double c = dot(cross(q00, e0), d);
    const double b = dot(cross(q10, e1), d) - a - c;

    // Roots without cancellation: q = -(b + sign(b) sqrt(disc)) / 2, u = c / q and q / a. A ray
    // tangent to the patch along a v-line has a double root; float corners put disc a rounding
    // error either side of 0, and a hair below counts as the tangent it is.
    double disc = b * b - 4 * a * c;
    if (disc < 0) {
        // g's rounding error: that of the products it is made of, scaled by float's precision.
        const double gError = kTangentSlack * length(d) * (length(q00) * length(e0) + length(q10) * length(e1));
        if (disc > -8 * gError * (std::fabs(a) + std::fabs(b) + std::fabs(c))) disc = 0;
    }
    if (!(disc >= 0)) return false;  // also NaN
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    double roots[2];
    int n = 0;
    if (q != 0) {
        roots[n++] = c / q;
        if (a != 0) roots[n++] = q / a;
    } else if (a != 0) {
        roots[n++] = 0;  // b = 0 and c = 0: a double root at u = 0
    }                     // else g is identically 0: the ray lies in the patch's plane (edge-on)

    bool found = false;
    double best = tMax;
    for (int i = 0; i < n; ++i) {
        const double u = roots[i];
        if (!(u >= -kParamSlack && u <= 1 + kParamSlack)) continue;
        // Solve o + t d = A(u) + v E(u) on the plane the two lines share: with n = d x E,
        // t = det[A - o, E, n] / |n|^2 and v = det[A - o, d, n] / |n|^2.
        const Vec3d qa = lerp(q00, q10, u), e = lerp(e0, e1, u);
        const Vec3d nrm = cross(d, e);
        const double n2 = dot(nrm, nrm);
        if (!(n2 > 0)) continue;  // the ray runs parallel to this v-line
        const double t = dot(cross(qa, e), nrm) / n2;
        const double v = dot(cross(qa, d), nrm) / n2;
        if (!(v >= -kParamSlack && v <= 1 + kParamSlack)) continue;
        if (!(t > double(tMin) && t < best)) continue;
        best = t;
        hit->t = float(t);
        hit->u = float(std::min(1.0, std::max(0.0, u)));
        hit->v = float(std::min(1.0, std::max(0.0, v)));
        found = true;
    }
    return found;
}

}  // namespace streyes
