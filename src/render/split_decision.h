// The split loop's choice for a body that lies in front of the eye plane and survived culling:
// dice it into nu x nv micropolygons, or split it along u, v or t. Inline, so that the bucket's
// hot loop (bucket.cpp) pays no call for it; the benchmarks and tests that rebuild the loop's
// recursion (bench/split_loop.h, tests/core/curved_render_test.cpp) ask the same function, so
// they split and dice as the renderer does.
#pragma once

#include <algorithm>
#include <cmath>

#include "bodies/material.h"
#include "geom/body.h"
#include "streyes/render_options.h"

namespace streyes {

struct SplitDecision {
    bool dice = false;
    int nu = 0, nv = 0;             // micropolygons, when dicing
    SplitAxis axis = SplitAxis::U;  // when splitting
};

inline SplitDecision decideSplit(const Body& body, const RasterMeasure& m, const RenderOptions& options,
                                 double exposure) {
    const float side = std::sqrt(std::max(dicingRate(body, m, exposure), 1e-4f));
    const float size = std::max(m.extentU, m.extentV);
    SplitDecision d;
    if (!body.diceableInTime() && !body.dicesAtKeys()) {
        d.axis = SplitAxis::T;  // more than two motion keys: cut at a key first
    } else if (body.moving() && m.motion > std::max(options.timeSplitRatio * size, options.timeSplitMinMotion)) {
        d.axis = SplitAxis::T;  // only when asked (timeSplitMinMotion is off by default): cut its span
    } else {
        const double nu = std::max(1.0, std::ceil(double(m.extentU) / side));
        const double nv = std::max(1.0, std::ceil(double(m.extentV) / side));
        if (nu * nv <= double(options.maxGridSize > 0 ? options.maxGridSize : kDefaultGridSize)) {
            d.dice = true;
            d.nu = int(nu);
            d.nv = int(nv);
        } else {
            d.axis = m.extentU >= m.extentV ? SplitAxis::U : SplitAxis::V;
        }
    }
    return d;
}

}  // namespace streyes
