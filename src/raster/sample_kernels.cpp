// The sampler's SIMD kernels, compiled once per instruction set (Highway's foreach_target) and
// chosen at run time. No fused multiply-add here (-ffp-contract=off for this file): the kernels
// must give micropolygon.h's scalar results bit for bit.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "raster/sample_kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstddef>
#include <cstring>
#include <limits>
#include <string>

#include "raster/sample_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace streyes {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using micropolygon::QuadSetup;

namespace {

const hn::ScalableTag<float> kD;
using V = hn::Vec<decltype(kD)>;
using M = hn::Mask<decltype(kD)>;

// micropolygon.h's insideTriangle, lane by lane: mixed signs are outside, all zero (a triangle
// with no area) too; a lane exactly on an edge goes by the edge's canonical direction. A lane is
// inside the positive way when every edge is > 0, or = 0 where the edge is canonical; the negative
// way likewise. A lane with all three edges 0 passes neither: a triangle's edges go round, so they
// cannot all run the canonical (increasing) way, and run none of them only where its corners are
// one point, which nothing is inside. NaN fails every comparison, as in the scalar test.
HWY_INLINE M insideTriangle(V e0, bool c0, V e1, bool c1, V e2, bool c2) {
    if (!c0 && !c1 && !c2) return hn::FirstN(kD, 0);
    const V zero = hn::Zero(kD);
    auto atLeast = [&](V e, bool orZero) { return orZero ? hn::Ge(e, zero) : hn::Gt(e, zero); };
    auto atMost = [&](V e, bool orZero) { return orZero ? hn::Le(e, zero) : hn::Lt(e, zero); };
    const M positive = hn::And(hn::And(atLeast(e0, c0), atLeast(e1, c1)), atLeast(e2, c2));
    const M negative = hn::And(hn::And(atMost(e0, !c0), atMost(e1, !c1)), atMost(e2, !c2));
    return hn::Or(positive, negative);
}

// insideTriangle with each lane's own canonical directions (a moving quad's edges differ by lane),
// given as a tie value per edge and lane: +1 where the edge is canonical, -1 where not. A lane
// exactly on an edge (e = 0) takes the tie for its value, and is inside when all three values are
// > 0, or all < 0, but for a triangle with no area (all three e = 0). That is insideTriangle's rule
// case by case (NaN fails every comparison), in half the operations of testing each edge's two
// ways with its canonical mask.
template <class D, class VD = hn::Vec<D>, class MD = hn::Mask<D>>
HWY_INLINE MD insideTriangleLanes(D d, VD e0, VD tie0, VD e1, VD tie1, VD e2, VD tie2) {
    const VD zero = hn::Zero(d);
    const MD z0 = hn::Eq(e0, zero), z1 = hn::Eq(e1, zero), z2 = hn::Eq(e2, zero);
    const VD t0 = hn::IfThenElse(z0, tie0, e0), t1 = hn::IfThenElse(z1, tie1, e1), t2 = hn::IfThenElse(z2, tie2, e2);
    const MD positive = hn::And(hn::And(hn::Gt(t0, zero), hn::Gt(t1, zero)), hn::Gt(t2, zero));
    const MD negative = hn::And(hn::And(hn::Lt(t0, zero), hn::Lt(t1, zero)), hn::Lt(t2, zero));
    return hn::AndNot(hn::And(hn::And(z0, z1), z2), hn::Or(positive, negative));
}

template <class D>
HWY_INLINE uint64_t maskBits(D d, hn::Mask<D> m) {
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
    // AVX-512: the mask is a k register already (StoreMaskBits would go through memory).
    constexpr size_t kN = hn::MaxLanes(d);
    const uint64_t bits = uint64_t(m.raw);
    return kN >= 64 ? bits : bits & ((uint64_t(1) << hn::Lanes(d)) - 1);
#endif
    uint8_t out[8] = {0};
    hn::StoreMaskBits(d, m, out);
    uint64_t v = 0;
    for (size_t b = 0; b < (hn::Lanes(d) + 7) / 8; ++b) v |= uint64_t(out[b]) << (8 * b);
    return v;
}

// The lanes whose sample lies inside the bound of their moved quad (corners cxs, cys), its ends
// found as lensQuad's std::min and std::max of the four corners find them (the first of equals).
template <class D, class VD = hn::Vec<D>>
HWY_INLINE hn::Mask<D> lensBound(D, VD x, VD y, const VD* cxs, const VD* cys) {
    VD x0 = cxs[0], x1 = cxs[0], y0 = cys[0], y1 = cys[0];
    for (int c = 1; c < 4; ++c) {
        x0 = hn::IfThenElse(hn::Lt(cxs[c], x0), cxs[c], x0), x1 = hn::IfThenElse(hn::Lt(x1, cxs[c]), cxs[c], x1);
        y0 = hn::IfThenElse(hn::Lt(cys[c], y0), cys[c], y0), y1 = hn::IfThenElse(hn::Lt(y1, cys[c]), cys[c], y1);
    }
    return hn::And(hn::And(hn::Ge(x, x0), hn::Le(x, x1)), hn::And(hn::Ge(y, y0), hn::Le(y, y1)));
}

// Lanes [i, i + N) of a lane test: each lane's quad (corners cxs, cys) set up as makeEdge does,
// with the canonical choice made lane by lane, its five edges (q0q1, q1q2, q2q3, q3q0, q2q0)
// evaluated at the lane's sample and stored, and the lanes inside each triangle (hitQuad's
// test) among `inBound` added to r.
template <class D, class VD = hn::Vec<D>, class MD = hn::Mask<D>>
HWY_INLINE void testLanes(D d, VD x, VD y, const VD* cxs, const VD* cys, MD inBound, float* edges, int stride, size_t i,
                          MovingTest& r) {
    const VD zero = hn::Zero(d), one = hn::Set(d, 1.0f), minusOne = hn::Set(d, -1.0f);
    static constexpr int kFrom[5] = {0, 1, 2, 3, 2}, kTo[5] = {1, 2, 3, 0, 0};
    VD e[5], tie[5];
    MD diagonalDegenerate = hn::FirstN(d, 0);
    for (int k = 0; k < 5; ++k) {
        const VD ax = cxs[kFrom[k]], ay = cys[kFrom[k]], bx = cxs[kTo[k]], by = cys[kTo[k]];
        const MD can = hn::Or(hn::Lt(ax, bx), hn::And(hn::Eq(ax, bx), hn::Lt(ay, by)));
        const VD px = hn::IfThenElse(can, ax, bx), py = hn::IfThenElse(can, ay, by);
        const VD dx = hn::Sub(bx, ax), dy = hn::Sub(by, ay);
        e[k] = hn::Sub(hn::Mul(dx, hn::Sub(y, py)), hn::Mul(dy, hn::Sub(x, px)));
        tie[k] = hn::IfThenElse(can, one, minusOne);
        if (k == 4) diagonalDegenerate = hn::And(hn::Eq(dx, zero), hn::Eq(dy, zero));
        hn::StoreU(e[k], d, edges + k * stride);
    }
    // Triangle 2 runs the diagonal the other way: the opposite canonical flag, but false where the
    // diagonal has no length (hitQuad's c02).
    const VD tie02 = hn::IfThenElse(diagonalDegenerate, minusOne, hn::Neg(tie[4]));
    const MD first = hn::And(inBound, insideTriangleLanes(d, e[0], tie[0], e[1], tie[1], e[4], tie[4]));
    const MD second =
        hn::AndNot(first, hn::And(inBound, insideTriangleLanes(d, hn::Neg(e[4]), tie02, e[2], tie[2], e[3], tie[3])));
    r.first |= maskBits(d, first) << i;
    r.second |= maskBits(d, second) << i;
}

}  // namespace

// Lanes [i, i + Lanes(d)) of TestMoving (those below n): each lane's quad at its own time, set up
// and tested as movingQuadAt and hitQuad do, the same operations in the same order (lerp is
// a (1 - w) + b w; makeEdge's canonical choice by lane).
template <class D>
HWY_INLINE void movingLanes(D d, const MovingQuad& q, const float* xs, const float* ys, const float* tfs,
                            const float* seenZ, const float* lus, const float* lvs, size_t i, int n, int stride,
                            float* edges, MovingTest& r) {
    using VD = hn::Vec<D>;
    using MD = hn::Mask<D>;
    const VD zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    const VD x = hn::LoadU(d, xs + i), y = hn::LoadU(d, ys + i), tf = hn::LoadU(d, tfs + i);
    MD inBound = hn::And(hn::And(hn::Not(hn::Lt(x, hn::Set(d, q.xmin))), hn::Not(hn::Gt(x, hn::Set(d, q.xmax)))),
                         hn::And(hn::Not(hn::Lt(y, hn::Set(d, q.ymin))), hn::Not(hn::Gt(y, hn::Set(d, q.ymax)))));
    inBound = hn::And(inBound, hn::FirstN(d, size_t(n) - i));
    const MD behind = hn::And(inBound, hn::Gt(hn::Set(d, q.zmin), hn::LoadU(d, seenZ + i)));
    r.behind |= maskBits(d, behind) << i;
    inBound = hn::AndNot(behind, inBound);
    if (hn::AllFalse(d, inBound)) return;
    // std::min(1, std::max(0, v)), NaN and signed zeros included.
    const VD v = hn::Mul(hn::Sub(tf, hn::Set(d, q.tfA)), hn::Set(d, q.invSpan));
    const VD m = hn::IfThenElse(hn::Lt(zero, v), v, zero);
    const VD w = hn::IfThenElse(hn::Lt(m, one), m, one), omw = hn::Sub(one, w);
    auto lerpV = [&](float a, float b) { return hn::Add(hn::Mul(hn::Set(d, a), omw), hn::Mul(hn::Set(d, b), w)); };
    VD cxs[4], cys[4], zs[4];  // zs: the corners' depths, where read (exact corners, a lens)
    for (int c = 0; c < 4; ++c) {
        if (q.exact[c]) {
            const VD px = lerpV(q.cx[0][c], q.cx[1][c]), py = lerpV(q.cy[0][c], q.cy[1][c]);
            zs[c] = lerpV(q.cz[0][c], q.cz[1][c]);
            const VD iz = hn::Div(one, zs[c]);
            cxs[c] = hn::Add(hn::Mul(hn::Mul(hn::Set(d, q.ax), px), iz), hn::Set(d, q.bx));
            cys[c] = hn::Add(hn::Mul(hn::Mul(hn::Set(d, q.ay), py), iz), hn::Set(d, q.by));
        } else {
            cxs[c] = lerpV(q.x[0][c], q.x[1][c]);
            cys[c] = lerpV(q.y[0][c], q.y[1][c]);
            if (q.lens) zs[c] = lerpV(q.z[0][c], q.z[1][c]);
        }
    }
    r.tested |= maskBits(d, inBound) << i;
    if (q.lens) {  // each corner moved by its lens shift at its depth then (movingLensQuadAt)
        const VD lu = hn::LoadU(d, lus + i), lv = hn::LoadU(d, lvs + i);
        const VD eye = hn::Set(d, q.eyePlane), radius = hn::Set(d, q.lensRadius), invFocal = hn::Set(d, q.invFocal);
        for (int c = 0; c < 4; ++c) {
            const VD zc = hn::IfThenElse(hn::Lt(zs[c], eye), eye, zs[c]);  // std::max(z, eyePlane)
            const VD shift = hn::Mul(radius, hn::Sub(invFocal, hn::Div(one, zc)));
            cxs[c] = hn::Add(cxs[c], hn::Mul(hn::Mul(shift, hn::Set(d, q.ax)), lu));
            cys[c] = hn::Add(cys[c], hn::Mul(hn::Mul(shift, hn::Set(d, q.ay)), lv));
        }
        inBound = hn::And(inBound, lensBound(d, x, y, cxs, cys));
        if (hn::AllFalse(d, inBound)) return;  // as in TestLens
    }
    testLanes(d, x, y, cxs, cys, inBound, edges + i, stride, i, r);
}

// Sixteen lanes a vector where a whole one of lanes is left (AVX-512), eight for the rest: a
// quad's row of pixels over a group of slices is often 32 or 40 lanes, where sixteen test fastest,
// but a group of one or two slices gives rows of 4 to 10, where a sixteen-lane vector tests mostly
// empty lanes (docs/ARCHITECTURE.md). Lanes do not depend on their vector's width.
MovingTest TestMoving(const MovingQuad& q, const float* xs, const float* ys, const float* tfs, const float* seenZ,
                      const float* lus, const float* lvs, int n, float* edges) {
    const hn::CappedTag<float, 16> wide;
    const hn::CappedTag<float, 8> narrow;
    const int stride = edgeStride(n);
    MovingTest r;
    size_t i = 0;
    if (hn::Lanes(wide) > hn::Lanes(narrow))
        for (; i + hn::Lanes(wide) <= size_t(n); i += hn::Lanes(wide))
            movingLanes(wide, q, xs, ys, tfs, seenZ, lus, lvs, i, n, stride, edges, r);
    for (; i < size_t(n); i += hn::Lanes(narrow))
        movingLanes(narrow, q, xs, ys, tfs, seenZ, lus, lvs, i, n, stride, edges, r);
    return r;
}

// Each lane's quad moved by its lens point, bounded and tested as lensQuad and hitQuad do (its
// bound's ends found as std::min and std::max of the four corners find them: the first of equals).
MovingTest TestLens(const LensQuad& q, const float* xs, const float* ys, const float* lus, const float* lvs, int n,
                    float* edges) {
    const hn::CappedTag<float, 8> kD;  // as TestMoving's narrow vectors
    using V = hn::Vec<decltype(kD)>;
    using M = hn::Mask<decltype(kD)>;
    const size_t N = hn::Lanes(kD);
    const int stride = edgeStride(n);
    const V xmin = hn::Set(kD, q.xmin), xmax = hn::Set(kD, q.xmax), ymin = hn::Set(kD, q.ymin), ymax = hn::Set(kD, q.ymax);
    MovingTest r;
    for (size_t i = 0; i < size_t(n); i += N) {
        const V x = hn::LoadU(kD, xs + i), y = hn::LoadU(kD, ys + i);
        M inBound = hn::And(hn::And(hn::Not(hn::Lt(x, xmin)), hn::Not(hn::Gt(x, xmax))),
                            hn::And(hn::Not(hn::Lt(y, ymin)), hn::Not(hn::Gt(y, ymax))));
        inBound = hn::And(inBound, hn::FirstN(kD, size_t(n) - i));
        if (hn::AllFalse(kD, inBound)) continue;
        r.tested |= maskBits(kD, inBound) << i;
        const V lu = hn::LoadU(kD, lus + i), lv = hn::LoadU(kD, lvs + i);
        V cxs[4], cys[4];
        for (int c = 0; c < 4; ++c) {
            cxs[c] = hn::Add(hn::Set(kD, q.x[c]), hn::Mul(hn::Set(kD, q.sx[c]), lu));
            cys[c] = hn::Add(hn::Set(kD, q.y[c]), hn::Mul(hn::Set(kD, q.sy[c]), lv));
        }
        // Out of focus, a lane's moved quad seldom covers its sample: skip the edges where none does
        // (the edges of lanes that hit are all a caller reads).
        const M inMoved = hn::And(inBound, lensBound(kD, x, y, cxs, cys));
        if (hn::AllFalse(kD, inMoved)) continue;
        testLanes(kD, x, y, cxs, cys, inMoved, edges + i, stride, i, r);
    }
    return r;
}

PixelTest TestPixel(const QuadSetup& q, const float* xs, const float* ys, int n, uint64_t candidates, float* edges) {
    const size_t N = hn::Lanes(kD);
    const int stride = edgeStride(n);
    V px[5], py[5], dx[5], dy[5];
    for (int k = 0; k < 5; ++k) {
        px[k] = hn::Set(kD, q.e[k].px), py[k] = hn::Set(kD, q.e[k].py);
        dx[k] = hn::Set(kD, q.e[k].dx), dy[k] = hn::Set(kD, q.e[k].dy);
    }
    const bool diagonalDegenerate = q.e[4].dx == 0 && q.e[4].dy == 0;
    const bool c02 = diagonalDegenerate ? false : !q.e[4].canonical;
    const V xmin = hn::Set(kD, q.xmin), xmax = hn::Set(kD, q.xmax), ymin = hn::Set(kD, q.ymin), ymax = hn::Set(kD, q.ymax);
    PixelTest r;
    for (size_t i = 0; i < size_t(n); i += N) {
        uint64_t bits = candidates >> i;
        if (N < 64) bits &= (uint64_t(1) << N) - 1;
        if (!bits) continue;
        uint8_t maskBytes[8];
        for (int b = 0; b < 8; ++b) maskBytes[b] = uint8_t(bits >> (8 * b));
        const M cand = hn::LoadMaskBits(kD, maskBytes);
        const V x = hn::LoadU(kD, xs + i), y = hn::LoadU(kD, ys + i);
        const M inBound = hn::And(hn::And(hn::Not(hn::Lt(x, xmin)), hn::Not(hn::Gt(x, xmax))),
                                  hn::And(hn::Not(hn::Lt(y, ymin)), hn::Not(hn::Gt(y, ymax))));
        const M tested = hn::And(cand, inBound);
        V e[5];
        for (int k = 0; k < 5; ++k) {
            // Edge::eval: dx * (sy - py) - dy * (sx - px), in this order.
            e[k] = hn::Sub(hn::Mul(dx[k], hn::Sub(y, py[k])), hn::Mul(dy[k], hn::Sub(x, px[k])));
            hn::StoreU(e[k], kD, edges + k * stride + int(i));
        }
        const M first = hn::And(tested, insideTriangle(e[0], q.e[0].canonical, e[1], q.e[1].canonical, e[4], q.e[4].canonical));
        const M second = hn::AndNot(first, hn::And(tested, insideTriangle(hn::Neg(e[4]), c02, e[2], q.e[2].canonical,
                                                                          e[3], q.e[3].canonical)));
        uint8_t out[8] = {0};
        auto bitsOf = [&](M m) {
            std::fill(out, out + 8, uint8_t(0));
            hn::StoreMaskBits(kD, m, out);
            uint64_t v = 0;
            for (int b = 0; b < 8; ++b) v |= uint64_t(out[b]) << (8 * b);
            return v << i;
        };
        r.tested |= bitsOf(tested);
        r.first |= bitsOf(first);
        r.second |= bitsOf(second);
    }
    return r;
}

// The candidate samples of one pixel for a quad: those of the strata [ix0, ix1] x [iy0, iy1] its
// bound overlaps there (rows from the pixel's row, columns from its column: found once each).
HWY_INLINE uint64_t strataCandidates(const SampleLayout& L, int ix0, int ix1, int iy0, int iy1, int c0, int n) {
    uint64_t candidates = 0;
    for (int iy = iy0; iy <= iy1; ++iy) {
        const int row = iy * L.sx - c0;  // the row's first sample, in this chunk
        const int a = std::max(0, row + ix0), b = std::min(n - 1, row + ix1);
        if (a <= b) candidates |= (b - a == 63 ? ~uint64_t(0) : ((uint64_t(2) << (b - a)) - 1)) << a;
    }
    return candidates;
}

// 0, 1, 2 ... for the widest vector.
HWY_ALIGN constexpr int32_t kLaneIndex[64] = {0,  1,  2,  3,  4,  5,  6,  7,  8,  9,  10, 11, 12, 13, 14, 15,
                                              16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31,
                                              32, 33, 34, 35, 36, 37, 38, 39, 40, 41, 42, 43, 44, 45, 46, 47,
                                              48, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60, 61, 62, 63};
static_assert(hn::MaxLanes(kD) <= 64);

// Compress tables for 4 and 8 lanes, in static storage. Highway 1.0.3 keeps its own in
// function-local constexpr arrays, which GCC 12 copies onto the stack at every call: on AVX2, a
// 1 KB rep movsq per Compress, three a packed vector, then the larger part of the still kernel's
// instructions. kCompress8[m]: the lanes set in m, in order, then the others, 4 bits a lane.
constexpr std::array<uint32_t, 256> compressNibbles() {
    std::array<uint32_t, 256> t{};
    for (uint32_t m = 0; m < 256; ++m) {
        uint32_t packed = 0, out = 0;
        for (uint32_t pass = 0; pass < 2; ++pass)
            for (uint32_t lane = 0; lane < 8; ++lane)
                if (((m >> lane) & 1) == (pass == 0 ? 1u : 0u)) packed |= lane << (4 * out++);
        t[m] = packed;
    }
    return t;
}
HWY_ALIGN constexpr std::array<uint32_t, 256> kCompress8 = compressNibbles();
HWY_ALIGN constexpr uint32_t kNibbleShifts[8] = {0, 4, 8, 12, 16, 20, 24, 28};
constexpr std::array<std::array<int32_t, 4>, 16> compressIndices4() {
    std::array<std::array<int32_t, 4>, 16> t{};
    for (int m = 0; m < 16; ++m) {
        int out = 0;
        for (int pass = 0; pass < 2; ++pass)
            for (int lane = 0; lane < 4; ++lane)
                if (((m >> lane) & 1) == (pass == 0 ? 1 : 0)) t[size_t(m)][size_t(out++)] = lane;
    }
    return t;
}
HWY_ALIGN constexpr std::array<std::array<int32_t, 4>, 16> kCompress4 = compressIndices4();

// hn::Compress(v, m) where `bits` are m's lanes (bit i for lane i): the lanes of m first, in order.
template <class D>
HWY_INLINE hn::Vec<D> compressLanes(D d, hn::Vec<D> v, hn::Mask<D> m, uint64_t bits) {
    constexpr size_t kN = hn::MaxLanes(d);
    static_assert(sizeof(hn::TFromD<D>) == 4);
    if constexpr (kN == 8 && HWY_TARGET != HWY_EMU128 && HWY_TARGET != HWY_SCALAR) {
        const hn::RebindToUnsigned<D> du;
        const auto idx = hn::And(hn::Set(du, kCompress8[bits & 0xFF]) >> hn::Load(du, kNibbleShifts), hn::Set(du, 15u));
        return hn::TableLookupLanes(v, hn::IndicesFromVec(d, idx));
    } else if constexpr (kN == 4 && HWY_TARGET != HWY_EMU128 && HWY_TARGET != HWY_SCALAR) {
        return hn::TableLookupLanes(v, hn::SetTableIndices(d, kCompress4[bits & 0xF].data()));
    } else {
        (void)bits;
        return hn::Compress(v, m);
    }
}

// The still kernel packs each quad's candidates (the samples of the strata its bound overlaps, and
// inside the bound) from all the pixels of its bound into full vectors before testing them: a
// micropolygon of about a pixel has a few candidates in each of about four pixels, so testing
// pixel by pixel ran mostly empty lanes. Packing keeps pixel order then sample order, so the hits
// come out in the order the scalar reference makes them.
//
// With a StillWrite (Write), each vector's hits are depth-tested against the still layer at once
// (a gather of its samples' depths) and the winners written there; only ties and pixels with
// records come out as QuadHits.
template <bool Write>
HWY_INLINE uint64_t testQuad(const QuadSetup& q, const SampleLayout& L, const QuadShading* shading, StillWrite* write,
                             QuadHit* out, size_t* hitCount) {
    const size_t N = hn::Lanes(kD);
    const hn::RebindToSigned<decltype(kD)> kI;
    V px[5], py[5], dx[5], dy[5];
    for (int k = 0; k < 5; ++k) {
        px[k] = hn::Set(kD, q.e[k].px), py[k] = hn::Set(kD, q.e[k].py);
        dx[k] = hn::Set(kD, q.e[k].dx), dy[k] = hn::Set(kD, q.e[k].dy);
    }
    const bool c02 = q.e[4].dx == 0 && q.e[4].dy == 0 ? false : !q.e[4].canonical;
    const V xmin = hn::Set(kD, q.xmin), xmax = hn::Set(kD, q.xmax), ymin = hn::Set(kD, q.ymin), ymax = hn::Set(kD, q.ymax);
    const V one = hn::Set(kD, 1.0f);
    const auto lanes = hn::Load(kI, kLaneIndex);  // (hn::Iota goes through memory)
    // The packed candidates: positions, pixels and sample indices of lanes [0, packed), gathered
    // from all the quad's pixels first and tested after, a vector at a time (testing as each
    // vector filled made a branch that mispredicted and a load from stores in flight). Room for
    // kVectors vectors and one more: a store after fewer than N lanes writes a whole vector (the
    // lanes past it unused; the positions start at zero so that the lanes past a last partial
    // vector compute on numbers). A quad with more candidates tests its full vectors on the way.
    constexpr size_t kVectors = 16;
    constexpr size_t kRoom = (kVectors + 1) * hn::MaxLanes(kD);
    HWY_ALIGN float bx[kRoom], by[kRoom], l1s[hn::MaxLanes(kD)], l2s[hn::MaxLanes(kD)];
    HWY_ALIGN float zs[hn::MaxLanes(kD)] = {}, rs[hn::MaxLanes(kD)] = {}, gs[hn::MaxLanes(kD)] = {}, bs[hn::MaxLanes(kD)] = {};
    HWY_ALIGN int32_t bpixel[kRoom], bslot[kRoom];  // pixel, and pixel * S + sample; read only for packed lanes
    size_t packed = 0;
    uint64_t tested = 0;
    size_t hits = *hitCount;
    // Tests packed lanes [at, at + n) (at a multiple of N) and appends their hits.
    auto testPacked = [&](size_t at, size_t n) HWY_ATTR __attribute__((always_inline)) {
        const V x = hn::Load(kD, bx + at), y = hn::Load(kD, by + at);
        const M t = hn::FirstN(kD, n);
        // With a write, the depths the lanes' samples see (SampleHit is 6 floats, z first),
        // gathered before the inside test so that the loads overlap it; lanes past n read sample 0.
        V seen = hn::Zero(kD);
        if constexpr (Write) {
            const auto slot = hn::IfThenElseZero(hn::RebindMask(kI, t), hn::Load(kI, bslot + at));
            seen = hn::GatherIndex(kD, &write->still[0].z, hn::Add(hn::ShiftLeft<2>(slot), hn::ShiftLeft<1>(slot)));
        }
        V ev[5];
        for (int k = 0; k < 5; ++k)
            ev[k] = hn::Sub(hn::Mul(dx[k], hn::Sub(y, py[k])), hn::Mul(dy[k], hn::Sub(x, px[k])));
        const M first =
            hn::And(t, insideTriangle(ev[0], q.e[0].canonical, ev[1], q.e[1].canonical, ev[4], q.e[4].canonical));
        const M second = hn::AndNot(
            first, hn::And(t, insideTriangle(hn::Neg(ev[4]), c02, ev[2], q.e[2].canonical, ev[3], q.e[3].canonical)));
        const M inside = hn::Or(first, second);
        if (hn::AllFalse(kD, inside)) return;
        // Barycentrics as hitQuad makes them (the same operations in the same order): triangle 1
        // weighs q1 by e20 and q2 by e01; triangle 2 weighs q2 by e30 and q3 by e02 = -e20. One
        // division: each lane needs only its own triangle's.
        const V e02 = hn::Neg(ev[4]);
        const V inv = hn::Div(one, hn::IfThenElse(first, hn::Add(hn::Add(ev[0], ev[1]), ev[4]), hn::Add(hn::Add(e02, ev[2]), ev[3])));
        const V l1 = hn::Mul(hn::IfThenElse(first, ev[4], ev[3]), inv), l2 = hn::Mul(hn::IfThenElse(first, ev[0], e02), inv);
        hn::Store(l1, kD, l1s);
        hn::Store(l2, kD, l2s);
        if (shading) {  // each lane's triangle's value at its first corner, plus l1 d1, plus l2 d2
            const QuadShading& s = *shading;
            auto at = [&](float a0, float a1, float d10, float d11, float d20, float d21, float* to) {
                const V a = hn::IfThenElse(first, hn::Set(kD, a0), hn::Set(kD, a1));
                const V d1 = hn::IfThenElse(first, hn::Set(kD, d10), hn::Set(kD, d11));
                const V d2 = hn::IfThenElse(first, hn::Set(kD, d20), hn::Set(kD, d21));
                hn::Store(hn::Add(hn::Add(a, hn::Mul(l1, d1)), hn::Mul(l2, d2)), kD, to);
            };
            at(s.z0[0], s.z0[1], s.dz1[0], s.dz1[1], s.dz2[0], s.dz2[1], zs);
            at(s.c0[0].x, s.c0[1].x, s.dc1[0].x, s.dc1[1].x, s.dc2[0].x, s.dc2[1].x, rs);
            at(s.c0[0].y, s.c0[1].y, s.dc1[0].y, s.dc1[1].y, s.dc2[0].y, s.dc2[1].y, gs);
            at(s.c0[0].z, s.c0[1].z, s.dc1[0].z, s.dc1[1].z, s.dc2[0].z, s.dc2[1].z, bs);
        }
        const uint64_t fi = maskBits(kD, first);
        auto emit = [&](int lane) {
            QuadHit& h = out[hits++];
            h.pixel = uint32_t(bpixel[at + size_t(lane)]);
            h.sample = uint16_t(bslot[at + size_t(lane)] - bpixel[at + size_t(lane)] * L.S);
            h.first = uint8_t((fi >> lane) & 1);
            h.l1 = l1s[lane];
            h.l2 = l2s[lane];
            if (shading) h.z = zs[lane], h.c = {rs[lane], gs[lane], bs[lane]};
        };
        if constexpr (Write) {
            const V z = hn::Load(kD, zs);
            const M inRange = hn::And(inside, hn::And(hn::Ge(z, hn::Set(kD, write->nearZ)), hn::Le(z, hn::Set(kD, write->farZ))));
            const uint64_t nearer = maskBits(kD, hn::And(inRange, hn::Lt(z, seen)));
            const uint64_t tie = maskBits(kD, hn::And(inRange, hn::Eq(z, seen)));
            write->inside += uint64_t(__builtin_popcountll(maskBits(kD, inside)));
            // The write's fields in locals: the stores to the layer could alias them.
            SampleHit* const still = write->still;
            uint8_t* const touched = write->touched;
            // Ties, and winners in pixels with records, are left to the sampler (in lane order).
            uint64_t written = nearer;
            if (const uint16_t* const recordsOf = write->recordsOf)
                for (uint64_t left = nearer; left; left &= left - 1) {
                    const int lane = __builtin_ctzll(left);
                    if (recordsOf[bpixel[at + size_t(lane)]]) written &= ~(uint64_t(1) << lane);
                }
            for (uint64_t left = (nearer | tie) & ~written; left; left &= left - 1) emit(__builtin_ctzll(left));
            if (written) {
                // A winner's hit is its {z, r, g, b}, interleaved from the four vectors at once,
                // then the quad's id. A first hit is one over a depth of +inf: the still layer
                // has no hit exactly there (Camera's far plane is finite).
                HWY_ALIGN float zrgb[4 * hn::MaxLanes(kD)];
                hn::StoreInterleaved4(z, hn::Load(kD, rs), hn::Load(kD, gs), hn::Load(kD, bs), kD, zrgb);
                const uint64_t empty = maskBits(kD, hn::Eq(seen, hn::Set(kD, std::numeric_limits<float>::infinity())));
                write->firstHits += uint64_t(__builtin_popcountll(written & empty));
                const uint64_t id = write->id;
                for (uint64_t left = written; left; left &= left - 1) {
                    const int lane = __builtin_ctzll(left);
                    SampleHit& cur = still[bslot[at + size_t(lane)]];
                    char* const bytes = reinterpret_cast<char*>(&cur);
                    std::memcpy(bytes, zrgb + 4 * lane, 4 * sizeof(float));
                    std::memcpy(bytes + offsetof(SampleHit, id), &id, sizeof id);
                    touched[bpixel[at + size_t(lane)]] = 1;
                }
            }
        } else {
            for (uint64_t left = maskBits(kD, inside); left; left &= left - 1) emit(__builtin_ctzll(left));
        }
    };
    // Up to 64 samples a pixel (one chunk), a pixel's candidates are its columns' strata in each
    // of its rows: the columns' bits times one bit a row (sx bits apart, so no carries). The
    // columns of each pixel of the bound are found once, not once a row.
    constexpr int kColumns = 8;
    const bool columnsKnown = L.S <= 64 && q.px1 - q.px0 < kColumns;
    uint64_t columnBits[kColumns] = {};
    if (columnsKnown)
        for (int ppx = q.px0; ppx <= q.px1; ++ppx) {
            const int ix0 = stratumAt(q.xmin, ppx, L.sx), ix1 = stratumAt(q.xmax, ppx, L.sx);
            columnBits[ppx - q.px0] = ((uint64_t(2) << (ix1 - ix0)) - 1) << ix0;
        }
    for (int ppy = q.py0; ppy <= q.py1; ++ppy) {
        const int iy0 = stratumAt(q.ymin, ppy, L.sy);
        const int iy1 = stratumAt(q.ymax, ppy, L.sy);
        uint64_t rowBits = 0;
        if (columnsKnown)
            for (int iy = iy0; iy <= iy1; ++iy) rowBits |= uint64_t(1) << (iy * L.sx);
        for (int ppx = q.px0; ppx <= q.px1; ++ppx) {
            const uint32_t pixel = uint32_t((ppy - L.y0) * L.width + (ppx - L.x0));
            const float* xs = L.xs + size_t(pixel) * size_t(L.S);
            const float* ys = L.ys + size_t(pixel) * size_t(L.S);
            // Otherwise the pixel's columns, once for all its chunks of 64 samples.
            const int ix0 = columnsKnown ? 0 : stratumAt(q.xmin, ppx, L.sx);
            const int ix1 = columnsKnown ? 0 : stratumAt(q.xmax, ppx, L.sx);
            for (int c0 = 0; c0 < L.S; c0 += 64) {
                const int n = std::min(64, L.S - c0);
                const uint64_t candidates = columnsKnown ? columnBits[ppx - q.px0] * rowBits
                                                         : strataCandidates(L, ix0, ix1, iy0, iy1, c0, n);
                for (size_t i = 0; i < size_t(n); i += N) {
                    uint64_t bits = candidates >> i;
                    if (N < 64) bits &= (uint64_t(1) << N) - 1;
                    if (!bits) continue;
                    uint8_t maskBytes[8];
                    for (size_t b = 0; b < (N + 7) / 8; ++b) maskBytes[b] = uint8_t(bits >> (8 * b));
                    const M cand = hn::LoadMaskBits(kD, maskBytes);
                    const V x = hn::LoadU(kD, xs + c0 + i), y = hn::LoadU(kD, ys + c0 + i);
                    const M inBound = hn::And(hn::And(hn::Not(hn::Lt(x, xmin)), hn::Not(hn::Gt(x, xmax))),
                                              hn::And(hn::Not(hn::Lt(y, ymin)), hn::Not(hn::Gt(y, ymax))));
                    const M t = hn::And(cand, inBound);
                    if (hn::AllFalse(kD, t)) continue;
                    // Append the lanes to the packed ones; test a vector once one is full.
                    const uint64_t tb = maskBits(kD, t);
                    const size_t k = size_t(__builtin_popcountll(tb));
                    hn::StoreU(compressLanes(kD, x, t, tb), kD, bx + packed);
                    hn::StoreU(compressLanes(kD, y, t, tb), kD, by + packed);
                    hn::StoreU(hn::Set(kI, int32_t(pixel)), kI, bpixel + packed);
                    const int32_t first = int32_t(pixel) * L.S + int32_t(c0) + int32_t(i);
                    hn::StoreU(compressLanes(kI, hn::Add(lanes, hn::Set(kI, first)), hn::RebindMask(kI, t), tb), kI, bslot + packed);
                    packed += k;
                    tested += k;
                    if (packed >= kVectors * N) {  // a large quad: test the full vectors, keep the rest
                        for (size_t at = 0; at < kVectors * N; at += N) testPacked(at, N);
                        packed -= kVectors * N;
                        hn::Store(hn::LoadU(kD, bx + kVectors * N), kD, bx);
                        hn::Store(hn::LoadU(kD, by + kVectors * N), kD, by);
                        hn::Store(hn::LoadU(kI, bpixel + kVectors * N), kI, bpixel);
                        hn::Store(hn::LoadU(kI, bslot + kVectors * N), kI, bslot);
                    }
                }
            }
        }
    }
    for (size_t at = 0; at < packed; at += N) testPacked(at, std::min(N, packed - at));
    *hitCount = hits;
    return tested;
}

uint64_t TestQuad(const QuadSetup& q, const SampleLayout& L, const QuadShading* shading, QuadHit* out, size_t* hitCount) {
    return testQuad<false>(q, L, shading, nullptr, out, hitCount);
}

uint64_t WriteQuad(const QuadSetup& q, const SampleLayout& L, const QuadShading& shading, StillWrite& write, QuadHit* out,
                   size_t* left) {
    return testQuad<true>(q, L, &shading, &write, out, left);
}

PixelTestFn Kernel() { return &TestPixel; }
QuadTestFn QuadKernel() { return &TestQuad; }
QuadWriteFn QuadWriteKernel() { return &WriteQuad; }
MovingTestFn MovingKernel() { return &TestMoving; }
LensTestFn LensKernel() { return &TestLens; }
const char* Target() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace streyes
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace streyes {

HWY_EXPORT(Kernel);
HWY_EXPORT(QuadKernel);
HWY_EXPORT(QuadWriteKernel);
HWY_EXPORT(MovingKernel);
HWY_EXPORT(LensKernel);
HWY_EXPORT(Target);

QuadWriteFn quadWriteKernel() {
    static const QuadWriteFn kernel = HWY_DYNAMIC_DISPATCH(QuadWriteKernel)();
    return kernel;
}

QuadTestFn quadTestKernel() {
    static const QuadTestFn kernel = HWY_DYNAMIC_DISPATCH(QuadKernel)();
    return kernel;
}

PixelTestFn pixelTestKernel() {
    static const PixelTestFn kernel = HWY_DYNAMIC_DISPATCH(Kernel)();
    return kernel;
}

MovingTestFn movingTestKernel() {
    static const MovingTestFn kernel = HWY_DYNAMIC_DISPATCH(MovingKernel)();
    return kernel;
}

LensTestFn lensTestKernel() {
    static const LensTestFn kernel = HWY_DYNAMIC_DISPATCH(LensKernel)();
    return kernel;
}

const char* pixelTestTarget() { return HWY_DYNAMIC_DISPATCH(Target)(); }

namespace {

// Highway's name of a target a user names: case-insensitive, and "AVX512" for AVX3.
std::string targetNamed(std::string s) {
    for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
    return s == "AVX512" ? "AVX3" : s;
}

std::string joined(const std::vector<std::string>& names) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    return list;
}

}  // namespace

std::vector<std::string> simdTargets() {
    std::vector<std::string> names;
    for (const int64_t target : hwy::SupportedAndGeneratedTargets()) names.push_back(hwy::TargetName(target));
    return names;
}

bool simdNameKnown(const std::string& name, std::string* error) {
    const std::string want = targetNamed(name);
    std::vector<std::string> built;
    for (int64_t targets = HWY_TARGETS; targets != 0; targets &= targets - 1) {
        built.push_back(hwy::TargetName(targets & ~(targets - 1)));
        if (want == built.back()) return true;
    }
    *error = "no instruction set '" + name + "' for the sample kernels; this build has " + joined(built);
    return false;
}

bool capSimd(const std::string& name, std::string* error) {
    const std::string want = targetNamed(name);
    const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();  // best (lowest bit) first
    int64_t better = 0;
    for (const int64_t target : targets) {
        if (want == hwy::TargetName(target)) {
            if (better) hwy::DisableTargets(better);
            return true;
        }
        better |= target;
    }
    *error = "no instruction set '" + name + "' for the sample kernels on this CPU; it runs " + joined(simdTargets());
    return false;
}

std::vector<KernelSet> kernelsOfEveryTarget() {
    std::vector<KernelSet> out;
    for (const int64_t target : hwy::SupportedAndGeneratedTargets()) {
        hwy::SetSupportedTargetsForTest(target);  // the next dispatch chooses it
        out.push_back({hwy::TargetName(target), HWY_DYNAMIC_DISPATCH(Kernel)(), HWY_DYNAMIC_DISPATCH(QuadKernel)(),
                       HWY_DYNAMIC_DISPATCH(QuadWriteKernel)(), HWY_DYNAMIC_DISPATCH(MovingKernel)(), HWY_DYNAMIC_DISPATCH(LensKernel)()});
    }
    hwy::SetSupportedTargetsForTest(0);
    return out;
}

}  // namespace streyes
#endif  // HWY_ONCE
