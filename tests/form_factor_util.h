// Lambert's form factor, the closed form the ambient-occlusion tests (ray-traced and point-based)
// hold their results to.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace streyes::test {

// From a point p of a plane with normal +z to a polygon: the cosine-weighted share of the
// hemisphere it covers, 1/(2 pi) times the sum over its edges of each edge's angle at p times the
// z of the unit normal of the plane through p and the edge.
inline double lambertFormFactor(const std::array<double, 3>& p, const std::vector<std::array<double, 3>>& poly) {
    double sum = 0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const auto& a = poly[i];
        const auto& b = poly[(i + 1) % poly.size()];
        const double r0[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]}, r1[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
        const double c[3] = {r0[1] * r1[2] - r0[2] * r1[1], r0[2] * r1[0] - r0[0] * r1[2], r0[0] * r1[1] - r0[1] * r1[0]};
        const double cl = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (cl == 0) continue;
        const double l0 = std::sqrt(r0[0] * r0[0] + r0[1] * r0[1] + r0[2] * r0[2]);
        const double l1 = std::sqrt(r1[0] * r1[0] + r1[1] * r1[1] + r1[2] * r1[2]);
        const double angle = std::acos(std::clamp((r0[0] * r1[0] + r0[1] * r1[1] + r0[2] * r1[2]) / (l0 * l1), -1.0, 1.0));
        sum += angle * c[2] / cl;
    }
    return std::fabs(sum) / (2 * M_PI);
}

}  // namespace streyes::test
