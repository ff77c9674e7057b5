// The split loop's decision and recursion (as in the bucket), without culling or sampling:
// splits a body until each piece dices to at most 256 micropolygons at shading rate 1. Shared by
// the split-loop kernels.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "geom/body.h"

namespace streyes {

inline void splitToGrids(const Body& root, const Camera& camera, std::vector<BodyPtr>& stack, uint64_t& splits,
                         uint64_t& grids) {
    stack.clear();
    stack.push_back(root.restrictedTo(root.time().t0, root.time().t1));
    while (!stack.empty()) {
        BodyPtr b = std::move(stack.back());
        stack.pop_back();
        const RasterMeasure m = b->measure(camera);
        const double nu = std::max(1.0, std::ceil(double(m.extentU))), nv = std::max(1.0, std::ceil(double(m.extentV)));
        if (nu * nv <= 256) {
            ++grids;
            continue;
        }
        BodyPtr h[2];
        b->split(m.extentU >= m.extentV ? SplitAxis::U : SplitAxis::V, h);
        stack.push_back(std::move(h[1]));
        stack.push_back(std::move(h[0]));
        ++splits;
    }
}

}  // namespace streyes
