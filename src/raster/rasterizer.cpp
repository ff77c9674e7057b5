#include "streyes/rasterizer.h"

#include <algorithm>
#include <cmath>

#include "streyes/grid.h"

namespace streyes {

namespace {

struct V2 {
    float x, y, z;
};

// Edge function of the directed edge p->q at (sx, sy), computed in the canonical direction of
// the edge (lexicographically smaller endpoint first) and negated when p->q runs the other way:
// the two triangles that share an edge see exactly opposite values.
inline float edgeFn(const V2& p, const V2& q, float sx, float sy, bool& canonical) {
    canonical = p.x < q.x || (p.x == q.x && p.y < q.y);
    if (canonical) return (q.x - p.x) * (sy - p.y) - (q.y - p.y) * (sx - p.x);
    return -((p.x - q.x) * (sy - q.y) - (p.y - q.y) * (sx - q.x));
}

// A sample exactly on an edge belongs to the side where the canonical edge function is
// positive: the side the sample would fall on if nudged by (-e^2, e).
inline bool edgeInside(float e, bool canonical, float orientation) {
    float g = e * orientation;
    if (g != 0) return g > 0;
    return canonical ? orientation > 0 : orientation < 0;
}

// Inside test with barycentric weights (of a, b, c). Works for either orientation; a
// zero-area triangle contains nothing.
inline bool insideTriangle(const V2& a, const V2& b, const V2& c, float sx, float sy, float& la, float& lb,
                           float& lc) {
    bool cab, cbc, cca;
    float eab = edgeFn(a, b, sx, sy, cab);
    float ebc = edgeFn(b, c, sx, sy, cbc);
    float eca = edgeFn(c, a, sx, sy, cca);
    bool anyPos = eab > 0 || ebc > 0 || eca > 0;
    bool anyNeg = eab < 0 || ebc < 0 || eca < 0;
    if (anyPos == anyNeg) return false;  // mixed signs: outside; all zero: degenerate
    float orientation = anyPos ? 1.0f : -1.0f;
    if (!edgeInside(eab, cab, orientation) || !edgeInside(ebc, cbc, orientation) ||
        !edgeInside(eca, cca, orientation))
        return false;
    float inv = 1.0f / (eab + ebc + eca);
    la = ebc * inv;
    lb = eca * inv;
    lc = eab * inv;
    return true;
}

}  // namespace

void GridRasterizer::project(const Grid& grid, double t, const Camera& camera,
                             std::vector<RasterVertex>& out) const {
    const size_t n = size_t(grid.vertexCount());
    out.resize(n);
    if (!grid.moving) {
        for (size_t i = 0; i < n; ++i) {
            Vec3f r = camera.toRaster(grid.P[0][i]);
            out[i] = {r.x, r.y, r.z};
        }
        return;
    }
    float s = float((t - grid.t0) / (grid.t1 - grid.t0));
    if (t <= grid.t0) s = 0;
    if (t >= grid.t1) s = 1;
    for (size_t i = 0; i < n; ++i) {
        Vec3f r = camera.toRaster(lerp(grid.P[0][i], grid.P[1][i], s));
        out[i] = {r.x, r.y, r.z};
    }
}

void GridRasterizer::rasterize(const Grid& grid, const Camera& camera, const Shutter& shutter, ImageBlock& block,
                               RasterCounters& counters) {
    counters.micropolygons += uint64_t(grid.nu) * uint64_t(grid.nv);
    const double d = shutter.close - shutter.open;
    const int K = block.slices();
    if (!grid.moving) project(grid, grid.t0, camera, ra_);

    for (int fi = 0; fi < block.frameCount(); ++fi) {
        const double e0 = block.firstFrame() + fi + shutter.open, e1 = e0 + d;
        if (grid.t1 < e0 || grid.t0 > e1) continue;
        double projected = std::numeric_limits<double>::quiet_NaN();  // time rb_ holds
        for (int k = 0; k < K; ++k) {
            // Slice k of this frame's exposure, clipped to the grid's time span.
            const double sa = d > 0 ? e0 + d * k / K : e0;
            const double sb = d > 0 ? e0 + d * (k + 1) / K : e0;
            const double ta = std::max(sa, grid.t0), tb = std::min(sb, grid.t1);
            if (ta > tb) continue;
            const bool partial = d > 0 && (ta > sa || tb < sb);
            float tfA = float(k) / float(K), tfB = float(k + 1) / float(K);
            if (partial) {
                tfA = float((ta - e0) / d);
                tfB = float((tb - e0) / d);
            }
            if (!grid.moving) {
                sampleSlice<false>(grid, ra_.data(), ra_.data(), tfA, tfB, 0, 0, partial, fi, k, camera, block,
                                   counters);
                continue;
            }
            if (projected == ta) std::swap(ra_, rb_);  // the last slice ended where this one starts
            else project(grid, ta, camera, ra_);
            project(grid, tb, camera, rb_);
            projected = tb;
            const double span = grid.t1 - grid.t0;
            sampleSlice<true>(grid, ra_.data(), rb_.data(), tfA, tfB, float((ta - grid.t0) / span),
                              float((tb - grid.t0) / span), partial, fi, k, camera, block, counters);
        }
    }
}

template <bool Moving>
void GridRasterizer::sampleSlice(const Grid& grid, const RasterVertex* ra, const RasterVertex* rb, float tfA,
                                 float tfB, float sA, float sB, bool checkTime, int fi, int k,
                                 const Camera& camera, ImageBlock& block, RasterCounters& counters) {
    const PixelRect& R = block.rect();
    const int nu = grid.nu, nv = grid.nv, stride = nu + 1;
    const float nearZ = camera.nearClip(), farZ = camera.farClip();
    const float invSpan = tfB > tfA ? 1.0f / (tfB - tfA) : 0.0f;
    const Color* ci0 = grid.Ci[0].data();
    const Color* ci1 = Moving ? grid.Ci[1].data() : ci0;

    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            // Corners around the quad: (0,0) (1,0) (1,1) (0,1).
            const int idx[4] = {j * stride + i, j * stride + i + 1, (j + 1) * stride + i + 1, (j + 1) * stride + i};
            float xmin = ra[idx[0]].x, xmax = xmin, ymin = ra[idx[0]].y, ymax = ymin, zmin = ra[idx[0]].z,
                  zmax = zmin;
            for (int c = 0; c < 4; ++c) {
                for (int e = 0; e < (Moving ? 2 : 1); ++e) {
                    const RasterVertex& v = (e == 0 ? ra : rb)[idx[c]];
                    xmin = std::min(xmin, v.x), xmax = std::max(xmax, v.x);
                    ymin = std::min(ymin, v.y), ymax = std::max(ymax, v.y);
                    zmin = std::min(zmin, v.z), zmax = std::max(zmax, v.z);
                }
            }
            if (zmax < nearZ || zmin > farZ) continue;
            if (!(xmax >= float(R.x0) && xmin < float(R.x1 + 1) && ymax >= float(R.y0) && ymin < float(R.y1 + 1)))
                continue;  // also rejects NaN bounds
            const int px0 = std::max(R.x0, int(std::floor(xmin))), px1 = std::min(R.x1, int(std::floor(xmax)));
            const int py0 = std::max(R.y0, int(std::floor(ymin))), py1 = std::min(R.y1, int(std::floor(ymax)));

            for (int py = py0; py <= py1; ++py) {
                Sample* row = block.row(fi, k, py) - R.x0;
                for (int px = px0; px <= px1; ++px) {
                    Sample& s = row[px];
                    if (s.x < xmin || s.x > xmax || s.y < ymin || s.y > ymax) continue;
                    if (checkTime && (s.tf < tfA || s.tf > tfB)) continue;
                    ++counters.sampleTests;
                    V2 q[4];
                    float w = 0;
                    if (Moving) {
                        w = std::min(1.0f, std::max(0.0f, (s.tf - tfA) * invSpan));
                        for (int c = 0; c < 4; ++c) {
                            const RasterVertex &a = ra[idx[c]], &b = rb[idx[c]];
                            q[c] = {lerp(a.x, b.x, w), lerp(a.y, b.y, w), lerp(a.z, b.z, w)};
                        }
                    } else {
                        for (int c = 0; c < 4; ++c) q[c] = {ra[idx[c]].x, ra[idx[c]].y, ra[idx[c]].z};
                    }
                    float l0, l1, l2;
                    int v0 = 0, v1 = 1, v2 = 2;
                    if (!insideTriangle(q[0], q[1], q[2], s.x, s.y, l0, l1, l2)) {
                        if (!insideTriangle(q[0], q[2], q[3], s.x, s.y, l0, l1, l2)) continue;
                        v1 = 2;
                        v2 = 3;
                    }
                    ++counters.sampleHits;
                    // Relative to the first vertex: exact where depth or colour is constant.
                    (void)l0;
                    const float z = q[v0].z + l1 * (q[v1].z - q[v0].z) + l2 * (q[v2].z - q[v0].z);
                    if (!(z >= nearZ && z <= farZ && z < s.z)) continue;
                    Color c0 = ci0[idx[v0]], c1 = ci0[idx[v1]], c2 = ci0[idx[v2]];
                    if (Moving) {
                        const float sg = lerp(sA, sB, w);
                        c0 = lerp(c0, ci1[idx[v0]], sg);
                        c1 = lerp(c1, ci1[idx[v1]], sg);
                        c2 = lerp(c2, ci1[idx[v2]], sg);
                    }
                    s.z = z;
                    s.c = c0 + (c1 - c0) * l1 + (c2 - c0) * l2;
                    s.a = 1.0f;
                }
            }
        }
    }
}

template void GridRasterizer::sampleSlice<true>(const Grid&, const RasterVertex*, const RasterVertex*, float, float,
                                                float, float, bool, int, int, const Camera&, ImageBlock&,
                                                RasterCounters&);
template void GridRasterizer::sampleSlice<false>(const Grid&, const RasterVertex*, const RasterVertex*, float,
                                                 float, float, float, bool, int, int, const Camera&, ImageBlock&,
                                                 RasterCounters&);

}  // namespace streyes
