#include "raster/rasterizer.h"

#include <algorithm>
#include <cmath>

#include "geom/grid.h"

namespace streyes {

// ---- The micropolygon hit test ----------------------------------------------------------------
// A quad q0 q1 q2 q3 (grid order (0,0) (1,0) (1,1) (0,1)) is two triangles, (q0 q1 q2) and
// (q0 q2 q3), sharing the diagonal q0-q2. Its five edges are set up once in canonical form
// (lexicographically smaller endpoint first), so an edge shared with a neighbouring micropolygon,
// or the diagonal shared by the two triangles, gives exactly opposite values on its two sides.

namespace {

struct Edge {
    float px, py, dx, dy;  // canonical start point and direction
    float sign;            // +1 when the quad runs along the edge in canonical direction, else -1
    bool canonical;
    float eval(float sx, float sy) const { return sign * (dx * (sy - py) - dy * (sx - px)); }
};

inline Edge makeEdge(float ax, float ay, float bx, float by) {
    bool canonical = ax < bx || (ax == bx && ay < by);
    if (canonical) return {ax, ay, bx - ax, by - ay, 1.0f, true};
    return {bx, by, ax - bx, ay - by, -1.0f, false};
}

// A sample exactly on an edge belongs to the side where the canonical edge function is
// positive: the side it would fall on if nudged by (-e^2, e).
inline bool edgeInside(float e, bool canonical, float orientation) {
    float g = e * orientation;
    if (g != 0) return g > 0;
    return canonical ? orientation > 0 : orientation < 0;
}

// Inside test for a triangle given its three directed edge values; works for either
// orientation; a zero-area triangle contains nothing.
inline bool insideTriangle(float e0, bool c0, float e1, bool c1, float e2, bool c2) {
    bool anyPos = e0 > 0 || e1 > 0 || e2 > 0;
    bool anyNeg = e0 < 0 || e1 < 0 || e2 < 0;
    if (anyPos == anyNeg) return false;  // mixed signs: outside; all zero: degenerate
    float o = anyPos ? 1.0f : -1.0f;
    return edgeInside(e0, c0, o) && edgeInside(e1, c1, o) && edgeInside(e2, c2, o);
}

struct QuadSetup {
    float x[4], y[4], z[4];
    Edge e[5];  // q0q1, q1q2, q2q3, q3q0, q2q0 (the diagonal as triangle 1 runs it)
    float xmin, xmax, ymin, ymax;
    int px0, px1, py0, py1;  // pixels the bound touches, clipped to the block
};


inline void setupEdges(QuadSetup& q) {
    q.e[0] = makeEdge(q.x[0], q.y[0], q.x[1], q.y[1]);
    q.e[1] = makeEdge(q.x[1], q.y[1], q.x[2], q.y[2]);
    q.e[2] = makeEdge(q.x[2], q.y[2], q.x[3], q.y[3]);
    q.e[3] = makeEdge(q.x[3], q.y[3], q.x[0], q.y[0]);
    q.e[4] = makeEdge(q.x[2], q.y[2], q.x[0], q.y[0]);
}

struct Hit {
    int v0, v1, v2;  // corners of the triangle hit (0..3)
    float l1, l2;    // barycentric weights of v1 and v2
};

inline bool hitQuad(const QuadSetup& q, float sx, float sy, Hit& h) {
    const float e01 = q.e[0].eval(sx, sy), e12 = q.e[1].eval(sx, sy), e20 = q.e[4].eval(sx, sy);
    const bool diagDegenerate = q.e[4].dx == 0 && q.e[4].dy == 0;
    if (insideTriangle(e01, q.e[0].canonical, e12, q.e[1].canonical, e20, q.e[4].canonical)) {
        float inv = 1.0f / (e01 + e12 + e20);
        h = {0, 1, 2, e20 * inv, e01 * inv};  // weight of q1 is its opposite edge q2q0, of q2 is q0q1
        return true;
    }
    // Triangle 2 runs the diagonal the other way: exactly -e20, the opposite canonical flag.
    const float e02 = -e20, e23 = q.e[2].eval(sx, sy), e30 = q.e[3].eval(sx, sy);
    const bool c02 = diagDegenerate ? false : !q.e[4].canonical;
    if (insideTriangle(e02, c02, e23, q.e[2].canonical, e30, q.e[3].canonical)) {
        float inv = 1.0f / (e02 + e23 + e30);
        h = {0, 2, 3, e30 * inv, e02 * inv};  // q2 is opposite q3q0, q3 opposite q0q2
        return true;
    }
    return false;
}

// How many of the quad's two triangles hold the sample (2 where a quad folded along its
// diagonal at a silhouette covers it twice), and their windings summed (+1 for a triangle that
// runs one way round in raster space, -1 the other). Rendering takes one hit per quad; tests of
// watertightness count coverage (GridRasterizer::countHitsInto).
inline void trianglesCovering(const QuadSetup& q, float sx, float sy, uint32_t* count, int32_t* winding) {
    const float e01 = q.e[0].eval(sx, sy), e12 = q.e[1].eval(sx, sy), e20 = q.e[4].eval(sx, sy);
    const float e23 = q.e[2].eval(sx, sy), e30 = q.e[3].eval(sx, sy);
    const bool c02 = q.e[4].dx == 0 && q.e[4].dy == 0 ? false : !q.e[4].canonical;
    if (insideTriangle(e01, q.e[0].canonical, e12, q.e[1].canonical, e20, q.e[4].canonical)) {
        ++*count;
        *winding += e01 + e12 + e20 > 0 ? 1 : -1;
    }
    if (insideTriangle(-e20, c02, e23, q.e[2].canonical, e30, q.e[3].canonical)) {
        ++*count;
        *winding += -e20 + e23 + e30 > 0 ? 1 : -1;
    }
}

// Bound and pixel range of a quad; false when it misses the block or the clipping range.
inline bool boundQuad(QuadSetup& q, const float* x2, const float* y2, const float* z2, const PixelRect& R,
                      float nearZ, float farZ) {
    float zmin = q.z[0], zmax = q.z[0];
    q.xmin = q.xmax = q.x[0];
    q.ymin = q.ymax = q.y[0];
    for (int c = 0; c < 4; ++c) {
        q.xmin = std::min(q.xmin, q.x[c]), q.xmax = std::max(q.xmax, q.x[c]);
        q.ymin = std::min(q.ymin, q.y[c]), q.ymax = std::max(q.ymax, q.y[c]);
        zmin = std::min(zmin, q.z[c]), zmax = std::max(zmax, q.z[c]);
        if (x2) {  // the corners at the other end of a time slice
            q.xmin = std::min(q.xmin, x2[c]), q.xmax = std::max(q.xmax, x2[c]);
            q.ymin = std::min(q.ymin, y2[c]), q.ymax = std::max(q.ymax, y2[c]);
            zmin = std::min(zmin, z2[c]), zmax = std::max(zmax, z2[c]);
        }
    }
    if (zmax < nearZ || zmin > farZ) return false;
    if (!(q.xmax >= float(R.x0) && q.xmin < float(R.x1 + 1) && q.ymax >= float(R.y0) && q.ymin < float(R.y1 + 1)))
        return false;  // also rejects NaN
    q.px0 = floorClamped(q.xmin, R.x0, R.x1);
    q.px1 = floorClamped(q.xmax, R.x0, R.x1);
    q.py0 = floorClamped(q.ymin, R.y0, R.y1);
    q.py1 = floorClamped(q.ymax, R.y0, R.y1);
    return true;
}

}  // namespace

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
    const int K = block.slices();
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

void GridRasterizer::rasterize(const Grid& grid, const Camera& camera, const Shutter& shutter, ImageBlock& block,
                               RasterCounters& counters) {
    counters.micropolygons += uint64_t(grid.nu) * uint64_t(grid.nv);
    if (grid.moving) {
        collectSlices(grid, shutter, block);
        if (slices_.empty()) return;
        if (grid.shadowSlots) sampleMoving<true>(grid, camera, block, counters);
        else sampleMoving<false>(grid, camera, block, counters);
    } else {
        collectFrames(grid, shutter, block);
        if (frames_.empty()) return;
        if (grid.shadowSlots) sampleStill<true>(grid, camera, block, counters);
        else sampleStill<false>(grid, camera, block, counters);
    }
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

// Writes a hit into the sample when it beats the one there (nearer, or equal depth and an
// earlier primitive: see SampleHit::beatenBy). Returns 0 when it does not, 1 when it does, 2
// when it does and the sample had no hit before.
template <typename ColorAt>
static inline int resolveHit(SampleHit& s, const float* z, const Hit& h, float nearZ, float farZ, uint64_t id,
                             ColorAt colorAt) {
    const float zh = z[h.v0] + h.l1 * (z[h.v1] - z[h.v0]) + h.l2 * (z[h.v2] - z[h.v0]);
    if (!(zh >= nearZ && zh <= farZ && zh <= s.z)) return 0;
    // Relative to the first corner: exact where depth or colour is constant.
    const Color c0 = colorAt(h.v0), c1 = colorAt(h.v1), c2 = colorAt(h.v2);
    const Color c = c0 + (c1 - c0) * h.l1 + (c2 - c0) * h.l2;
    if (zh == s.z && !s.beatenBy(zh, id, c)) return 0;
    const int first = s.a == 0 ? 2 : 1;
    s.z = zh;
    s.c = c;
    s.a = 1.0f;
    s.id = id;
    return first;
}

// With the hit, the K contributions of lights that cast shadows, interpolated the same way.
template <typename PartAt>
static inline void writeShadowed(Color* out, int K, const Hit& h, PartAt partAt) {
    for (int k = 0; k < K; ++k) {
        const Color c0 = partAt(h.v0, k), c1 = partAt(h.v1, k), c2 = partAt(h.v2, k);
        out[k] = c0 + (c1 - c0) * h.l1 + (c2 - c0) * h.l2;
    }
}

// A still grid: each quad is projected and set up once, then tested against the samples of
// every frame it exists in, visiting in each pixel only the (x, y) strata its bound overlaps.
template <bool Shadowed>
void GridRasterizer::sampleStill(const Grid& grid, const Camera& camera, ImageBlock& block, RasterCounters& counters) {
    const PixelRect& R = block.rect();
    const int nu = grid.nu, nv = grid.nv, stride = nu + 1, S = block.slices();
    const int sx = block.pattern().sx, sy = block.pattern().sy;
    const float nearZ = camera.nearClip(), farZ = camera.farClip();
    project(grid, grid.t0, camera, ra_);
    const SamplePosition* pos = block.positions();
    SampleHit* hit = block.hits();
    const Color* ci = grid.Ci[0].data();
    const int K = grid.shadowSlots;
    const Color* cl = grid.Cl[0].data();
    uint64_t tests = 0, hits = 0, firstHits = 0;
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
            QuadSetup q;
            for (int c = 0; c < 4; ++c) {
                const RasterVertex& v = ra_[size_t(idx[c])];
                q.x[c] = v.x, q.y[c] = v.y, q.z[c] = v.z;
            }
            if (!boundQuad(q, nullptr, nullptr, nullptr, R, nearZ, farZ)) continue;
            setupEdges(q);
            for (int py = q.py0; py <= q.py1; ++py) {
                const int iy0 = floorClamped((q.ymin - float(py)) * float(sy), 0, sy - 1);
                const int iy1 = floorClamped((q.ymax - float(py)) * float(sy), 0, sy - 1);
                for (int px = q.px0; px <= q.px1; ++px) {
                    const int ix0 = floorClamped((q.xmin - float(px)) * float(sx), 0, sx - 1);
                    const int ix1 = floorClamped((q.xmax - float(px)) * float(sx), 0, sx - 1);
                    const size_t base = block.pixelOffset(px, py);
                    for (const FrameSpan& fr : frames_) {
                        const size_t fb = base + size_t(fr.fi) * size_t(S);
                        for (int iy = iy0; iy <= iy1; ++iy) {
                            for (int ix = ix0; ix <= ix1; ++ix) {
                                const size_t si = fb + size_t(iy * sx + ix);
                                const SamplePosition& s = pos[si];
                                if (s.x < q.xmin || s.x > q.xmax || s.y < q.ymin || s.y > q.ymax) continue;
                                if (!fr.whole && !inTimeSpan(s.tf, fr.tfA, fr.tfB, fr.openB)) continue;
                                ++tests;
                                Hit h;
                                if (!hitQuad(q, s.x, s.y, h)) continue;
                                ++hits;
                                if (hitCounts_) trianglesCovering(q, s.x, s.y, &hitCounts_[si], &windings_[si]);
                                const int r = resolveHit(hit[si], q.z, h, nearZ, farZ, grid.primitiveId,
                                                         [&](int c) { return ci[idx[c]]; });
                                firstHits += r == 2;
                                if (Shadowed && r)
                                    writeShadowed(block.shadowed(si), K, h,
                                                  [&](int c, int k) { return cl[size_t(idx[c] * K + k)]; });
                            }
                        }
                    }
                }
            }
        }
    }
    counters.sampleTests += tests;
    counters.sampleHits += hits;
    counters.firstHits += firstHits;
}

// A moving grid: projected at both ends of each slice to bound its quads over the slice; a
// sample's quad is the quad at the sample's time. Orthographic projection is linear, so that is
// the raster quad interpolated linearly. Perspective is not: interpolating raster positions would
// move a vertex that lies on a neighbouring grid's edge (a T-junction, where grids split to
// different depths meet) off that edge, and open cracks between the grids. So under perspective
// the corners are interpolated in camera space, where they move linearly, and projected at the
// sample's time: vertices on a straight edge stay on its projection.
template <bool Shadowed>
void GridRasterizer::sampleMoving(const Grid& grid, const Camera& camera, ImageBlock& block,
                                  RasterCounters& counters) {
    const PixelRect& R = block.rect();
    const int nu = grid.nu, nv = grid.nv, stride = nu + 1;
    const bool perspective = camera.perspective();
    const float nearZ = camera.nearClip(), farZ = camera.farClip();
    const double span = grid.t1 - grid.t0;
    const Color *ci0 = grid.Ci[0].data(), *ci1 = grid.Ci[1].data();
    const int K = grid.shadowSlots;
    const Color *cl0 = grid.Cl[0].data(), *cl1 = grid.Cl[1].data();
    double projected = std::numeric_limits<double>::quiet_NaN();  // the time rb_ holds
    uint64_t tests = 0, hits = 0, firstHits = 0;
    for (const Slice& sl : slices_) {
        if (projected == sl.ta) {  // the last slice ended where this one starts
            std::swap(ra_, rb_);
            std::swap(ca_, cb_);
        } else {
            project(grid, sl.ta, camera, ra_, perspective ? &ca_ : nullptr);
        }
        project(grid, sl.tb, camera, rb_, perspective ? &cb_ : nullptr);
        projected = sl.tb;
        const float sA = float((sl.ta - grid.t0) / span), sB = float((sl.tb - grid.t0) / span);
        const float invSpan = sl.tfB > sl.tfA ? 1.0f / (sl.tfB - sl.tfA) : 0.0f;
        for (int j = 0; j < nv; ++j) {
            for (int i = 0; i < nu; ++i) {
                const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
                QuadSetup q;
                float xb[4], yb[4], zb[4];
                for (int c = 0; c < 4; ++c) {
                    const RasterVertex &a = ra_[size_t(idx[c])], &b = rb_[size_t(idx[c])];
                    q.x[c] = a.x, q.y[c] = a.y, q.z[c] = a.z;
                    xb[c] = b.x, yb[c] = b.y, zb[c] = b.z;
                }
                if (!boundQuad(q, xb, yb, zb, R, nearZ, farZ)) continue;
                const float xa[4] = {q.x[0], q.x[1], q.x[2], q.x[3]}, ya[4] = {q.y[0], q.y[1], q.y[2], q.y[3]},
                            za[4] = {q.z[0], q.z[1], q.z[2], q.z[3]};
                for (int py = q.py0; py <= q.py1; ++py) {
                    for (int px = q.px0; px <= q.px1; ++px) {
                        const size_t si = block.sliceIndex(sl.fi, sl.k, px, py);
                        const SamplePosition& s = block.positions()[si];
                        if (s.x < q.xmin || s.x > q.xmax || s.y < q.ymin || s.y > q.ymax) continue;
                        if (sl.checkTime && !inTimeSpan(s.tf, sl.tfA, sl.tfB, sl.openB)) continue;
                        ++tests;
                        const float w = std::min(1.0f, std::max(0.0f, (s.tf - sl.tfA) * invSpan));
                        QuadSetup qt;
                        if (perspective) {
                            for (int c = 0; c < 4; ++c) {
                                const Vec3f r = camera.toRaster(lerp(ca_[size_t(idx[c])], cb_[size_t(idx[c])], w));
                                qt.x[c] = r.x, qt.y[c] = r.y, qt.z[c] = r.z;
                            }
                        } else {
                            for (int c = 0; c < 4; ++c) {
                                qt.x[c] = lerp(xa[c], xb[c], w);
                                qt.y[c] = lerp(ya[c], yb[c], w);
                                qt.z[c] = lerp(za[c], zb[c], w);
                            }
                        }
                        setupEdges(qt);
                        Hit h;
                        if (!hitQuad(qt, s.x, s.y, h)) continue;
                        ++hits;
                        if (hitCounts_) trianglesCovering(qt, s.x, s.y, &hitCounts_[si], &windings_[si]);
                        const float sg = lerp(sA, sB, w);  // the grid's own time parameter
                        const int r = resolveHit(block.hits()[si], qt.z, h, nearZ, farZ, grid.primitiveId,
                                                 [&](int c) { return lerp(ci0[idx[c]], ci1[idx[c]], sg); });
                        firstHits += r == 2;
                        if (Shadowed && r)
                            writeShadowed(block.shadowed(si), K, h, [&](int c, int k) {
                                const size_t i = size_t(idx[c] * K + k);
                                return lerp(cl0[i], cl1[i], sg);
                            });
                    }
                }
            }
        }
    }
    counters.sampleTests += tests;
    counters.sampleHits += hits;
    counters.firstHits += firstHits;
}

}  // namespace streyes
