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

namespace {

// Whether every pixel of the block the raster bound b reaches already sees, in every sample of
// frame fi, something nearer than b's nearest depth.
bool boundBehind(ImageBlock& block, int fi, const Bounds3f& b) {
    const PixelRect& R = block.rect();
    const int x0 = floorClamped(b.lo.x, R.x0, R.x1), x1 = floorClamped(b.hi.x, R.x0, R.x1);
    const int y0 = floorClamped(b.lo.y, R.y0, R.y1), y1 = floorClamped(b.hi.y, R.y0, R.y1);
    for (int py = y0; py <= y1; ++py)
        for (int px = x0; px <= x1; ++px)
            if (!pixelBehind(block, fi, block.pixelIndex(px, py), b.lo.z, block.samplesPerPixel())) return false;
    return true;
}

// A solid's fragment's output variables at hit h, a moving grid's (its two ends' av0, av1 at the
// grid's own time sg). Out of line: inlined, it grew sampleMoving enough that ImageBlock::record
// stopped being inlined there (+0.07% instructions on atom.rib, which has no solid).
__attribute__((noinline)) void writeMovingFragmentAovs(float* out, int A, const Hit& h, const float* av0, const float* av1,
                                                       const int* idx, float sg) {
    writeAovs(out, A, h, [&](int c, int a) {
        const size_t v = size_t(idx[c]) * size_t(A) + size_t(a);
        return lerp(av0[v], av1[v], sg);
    });
}

}  // namespace

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
//
// A quad's samples of a group in the pixels of its bound are tested together, 8 at a time, each
// against the quad at its own time, as its lens point sees it with a lens (sample_kernels.h,
// MovingQuad: the kernel gives the scalar test's results bit for bit).
// Before any quad, the whole grid and then each patch of 4 x 4 quads is skipped where every pixel
// its bound over the group reaches already sees something nearer than all of it.
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
    const bool dissolves = grid.dissolves();  // a level of detail's transition: a share of the samples
    const int K = grid.shadowSlots;
    const Color *cl0 = grid.Cl[0].data(), *cl1 = grid.Cl[1].data();
    const int A = grid.aovCount;
    const float *av0 = grid.aov[0].data(), *av1 = grid.aov[1].data();
    const uint64_t id = hitId(grid.primitiveId, grid.matte);
    // A matte is opaque whatever its Oi.
    const Color *oi0 = grid.matte ? nullptr : opacities(grid, 0), *oi1 = grid.matte ? nullptr : opacities(grid, 1);
    const bool solid = grid.solid >= 0;  // a solid's boundary: every crossing a tagged fragment
    // Each quad's opacity, once for all its groups: none but opaque ones is the usual case.
    // A solid's boundary counts as see-through everywhere (even where clear): the quads' loop is
    // then the same as without solids.
    bool anySeeThrough = false;
    if (oi0 || oi1 || solid) {
        opacity_.resize(size_t(nu) * size_t(nv));
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
                const QuadOpacity o = solid ? QuadOpacity::SeeThrough : quadOpacity(oi0, oi1, ci0, ci1, idx);
                opacity_[size_t(j * nu + i)] = uint8_t(o);
                anySeeThrough = anySeeThrough || o != QuadOpacity::Opaque;
            }
    }
    const Color kOpaque{1, 1, 1};
    const float *lus = block.lus(), *lvs = block.lvs();
    // The moving test: the SIMD kernel, or the scalar reference while counting hits for tests of
    // watertightness (the kernel is held to it bit for bit).
    const MovingTestFn movingTest = Counting ? movingTestScalar() : movingTestKernel();
    // The lanes' quad: what the camera gives it is the same for the whole grid.
    MovingQuad& mq = quad_;
    mq.ax = camera.ax(), mq.bx = camera.bx(), mq.ay = camera.ay(), mq.by = camera.by();
    mq.lens = Lens;
    mq.lensRadius = camera.lensRadius(), mq.invFocal = camera.invFocalDistance(), mq.eyePlane = camera.eyePlane();
    // The group's slots: up to S a pixel, and room for the kernel to read a whole vector past the last.
    GroupSamples& gs = group_;
    const size_t slots = pixels * size_t(S) + size_t(kLanes);
    if (gs.x.size() < slots) {
        for (auto* v : {&gs.x, &gs.y, &gs.tf, &gs.z}) v->assign(slots, 0.0f);
        gs.sample.assign(slots, 0);
    }
    if (Lens && gs.lu.size() < slots) {  // lens points only with depth of field
        gs.lu.assign(slots, 0.0f);
        gs.lv.assign(slots, 0.0f);
    }
    if (gs.gathered.size() < pixels) gs.gathered.resize(pixels, 0);

    // Slices are bounded in groups (kGroupMotion): the grid's largest motion over a slice.
    project(grid, grid.t0, camera, ra_);
    project(grid, grid.t1, camera, rb_);
    float motion = 0;
    for (size_t v = 0; v < ra_.size(); ++v)
        motion = std::max({motion, std::fabs(rb_[v].x - ra_[v].x), std::fabs(rb_[v].y - ra_[v].y)});
    double sliceTime = 0;  // the longest slice, as a share of the grid's span
    // A grid of no time (a moving body cut to one instant: a closed shutter's frame at its last
    // key) is where it is at t0 throughout: no share of its span is taken (0 / 0 made NaN colours).
    auto share = [&](double t) { return span > 0 ? (t - grid.t0) / span : 0.0; };
    for (const Slice& sl : slices_) sliceTime = std::max(sliceTime, span > 0 ? (sl.tb - sl.ta) / span : 0.0);
    const double perSlice = double(motion) * sliceTime;
    const size_t group = slicesPerGroup(perSlice, S);

    double projected = std::numeric_limits<double>::quiet_NaN();  // the time rb_ holds
    uint64_t tests = 0, hits = 0, firstHits = 0, behind = 0, fragments = 0, gridsBehind = 0, patchesBehind = 0, patchesOutside = 0;
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
        const float sA = float(share(first.ta)), sB = float(share(last.tb));
        mq.tfA = first.tfA, mq.invSpan = last.tfB > first.tfA ? 1.0f / (last.tfB - first.tfA) : 0.0f;
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
            if (boundBehind(block, fi, groupBound)) {
                ++gridsBehind;
                s0 = s1;
                continue;
            }
        }
        // Patches of kPatch x kPatch quads, tested the same way: a grid partly in sight is often
        // hidden patch by patch (foliage behind foliage), and a hidden patch's quads are not visited.
        constexpr int kPatch = 4;
        const int patchesU = (nu + kPatch - 1) / kPatch, patchesV = (nv + kPatch - 1) / kPatch;
        patchHidden_.assign(size_t(patchesU * patchesV), 0);
        if (!Counting && !Lens && patchesU * patchesV > 1) {
            for (int pj = 0; pj < patchesV; ++pj)
                for (int pc = 0; pc < patchesU; ++pc) {
                    Bounds3f b;
                    for (int vj = pj * kPatch; vj <= std::min(nv, (pj + 1) * kPatch); ++vj)
                        for (int vi = pc * kPatch; vi <= std::min(nu, (pc + 1) * kPatch); ++vi) {
                            const size_t v = size_t(vj * stride + vi);
                            b.extend(Vec3f{ra_[v].x, ra_[v].y, ra_[v].z});
                            b.extend(Vec3f{rb_[v].x, rb_[v].y, rb_[v].z});
                        }
                    // A patch whose bound misses the block (the grid's test, above): none of its
                    // quads' bounds reaches it (boundQuad would drop each). A grid a bucket shares
                    // with its neighbours, as a piece swept over a chunk of frames is, lies
                    // largely outside each of them in any one frame.
                    if (!(b.hi.x >= float(R.x0) && b.lo.x < float(R.x1 + 1) && b.hi.y >= float(R.y0) &&
                          b.lo.y < float(R.y1 + 1))) {
                        patchHidden_[size_t(pj * patchesU + pc)] = 1;
                        ++patchesOutside;
                    } else if (boundBehind(block, fi, b)) {
                        patchHidden_[size_t(pj * patchesU + pc)] = 1;
                        ++patchesBehind;
                    }
                }
        }
        // A new serial for the group's slots: every pixel is gathered again when a quad first reaches it.
        if (++gs.serial == 0) {
            std::fill(gs.gathered.begin(), gs.gathered.end(), 0u);
            gs.serial = 1;
        }
        const size_t g = s1 - s0;
        // Pixel pi at (px, py): its samples' positions come from its pattern's offsets (8 KB, in
        // L1), the way ImageBlock::reset makes xs() and ys() (the same bits), not from those
        // arrays, whose loads missed the cache in a bucket-sized block.
        auto gather = [&](size_t pi, int px, int py) {
            const float* offsets = patterns.offsets(block.patternOf(pi));
            const float fx = float(px), fy = float(py);
            const int perm = block.permutation(fi, pi);
            const uint16_t* sampleOf = patterns.sampleOfStratum(perm);
            const float* times = patterns.stratumTimes(perm);
            const SampleHit* rec = block.record(fi, pi);
            const SampleHit* seen = rec ? rec : block.still(pi);
            size_t o = pi * g;
            for (size_t s = s0; s < s1; ++s, ++o) {
                const Slice& sl = slices_[s];
                const int sj = sampleOf[sl.k];
                gs.sample[o] = uint16_t(sj);
                if ((sl.checkTime && !inTimeSpan(times[sl.k], sl.tfA, sl.tfB, sl.openB)) ||
                    (dissolves && !block.dissolveKeeps(fi, pi, sj, grid.dissolveLo, grid.dissolveHi))) {
                    // A sample outside the part of its slice the grid covers meets none of it; nor
                    // does one outside the share a dissolving grid is seen by.
                    constexpr float kNever = std::numeric_limits<float>::infinity();
                    gs.x[o] = kNever, gs.y[o] = kNever, gs.tf[o] = 0, gs.z[o] = kNever;
                    if constexpr (Lens) gs.lu[o] = 0, gs.lv[o] = 0;
                    continue;
                }
                gs.x[o] = fx + offsets[2 * sj], gs.y[o] = fy + offsets[2 * sj + 1];
                gs.tf[o] = times[sl.k], gs.z[o] = seen[sj].z;
                if constexpr (Lens) {
                    const size_t si = pi * size_t(S) + size_t(sj);
                    gs.lu[o] = lus[si], gs.lv[o] = lvs[si];
                }
            }
            gs.gathered[pi] = gs.serial;
        };
        for (int j = 0; j < nv; ++j) {
            for (int i = 0; i < nu; ++i) {
                if (hole && hole[j * nu + i]) continue;  // trimmed away
                if (patchHidden_[size_t((j / kPatch) * patchesU + i / kPatch)]) continue;
                const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
                const QuadOpacity opacity = anySeeThrough ? QuadOpacity(opacity_[size_t(j * nu + i)]) : QuadOpacity::Opaque;
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
                // A hit: sample sj of pixel pi (at (x, y), weight w across the group) inside qt's
                // triangle h (of qt, only the corner depths are set but while counting). rec is the
                // frame's record of the pixel (null until something only this frame sees lands
                // there); cur the sample's hit.
                auto onHit = [&](size_t pi, int sj, SampleHit*& rec, const SampleHit& cur, float w, const Hit& h,
                                 const QuadSetup& qt, float x, float y, size_t slot) __attribute__((always_inline)) {
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
                        if (!fragmentBeats(cur, qt.z, h, nearZ, farZ, id, colorAt, opacityAt, &frag)) return;
                        if (solid) {  // which way the triangle runs at the sample's time
                            QuadSetup at;
                            movingQuadAt(mq, w, at);
                            frag.solid = solidTag(grid.solid, entersSolid(at.x, at.y, h, grid.frontWinding));
                        }
                        const int32_t fk = keepFrameFragment(block, fi, pi, sj, frag, rec);
                        if (solid && A)  // the surface the sample may show (film.cpp's solidSurfaces)
                            writeMovingFragmentAovs(block.fragmentAov(fk), A, h, av0, av1, idx, sg);
                        ++fragments;
                        if (Shadowed)
                            writeShadowed(block.fragmentShadowed(fk), block.fragmentStillTested(fk), false, K, h, [&](int c, int k) {
                                const size_t v = size_t(idx[flat ? 0 : c] * K + k);
                                return lerp(cl0[v], cl1[v], sg);
                            });
                        return;
                    }
                    SampleHit hit;
                    if (!beats(cur, qt.z, h, nearZ, farZ, id,
                               [&](int c) { return lerp(ci0[idx[flat ? 0 : c]], ci1[idx[flat ? 0 : c]], sg); }, &hit))
                        return;
                    firstHits += cur.empty();
                    if (!Counting) {
                        // The pixel's farthest sample came nearer: its bound goes stale.
                        float& bound = block.farthestBound(fi, pi);
                        if (!(cur.z < std::fabs(bound))) bound = -std::fabs(bound);
                    }
                    if (!rec) rec = block.makeRecord(fi, pi);
                    rec[sj] = hit;
                    gs.z[slot] = hit.z;  // what the grid's next quads see there
                    block.touch(pi);
                    if (A)
                        writeAovs(block.recordAov(fi, pi) + size_t(sj) * size_t(A), A, h, [&](int c, int a) {
                            const size_t v = size_t(idx[c]) * size_t(A) + size_t(a);
                            return lerp(av0[v], av1[v], sg);
                        });
                    if (Shadowed)
                        writeShadowed(block.shadowed(fi, pi) + size_t(sj) * size_t(K), block.stillTested(fi, pi) + sj, false, K, h, [&](int c, int k) {
                            const size_t v = size_t(idx[flat ? 0 : c] * K + k);
                            return lerp(cl0[v], cl1[v], sg);
                        });
                };
                // Each row of the quad's pixels: the group's samples of its pixels lie side by side
                // in the group's slots, tested up to kLanes at a time against the quad at each
                // sample's own time, as its lens point sees it with a lens (sample_kernels.h,
                // MovingQuad); lanes inside the quad's bound are tests, as one by one.
                for (int c = 0; c < 4; ++c) {
                    const size_t v = size_t(idx[c]);
                    mq.x[0][c] = q.x[c], mq.y[0][c] = q.y[c], mq.z[0][c] = q.z[c];
                    mq.x[1][c] = xb[c], mq.y[1][c] = yb[c], mq.z[1][c] = zb[c];
                    mq.exact[c] = perspective && exact_[v];
                    if (mq.exact[c]) {
                        mq.cx[0][c] = ca_[v].x, mq.cy[0][c] = ca_[v].y, mq.cz[0][c] = ca_[v].z;
                        mq.cx[1][c] = cb_[v].x, mq.cy[1][c] = cb_[v].y, mq.cz[1][c] = cb_[v].z;
                    }
                }
                mq.xmin = q.xmin, mq.xmax = q.xmax, mq.ymin = q.ymin, mq.ymax = q.ymax;
                // A lane whose sample already sees something nearer than all of the quad is not
                // tested (counted behind); while counting hits, every lane is.
                mq.zmin = Counting ? std::numeric_limits<float>::quiet_NaN() : q.zmin;
                for (int py = q.py0; py <= q.py1; ++py) {
                    const size_t row = block.pixelIndex(q.px0, py), rowEnd = row + size_t(q.px1 - q.px0 + 1);
                    for (size_t pi = row; pi < rowEnd; ++pi)
                        if (gs.gathered[pi] != gs.serial) gather(pi, q.px0 + int(pi - row), py);
                    for (size_t first = row * g, end = rowEnd * g; first < end; first += kLanes) {
                        const int n = int(std::min(end - first, size_t(kLanes)));
                        const MovingTest t =
                            movingTest(mq, &gs.x[first], &gs.y[first], &gs.tf[first], &gs.z[first],
                                       Lens ? &gs.lu[first] : nullptr, Lens ? &gs.lv[first] : nullptr, n, movingEdges_);
                        tests += uint64_t(__builtin_popcountll(t.tested));
                        behind += uint64_t(__builtin_popcountll(t.behind));
                        for (uint64_t b = t.first | t.second; b; b &= b - 1) {
                            const int l = __builtin_ctzll(b);
                            const size_t slot = first + size_t(l), pi = slot / g;
                            const int sj = gs.sample[slot];
                            SampleHit* rec = block.record(fi, pi);
                            const SampleHit& cur = rec ? rec[sj] : block.still(pi)[sj];
                            const Hit h = pixelHit(movingEdges_, n, l, (t.first >> l) & 1);
                            const float w = movingWeight(mq, gs.tf[slot]);
                            QuadSetup qt;
                            if constexpr (Counting) qt = QuadSetup{};  // set below; GCC cannot tell once onHit is inlined
                            if (Counting && Lens) movingLensQuadAt(mq, w, gs.lu[slot], gs.lv[slot], gs.x[slot], gs.y[slot], qt);
                            else if (Counting) movingQuadAt(mq, w, qt);
                            else
                                for (int c = 0; c < 4; ++c) qt.z[c] = movingDepth(mq, c, w);  // all a hit needs
                            onHit(pi, sj, rec, cur, w, h, qt, gs.x[slot], gs.y[slot], slot);
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
    counters.patchGroupsBehind += patchesBehind;
    counters.patchGroupsOutside += patchesOutside;
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
