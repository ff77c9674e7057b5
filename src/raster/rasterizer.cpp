#include "raster/rasterizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "geom/grid.h"
namespace streyes {

// ---- Projection ----------------------------------------------------------------------------------

void GridRasterizer::project(const Grid& grid, double t, const Camera& camera, std::vector<RasterVertex>& out,
                             std::vector<Vec3f>* cameraOut) const {
    const size_t n = size_t(grid.vertexCount());
    out.resize(n);
    if (cameraOut) cameraOut->resize(n);
    float s = 0;
    if (grid.moving && grid.t1 > grid.t0) {
        s = float((t - grid.t0) / (grid.t1 - grid.t0));
        if (t <= grid.t0) s = 0;
        if (t >= grid.t1) s = 1;
    }
    for (size_t i = 0; i < n; ++i) {
        Vec3f p = grid.moving ? lerp(grid.P[0][i], grid.P[1][i], s) : grid.P[0][i];
        Vec3f r = camera.toRaster(p);
        out[i] = {r.x, r.y, r.z};
        if (cameraOut) (*cameraOut)[i] = p;
    }
}

// ---- Time --------------------------------------------------------------------------------------------
// A frame's samples lie in [e0, e1) = [f + open, f + close), or at e0 when the shutter is closed.
// A grid's span is [t0, t1], or [t0, t1) when another piece of the surface continues at t1
// (grid.openEnd): pieces that meet at a time share no sample, and leave none out.

namespace {

// Does the grid exist at some sample time of the exposure [e0, e1) (at e0 when d == 0)?
bool meetsExposure(const Grid& grid, double e0, double e1, double d) {
    const bool fromStart = e0 < grid.t1 || (e0 == grid.t1 && !grid.openEnd);  // still there at e0
    return d > 0 ? grid.t0 < e1 && fromStart : grid.t0 <= e0 && fromStart;
}

}  // namespace

void GridRasterizer::collectSlices(const Grid& grid, const Shutter& shutter, const ImageBlock& block) {
    slices_.clear();
    const double d = shutter.close - shutter.open;
    const int K = block.samplesPerPixel();
    for (int fi = 0; fi < block.frameCount(); ++fi) {
        const double e0 = block.firstFrame() + fi + shutter.open, e1 = e0 + d;
        if (!meetsExposure(grid, e0, e1, d)) continue;
        for (int k = 0; k < K; ++k) {
            // Slice k of this frame's exposure, [sa, sb), clipped to the grid's time span.
            const double sa = d > 0 ? e0 + d * k / K : e0;
            const double sb = d > 0 ? e0 + d * (k + 1) / K : e0;
            const double ta = std::max(sa, grid.t0), tb = std::min(sb, grid.t1);
            const bool endsInside = d > 0 && grid.t1 < sb;  // the grid's end, not the slice's, closes it
            if (d > 0 && (ta > tb || (ta == tb && (!endsInside || grid.openEnd)))) continue;
            Slice s;
            s.fi = fi;
            s.k = k;
            s.ta = ta;
            s.tb = tb;
            s.checkTime = d > 0 && (ta > sa || tb < sb);
            s.openB = endsInside && grid.openEnd;
            s.tfA = s.checkTime ? float((ta - e0) / d) : float(k) / float(K);
            s.tfB = s.checkTime ? float((tb - e0) / d) : float(k + 1) / float(K);
            slices_.push_back(s);
        }
    }
}

// ---- Sampling --------------------------------------------------------------------------------------

namespace {
// Calls f with std::true_type or std::false_type as `flag` is: a run-time flag to a template one.
template <typename F>
void withFlag(bool flag, F&& f) {
    if (flag) f(std::true_type{});
    else f(std::false_type{});
}
}  // namespace

void GridRasterizer::rasterize(const Grid& grid, const Camera& camera, const Shutter& shutter, ImageBlock& block,
                               RasterCounters& counters) {
    counters.micropolygons += uint64_t(grid.nu) * uint64_t(grid.nv);
    if (grid.moving) collectSlices(grid, shutter, block);
    else collectFrames(grid, shutter, block);
    if (grid.moving ? slices_.empty() : frames_.empty()) return;
    // Sample times, in the frames where they decide (a grid over part of an exposure, or moving).
    // Permutations too where a level of detail dissolves (dissolveKeeps).
    if (grid.moving) {
        for (const Slice& sl : slices_) block.needTimes(sl.fi);
    } else {
        for (const FrameSpan& fr : frames_)
            if (!fr.whole || grid.dissolves()) block.needTimes(fr.fi);
    }
    const bool lens = block.hasLens() && camera.depthOfField();
    // One instance per combination of the three flags: scenes without shadows, counting or a lens
    // pay nothing for them.
    withFlag(grid.shadowSlots > 0, [&](auto shadowed) {
        withFlag(hitCounts_ != nullptr, [&](auto counting) {
            withFlag(lens, [&](auto withLens) {
                sample<decltype(shadowed)::value, decltype(counting)::value, decltype(withLens)::value>(grid, camera, block,
                                                                                                      counters);
            });
        });
    });
}

template <bool Shadowed, bool Counting, bool Lens>
void GridRasterizer::sample(const Grid& grid, const Camera& camera, ImageBlock& block, RasterCounters& counters) {
    if (grid.moving) sampleMoving<Shadowed, Counting, Lens>(grid, camera, block, counters);
    else sampleStill<Shadowed, Counting, Lens>(grid, camera, block, counters);
}

// The frames a still grid exists in, and the part of each exposure it covers.
void GridRasterizer::collectFrames(const Grid& grid, const Shutter& shutter, const ImageBlock& block) {
    frames_.clear();
    const double d = shutter.close - shutter.open;
    for (int fi = 0; fi < block.frameCount(); ++fi) {
        const double e0 = block.firstFrame() + fi + shutter.open, e1 = e0 + d;
        if (!meetsExposure(grid, e0, e1, d)) continue;
        FrameSpan f;
        f.fi = fi;
        f.whole = d == 0 || (grid.t0 <= e0 && grid.t1 >= e1);
        f.openB = grid.openEnd;
        f.tfA = f.whole ? 0.0f : float((std::max(grid.t0, e0) - e0) / d);
        f.tfB = f.whole ? 1.0f : float((std::min(grid.t1, e1) - e0) / d);
        frames_.push_back(f);
    }
}

// The eight instances are made beside their samplers (still_sampler.cpp, moving_sampler.cpp).

}  // namespace streyes
