#include "raster/rasterizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "geom/grid.h"
#include "raster/micropolygon.h"
#include "raster/sample_kernels.h"

namespace streyes {

using namespace micropolygon;

// ---- Projection ----------------------------------------------------------------------------------

void GridRasterizer::project(const Grid& grid, double t, const Camera& camera, std::vector<RasterVertex>& out,
                             std::vector<Vec3f>* cameraOut) const {
    const size_t n = size_t(grid.vertexCount());
    out.resize(n);
    if (cameraOut) cameraOut->resize(n);
    float s = 0;
    if (grid.moving) {
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

// Is the sample at fraction tf of the exposure inside the part [tfA, tfB] a grid covers, open at
// tfB when the grid ends there half-open?
inline bool inTimeSpan(float tf, float tfA, float tfB, bool openB) {
    return tf >= tfA && (tf < tfB || (tf == tfB && !openB));
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
    if (grid.moving) {
        for (const Slice& sl : slices_) block.needTimes(sl.fi);
    } else {
        for (const FrameSpan& fr : frames_)
            if (!fr.whole) block.needTimes(fr.fi);
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

namespace {

// The hit of a triangle at a sample, when it beats `cur` (nearer, or equal depth and an earlier
// primitive: SampleHit::beatenBy) and lies inside the clipping range: then *out is the new hit.
// Depth first, colour only for a hit that passes the depth test.
template <typename ColorAt>
[[gnu::always_inline]] inline bool beats(const SampleHit& cur, const float* z, const Hit& h, float nearZ, float farZ,
                                         uint64_t id, ColorAt colorAt, SampleHit* out) {
    const float zh = z[h.v0] + h.l1 * (z[h.v1] - z[h.v0]) + h.l2 * (z[h.v2] - z[h.v0]);
    if (!(zh >= nearZ && zh <= farZ && zh <= cur.z)) return false;
    // Relative to the first corner: exact where depth or colour is constant.
    const Color c0 = colorAt(h.v0), c1 = colorAt(h.v1), c2 = colorAt(h.v2);
    const Color c = c0 + (c1 - c0) * h.l1 + (c2 - c0) * h.l2;
    if (zh == cur.z && !cur.beatenBy(zh, id, c)) return false;
    *out = {zh, c, 1.0f, id};
    return true;
}

// The fragment of a see-through triangle at a sample, when it is nearer than the sample's opaque
// hit `cur` (or beats it at equal depth) and inside the clipping range.
template <typename ColorAt, typename OpacityAt>
inline bool fragmentBeats(const SampleHit& cur, const float* z, const Hit& h, float nearZ, float farZ, uint64_t id,
                          ColorAt colorAt, OpacityAt opacityAt, SampleFragment* out) {
    SampleHit hit;
    if (!beats(cur, z, h, nearZ, farZ, id, colorAt, &hit)) return false;
    const Color o0 = opacityAt(h.v0), o1 = opacityAt(h.v1), o2 = opacityAt(h.v2);
    const Color o = o0 + (o1 - o0) * h.l1 + (o2 - o0) * h.l2;
    *out = {hit.z, hit.c, {std::clamp(o.x, 0.0f, 1.0f), std::clamp(o.y, 0.0f, 1.0f), std::clamp(o.z, 0.0f, 1.0f)}, id, -1};
    return true;
}

// Keeps a fragment that frame fi alone sees at sample sj of pixel pi: in the frame's record of the
// pixel, made for it when missing (so the frame resolves the pixel itself). Its index.
inline int32_t keepFrameFragment(ImageBlock& block, int fi, size_t pi, int sj, const SampleFragment& f, SampleHit*& rec) {
    if (!rec) rec = block.makeRecord(fi, pi);
    block.startFragments();
    return block.addFragment(block.recordFragments(fi, pi) + sj, f);
}

enum class QuadOpacity { Opaque, SeeThrough, Clear };

// How a quad's corners idx[] (in either slot of a moving grid: oi1, ci1 non-null) let light through.
// Missing opacities (null oi) are 1.
inline QuadOpacity quadOpacity(const Color* oi0, const Color* oi1, const Color* ci0, const Color* ci1, const int* idx) {
    bool opaque = true, clear = true;
    auto look = [&](const Color* oi, const Color* ci) {
        for (int c = 0; c < 4; ++c) {
            const Color o = oi ? oi[idx[c]] : Color{1, 1, 1}, col = ci[idx[c]];
            opaque = opaque && o.x >= 1 && o.y >= 1 && o.z >= 1;
            clear = clear && o.x == 0 && o.y == 0 && o.z == 0 && col.x == 0 && col.y == 0 && col.z == 0;
        }
    };
    look(oi0, ci0);
    if (ci1) look(oi1, ci1);
    return opaque ? QuadOpacity::Opaque : clear ? QuadOpacity::Clear : QuadOpacity::SeeThrough;
}

// A grid's opacities at slot k, or null where the slot was shaded opaque.
inline const Color* opacities(const Grid& grid, int k) {
    return grid.Oi[k].size() == size_t(grid.vertexCount()) ? grid.Oi[k].data() : nullptr;
}

// With the hit, the K contributions of lights that cast shadows, interpolated the same way.
template <typename PartAt>
inline void writeShadowed(Color* out, int K, const Hit& h, PartAt partAt) {
    for (int k = 0; k < K; ++k) {
        const Color c0 = partAt(h.v0, k), c1 = partAt(h.v1, k), c2 = partAt(h.v2, k);
        out[k] = c0 + (c1 - c0) * h.l1 + (c2 - c0) * h.l2;
    }
}

// With the hit, the A output variables (util/aov.h), interpolated as the colour is.
template <typename AovAt>
inline void writeAovs(float* out, int A, const Hit& h, AovAt aovAt) {
    for (int a = 0; a < A; ++a) {
        const float a0 = aovAt(h.v0, a), a1 = aovAt(h.v1, a), a2 = aovAt(h.v2, a);
        out[a] = a0 + (a1 - a0) * h.l1 + (a2 - a0) * h.l2;
    }
}

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

// Whether every sample of pixel pi in frame fi already sees something nearer than zmin. The
// pixel's farthest bound (ImageBlock::farthestBound) says so without reading its hits; a stale one
// (negative: its farthest sample came nearer since) is measured again only when it fails.
inline bool pixelBehind(ImageBlock& block, int fi, size_t pi, float zmin, int S) {
    float& bound = block.farthestBound(fi, pi);
    if (bound < 0 && !(zmin > -bound)) {
        const SampleHit* seen = block.hits(fi, pi);
        bound = seen[0].z;
        for (int k = 1; k < S; ++k) bound = std::max(bound, seen[k].z);
    }
    return zmin > std::fabs(bound);
}

// The margin a quad's bound grows by: the circle of confusion over its depths with depth of
// field (Lens), nothing without.
template <bool Lens>
inline auto lensMargin(const Camera& camera) {
    const Camera* cam = &camera;  // by pointer: unused without a lens, and a lambda capture would warn
    return [cam](float zmin, float zmax) {
        if constexpr (Lens) {
            const float e = cam->eyePlane();
            return cam->cocMargin(std::max(zmin, e), std::max(zmax, e));
        }
        (void)cam;
        return Vec2f{0, 0};
    };
}

// The quad `q` as the lens point (lu, lv) sees it: each vertex moved by its raster lens shift
// (sx[c] lu, sy[c] lv). False when the sample (x, y) is outside the moved quad's bound (then the
// edges are not set up).
inline bool lensQuad(const QuadSetup& q, const float* sx, const float* sy, float lu, float lv, float x, float y,
                     QuadSetup& out) {
    for (int c = 0; c < 4; ++c) {
        out.x[c] = q.x[c] + sx[c] * lu;
        out.y[c] = q.y[c] + sy[c] * lv;
        out.z[c] = q.z[c];
    }
    const float x0 = std::min({out.x[0], out.x[1], out.x[2], out.x[3]});
    const float x1 = std::max({out.x[0], out.x[1], out.x[2], out.x[3]});
    const float y0 = std::min({out.y[0], out.y[1], out.y[2], out.y[3]});
    const float y1 = std::max({out.y[0], out.y[1], out.y[2], out.y[3]});
    if (!(x >= x0 && x <= x1 && y >= y0 && y <= y1)) return false;
    setupEdges(out);
    return true;
}

// The raster lens shifts of a quad's corners per unit lens coordinate.
inline void lensShifts(const Camera& camera, const float* z, float* sx, float* sy) {
    for (int c = 0; c < 4; ++c) {
        const float s = camera.lensShift(std::max(z[c], camera.eyePlane()));
        sx[c] = s * camera.ax();
        sy[c] = s * camera.ay();
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
    bool intoStill = !block.dense() && int(frames_.size()) == F;
    for (const FrameSpan& fr : frames_) intoStill = intoStill && fr.whole;
    project(grid, grid.t0, camera, ra_);
    const float* xs = block.xs();
    const float* ys = block.ys();
    const float *lus = block.lus(), *lvs = block.lvs();
    const Color* ci = grid.Ci[0].data();
    const bool flat = grid.flatShading;  // ShadingInterpolation "constant": the first corner's colour
    const int K = grid.shadowSlots;
    const Color* cl = grid.Cl[0].data();
    const int A = grid.aovCount;
    const float* av = grid.aov[0].data();
    const uint64_t id = grid.primitiveId;
    const Color* oi = opacities(grid, 0);
    // The kernel: SIMD, or scalar while counting hits for tests of watertightness (the counting
    // instance runs the scalar reference: the kernels are held to it bit for bit).
    const QuadTestFn test = Counting ? quadTestScalar() : quadTestKernel();
    const SampleLayout layout{xs, ys, R.x0, R.y0, R.width(), S, sx, sy};
    uint64_t tests = 0, hits = 0, firstHits = 0, fragments = 0;
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            if (hole && hole[j * nu + i]) continue;  // trimmed away
            const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
            const QuadOpacity opacity = oi ? quadOpacity(oi, nullptr, ci, nullptr, idx) : QuadOpacity::Opaque;
            if (!Counting && opacity == QuadOpacity::Clear) continue;
            const bool seeThrough = opacity != QuadOpacity::Opaque;
            QuadSetup q;
            for (int c = 0; c < 4; ++c) {
                const RasterVertex& v = ra_[size_t(idx[c])];
                q.x[c] = v.x, q.y[c] = v.y, q.z[c] = v.z;
            }
            if (!boundQuad(q, nullptr, nullptr, nullptr, R, nearZ, farZ, lensMargin<Lens>(camera))) continue;
            if (!Counting && intoStill && behindStillLayer(block, q)) continue;
            auto colorAt = [&](int c) { return ci[idx[flat ? 0 : c]]; };
            auto opacityAt = [&](int c) { return oi[idx[flat ? 0 : c]]; };
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
                        block.startFragments();
                        block.addFragment(block.stillFragments(pi) + sj, frag);
                        ++fragments;
                        return;
                    }
                    if (!beats(cur, q.z, h, nearZ, farZ, id, colorAt, &hit)) return;
                    if (cur.a == 0) firstHits += uint64_t(F);  // a first hit in every frame
                    cur = hit;
                    float* stillAov = A ? block.stillAov(pi) + size_t(sj) * size_t(A) : nullptr;
                    if (A) writeAovs(stillAov, A, h, [&](int c, int a) { return av[size_t(idx[c]) * size_t(A) + size_t(a)]; });
                    // Frames that already have a record of the pixel (something only they see came
                    // first) see this too, where it is nearer.
                    for (int fi = 0, left = block.recordsOf(pi); left > 0; ++fi) {
                        SampleHit* rec = block.record(fi, pi);
                        if (!rec) continue;
                        --left;
                        if (!rec[sj].beatenBy(hit.z, hit.id, hit.c)) continue;
                        rec[sj] = hit;
                        if (A) std::copy(stillAov, stillAov + A, block.recordAov(fi, pi) + size_t(sj) * size_t(A));
                    }
                    return;
                }
                // The frames it exists in at the sample's time (the position, and so the inside
                // test, is the same in every frame).
                for (const FrameSpan& fr : frames_) {
                    if (!fr.whole && !inTimeSpan(block.sampleTime(fr.fi, pi, sj), fr.tfA, fr.tfB, fr.openB)) continue;
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
                        const int32_t fk = keepFrameFragment(block, fr.fi, pi, sj, frag, rec);
                        ++fragments;
                        if (Shadowed)
                            writeShadowed(block.fragmentShadowed(fk), K, h,
                                          [&](int c, int k) { return cl[size_t(idx[flat ? 0 : c] * K + k)]; });
                        continue;
                    }
                    if (!beats(cur, q.z, h, nearZ, farZ, id, colorAt, &hit)) continue;
                    firstHits += cur.a == 0;
                    if (!rec) rec = block.makeRecord(fr.fi, pi);
                    rec[sj] = hit;
                    if (A)
                        writeAovs(block.recordAov(fr.fi, pi) + size_t(sj) * size_t(A), A, h,
                                  [&](int c, int a) { return av[size_t(idx[c]) * size_t(A) + size_t(a)]; });
                    if (Shadowed)
                        writeShadowed(block.shadowed(fr.fi, pi) + size_t(sj) * size_t(K), K, h,
                                      [&](int c, int k) { return cl[size_t(idx[flat ? 0 : c] * K + k)]; });
                }
            };
            if constexpr (Lens) {
                // Every sample of the pixels of the grown bound, against the quad its lens point sees.
                float shx[4], shy[4];
                lensShifts(camera, q.z, shx, shy);
                for (int py = q.py0; py <= q.py1; ++py)
                    for (int px = q.px0; px <= q.px1; ++px) {
                        const size_t pi = block.pixelIndex(px, py);
                        for (int sj = 0; sj < S; ++sj) {
                            const size_t si = pi * size_t(S) + size_t(sj);
                            const float x = xs[si], y = ys[si];
                            if (x < q.xmin || x > q.xmax || y < q.ymin || y > q.ymax) continue;
                            ++tests;
                            QuadSetup ql;
                            Hit h;
                            if (!lensQuad(q, shx, shy, lus[si], lvs[si], x, y, ql) || !hitQuad(ql, x, y, h)) continue;
                            onHit(pi, sj, h, ql);
                        }
                    }
            } else {
                setupEdges(q);
                // The samples of the strata the bound overlaps in each pixel, tested at once (SIMD).
                const size_t room = size_t(q.px1 - q.px0 + 1) * size_t(q.py1 - q.py0 + 1) * size_t(S);
                if (quadHits_.size() < room) quadHits_.resize(room);
                size_t found = 0;
                tests += test(q, layout, quadHits_.data(), &found);
                for (size_t n = 0; n < found; ++n) {
                    const QuadHit& qh = quadHits_[n];
                    onHit(qh.pixel, qh.sample, quadHit(qh), q);
                }
            }
        }
    }
    counters.sampleTests += tests;
    counters.sampleHits += hits;
    counters.firstHits += firstHits;
    counters.fragments += fragments;
}

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

}  // namespace streyes
