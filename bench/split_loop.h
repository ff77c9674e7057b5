// The bucket's recursion without culling or sampling: a body is split as the renderer's split
// loop decides (decideSplit, render/split_decision.h: the same function bucket.cpp calls) until
// every piece would be diced; the pieces are counted, not diced. Shared by the split-loop kernels.
#pragma once

#include <cstdint>
#include <vector>

#include "geom/body.h"
#include "render/split_decision.h"

namespace streyes {

// `exposure`: the shutter's length in frames (for GeometricApproximation "motionfactor").
inline void splitToGrids(const Body& root, const Camera& camera, const RenderOptions& options, double exposure,
                         std::vector<BodyPtr>& stack, uint64_t& splits, uint64_t& grids) {
    stack.clear();
    stack.push_back(root.restrictedTo(root.time().t0, root.time().t1));
    while (!stack.empty()) {
        BodyPtr b = std::move(stack.back());
        stack.pop_back();
        const SplitDecision d = decideSplit(*b, b->measure(camera), options, exposure);
        if (d.dice) {
            ++grids;
            continue;
        }
        BodyPtr h[2];
        b->split(d.axis, h);
        stack.push_back(std::move(h[1]));  // as in the bucket: the first half is processed next
        stack.push_back(std::move(h[0]));
        ++splits;
    }
}

}  // namespace streyes
