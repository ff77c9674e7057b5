// The scalar references of the sampler's SIMD kernels (sample_kernels.cpp): micropolygon.h's
// tests, sample by sample, in the order and with the operations the kernels are held to bit for
// bit (SampleKernels.* tests), and the path that counts hits for the watertightness tests.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "raster/sample_kernels.h"

namespace streyes {

namespace {

using namespace micropolygon;

// micropolygon.h's test of the sample (x, y) against the set-up quad q: its five edge values into
// edges[k * stride + j]; 1 when inside the first triangle, 2 the second, 0 neither. The scalar
// references below share it.
int scalarInside(const QuadSetup& q, float x, float y, float* edges, int stride, int j) {
    const bool c02 = q.e[4].dx == 0 && q.e[4].dy == 0 ? false : !q.e[4].canonical;
    float e[5];
    for (int k = 0; k < 5; ++k) edges[k * stride + j] = e[k] = q.e[k].eval(x, y);
    if (insideTriangle(e[0], q.e[0].canonical, e[1], q.e[1].canonical, e[4], q.e[4].canonical)) return 1;
    if (insideTriangle(-e[4], c02, e[2], q.e[2].canonical, e[3], q.e[3].canonical)) return 2;
    return 0;
}

// The bits of a sample that scalarInside put in the first or the second triangle.
void addInside(int inside, uint64_t bit, uint64_t& first, uint64_t& second) {
    if (inside == 1) first |= bit;
    if (inside == 2) second |= bit;
}

PixelTest scalarTest(const micropolygon::QuadSetup& q, const float* xs, const float* ys, int n, uint64_t candidates,
                     float* edges) {
    const int stride = edgeStride(n);
    PixelTest r;
    for (int j = 0; j < n; ++j) {
        if (!((candidates >> j) & 1)) continue;
        const float x = xs[j], y = ys[j];
        if (x < q.xmin || x > q.xmax || y < q.ymin || y > q.ymax) continue;
        const uint64_t bit = uint64_t(1) << j;
        r.tested |= bit;
        addInside(scalarInside(q, x, y, edges, stride, j), bit, r.first, r.second);
    }
    return r;
}

MovingTest scalarMovingTest(const MovingQuad& m, const float* xs, const float* ys, const float* tfs, const float* seenZ,
                             const float* lus, const float* lvs, int n, float* edges) {
    const int stride = edgeStride(n);
    MovingTest r;
    for (int j = 0; j < n; ++j) {
        const float x = xs[j], y = ys[j];
        if (x < m.xmin || x > m.xmax || y < m.ymin || y > m.ymax) continue;
        const uint64_t bit = uint64_t(1) << j;
        if (m.zmin > seenZ[j]) {
            r.behind |= bit;
            continue;
        }
        r.tested |= bit;
        QuadSetup q;
        if (!m.lens) movingQuadAt(m, movingWeight(m, tfs[j]), q);
        else if (!movingLensQuadAt(m, movingWeight(m, tfs[j]), lus[j], lvs[j], x, y, q)) continue;
        addInside(scalarInside(q, x, y, edges, stride, j), bit, r.first, r.second);
    }
    return r;
}

MovingTest scalarLensTest(const LensQuad& m, const float* xs, const float* ys, const float* lus, const float* lvs, int n,
                          float* edges) {
    const int stride = edgeStride(n);
    QuadSetup q;
    for (int c = 0; c < 4; ++c) q.x[c] = m.x[c], q.y[c] = m.y[c], q.z[c] = 0;
    MovingTest r;
    for (int j = 0; j < n; ++j) {
        const float x = xs[j], y = ys[j];
        if (x < m.xmin || x > m.xmax || y < m.ymin || y > m.ymax) continue;
        const uint64_t bit = uint64_t(1) << j;
        r.tested |= bit;
        QuadSetup l;
        if (!lensQuad(q, m.sx, m.sy, lus[j], lvs[j], x, y, l)) continue;
        addInside(scalarInside(l, x, y, edges, stride, j), bit, r.first, r.second);
    }
    return r;
}

uint64_t scalarQuadTest(const micropolygon::QuadSetup& q, const SampleLayout& L, const QuadShading* shading, QuadHit* out,
                        size_t* hitCount) {
    float edges[kMaxEdgeValues];
    uint64_t tested = 0;
    size_t hits = *hitCount;
    for (int py = q.py0; py <= q.py1; ++py) {
        const int iy0 = stratumAt(q.ymin, py, L.sy);
        const int iy1 = stratumAt(q.ymax, py, L.sy);
        for (int px = q.px0; px <= q.px1; ++px) {
            const int ix0 = stratumAt(q.xmin, px, L.sx);
            const int ix1 = stratumAt(q.xmax, px, L.sx);
            const uint32_t pixel = uint32_t((py - L.y0) * L.width + (px - L.x0));
            for (int c0 = 0; c0 < L.S; c0 += 64) {
                const int n = std::min(64, L.S - c0);
                uint64_t candidates = 0;
                for (int iy = iy0; iy <= iy1; ++iy) {
                    const int row = iy * L.sx - c0;
                    const int a = std::max(0, row + ix0), b = std::min(n - 1, row + ix1);
                    if (a <= b) candidates |= (b - a == 63 ? ~uint64_t(0) : ((uint64_t(2) << (b - a)) - 1)) << a;
                }
                const size_t base = size_t(pixel) * size_t(L.S) + size_t(c0);
                const PixelTest t = scalarTest(q, L.xs + base, L.ys + base, n, candidates, edges);
                tested += uint64_t(__builtin_popcountll(t.tested));
                for (uint64_t in = t.first | t.second; in; in &= in - 1) {
                    const int j = __builtin_ctzll(in);
                    QuadHit& h = out[hits++];
                    h.pixel = pixel;
                    h.sample = uint16_t(c0 + j);
                    h.first = uint8_t((t.first >> j) & 1);
                    const micropolygon::Hit b = pixelHit(edges, n, j, h.first);
                    h.l1 = b.l1;
                    h.l2 = b.l2;
                    if (shading) {
                        const int k = h.first ? 0 : 1;
                        h.z = shading->z0[k] + h.l1 * shading->dz1[k] + h.l2 * shading->dz2[k];
                        h.c = shading->c0[k] + shading->dc1[k] * h.l1 + shading->dc2[k] * h.l2;
                    }
                }
            }
        }
    }
    *hitCount = hits;
    return tested;
}

// StillWrite's rule, hit by hit, on quadTestScalar's hits (in their order; a quad's hits are of
// distinct samples, so the order does not change what is written).
uint64_t scalarQuadWrite(const micropolygon::QuadSetup& q, const SampleLayout& L, const QuadShading& shading,
                         StillWrite& w, QuadHit* out, size_t* left) {
    std::vector<QuadHit> found(size_t(q.px1 - q.px0 + 1) * size_t(q.py1 - q.py0 + 1) * size_t(L.S));
    size_t n = 0;
    const uint64_t tested = scalarQuadTest(q, L, &shading, found.data(), &n);
    for (size_t k = 0; k < n; ++k) {
        const QuadHit& h = found[k];
        ++w.inside;
        SampleHit& cur = w.still[size_t(h.pixel) * size_t(L.S) + h.sample];
        if (!(h.z >= w.nearZ && h.z <= w.farZ && h.z <= cur.z)) continue;  // clipped or hidden
        if (h.z == cur.z || (w.recordsOf && w.recordsOf[h.pixel])) {
            out[(*left)++] = h;
            continue;
        }
        w.firstHits += cur.empty();
        cur = {h.z, h.c, w.id};
        w.touched[h.pixel] = 1;
    }
    return tested;
}

}  // namespace

PixelTestFn pixelTestScalar() { return &scalarTest; }
QuadTestFn quadTestScalar() { return &scalarQuadTest; }
QuadWriteFn quadWriteScalar() { return &scalarQuadWrite; }
MovingTestFn movingTestScalar() { return &scalarMovingTest; }
LensTestFn lensTestScalar() { return &scalarLensTest; }

}  // namespace streyes
