// The still sampler: GridRasterizer::sampleStill (rasterizer.h).
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

// Whether every sample of every pixel of the quad's bound already sees, in the still layer,
// something nearer than the whole quad: then the quad cannot change one of them.
inline bool behindStillLayer(const ImageBlock& block, const QuadSetup& q) {
    const int S = block.samplesPerPixel();
    for (int py = q.py0; py <= q.py1; ++py)
        for (int px = q.px0; px <= q.px1; ++px) {
            const SampleHit* h = block.still(block.pixelIndex(px, py));
            for (int k = 0; k < S; ++k)
                if (!(q.zmin > h[k].z)) return false;
        }
    return true;
}

// A new hit of the still layer at sample sj of pixel pi: frames that already have a record of the
// pixel (something only they see came first) see it too, where it is nearer, with its A output
// variables (at stillAov) when the block keeps them.
// With shadows the still layer's hits are folded still grids': the record's sample needs no
// shadow pass.
inline void stillHitToRecords(ImageBlock& block, size_t pi, int sj, const SampleHit& hit, int A, const float* stillAov) {
    for (int fi = 0, left = block.recordsOf(pi); left > 0; ++fi) {
        SampleHit* rec = block.record(fi, pi);
        if (!rec) continue;
        --left;
        if (!rec[sj].beatenBy(hit.z, hit.id, hit.c)) continue;
        rec[sj] = hit;
        if (A) std::copy(stillAov, stillAov + A, block.recordAov(fi, pi) + size_t(sj) * size_t(A));
        if (block.shadowSlots() > 0) block.stillTested(fi, pi)[sj] = kFoldedShadows;
    }
}

}  // namespace

// A still grid: each quad is projected and set up once, then tested against the samples its
// bound overlaps, visiting in each pixel only the (x, y) strata the bound overlaps. Positions are
// the same in every frame, so a sample is tested once; a grid over every frame of the block (the
// usual still geometry) writes the still layer, once for all of them, and any other grid the
// records of the frames it exists in (at the sample's time within the exposure, where it exists
// in part of one).
template <bool Shadowed, bool Counting, bool Lens>
void GridRasterizer::sampleStill(const Grid& grid, const Camera& camera, ImageBlock& block, RasterCounters& counters) {
    const PixelRect& R = block.rect();
    const int nu = grid.nu, nv = grid.nv, stride = nu + 1, S = block.samplesPerPixel(), F = block.frameCount();
    const uint8_t* hole = grid.hole.empty() ? nullptr : grid.hole.data();
    const int sx = block.pattern().sx, sy = block.pattern().sy;
    const size_t pixels = size_t(block.pixelCount());
    const float nearZ = camera.nearClip(), farZ = camera.farClip();
    // A dissolving grid (a level of detail's transition) is seen by a share of each frame's samples
    // that differs from frame to frame: it writes the frames' records.
    const bool dissolves = grid.dissolves();
    // With shadows, only a grid whose shadows are in its colour: any other's samples carry its
    // lights' parts, per frame.
    bool intoStill = !block.dense() && int(frames_.size()) == F && !dissolves &&
                     (!Shadowed || grid.stillShadows == kFoldedShadows);
    for (const FrameSpan& fr : frames_) intoStill = intoStill && fr.whole;
    project(grid, grid.t0, camera, ra_);
    const float* xs = block.xs();
    const float* ys = block.ys();
    const float *lus = block.lus(), *lvs = block.lvs();
    const Color* ci = grid.Ci[0].data();
    const Color* ciNow = ci;  // the colours colorAt reads: a frame's folded ones (Grid::CiFolded) where it has them
    const bool flat = grid.flatShading;  // ShadingInterpolation "constant": the first corner's colour
    const int K = grid.shadowSlots;
    const Color* cl = grid.Cl[0].data();
    const int A = grid.aovCount;
    const float* av = grid.aov[0].data();
    const uint64_t id = hitId(grid.primitiveId, grid.matte);
    const Color* oi = grid.matte ? nullptr : opacities(grid, 0);  // a matte is opaque whatever its Oi
    // A solid's boundary: every crossing is a fragment, tagged, and resolved with the others
    // (geom/solid_tree.h); even a clear one counts in classifying inside from outside.
    const bool solid = grid.solid >= 0;
    // The kernel: SIMD, or scalar while counting hits for tests of watertightness (the counting
    // instance runs the scalar reference: the kernels are held to it bit for bit).
    const QuadTestFn test = Counting ? quadTestScalar() : quadTestKernel();
    const LensTestFn lensTest = Counting ? lensTestScalar() : lensTestKernel();
    const SampleLayout layout{xs, ys, R.x0, R.y0, R.width(), S, sx, sy};
    // Opaque quads into the still layer go to the kernel that writes them (its gather indexes
    // the layer's floats with 32-bit lanes).
    const bool fastStill = !Counting && intoStill && A == 0 &&
                           pixels * size_t(S) * (sizeof(SampleHit) / sizeof(float)) <= size_t(INT32_MAX);
    const QuadWriteFn writeQuad = quadWriteKernel();
    // Without records in the block (none is made while a grid samples into the still layer),
    // the kernel need not look for them.
    StillWrite write{fastStill ? block.stillLayer() : nullptr, block.touchFlags(),
                     fastStill && block.recordCount() ? block.recordCounts() : nullptr, id, nearZ, farZ};
    uint64_t tests = 0, hits = 0, firstHits = 0, fragments = 0;
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            if (hole && hole[j * nu + i]) continue;  // trimmed away
            const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
            const QuadOpacity opacity = solid ? QuadOpacity::SeeThrough
                                        : oi  ? quadOpacity(oi, nullptr, ci, nullptr, idx)
                                              : QuadOpacity::Opaque;
            if (!Counting && opacity == QuadOpacity::Clear) continue;
            const bool seeThrough = opacity != QuadOpacity::Opaque;
            QuadSetup q;
            for (int c = 0; c < 4; ++c) {
                const RasterVertex& v = ra_[size_t(idx[c])];
                q.x[c] = v.x, q.y[c] = v.y, q.z[c] = v.z;
            }
            if (!boundQuad(q, nullptr, nullptr, nullptr, R, nearZ, farZ, lensMargin<Lens>(camera))) continue;
            if (!Counting && intoStill && behindStillLayer(block, q)) continue;
            auto colorAt = [&](int c) { return ciNow[idx[flat ? 0 : c]]; };
            auto opacityAt = [&](int c) { return oi ? oi[idx[flat ? 0 : c]] : Color{1, 1, 1}; };
            // A hit of sample sj of pixel pi, h on quad qc (q as the sample sees it).
            auto onHit = [&](size_t pi, int sj, const Hit& h, const QuadSetup& qc) {
                SampleHit hit;
                SampleFragment frag;
                if (intoStill) {
                    ++hits;
                    if (Counting) {
                        const float x = xs[pi * size_t(S) + size_t(sj)], y = ys[pi * size_t(S) + size_t(sj)];
                        for (int fi = 0; fi < F; ++fi) {
                            const size_t ci2 = (size_t(fi) * pixels + pi) * size_t(S) + size_t(sj);
                            trianglesCovering(qc, x, y, &hitCounts_[ci2], &windings_[ci2]);
                        }
                    }
                    SampleHit& cur = block.still(pi)[sj];
                    if (seeThrough) {  // a fragment every frame sees (where nothing opaque of its own is nearer)
                        if (!fragmentBeats(cur, q.z, h, nearZ, farZ, id, colorAt, opacityAt, &frag)) return;
                        if (solid) frag.solid = solidTag(grid.solid, entersSolid(q.x, q.y, h, grid.frontWinding));
                        block.startFragments();
                        const int32_t fk = block.addFragment(block.stillFragments(pi) + sj, frag);
                        if (solid && A)  // the surface the sample may show (film.cpp's solidSurfaces)
                            writeAovs(block.fragmentAov(fk), A, h,
                                      [&](int c, int a) { return av[size_t(idx[c]) * size_t(A) + size_t(a)]; });
                        ++fragments;
                        return;
                    }
                    if (!beats(cur, q.z, h, nearZ, farZ, id, colorAt, &hit)) return;
                    if (cur.empty()) firstHits += uint64_t(F);  // a first hit in every frame
                    cur = hit;
                    block.touch(pi);
                    float* stillAov = A ? block.stillAov(pi) + size_t(sj) * size_t(A) : nullptr;
                    if (A) writeAovs(stillAov, A, h, [&](int c, int a) { return av[size_t(idx[c]) * size_t(A) + size_t(a)]; });
                    stillHitToRecords(block, pi, sj, hit, A, stillAov);
                    return;
                }
                // The frames it exists in at the sample's time (the position, and so the inside
                // test, is the same in every frame).
                for (const FrameSpan& fr : frames_) {
                    if (!fr.whole && !inTimeSpan(block.sampleTime(fr.fi, pi, sj), fr.tfA, fr.tfB, fr.openB)) continue;
                    if (dissolves && !block.dissolveKeeps(fr.fi, pi, sj, grid.dissolveLo, grid.dissolveHi)) continue;
                    const uint8_t stillTested = Shadowed ? grid.stillShadowsOf(block.firstFrame() + fr.fi) : 0;
                    ciNow = Shadowed && stillTested == kFoldedShadows && !grid.CiFolded.empty() ? grid.CiFolded.data() : ci;
                    ++hits;
                    if (Counting) {
                        const float x = xs[pi * size_t(S) + size_t(sj)], y = ys[pi * size_t(S) + size_t(sj)];
                        const size_t ci2 = (size_t(fr.fi) * pixels + pi) * size_t(S) + size_t(sj);
                        trianglesCovering(qc, x, y, &hitCounts_[ci2], &windings_[ci2]);
                    }
                    SampleHit* rec = block.record(fr.fi, pi);
                    const SampleHit& cur = rec ? rec[sj] : block.still(pi)[sj];
                    if (seeThrough) {
                        if (!fragmentBeats(cur, q.z, h, nearZ, farZ, id, colorAt, opacityAt, &frag)) continue;
                        if (solid) frag.solid = solidTag(grid.solid, entersSolid(q.x, q.y, h, grid.frontWinding));
                        const int32_t fk = keepFrameFragment(block, fr.fi, pi, sj, frag, rec);
                        if (solid && A)
                            writeAovs(block.fragmentAov(fk), A, h,
                                      [&](int c, int a) { return av[size_t(idx[c]) * size_t(A) + size_t(a)]; });
                        ++fragments;
                        if (Shadowed)
                            writeShadowed(block.fragmentShadowed(fk), block.fragmentStillTested(fk), stillTested, K, h,
                                          [&](int c, int k) { return cl[size_t(idx[flat ? 0 : c] * K + k)]; });
                        continue;
                    }
                    if (!beats(cur, q.z, h, nearZ, farZ, id, colorAt, &hit)) continue;
                    firstHits += cur.empty();
                    if (!rec) rec = block.makeRecord(fr.fi, pi);
                    rec[sj] = hit;
                    block.touch(pi);
                    if (A)
                        writeAovs(block.recordAov(fr.fi, pi) + size_t(sj) * size_t(A), A, h,
                                  [&](int c, int a) { return av[size_t(idx[c]) * size_t(A) + size_t(a)]; });
                    if (Shadowed)
                        writeShadowed(block.shadowed(fr.fi, pi) + size_t(sj) * size_t(K), block.stillTested(fr.fi, pi) + sj,
                                      stillTested, K, h,
                                      [&](int c, int k) { return cl[size_t(idx[flat ? 0 : c] * K + k)]; });
                }
            };
            if constexpr (Lens) {
                // Every sample of the pixels of the grown bound, against the quad its lens point
                // sees, up to 64 of a pixel at once (sample_kernels.h, LensQuad).
                LensQuad lq;
                lensShifts(camera, q.z, lq.sx, lq.sy);
                for (int c = 0; c < 4; ++c) lq.x[c] = q.x[c], lq.y[c] = q.y[c];
                lq.xmin = q.xmin, lq.xmax = q.xmax, lq.ymin = q.ymin, lq.ymax = q.ymax;
                for (int py = q.py0; py <= q.py1; ++py)
                    for (int px = q.px0; px <= q.px1; ++px) {
                        const size_t pi = block.pixelIndex(px, py);
                        for (int c0 = 0; c0 < S; c0 += 64) {
                            const int n = std::min(64, S - c0);
                            const size_t at = pi * size_t(S) + size_t(c0);
                            const MovingTest t = lensTest(lq, xs + at, ys + at, lus + at, lvs + at, n, lensEdges_);
                            tests += uint64_t(__builtin_popcountll(t.tested));
                            for (uint64_t in = t.first | t.second; in; in &= in - 1) {
                                const int j = __builtin_ctzll(in);
                                const Hit h = pixelHit(lensEdges_, n, j, (t.first >> j) & 1);
                                if constexpr (Counting) {  // the quad as the sample saw it
                                    QuadSetup ql;
                                    const size_t si = at + size_t(j);
                                    lensQuad(q, lq.sx, lq.sy, lus[si], lvs[si], xs[si], ys[si], ql);
                                    onHit(pi, c0 + j, h, ql);
                                } else {
                                    onHit(pi, c0 + j, h, q);
                                }
                            }
                        }
                    }
            } else {
                setupEdges(q);
                // The samples of the strata the bound overlaps in each pixel, tested at once (SIMD).
                const size_t room = size_t(q.px1 - q.px0 + 1) * size_t(q.py1 - q.py0 + 1) * size_t(S);
                if (quadHits_.size() < room) quadHits_.resize(room);
                size_t found = 0;
                if (fastStill && !seeThrough) {
                    // The usual hit, opaque into the still layer: the kernel makes each hit's depth
                    // and colour, from each triangle's differences made once for the quad (the
                    // same operations as beats(), which takes them from the first corner too),
                    // and writes those that win; ties and pixels with records come back here.
                    const Color corners[4] = {colorAt(0), colorAt(1), colorAt(2), colorAt(3)};
                    const QuadShading shading = quadShading(q.z, corners);
                    tests += writeQuad(q, layout, shading, write, quadHits_.data(), &found);
                    for (size_t n = 0; n < found; ++n) {
                        const QuadHit& qh = quadHits_[n];
                        const float zh = qh.z;
                        SampleHit& cur = block.still(qh.pixel)[qh.sample];
                        if (!(zh >= nearZ && zh <= farZ && zh <= cur.z)) continue;
                        const Color c = qh.c;
                        if (zh == cur.z && !cur.beatenBy(zh, id, c)) continue;
                        if (cur.empty()) firstHits += uint64_t(F);  // a first hit in every frame
                        cur = {zh, c, id};
                        block.touch(qh.pixel);
                        stillHitToRecords(block, qh.pixel, qh.sample, cur, 0, nullptr);
                    }
                } else {
                    tests += test(q, layout, nullptr, quadHits_.data(), &found);
                    for (size_t n = 0; n < found; ++n) {
                        const QuadHit& qh = quadHits_[n];
                        onHit(qh.pixel, qh.sample, quadHit(qh), q);
                    }
                }
            }
        }
    }
    counters.sampleTests += tests;
    counters.sampleHits += hits + write.inside;
    counters.firstHits += firstHits + write.firstHits * uint64_t(F);  // a first hit in every frame
    counters.fragments += fragments;
}

template void GridRasterizer::sampleStill<false, false, false>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleStill<false, false, true>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleStill<false, true, false>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleStill<false, true, true>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleStill<true, false, false>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleStill<true, false, true>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleStill<true, true, false>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);
template void GridRasterizer::sampleStill<true, true, true>(const Grid&, const Camera&, ImageBlock&, RasterCounters&);

}  // namespace streyes
