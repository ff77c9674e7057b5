#include "raster/sample_kernels.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace streyes {
namespace {

using namespace micropolygon;

// A quad from four corners, set up as the rasterizer sets it up (bound over the whole image).
QuadSetup quad(const float (&x)[4], const float (&y)[4]) {
    QuadSetup q;
    for (int c = 0; c < 4; ++c) q.x[c] = x[c], q.y[c] = y[c], q.z[c] = 1;
    boundQuad(q, nullptr, nullptr, nullptr, {-100, -100, 100, 100}, 0, 10);
    setupEdges(q);
    return q;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Two kernels' hits: the same sample, triangle and barycentrics, bit for bit, and with `shaded`
// the same depth and colour.
bool sameQuadHit(const QuadHit& a, const QuadHit& b, bool shaded) {
    const bool same = a.pixel == b.pixel && a.sample == b.sample && a.first == b.first && sameBits(a.l1, b.l1) &&
                      sameBits(a.l2, b.l2);
    return same && (!shaded || (sameBits(a.z, b.z) && sameBits(a.c.x, b.c.x) && sameBits(a.c.y, b.c.y) &&
                                sameBits(a.c.z, b.c.z)));
}

// The kernel against the scalar reference, and both against micropolygon::hitQuad, on quads of
// every shape (convex, concave, bow-ties, collapsed edges, no area) and samples anywhere, on the
// corners and on the edges (where the tie rule decides).
void pixelKernelAgrees(PixelTestFn kernel) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 4.0f);
    const PixelTestFn scalar = pixelTestScalar();
    uint64_t tested = 0, hits = 0;
    for (int t = 0; t < 20000; ++t) {
        float x[4], y[4];
        for (int c = 0; c < 4; ++c) x[c] = std::round(u(rng) * 4) / 4, y[c] = std::round(u(rng) * 4) / 4;
        if (t % 7 == 0) x[1] = x[0], y[1] = y[0];  // a collapsed edge
        if (t % 11 == 0) x[2] = x[0], y[2] = y[0];  // a collapsed diagonal
        const QuadSetup q = quad(x, y);
        const int n = 1 + int(rng() % 64);
        std::vector<float> xs(size_t(edgeStride(n))), ys(xs.size());
        for (int j = 0; j < n; ++j) {
            switch (rng() % 4) {
            case 0: xs[size_t(j)] = x[rng() % 4], ys[size_t(j)] = y[rng() % 4]; break;  // corner coordinates
            case 1: {                                                                     // an edge's midpoint
                const int a = int(rng() % 4), b = (a + 1) % 4;
                xs[size_t(j)] = 0.5f * (x[a] + x[b]), ys[size_t(j)] = 0.5f * (y[a] + y[b]);
                break;
            }
            default: xs[size_t(j)] = u(rng), ys[size_t(j)] = u(rng);
            }
        }
        const uint64_t candidates = n == 64 ? ~uint64_t(0) : ((uint64_t(1) << n) - 1) & rng();
        float ek[kMaxEdgeValues], es[kMaxEdgeValues];
        const PixelTest a = kernel(q, xs.data(), ys.data(), n, candidates, ek);
        const PixelTest b = scalar(q, xs.data(), ys.data(), n, candidates, es);
        ASSERT_EQ(a.tested, b.tested) << "quad " << t;
        ASSERT_EQ(a.first, b.first) << "quad " << t;
        ASSERT_EQ(a.second, b.second) << "quad " << t;
        for (int j = 0; j < n; ++j) {
            if (!((a.tested >> j) & 1)) continue;
            ++tested;
            for (int k = 0; k < 5; ++k)
                ASSERT_TRUE(sameBits(ek[k * edgeStride(n) + j], es[k * edgeStride(n) + j])) << "quad " << t;
            Hit h{};
            const bool inside = hitQuad(q, xs[size_t(j)], ys[size_t(j)], h);
            const bool first = (a.first >> j) & 1, second = (a.second >> j) & 1;
            ASSERT_EQ(inside, first || second) << "quad " << t << " sample " << j;
            if (!inside) continue;
            ++hits;
            const Hit k = pixelHit(ek, n, j, first);
            EXPECT_EQ(k.v0, h.v0);
            EXPECT_EQ(k.v1, h.v1);
            EXPECT_EQ(k.v2, h.v2);
            EXPECT_TRUE(sameBits(k.l1, h.l1) && sameBits(k.l2, h.l2)) << "quad " << t << " sample " << j;
        }
    }
    EXPECT_GT(tested, 100000u);
    EXPECT_GT(hits, 20000u);
}

// The kernel the renderer calls for a still quad (every pixel of its bound, the samples of the
// strata it overlaps) against the scalar reference: the same samples tested, the same hits in
// the same order, each with the same barycentrics bit for bit, and each hit the one hitQuad makes.
// sx x sy strata a pixel: the kernel packs candidates across pixels, and across the 64-sample
// chunks of a pixel with more.
// A block of W x H pixels at (10, 20) with sx x sy strata a pixel: one sample in each stratum,
// some on a stratum's edge, padded as ImageBlock pads them.
struct StrataBlock {
    static constexpr int W = 6, H = 5;
    int S;
    PixelRect R{10, 20, 10 + W - 1, 20 + H - 1};
    std::vector<float> xs, ys;
    SampleLayout layout;
    StrataBlock(std::mt19937& rng, int sx, int sy) : S(sx * sy), xs(size_t(W * H * S) + 64), ys(xs.size()) {
        std::uniform_real_distribution<float> jitter(0.0f, 1.0f);
        for (int py = 0; py < H; ++py)
            for (int px = 0; px < W; ++px)
                for (int j = 0; j < S; ++j) {
                    const size_t i = size_t((py * W + px) * S + j);
                    const float u = j % 5 == 0 ? 0.0f : jitter(rng), v = j % 7 == 0 ? 0.0f : jitter(rng);
                    xs[i] = float(R.x0 + px) + (float(j % sx) + u) / float(sx);
                    ys[i] = float(R.y0 + py) + (float(j / sx) + v) / float(sy);
                }
        layout = {xs.data(), ys.data(), R.x0, R.y0, W, S, sx, sy};
    }
    // Quad t of a stream over the block and beyond it: every shape, on a quarter-pixel lattice
    // now and then (samples on edges and corners), depths in [1, 2]; false when it misses.
    bool nextQuad(std::mt19937& rng, int t, QuadSetup& q) const {
        std::uniform_real_distribution<float> jitter(0.0f, 1.0f), corner(9.0f, 17.0f);
        for (int c = 0; c < 4; ++c) {
            q.x[c] = t % 3 == 0 ? std::round(corner(rng) * 4) / 4 : corner(rng);
            q.y[c] = t % 3 == 0 ? std::round((corner(rng) + 10) * 4) / 4 : corner(rng) + 10;
            q.z[c] = 1 + jitter(rng);
        }
        if (t % 7 == 0) q.x[1] = q.x[0], q.y[1] = q.y[0];  // a collapsed edge
        if (t % 13 == 0) q.x[2] = q.x[0], q.y[2] = q.y[0];  // a collapsed diagonal (with the above, a triangle a point)
        if (!boundQuad(q, nullptr, nullptr, nullptr, R, 0, 10)) return false;
        setupEdges(q);
        return true;
    }
};

void quadKernelAgrees(QuadTestFn kernel, int sx, int sy) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> jitter(0.0f, 1.0f);
    const StrataBlock block(rng, sx, sy);
    const int S = block.S;
    const std::vector<float>& xs = block.xs;
    const std::vector<float>& ys = block.ys;
    const SampleLayout& layout = block.layout;
    const QuadTestFn scalar = quadTestScalar();
    std::vector<QuadHit> a(xs.size()), b(a.size());
    uint64_t hits = 0;
    for (int t = 0; t < 5000; ++t) {
        QuadSetup q;
        if (!block.nextQuad(rng, t, q)) continue;
        // Every other quad asks for its hits' depths and colours, from its corners' as the still
        // sampler makes them.
        Color col[4];
        for (Color& c : col) c = {jitter(rng), jitter(rng), jitter(rng)};
        const QuadShading shading = quadShading(q.z, col);
        const QuadShading* shade = t % 2 ? &shading : nullptr;
        size_t na = 0, nb = 0;
        ASSERT_EQ(kernel(q, layout, shade, a.data(), &na), scalar(q, layout, shade, b.data(), &nb)) << "quad " << t;
        ASSERT_EQ(na, nb) << "quad " << t;
        for (size_t n = 0; n < na; ++n) {
            ASSERT_TRUE(sameQuadHit(a[n], b[n], false)) << "quad " << t << " hit " << n;
            const size_t i = size_t(a[n].pixel) * S + a[n].sample;
            Hit h{};
            ASSERT_TRUE(hitQuad(q, xs[i], ys[i], h)) << "quad " << t << " hit " << n;
            const Hit k = quadHit(a[n]);
            EXPECT_TRUE(k.v2 == h.v2 && sameBits(k.l1, h.l1) && sameBits(k.l2, h.l2)) << "quad " << t << " hit " << n;
            if (!shade) continue;
            // The depth and colour the sampler's beats() makes of the hit, bit for bit.
            const float z = q.z[k.v0] + k.l1 * (q.z[k.v1] - q.z[k.v0]) + k.l2 * (q.z[k.v2] - q.z[k.v0]);
            const Color c = col[k.v0] + (col[k.v1] - col[k.v0]) * k.l1 + (col[k.v2] - col[k.v0]) * k.l2;
            ASSERT_TRUE(sameBits(a[n].z, z) && sameBits(b[n].z, z)) << "quad " << t << " hit " << n;
            ASSERT_TRUE(sameBits(a[n].c.x, c.x) && sameBits(a[n].c.y, c.y) && sameBits(a[n].c.z, c.z) &&
                        sameBits(b[n].c.x, c.x) && sameBits(b[n].c.y, c.y) && sameBits(b[n].c.z, c.z))
                << "quad " << t << " hit " << n;
        }
        hits += na;
    }
    EXPECT_GT(hits, 25000u * unsigned(S));  // about 31,500 a stratum
}

// The moving kernel (each lane's quad at its own time) against its scalar reference, and both
// against micropolygon::hitQuad on the quad movingQuadAt makes: quads moving from one shape to
// another, some corners projected from camera space, some seen through a lens, samples on the
// ends' corners and edges at the group's ends (where the tie rule decides), collapsed edges and
// diagonals, every count of lanes.
void movingKernelAgrees(MovingTestFn kernel) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> u(0.0f, 4.0f), depth(2.0f, 6.0f);
    const MovingTestFn scalar = movingTestScalar();
    uint64_t tested = 0, behind = 0, hits = 0, exactHits = 0, lensHits = 0;
    for (int t = 0; t < 20000; ++t) {
        MovingQuad m{};
        for (int e = 0; e < 2; ++e)
            for (int c = 0; c < 4; ++c) {
                m.x[e][c] = std::round(u(rng) * 4) / 4, m.y[e][c] = std::round(u(rng) * 4) / 4, m.z[e][c] = depth(rng);
                m.cz[e][c] = m.z[e][c];  // camera space that projects onto the raster corner
                m.cx[e][c] = (m.x[e][c] - 0.5f) * m.cz[e][c] / 2.0f, m.cy[e][c] = (m.y[e][c] - 0.25f) * m.cz[e][c] / 2.0f;
            }
        m.ax = 2.0f, m.bx = 0.5f, m.ay = 2.0f, m.by = 0.25f;
        if (t % 7 == 0) m.x[0][1] = m.x[0][0], m.y[0][1] = m.y[0][0];  // a collapsed edge at the start
        if (t % 11 == 0)
            for (int e = 0; e < 2; ++e) m.x[e][2] = m.x[e][0], m.y[e][2] = m.y[e][0];  // a collapsed diagonal
        for (int c = 0; c < 4; ++c) m.exact[c] = t % 3 == 0 && (rng() & 1);
        m.tfA = 0.25f, m.invSpan = 4.0f;  // the group is [0.25, 0.5] of the exposure
        m.lens = t % 4 == 1;  // seen through a lens focused at depth 4, some corners nearer than the eye plane
        m.lensRadius = 0.75f, m.invFocal = 0.25f, m.eyePlane = 2.5f;
        m.xmin = m.ymin = 0.0f, m.xmax = m.ymax = 4.0f;
        if (t % 5 == 0) m.xmin = 1.0f, m.ymax = 3.0f;  // a bound that leaves samples out
        const int n = 1 + int(rng() % 64);
        std::vector<float> xs(size_t(edgeStride(n))), ys(xs.size()), tfs(xs.size()), lus(xs.size()), lvs(xs.size());
        for (int j = 0; j < n; ++j) {
            const int e = int(rng() % 2);
            lus[size_t(j)] = rng() % 4 == 0 ? 0.0f : u(rng) / 2 - 1, lvs[size_t(j)] = u(rng) / 2 - 1;
            tfs[size_t(j)] = rng() % 3 == 0 ? 0.25f + 0.25f * float(e) : 0.2f + 0.35f * float(rng() % 1000) / 1000.0f;
            switch (rng() % 4) {
            case 0: xs[size_t(j)] = m.x[e][rng() % 4], ys[size_t(j)] = m.y[e][rng() % 4]; break;
            case 1: {
                const int a = int(rng() % 4), b = (a + 1) % 4;
                xs[size_t(j)] = 0.5f * (m.x[e][a] + m.x[e][b]), ys[size_t(j)] = 0.5f * (m.y[e][a] + m.y[e][b]);
                break;
            }
            default: xs[size_t(j)] = u(rng), ys[size_t(j)] = u(rng);
            }
        }
        float ek[kMaxEdgeValues], es[kMaxEdgeValues];
        const float* lu = m.lens ? lus.data() : nullptr;
        const float* lv = m.lens ? lvs.data() : nullptr;
        // What each sample already sees: nearer than the quad, farther, or exactly at its nearest
        // depth; the quad's nearest depth NaN now and then (every lane tested, as when counting).
        m.zmin = t % 9 == 0 ? std::numeric_limits<float>::quiet_NaN() : 4.0f;
        std::vector<float> seenZ(xs.size());
        for (int j = 0; j < n; ++j) seenZ[size_t(j)] = rng() % 5 == 0 ? 3.0f : rng() % 4 == 0 ? 4.0f : 100.0f;
        const MovingTest a = kernel(m, xs.data(), ys.data(), tfs.data(), seenZ.data(), lu, lv, n, ek);
        const MovingTest b = scalar(m, xs.data(), ys.data(), tfs.data(), seenZ.data(), lu, lv, n, es);
        ASSERT_EQ(a.tested, b.tested) << "quad " << t;
        ASSERT_EQ(a.behind, b.behind) << "quad " << t;
        ASSERT_EQ(a.first, b.first) << "quad " << t;
        ASSERT_EQ(a.second, b.second) << "quad " << t;
        for (int j = 0; j < n; ++j) {
            const bool inBox = xs[size_t(j)] >= m.xmin && xs[size_t(j)] <= m.xmax && ys[size_t(j)] >= m.ymin &&
                               ys[size_t(j)] <= m.ymax;
            const bool nearer = m.zmin > seenZ[size_t(j)];
            ASSERT_EQ(bool((a.behind >> j) & 1), inBox && nearer) << "quad " << t << " sample " << j;
            ASSERT_EQ(bool((a.tested >> j) & 1), inBox && !nearer) << "quad " << t << " sample " << j;
            behind += inBox && nearer;
            if (!((a.tested >> j) & 1)) continue;
            ++tested;
            QuadSetup q;
            const float w = movingWeight(m, tfs[size_t(j)]), x = xs[size_t(j)], y = ys[size_t(j)];
            const bool seen = !m.lens || movingLensQuadAt(m, w, lus[size_t(j)], lvs[size_t(j)], x, y, q);
            if (!m.lens) movingQuadAt(m, w, q);
            Hit h{};
            const bool in = seen && hitQuad(q, x, y, h);
            ASSERT_EQ(in, bool(((a.first | a.second) >> j) & 1)) << "quad " << t << " sample " << j;
            if (seen) {  // the scalar reference sets up no edges for a sample outside the moved bound
                for (int k = 0; k < 5; ++k)
                    ASSERT_TRUE(sameBits(ek[k * edgeStride(n) + j], es[k * edgeStride(n) + j])) << "quad " << t << " edge " << k;
            }
            if (!in) continue;
            ++hits;
            lensHits += m.lens;
            exactHits += m.exact[0] || m.exact[1] || m.exact[2] || m.exact[3];
            const Hit k = pixelHit(ek, n, j, (a.first >> j) & 1);
            EXPECT_TRUE(k.v2 == h.v2 && sameBits(k.l1, h.l1) && sameBits(k.l2, h.l2)) << "quad " << t << " sample " << j;
        }
    }
    EXPECT_GT(tested, 200000u);  // both outcomes, often, and hits through projected corners
    EXPECT_GT(hits, 50000u);
    EXPECT_GT(exactHits, 5000u);
    EXPECT_GT(lensHits, 5000u);
    EXPECT_GT(behind, 20000u);
}


// The lens kernel (each lane's quad moved by its lens point) against its scalar reference, and
// both against micropolygon::lensQuad and hitQuad: corners and shifts on a quarter-pixel lattice,
// lens points at the disc's edge and centre now and then, samples on the moved corners and edges
// (where the tie rule decides), collapsed edges, every count of lanes.
void lensKernelAgrees(LensTestFn kernel) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> u(0.0f, 4.0f), shift(-1.5f, 1.5f), disc(-1.0f, 1.0f);
    const LensTestFn scalar = lensTestScalar();
    uint64_t tested = 0, hits = 0;
    for (int t = 0; t < 20000; ++t) {
        LensQuad m{};
        for (int c = 0; c < 4; ++c) {
            m.x[c] = std::round(u(rng) * 4) / 4, m.y[c] = std::round(u(rng) * 4) / 4;
            m.sx[c] = t % 4 == 0 ? 0.5f : std::round(shift(rng) * 4) / 4, m.sy[c] = std::round(shift(rng) * 4) / 4;
        }
        if (t % 7 == 0) m.x[1] = m.x[0], m.y[1] = m.y[0], m.sx[1] = m.sx[0], m.sy[1] = m.sy[0];  // a collapsed edge
        m.xmin = m.ymin = -1.0f, m.xmax = m.ymax = 5.0f;
        if (t % 5 == 0) m.xmin = 1.0f, m.ymax = 3.0f;  // a bound that leaves samples out
        const int n = 1 + int(rng() % 64);
        std::vector<float> xs(size_t(edgeStride(n))), ys(xs.size()), lus(xs.size()), lvs(xs.size());
        for (int j = 0; j < n; ++j) {
            const float lu = rng() % 4 == 0 ? float(int(rng() % 5) - 2) * 0.5f : disc(rng), lv = disc(rng);
            lus[size_t(j)] = lu, lvs[size_t(j)] = lv;
            auto at = [&](int c) { return std::pair<float, float>{m.x[c] + m.sx[c] * lu, m.y[c] + m.sy[c] * lv}; };
            switch (rng() % 4) {
            case 0: std::tie(xs[size_t(j)], ys[size_t(j)]) = at(int(rng() % 4)); break;  // a moved corner
            case 1: {                                                                     // a moved edge's midpoint
                const int a = int(rng() % 4);
                const auto [ax, ay] = at(a);
                const auto [bx, by] = at((a + 1) % 4);
                xs[size_t(j)] = 0.5f * (ax + bx), ys[size_t(j)] = 0.5f * (ay + by);
                break;
            }
            default: xs[size_t(j)] = u(rng), ys[size_t(j)] = u(rng);
            }
        }
        float ek[kMaxEdgeValues], es[kMaxEdgeValues];
        const MovingTest a = kernel(m, xs.data(), ys.data(), lus.data(), lvs.data(), n, ek);
        const MovingTest b = scalar(m, xs.data(), ys.data(), lus.data(), lvs.data(), n, es);
        ASSERT_EQ(a.tested, b.tested) << "quad " << t;
        ASSERT_EQ(a.behind, 0u) << "quad " << t;
        ASSERT_EQ(a.first, b.first) << "quad " << t;
        ASSERT_EQ(a.second, b.second) << "quad " << t;
        QuadSetup q;
        for (int c = 0; c < 4; ++c) q.x[c] = m.x[c], q.y[c] = m.y[c], q.z[c] = 0;
        for (int j = 0; j < n; ++j) {
            if (!((a.tested >> j) & 1)) continue;
            ++tested;
            QuadSetup l;
            Hit h{};
            const bool in = lensQuad(q, m.sx, m.sy, lus[size_t(j)], lvs[size_t(j)], xs[size_t(j)], ys[size_t(j)], l) &&
                            hitQuad(l, xs[size_t(j)], ys[size_t(j)], h);
            ASSERT_EQ(in, bool(((a.first | a.second) >> j) & 1)) << "quad " << t << " sample " << j;
            if (!in) continue;
            ++hits;
            for (int k = 0; k < 5; ++k)
                ASSERT_TRUE(sameBits(ek[k * edgeStride(n) + j], es[k * edgeStride(n) + j])) << "quad " << t << " edge " << k;
            const Hit k = pixelHit(ek, n, j, (a.first >> j) & 1);
            EXPECT_TRUE(k.v2 == h.v2 && sameBits(k.l1, h.l1) && sameBits(k.l2, h.l2)) << "quad " << t << " sample " << j;
        }
    }
    EXPECT_GT(tested, 200000u);  // both outcomes, often
    EXPECT_GT(hits, 50000u);
}

bool sameHit(const SampleHit& a, const SampleHit& b) {
    return sameBits(a.z, b.z) && sameBits(a.c.x, b.c.x) && sameBits(a.c.y, b.c.y) && sameBits(a.c.z, b.c.z) &&
           a.id == b.id;
}

// The kernel that writes a still quad's hits into the still layer against its scalar reference
// (StillWrite's rule hit by hit): over a stream of quads into one layer that holds nothing, nearer
// and farther hits, hits at exactly the depth a quad makes there (ties) and pixels with records,
// the same samples tested, the same layer, touched pixels and counts bit for bit, and the same hits
// left to the sampler in the same order. Depths beyond 1.9 are clipped. Every fourth quad goes
// into a block without records (null recordsOf).
void quadWriteKernelAgrees(QuadWriteFn kernel, int sx, int sy) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> jitter(0.0f, 1.0f);
    const StrataBlock block(rng, sx, sy);
    const size_t pixels = size_t(block.W * block.H), samples = pixels * size_t(block.S);
    std::vector<SampleHit> layerA(samples, kNoHit), layerB;
    for (SampleHit& h : layerA)
        if (jitter(rng) < 0.3f) h = {1.0f + 1.2f * jitter(rng), {jitter(rng), 0, 0}, 7};
    layerB = layerA;
    std::vector<uint8_t> touchedA(pixels, 0), touchedB(pixels, 0);
    std::vector<uint16_t> recordsOf(pixels, 0);
    for (size_t p = 0; p < pixels; p += 4) recordsOf[p] = 1;
    const QuadWriteFn scalar = quadWriteScalar();
    std::vector<QuadHit> a(samples), b(samples), hits(samples);
    uint64_t written = 0, ties = 0, left = 0, dropped = 0;
    for (int t = 0; t < 3000; ++t) {
        QuadSetup q;
        if (!block.nextQuad(rng, t, q)) continue;
        Color col[4];
        for (Color& c : col) c = {jitter(rng), jitter(rng), jitter(rng)};
        const QuadShading shading = quadShading(q.z, col);
        // Every third hit of this quad made a tie: its sample already sees its depth.
        size_t nh = 0;
        quadTestScalar()(q, block.layout, &shading, hits.data(), &nh);
        for (size_t n = 0; n < nh; n += 3) {
            const size_t i = size_t(hits[n].pixel) * size_t(block.S) + hits[n].sample;
            layerA[i].z = layerB[i].z = hits[n].z;
            ++ties;
        }
        const std::vector<SampleHit> before = layerB;
        const uint16_t* records = t % 4 == 3 ? nullptr : recordsOf.data();  // now and then a block without any
        StillWrite wa{layerA.data(), touchedA.data(), records, uint64_t(t), 0.0f, 1.9f};
        StillWrite wb{layerB.data(), touchedB.data(), records, uint64_t(t), 0.0f, 1.9f};
        size_t na = 0, nb = 0;
        ASSERT_EQ(kernel(q, block.layout, shading, wa, a.data(), &na), scalar(q, block.layout, shading, wb, b.data(), &nb))
            << "quad " << t;
        ASSERT_EQ(wa.inside, wb.inside) << "quad " << t;
        ASSERT_EQ(wa.inside, nh) << "quad " << t;
        ASSERT_EQ(wa.firstHits, wb.firstHits) << "quad " << t;
        ASSERT_EQ(na, nb) << "quad " << t;
        for (size_t n = 0; n < na; ++n) ASSERT_TRUE(sameQuadHit(a[n], b[n], true)) << "quad " << t << " hit " << n;
        for (size_t i = 0; i < samples; ++i) {
            ASSERT_TRUE(sameHit(layerA[i], layerB[i])) << "quad " << t << " sample " << i;
            written += !sameHit(layerB[i], before[i]);
        }
        ASSERT_EQ(touchedA, touchedB) << "quad " << t;
        left += na;
        dropped += nh - na;
    }
    dropped -= written;
    // Every outcome, often: written, left to the sampler (ties and pixels with records), and
    // dropped (hidden or clipped).
    EXPECT_GT(written, 5000u);
    EXPECT_GT(ties, 5000u);
    EXPECT_GT(left, ties / 2);
    EXPECT_GT(dropped, 5000u);
}

// Each kernel of every instruction set this CPU runs (not only the one dispatched to) against
// its scalar reference: the same scene gives the same pixels on every machine.
template <typename Check>
void onEveryTarget(Check check) {
    for (const KernelSet& k : kernelsOfEveryTarget()) {
        SCOPED_TRACE(k.target);
        check(k);
    }
}

TEST(SampleKernels, KernelGivesTheScalarTestBitForBit) {
    RecordProperty("target", pixelTestTarget());
    onEveryTarget([](const KernelSet& k) { pixelKernelAgrees(k.pixel); });
}

TEST(SampleKernels, QuadKernelGivesTheScalarQuadTestBitForBit) {
    onEveryTarget([](const KernelSet& k) {
        for (const auto& [sx, sy] : {std::pair{4, 4}, {3, 3}, {5, 7}, {10, 10}}) {
            SCOPED_TRACE(::testing::Message() << sx << " x " << sy << " strata");
            quadKernelAgrees(k.quad, sx, sy);
        }
    });
}

TEST(SampleKernels, QuadWriteKernelGivesTheScalarWriteBitForBit) {
    onEveryTarget([](const KernelSet& k) {
        for (const auto& [sx, sy] : {std::pair{4, 4}, {3, 3}, {5, 7}, {10, 10}}) {
            SCOPED_TRACE(::testing::Message() << sx << " x " << sy << " strata");
            quadWriteKernelAgrees(k.quadWrite, sx, sy);
        }
    });
}

TEST(SampleKernels, MovingKernelGivesTheScalarTestBitForBit) {
    onEveryTarget([](const KernelSet& k) { movingKernelAgrees(k.moving); });
}

TEST(SampleKernels, LensKernelGivesTheScalarTestBitForBit) {
    onEveryTarget([](const KernelSet& k) { lensKernelAgrees(k.lens); });
}

// The renderer's kernels are those of one of these targets.
TEST(SampleKernels, EveryTargetIncludesTheDispatchedOne) {
    const std::vector<KernelSet> sets = kernelsOfEveryTarget();
    ASSERT_FALSE(sets.empty());
    bool found = false;
    for (const KernelSet& k : sets)
        found = found || (k.pixel == pixelTestKernel() && k.quad == quadTestKernel() && k.quadWrite == quadWriteKernel() && k.moving == movingTestKernel() && k.lens == lensTestKernel() &&
                          std::string(k.target) == pixelTestTarget());
    EXPECT_TRUE(found) << pixelTestTarget();
}

}  // namespace
}  // namespace streyes
