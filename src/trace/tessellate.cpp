#include "trace/tessellate.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "bodies/material.h"
#include "shade/vm/shader_instance.h"

namespace streyes {

bool displacementReadsTime(const Material& m) {
    return m.displacement && m.displacement->program().globalReg[size_t(sl::Global::time)] >= 0;
}

bool Tessellator::tessellate(const Body& body, std::deque<TrilinearBody>& out) {
    // A counting pass first, which stops at the cap: a body reaching the near plane can measure
    // in millions of pixels. Past the cap the body is left out; it cannot be diced coarser than
    // the split loop does, since a curved body's edges follow lattices made at its own rate.
    count_ = 0;
    out_ = nullptr;
    process(body, 0, 0);
    if (count_ > kMaxMicropolygonsPerBody) return false;  // the caller says what it does instead
    dropped_ = behind_ = false;
    out_ = &out;
    process(body, 0, 0);
    out_ = nullptr;
    if (dropped_)
        log_.warnOnce("trace:splitlimit", body.source() ? *body.source() : SourceLoc{},
                      "a surface is still too large to dice for the ray tracer after " +
                          std::to_string(options_.maxSplitDepth) + " splits (degenerate or huge geometry): dropped");
    if (behind_)
        log_.warnOnce("trace:behind", body.source() ? *body.source() : SourceLoc{},
                      "curved surfaces behind the camera (behind half the near clipping distance) are left out of "
                      "ray tracing: they cast no shadows");
    return true;
}

void Tessellator::process(const Body& body, int depth, int eyeDepth) {
    if (!out_ && count_ > kMaxMicropolygonsPerBody) return;  // counted enough
    if (!body.diceableInTime()) {  // more motion keys: cut at the middle one (not for roots: see TraceScene)
        split(body, SplitAxis::T, depth, eyeDepth);
        return;
    }
    const Bounds3f swept = body.bound().swept();
    const Camera& cam = cameras_.during(body.time().t0, body.time().t1);
    if (cam.perspective() && !(swept.lo.z >= cam.eyePlane())) {
        // Cannot be projected, so cannot be measured or diced (a curved body's lattices are made
        // in raster space): split across the eye plane as the split loop does, a few times, and
        // leave out what lies behind it.
        if (eyeDepth >= kMaxEyeSplits || !(swept.hi.z >= cam.eyePlane())) {
            behind_ = true;
            return;
        }
        const CameraExtents e = body.cameraExtents();
        SplitAxis axis = e.u >= e.v ? SplitAxis::U : SplitAxis::V;
        if (body.moving() && e.t > std::max(e.u, e.v)) axis = SplitAxis::T;
        split(body, axis, depth, eyeDepth + 1);
        return;
    }
    // The split loop's rule (decideSplit).
    const RasterMeasure m = body.measure(cam);
    const float side = std::sqrt(std::max(dicingRate(body, m, exposure_), 1e-4f));
    const float size = std::max(m.extentU, m.extentV);
    SplitAxis axis;
    if (body.moving() && m.motion > std::max(options_.timeSplitRatio * size, options_.timeSplitMinMotion)) {
        axis = SplitAxis::T;
    } else {
        const double nu = std::max(1.0, std::ceil(double(m.extentU) / side));
        const double nv = std::max(1.0, std::ceil(double(m.extentV) / side));
        if (nu * nv <= double(options_.maxGridSize > 0 ? options_.maxGridSize : kDefaultGridSize)) {
            dice(body, int(nu), int(nv));
            return;
        }
        axis = m.extentU >= m.extentV ? SplitAxis::U : SplitAxis::V;
    }
    split(body, axis, depth + 1, eyeDepth);
}

void Tessellator::split(const Body& body, SplitAxis axis, int depth, int eyeDepth) {
    if (depth > options_.maxSplitDepth) {
        dropped_ = true;
        return;
    }
    BodyPtr halves[2];
    body.split(axis, halves);
    if (axis != SplitAxis::T) {  // halves of the parameter rectangle, as BucketWorker::split keeps them
        const size_t lo = axis == SplitAxis::U ? 0 : 2;
        const float mid = 0.5f * (body.uv[lo] + body.uv[lo + 1]);
        halves[0]->uv[lo + 1] = mid;
        halves[1]->uv[lo] = mid;
    }
    for (BodyPtr& h : halves) process(*h, depth, eyeDepth);
}

// One TrilinearBody per micropolygon not trimmed away: its corners at the grid's t0 and t1,
// its colours, its share of the body's parameter rectangle (u, v and s, t at hits).
void Tessellator::dice(const Body& body, int nu, int nv) {
    if (!out_) {
        count_ += size_t(nu) * size_t(nv);
        return;
    }
    body.dice(nu, nv, grid_);
    nu = grid_.nu;  // a curved body may dice finer (its sides' lattices), or one cut quad where trimmed away
    nv = grid_.nv;
    const Material* m = body.material();
    if (displacer_ && m && m->displacement) {
        // As BucketWorker::diceShade prepares a grid for its shaders: normals turned to the
        // side Orientation calls outside, and a still grid whose displacement reads time
        // displaced at both ends of its span.
        grid_.shadowSlots = 0;
        grid_.aovCount = 0;
        for (int k = 0; k < (grid_.moving ? 2 : 1); ++k)
            if (m->flipNormals)
                for (Vec3f& n : grid_.N[k]) n = -n;
        if (!grid_.moving && grid_.t1 > grid_.t0 && displacementReadsTime(*m)) {
            grid_.resize(grid_.nu, grid_.nv, true);
            grid_.P[1] = grid_.P[0];
            grid_.N[1] = grid_.N[0];
        }
        displacer_->displaceOnly(grid_);
    }
    const TimeSpan span{grid_.t0, grid_.t1, grid_.openEnd};
    const bool flat = body.material() && !body.material()->smoothShading;
    const std::vector<Vec3f>& P0 = grid_.P[0];
    const std::vector<Vec3f>& P1 = grid_.moving ? grid_.P[1] : grid_.P[0];
    const float du = (grid_.u1 - grid_.u0) / float(nu), dv = (grid_.v1 - grid_.v0) / float(nv);
    const size_t vertices = size_t(grid_.vertexCount());
    const bool placed = grid_.paramU.size() == vertices && grid_.paramV.size() == vertices;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            if (!grid_.hole.empty() && grid_.hole[size_t(j * nu + i)]) continue;
            const size_t idx[4] = {size_t(grid_.index(i, j)), size_t(grid_.index(i + 1, j)),
                                   size_t(grid_.index(i, j + 1)), size_t(grid_.index(i + 1, j + 1))};
            TrilinearBody::Corners c0, c1;
            std::array<Color, 4> cs;
            bool finite = true;
            for (size_t k = 0; k < 4; ++k) {
                c0[k] = P0[idx[k]];
                c1[k] = P1[idx[k]];
                cs[k] = grid_.Cs[flat ? idx[0] : idx[k]];
                finite = finite && isFinite(c0[k]) && isFinite(c1[k]);
            }
            if (!finite) continue;
            TrilinearBody& mp = out_->emplace_back(span, c0, c1, cs, body.material());
            mp.inheritFrom(body);
            mp.uv = {grid_.u0 + du * float(i), grid_.u0 + du * float(i + 1), grid_.v0 + dv * float(j),
                     grid_.v0 + dv * float(j + 1)};
            if (placed) {  // a curved body's sides: the rectangle nearest its corners' own parameters
                const float* pu = grid_.paramU.data();
                const float* pv = grid_.paramV.data();
                const float su = grid_.u1 - grid_.u0, sv = grid_.v1 - grid_.v0;
                mp.uv = {grid_.u0 + su * 0.5f * (pu[idx[0]] + pu[idx[2]]), grid_.u0 + su * 0.5f * (pu[idx[1]] + pu[idx[3]]),
                         grid_.v0 + sv * 0.5f * (pv[idx[0]] + pv[idx[1]]), grid_.v0 + sv * 0.5f * (pv[idx[2]] + pv[idx[3]])};
            }
        }
}

}  // namespace streyes
