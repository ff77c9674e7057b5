// The micropolygon hit test: is a sample inside a quad, and where (for depth and colour). The
// scalar kernel: the rasterizer's loops (rasterizer.cpp) and the tests of watertightness use it.
#pragma once

#include <algorithm>
#include <cstdint>

#include "streyes/vecmath.h"

namespace streyes::micropolygon {

// A quad q0 q1 q2 q3 (grid order (0,0) (1,0) (1,1) (0,1)) is two triangles, (q0 q1 q2) and
// (q0 q2 q3), sharing the diagonal q0-q2. Its five edges are set up once from their canonical
// start point (the lexicographically smaller endpoint), so an edge shared with a neighbouring
// micropolygon, or the diagonal shared by the two triangles, gives exactly opposite values on its
// two sides.

// An edge a -> b as the quad runs it: from its canonical start point (px, py), along the quad's
// own direction (dx, dy) = b - a. The neighbour that runs it b -> a has the same start and
// a - b = -(b - a), so the two values are exactly opposite (IEEE rounding is symmetric in sign),
// or both zero. That is the canonical edge function times +-1 bit for bit, but for the sign of an
// exact zero (the inside test compares with 0; a corner's weight of -0 instead of +0 reaches a
// hit's value only where that value is -0 at every corner), with one multiplication and three
// selections fewer a lane in the moving kernel.
struct Edge {
    float px, py, dx, dy;
    bool canonical;  // whether the quad runs the edge in canonical direction
    float eval(float sx, float sy) const { return dx * (sy - py) - dy * (sx - px); }
};

inline Edge makeEdge(float ax, float ay, float bx, float by) {
    const bool canonical = ax < bx || (ax == bx && ay < by);
    return {canonical ? ax : bx, canonical ? ay : by, bx - ax, by - ay, canonical};
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
    float zmin;              // nearest depth of the bound: a sample with a nearer hit cannot be beaten
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

// The quad `q` as the lens point (lu, lv) sees it: each vertex moved by its raster lens shift
// (sx[c] lu, sy[c] lv). False when the sample (x, y) is outside the moved quad's bound (then the
// edges are not set up). The samplers' lens paths and the lens kernel (sample_kernels.h) use it.
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

// Bound and pixel range of a quad; false when it misses the block or the clipping range.
// `margin(zmin, zmax)` grows the raster bound in x and y (depth of field: the circle of
// confusion over the quad's depths, Camera::cocMargin); the plain form grows it by nothing.
// Always inlined: the moving sampler calls it once per quad and group of slices, and GCC left it
// a call there (4% of the forest's CPU time).
template <typename Margin>
[[gnu::always_inline]] inline bool boundQuad(QuadSetup& q, const float* x2, const float* y2, const float* z2,
                                             const PixelRect& R, float nearZ, float farZ, Margin margin) {
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
    q.zmin = zmin;
    const Vec2f m = margin(zmin, zmax);
    q.xmin -= m.x, q.xmax += m.x;
    q.ymin -= m.y, q.ymax += m.y;
    if (!(q.xmax >= float(R.x0) && q.xmin < float(R.x1 + 1) && q.ymax >= float(R.y0) && q.ymin < float(R.y1 + 1)))
        return false;  // also rejects NaN
    q.px0 = floorClamped(q.xmin, R.x0, R.x1);
    q.px1 = floorClamped(q.xmax, R.x0, R.x1);
    q.py0 = floorClamped(q.ymin, R.y0, R.y1);
    q.py1 = floorClamped(q.ymax, R.y0, R.y1);
    return true;
}
inline bool boundQuad(QuadSetup& q, const float* x2, const float* y2, const float* z2, const PixelRect& R,
                      float nearZ, float farZ) {
    return boundQuad(q, x2, y2, z2, R, nearZ, farZ, [](float, float) { return Vec2f{0, 0}; });
}

}  // namespace streyes::micropolygon
