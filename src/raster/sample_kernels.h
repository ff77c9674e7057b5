// The sampler's SIMD kernels: which of a pixel's samples a micropolygon holds, many samples at
// once (Highway, dispatched at run time to the widest the CPU has: AVX-512, AVX2, SSE4 ...).
//
// They compute exactly what the scalar kernel of micropolygon.h computes, bit for bit (the same
// operations in the same order, and no fused multiply-add: the kernel file is compiled with
// -ffp-contract=off), and tests hold them to it (sample_kernels_test.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "raster/image_block.h"
#include "raster/micropolygon.h"

namespace streyes {

// What a quad does to the samples of one pixel (bits by sample, up to 64 at a time).
struct PixelTest {
    uint64_t tested = 0;  // candidates inside the quad's bound: given the inside test
    uint64_t first = 0;   // inside the quad's first triangle (q0 q1 q2)
    uint64_t second = 0;  // inside the second (q0 q2 q3) and not the first
};

// Tests samples [0, n) (n <= 64) at xs, ys against the quad, those whose bit is set in
// `candidates`. edges[k * edgeStride(n) + j] receives sample j's value of the quad's edge k
// (micropolygon.h's QuadSetup::e order: q0q1, q1q2, q2q3, q3q0, q2q0), from which its hit is made
// (pixelHit). xs and ys must be readable up to edgeStride(n) past them.
constexpr int edgeStride(int n) { return (n + 15) / 16 * 16; }
constexpr int kMaxEdgeValues = 5 * 64;  // edges for n = 64

using PixelTestFn = PixelTest (*)(const micropolygon::QuadSetup& q, const float* xs, const float* ys, int n,
                                  uint64_t candidates, float* edges);

PixelTestFn pixelTestKernel();  // the best for this CPU
PixelTestFn pixelTestScalar();  // the reference: micropolygon.h's scalar test, sample by sample
const char* pixelTestTarget();  // the instruction set pixelTestKernel() uses ("AVX2", ...)

// The instruction sets the kernels can run on this CPU, best first, in Highway's names ("AVX3" is
// AVX-512; then "AVX2", "SSE4", "SSSE3", "SCALAR" ...), and a cap on them: capSimd makes every
// kernel run the best at or below `name` (case-insensitive; "AVX512" names AVX3). Images do not
// depend on it (each kernel gives its scalar reference's results bit for bit), only speed: for
// measuring the kernels of other machines on this one, and for ruling a wider instruction set out.
// Call before the first render (each kernel is chosen once). False, and what this CPU runs in
// *error, for a name it does not run.
std::vector<std::string> simdTargets();
bool capSimd(const std::string& name, std::string* error);
// Whether `name` is an instruction set this build has kernels for, whatever this CPU runs (for
// checking a render's options on a machine other than the one that renders); else false, and the
// names in *error.
bool simdNameKnown(const std::string& name, std::string* error);

// A still quad against every pixel of its bound at once (one call a quad, so that the quad's
// edges are set up once): the samples of the strata its bound overlaps in each pixel, S a pixel
// at xs/ys (pixel i's sample j at i * S + j, pixel index (y - y0) * width + x - x0), readable
// 64 floats past the last pixel's (a pixel's samples are loaded a whole vector at a time;
// ImageBlock pads them so).
struct SampleLayout {
    const float* xs;
    const float* ys;
    int x0, y0, width;  // the block's rect
    int S, sx, sy;      // samples a pixel, strata in x and y
};
struct QuadHit {
    uint32_t pixel;   // index in the block
    uint16_t sample;  // j
    uint8_t first;    // in the quad's first triangle (else the second)
    float l1, l2;     // barycentric weights, as micropolygon::hitQuad makes them (quadHit)
    float z;          // with QuadShading: the depth and colour at the hit
    Color c;
};
// What a still quad's hits carry when asked (the sampler's usual case, an opaque quad with no
// output variables): each triangle's depth and colour at its first corner, and their differences
// to its second and third, per triangle (first, second). A hit's depth is z0 + l1 dz1 + l2 dz2 and
// its colour c0 + dc1 l1 + dc2 l2, in this order, computed many hits at once.
struct QuadShading {
    float z0[2], dz1[2], dz2[2];
    Color c0[2], dc1[2], dc2[2];
};
// A quad's, from its corners' depths and colours (triangles q0 q1 q2 and q0 q2 q3).
inline QuadShading quadShading(const float* z, const Color* c) {
    QuadShading s;
    const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int k = 0; k < 2; ++k) {
        const int a = tri[k][0], b = tri[k][1], d = tri[k][2];
        s.z0[k] = z[a], s.dz1[k] = z[b] - z[a], s.dz2[k] = z[d] - z[a];
        s.c0[k] = c[a], s.dc1[k] = c[b] - c[a], s.dc2[k] = c[d] - c[a];
    }
    return s;
}
// The stratum, of `strata` across the pixel that starts at p, that coordinate v falls in (clamped
// to the pixel's): the kernels and the scalar reference visit the strata a quad's bound overlaps.
inline int stratumAt(float v, int p, int strata) {
    return floorClamped((v - float(p)) * float(strata), 0, strata - 1);
}
// Appends the hits to `out` (room for (px1 - px0 + 1) (py1 - py0 + 1) S hits), in pixel order
// then sample order, with their depths and colours when `shading` is given; returns how many
// samples were tested.
using QuadTestFn = uint64_t (*)(const micropolygon::QuadSetup& q, const SampleLayout& layout,
                                const QuadShading* shading, QuadHit* out, size_t* hits);
QuadTestFn quadTestKernel();
QuadTestFn quadTestScalar();

// The still sampler's usual case, an opaque quad with no output variables into the still layer
// (GridRasterizer::sampleStill): the kernel depth-tests its hits against the layer and writes the
// ones that win, so that they never go through memory as QuadHits. A hit inside the clipping range
// and strictly nearer than what its sample sees becomes {z, c, 1, id}, its pixel touched
// (ImageBlock::touch), and counts in firstHits where the sample saw nothing (a == 0, which in the
// still layer is exactly where z is +inf: every hit written there lies inside the finite clipping
// range). A hit that ties its sample's depth (SampleHit::beatenBy decides), or in a pixel with
// per-frame records (ImageBlock::recordsOf: the hit must reach them too), is appended to `out` for
// the sampler, in the order QuadTestFn makes them; any other is hidden or clipped and dropped.
struct StillWrite {
    SampleHit* still;            // the block's still layer, S hits a pixel
    uint8_t* touched;            // per pixel: ImageBlock::touch's flags
    const uint16_t* recordsOf;   // per pixel: frames with a record of it; null when none has
    uint64_t id;                 // the grid's primitive
    float nearZ, farZ;           // the camera's clipping range
    uint64_t inside = 0;         // out: the hits (inside the quad), written, left or dropped
    uint64_t firstHits = 0;      // out: written over a sample that saw nothing
};
// Returns how many samples were tested; *left counts the hits appended to out.
using QuadWriteFn = uint64_t (*)(const micropolygon::QuadSetup& q, const SampleLayout& layout,
                                 const QuadShading& shading, StillWrite& write, QuadHit* out, size_t* left);
QuadWriteFn quadWriteKernel();
QuadWriteFn quadWriteScalar();  // quadTestScalar's hits, then the rule above hit by hit

// A moving quad over a group of time slices (GridRasterizer::sampleMoving): each sample is tested
// against the quad at its own time, w = clamp((tf - tfA) invSpan, 0, 1) across the group. A corner
// moves linearly in raster space between the group's ends, or, where exact[c] (perspective: the
// grid's border, and where the projection bends a vertex's path), linearly in camera space and is
// projected at w, with Camera::toRaster's operations.
struct MovingQuad {
    float x[2][4], y[2][4], z[2][4];     // raster corners at the group's start [0] and end [1]
    float cx[2][4], cy[2][4], cz[2][4];  // camera-space corners, read where exact[c]
    bool exact[4];
    float ax, bx, ay, by;  // raster = a * (camera / z) + b (Camera::toRaster, perspective)
    float tfA, invSpan;
    float xmin, xmax, ymin, ymax;  // the quad's bound over the group (micropolygon::boundQuad)
    float zmin;  // its nearest depth over the group: a lane whose sample sees nearer is not tested (NaN: every lane is)
    // With depth of field: each lane's quad at its time is moved by the lane's lens point as
    // micropolygon::lensQuad moves it, by each corner's lens shift R (1/d - 1/max(z, eyePlane))
    // (Camera::lensShift) times (ax, ay).
    bool lens;
    float lensRadius, invFocal, eyePlane;
};
inline float movingWeight(const MovingQuad& m, float tf) {
    return std::min(1.0f, std::max(0.0f, (tf - m.tfA) * m.invSpan));
}
// Corner c at weight w, as the sampler sees it.
inline void movingCorner(const MovingQuad& m, int c, float w, float& x, float& y, float& z) {
    if (m.exact[c]) {
        const float px = lerp(m.cx[0][c], m.cx[1][c], w), py = lerp(m.cy[0][c], m.cy[1][c], w);
        z = lerp(m.cz[0][c], m.cz[1][c], w);
        const float iz = 1.0f / z;
        x = m.ax * px * iz + m.bx;
        y = m.ay * py * iz + m.by;
    } else {
        x = lerp(m.x[0][c], m.x[1][c], w);
        y = lerp(m.y[0][c], m.y[1][c], w);
        z = lerp(m.z[0][c], m.z[1][c], w);
    }
}
// Corner c's depth at weight w (movingCorner's z: toRaster keeps camera depth).
inline float movingDepth(const MovingQuad& m, int c, float w) {
    return m.exact[c] ? lerp(m.cz[0][c], m.cz[1][c], w) : lerp(m.z[0][c], m.z[1][c], w);
}
// The quad at weight w, its edges set up.
inline void movingQuadAt(const MovingQuad& m, float w, micropolygon::QuadSetup& q) {
    for (int c = 0; c < 4; ++c) movingCorner(m, c, w, q.x[c], q.y[c], q.z[c]);
    micropolygon::setupEdges(q);
}
// With a lens: the quad at weight w as lens point (lu, lv) sees it, its edges set up; false when
// (x, y) is outside its bound (micropolygon::lensQuad).
inline bool movingLensQuadAt(const MovingQuad& m, float w, float lu, float lv, float x, float y,
                             micropolygon::QuadSetup& q) {
    micropolygon::QuadSetup at;
    float sx[4], sy[4];
    for (int c = 0; c < 4; ++c) {
        movingCorner(m, c, w, at.x[c], at.y[c], at.z[c]);
        const float s = m.lensRadius * (m.invFocal - 1.0f / std::max(at.z[c], m.eyePlane));
        sx[c] = s * m.ax, sy[c] = s * m.ay;
    }
    return micropolygon::lensQuad(at, sx, sy, lu, lv, x, y, q);
}
// Samples [0, n) (n <= 64) at (xs, ys), at exposure fractions tfs (and lens points lus, lvs
// with a lens, else null), each seeing a hit at depth seenZ: behind, those inside the quad's
// bound whose hit is nearer than zmin; tested, the others inside it; first and second, those of
// tested inside the quad's triangles at their own time (as micropolygon::hitQuad finds them;
// with a lens, inside the moved quad's bound too). edges as PixelTestFn's. The arrays must be
// readable up to edgeStride(n).
struct MovingTest {
    uint64_t tested = 0, behind = 0, first = 0, second = 0;
};
using MovingTestFn = MovingTest (*)(const MovingQuad& q, const float* xs, const float* ys, const float* tfs,
                                    const float* seenZ, const float* lus, const float* lvs, int n, float* edges);
MovingTestFn movingTestKernel();
MovingTestFn movingTestScalar();  // movingQuadAt (movingLensQuadAt) and micropolygon.h's test, sample by sample

// A still quad seen through the lens (depth of field, GridRasterizer::sampleStill): sample j, at
// (xs[j], ys[j]) with lens point (lus[j], lvs[j]), sees corner c at (x[c] + sx[c] lu, y[c] + sy[c] lv)
// (micropolygon::lensQuad). tested: the samples inside the quad's bound grown by the circle of
// confusion; first and second: those also inside the moved quad's bound and its triangles, as
// lensQuad and hitQuad find them (behind: none). The results and edges as MovingTestFn's; every
// array readable up to edgeStride(n).
struct LensQuad {
    float x[4], y[4], sx[4], sy[4];
    float xmin, xmax, ymin, ymax;
};
using LensTestFn = MovingTest (*)(const LensQuad& q, const float* xs, const float* ys, const float* lus, const float* lvs,
                                  int n, float* edges);
LensTestFn lensTestKernel();
LensTestFn lensTestScalar();  // lensQuad and micropolygon.h's test, sample by sample

// For tests: the kernels of every instruction set compiled in that this CPU runs (AVX-512, AVX2,
// SSE4 ...), so that each, not only the one dispatched to, is held to the scalar references: the
// same scene gives the same pixels on every machine.
struct KernelSet {
    const char* target;
    PixelTestFn pixel;
    QuadTestFn quad;
    QuadWriteFn quadWrite;
    MovingTestFn moving;
    LensTestFn lens;
};
std::vector<KernelSet> kernelsOfEveryTarget();

inline micropolygon::Hit quadHit(const QuadHit& h) {
    return h.first ? micropolygon::Hit{0, 1, 2, h.l1, h.l2} : micropolygon::Hit{0, 2, 3, h.l1, h.l2};
}

// Sample j's hit from its edge values, as micropolygon::hitQuad makes it.
inline micropolygon::Hit pixelHit(const float* edges, int n, int j, bool first) {
    const int m = edgeStride(n);
    const float e01 = edges[0 * m + j], e12 = edges[1 * m + j], e23 = edges[2 * m + j], e30 = edges[3 * m + j],
                e20 = edges[4 * m + j];
    if (first) {
        const float inv = 1.0f / (e01 + e12 + e20);
        return {0, 1, 2, e20 * inv, e01 * inv};
    }
    const float e02 = -e20;
    const float inv = 1.0f / (e02 + e23 + e30);
    return {0, 2, 3, e30 * inv, e02 * inv};
}

}  // namespace streyes
