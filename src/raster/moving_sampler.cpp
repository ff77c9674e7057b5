// The moving sampler: GridRasterizer::sampleMoving (rasterizer.h).
#include "raster/rasterizer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geom/grid.h"
#include "raster/micropolygon.h"
#include "raster/sample_kernels.h"
#include "raster/sampler_common.h"

namespace streyes {

using namespace micropolygon;
using namespace sampler;

// A moving grid: projected at both ends of each slice to bound its quads over the slice; a
// sample's quad is the quad at the sample's time. Orthographic projection is linear, so that is
// the raster quad interpolated linearly. Perspective is not: interpolating raster positions would
// move a vertex that lies on a neighbouring grid's edge (a T-junction, where grids split to
// different depths meet) off that edge, and open cracks between the grids. So under perspective
// the corners are interpolated in camera space, where they move linearly, and projected at the
// sample's time: vertices on a straight edge stay on its projection. That is needed only on the
// grid's border, where another grid's vertices may lie on its edges, and where the projection
// bends a vertex's path: elsewhere (inside the grid, moving at nearly constant depth) a vertex's
// raster position is interpolated linearly within the slice, the same for every quad that shares
// it, so no crack opens. Hits go to the frames' records: what moves is seen by one frame only.
template <bool Shadowed, bool Counting, bool Lens>
void GridRasterizer::sampleMoving(const Grid& grid, const Camera& camera, ImageBlock& block,
                                  RasterCounters& counters) {
    const PixelRect& R = block.rect();
    const int nu = grid.nu, nv = grid.nv, stride = nu + 1, S = block.samplesPerPixel();
    const uint8_t* hole = grid.hole.empty() ? nullptr : grid.hole.data();
    const size_t pixels = size_t(block.pixelCount());
    const PatternTable& patterns = block.patterns();
    const bool perspective = camera.perspective();
    const float nearZ = camera.nearClip(), farZ = camera.farClip();
    const double span = grid.t1 - grid.t0;
    const Color *ci0 = grid.Ci[0].data(), *ci1 = grid.Ci[1].data();
    const bool flat = grid.flatShading;  // ShadingInterpolation "constant": the first corner's colour
    const int K = grid.shadowSlots;
    const Color *cl0 = grid.Cl[0].data(), *cl1 = grid.Cl[1].data();
    const int A = grid.aovCount;
    const float *av0 = grid.aov[0].data(), *av1 = grid.aov[1].data();
    const uint64_t id = grid.primitiveId;
    const Color *oi0 = opacities(grid, 0), *oi1 = opacities(grid, 1);
    const bool anySeeThrough = oi0 || oi1;
    const Color kOpaque{1, 1, 1};
    const float* xs = block.xs();
    const float* ys = block.ys();
    const float *lus = block.lus(), *lvs = block.lvs();
    const InBoxFn inBoxes = inBoxKernel();
    constexpr size_t kMaskSlices = 4;  // groups of this many slices find their samples by SIMD
    candidates_.resize(size_t(S));

    // Slices are bounded in groups: a quad's bound over a group's time holds every sample of it
    // that could hit, and a slow grid needs no finer bound than a few slices give. As many slices a
    // group as keep the grid's largest raster motion over a group under kGroupMotion pixels.
    constexpr float kGroupMotion = 0.5f;
    project(grid, grid.t0, camera, ra_);
    project(grid, grid.t1, camera, rb_);
    float motion = 0;
    for (size_t v = 0; v < ra_.size(); ++v)
        motion = std::max({motion, std::fabs(rb_[v].x - ra_[v].x), std::fabs(rb_[v].y - ra_[v].y)});
    double sliceTime = 0;  // the longest slice, as a share of the grid's span
    for (const Slice& sl : slices_) sliceTime = std::max(sliceTime, (sl.tb - sl.ta) / span);
    const double perSlice = double(motion) * sliceTime;
    const size_t group = perSlice > 0 ? size_t(std::clamp(double(kGroupMotion) / perSlice, 1.0, double(S))) : size_t(S);

    double projected = std::numeric_limits<double>::quiet_NaN();  // the time rb_ holds
    uint64_t tests = 0, hits = 0, firstHits = 0, behind = 0, fragments = 0, gridsBehind = 0;
    for (size_t s0 = 0; s0 < slices_.size();) {
        size_t s1 = s0 + 1;  // the group: consecutive slices of one frame
        while (s1 < slices_.size() && s1 - s0 < group && slices_[s1].fi == slices_[s0].fi &&
               slices_[s1].k == slices_[s1 - 1].k + 1)
            ++s1;
        const Slice &first = slices_[s0], &last = slices_[s1 - 1];
        const int fi = first.fi;
        if (projected == first.ta) {  // the last group ended where this one starts
            std::swap(ra_, rb_);
            std::swap(ca_, cb_);
        } else {
            project(grid, first.ta, camera, ra_, perspective ? &ca_ : nullptr);
        }
        project(grid, last.tb, camera, rb_, perspective ? &cb_ : nullptr);
        projected = last.tb;
        const float sA = float((first.ta - grid.t0) / span), sB = float((last.tb - grid.t0) / span);
        const float tfA = first.tfA, invSpan = last.tfB > first.tfA ? 1.0f / (last.tfB - first.tfA) : 0.0f;
        if (perspective) {
            // A vertex moving linearly in camera space leaves the straight raster segment between
            // its group's ends by at most 1/4 |raster motion| |dz| / min z. Where that is below
            // kLinearError it is interpolated in raster space; on the grid's border (where other
            // grids' vertices may sit on its edges) and elsewhere it is projected exactly.
            constexpr float kLinearError = 1e-5f;
            exact_.resize(ra_.size());
            for (int vj = 0; vj <= nv; ++vj)
                for (int vi = 0; vi <= nu; ++vi) {
                    const size_t v = size_t(vj * stride + vi);
                    const RasterVertex &a = ra_[v], &b = rb_[v];
                    const bool border = vi == 0 || vj == 0 || vi == nu || vj == nv;
                    const float move = std::max(std::fabs(b.x - a.x), std::fabs(b.y - a.y));
                    const float error = 0.25f * move * std::fabs(b.z - a.z) / std::min(a.z, b.z);
                    exact_[v] = border || !(error < kLinearError);
                }
        }
        // The whole grid over the group, against the block: most of a grid's groups lie in it, but a
        // grid crossing bucket borders meets some of them in none of its frames' time.
        Bounds3f groupBound;
        for (size_t v = 0; v < ra_.size(); ++v) {
            groupBound.extend(Vec3f{ra_[v].x, ra_[v].y, ra_[v].z});
            groupBound.extend(Vec3f{rb_[v].x, rb_[v].y, rb_[v].z});
        }
        if constexpr (Lens) {  // what the lens blurs reaches the block a circle of confusion away
            const Vec2f m = lensMargin<Lens>(camera)(groupBound.lo.z, groupBound.hi.z);
            groupBound.lo.x -= m.x, groupBound.hi.x += m.x;
            groupBound.lo.y -= m.y, groupBound.hi.y += m.y;
        }
        if (!(groupBound.hi.x >= float(R.x0) && groupBound.lo.x < float(R.x1 + 1) && groupBound.hi.y >= float(R.y0) &&
              groupBound.lo.y < float(R.y1 + 1))) {
            s0 = s1;
            continue;
        }
        // The same for the whole grid: every pixel its bound over the group reaches already sees,
        // in every sample, something nearer than all of it. None of its quads could change a
        // sample there (each quad's bound and depth lie within the grid's), so none is visited.
        // Without a lens only: a lens grows each quad's bound by its circle of confusion.
        if (!Counting && !Lens) {
            const int x0 = floorClamped(groupBound.lo.x, R.x0, R.x1), x1 = floorClamped(groupBound.hi.x, R.x0, R.x1);
            const int y0 = floorClamped(groupBound.lo.y, R.y0, R.y1), y1 = floorClamped(groupBound.hi.y, R.y0, R.y1);
            bool hidden = true;
            for (int py = y0; py <= y1 && hidden; ++py)
                for (int px = x0; px <= x1 && hidden; ++px)
                    hidden = pixelBehind(block, fi, block.pixelIndex(px, py), groupBound.lo.z, S);
            if (hidden) {
                ++gridsBehind;
                s0 = s1;
                continue;
            }
        }
        for (int j = 0; j < nv; ++j) {
            for (int i = 0; i < nu; ++i) {
                if (hole && hole[j * nu + i]) continue;  // trimmed away
                const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
                const QuadOpacity opacity =
                    anySeeThrough ? quadOpacity(oi0, oi1, ci0, ci1, idx) : QuadOpacity::Opaque;
                if (!Counting && opacity == QuadOpacity::Clear) continue;
                const bool seeThrough = opacity != QuadOpacity::Opaque;
                QuadSetup q;
                float xb[4], yb[4], zb[4];
                for (int c = 0; c < 4; ++c) {
                    const RasterVertex &a = ra_[size_t(idx[c])], &b = rb_[size_t(idx[c])];
                    q.x[c] = a.x, q.y[c] = a.y, q.z[c] = a.z;
                    xb[c] = b.x, yb[c] = b.y, zb[c] = b.z;
                }
                if (!boundQuad(q, xb, yb, zb, R, nearZ, farZ, lensMargin<Lens>(camera))) continue;
                const float xa[4] = {q.x[0], q.x[1], q.x[2], q.x[3]}, ya[4] = {q.y[0], q.y[1], q.y[2], q.y[3]},
                            za[4] = {q.z[0], q.z[1], q.z[2], q.z[3]};
                for (int py = q.py0; py <= q.py1; ++py) {
                    for (int px = q.px0; px <= q.px1; ++px) {
                        const size_t pi = block.pixelIndex(px, py);
                        // Every sample of the pixel already sees something nearer than the whole
                        // quad: none of them can change (the usual case deep in foliage).
                        if (!Counting && pixelBehind(block, fi, pi, q.zmin, S)) {
                            behind += s1 - s0;
                            continue;
                        }
                        SampleHit* rec = block.record(fi, pi);
                        const int perm = block.permutation(fi, pi);
                        // The group's samples inside the quad's bound, each with its slice. Of a
                        // group of many slices, found 64 samples at a time (SIMD) and listed in
                        // sample order: each sample is tested alone, so the order changes nothing.
                        size_t candidates = 0;
                        if (s1 - s0 >= kMaskSlices) {
                            const uint16_t* sliceOf = patterns.stratumOfSample(perm);
                            const Box box{q.xmin, q.xmax, q.ymin, q.ymax, float(first.k), float(last.k)};
                            for (int c0 = 0; c0 < S; c0 += 64) {
                                const size_t at = pi * size_t(S) + size_t(c0);
                                uint64_t in = inBoxes(xs + at, ys + at, patterns.stratumKeys(perm) + c0,
                                                      std::min(64, S - c0), box);
                                for (; in; in &= in - 1) {
                                    const int sj = c0 + __builtin_ctzll(in);
                                    const size_t s = s0 + size_t(sliceOf[sj] - first.k);
                                    candidates_[candidates++] = {uint32_t(s), uint32_t(sj)};
                                }
                            }
                        } else {
                            for (size_t s = s0; s < s1; ++s) {
                                const int sj = patterns.sampleOfStratum(perm)[slices_[s].k];
                                const size_t si = pi * size_t(S) + size_t(sj);
                                const float x = xs[si], y = ys[si];
                                if (x < q.xmin || x > q.xmax || y < q.ymin || y > q.ymax) continue;
                                candidates_[candidates++] = {uint32_t(s), uint32_t(sj)};
                            }
                        }
                        for (size_t n = 0; n < candidates; ++n) {
                            const Slice& sl = slices_[candidates_[n].slice];
                            const int sj = int(candidates_[n].sample);
                            const size_t si = pi * size_t(S) + size_t(sj);
                            const float x = xs[si], y = ys[si], tf = patterns.stratumTimes(perm)[sl.k];
                            if (sl.checkTime && !inTimeSpan(tf, sl.tfA, sl.tfB, sl.openB)) continue;
                            const SampleHit& cur = rec ? rec[sj] : block.still(pi)[sj];
                            if (!Counting && q.zmin > cur.z) {  // all of it behind what the sample already sees
                                ++behind;
                                continue;
                            }
                            ++tests;
                            const float w = std::min(1.0f, std::max(0.0f, (tf - tfA) * invSpan));
                            QuadSetup qt;
                            for (int c = 0; c < 4; ++c) {
                                if (perspective && exact_[size_t(idx[c])]) {
                                    const Vec3f r = camera.toRaster(lerp(ca_[size_t(idx[c])], cb_[size_t(idx[c])], w));
                                    qt.x[c] = r.x, qt.y[c] = r.y, qt.z[c] = r.z;
                                } else {
                                    qt.x[c] = lerp(xa[c], xb[c], w);
                                    qt.y[c] = lerp(ya[c], yb[c], w);
                                    qt.z[c] = lerp(za[c], zb[c], w);
                                }
                            }
                            Hit h;
                            if constexpr (Lens) {
                                // The quad at the sample's time as its lens point sees it.
                                float shx[4], shy[4];
                                lensShifts(camera, qt.z, shx, shy);
                                const QuadSetup qp = qt;
                                if (!lensQuad(qp, shx, shy, lus[si], lvs[si], x, y, qt)) continue;
                            } else {
                                setupEdges(qt);
                            }
                            if (!hitQuad(qt, x, y, h)) continue;
                            ++hits;
                            if (Counting) {
                                const size_t ci2 = (size_t(fi) * pixels + pi) * size_t(S) + size_t(sj);
                                trianglesCovering(qt, x, y, &hitCounts_[ci2], &windings_[ci2]);
                            }
                            const float sg = lerp(sA, sB, w);  // the grid's own time parameter
                            if (seeThrough) {
                                SampleFragment frag;
                                auto colorAt = [&](int c) { return lerp(ci0[idx[flat ? 0 : c]], ci1[idx[flat ? 0 : c]], sg); };
                                auto opacityAt = [&](int c) {
                                    const int v = idx[flat ? 0 : c];
                                    return lerp(oi0 ? oi0[v] : kOpaque, oi1 ? oi1[v] : kOpaque, sg);
                                };
                                if (!fragmentBeats(cur, qt.z, h, nearZ, farZ, id, colorAt, opacityAt, &frag)) continue;
                                const int32_t fk = keepFrameFragment(block, fi, pi, sj, frag, rec);
                                ++fragments;
                                if (Shadowed)
                                    writeShadowed(block.fragmentShadowed(fk), K, h, [&](int c, int k) {
                                        const size_t v = size_t(idx[flat ? 0 : c] * K + k);
                                        return lerp(cl0[v], cl1[v], sg);
                                    });
                                continue;
                            }
                            SampleHit hit;
                            if (!beats(cur, qt.z, h, nearZ, farZ, id,
                                       [&](int c) { return lerp(ci0[idx[flat ? 0 : c]], ci1[idx[flat ? 0 : c]], sg); }, &hit))
                                continue;
                            firstHits += cur.a == 0;
                            if (!Counting) {
                                // The pixel's farthest sample came nearer: its bound goes stale.
                                float& bound = block.farthestBound(fi, pi);
                                if (!(cur.z < std::fabs(bound))) bound = -std::fabs(bound);
                            }
                            if (!rec) rec = block.makeRecord(fi, pi);
                            rec[sj] = hit;
                            if (A)
                                writeAovs(block.recordAov(fi, pi) + size_t(sj) * size_t(A), A, h, [&](int c, int a) {
                                    const size_t v = size_t(idx[c]) * size_t(A) + size_t(a);
                                    return lerp(av0[v], av1[v], sg);
                                });
                            if (Shadowed)
                                writeShadowed(block.shadowed(fi, pi) + size_t(sj) * size_t(K), K, h, [&](int c, int k) {
                                    const size_t v = size_t(idx[flat ? 0 : c] * K + k);
                                    return lerp(cl0[v], cl1[v], sg);
                                });
                        }
                    }
                }
            }
        }
        s0 = s1;
    }
    counters.sampleTests += tests;
    counters.sampleHits += hits;
    counters.firstHits += firstHits;
    counters.samplesBehind += behind;
    counters.fragments += fragments;
    counters.gridGroupsBehind += gridsBehind;
}


template void GridRasterizer::sampleMoving<false, false, false>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleMoving<false, false, true>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleMoving<false, true, false>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleMoving<false, true, true>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleMoving<true, false, false>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleMoving<true, false, true>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleMoving<true, true, false>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleMoving<true, true, true>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);

}  // namespace streyes
