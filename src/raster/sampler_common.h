// What the still and the moving samplers share: the depth test and the writes of a sample's hit,
// a quad's opacity, the hidden-pixel tests and the lens's view of a quad. Internal to src/raster.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "geom/camera.h"
#include "geom/grid.h"
#include "raster/image_block.h"
#include "raster/micropolygon.h"

namespace streyes::sampler {

using namespace micropolygon;

// Internal linkage, as when the samplers were one file: GCC inlines what each file calls once.
namespace {

// Is the sample at fraction tf of the exposure inside the part [tfA, tfB] a grid covers, open at
// tfB when the grid ends there half-open?
inline bool inTimeSpan(float tf, float tfA, float tfB, bool openB) {
    return tf >= tfA && (tf < tfB || (tf == tfB && !openB));
}

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
    *out = {zh, c, id};
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
    const Color clamped{std::clamp(o.x, 0.0f, 1.0f), std::clamp(o.y, 0.0f, 1.0f), std::clamp(o.z, 0.0f, 1.0f)};
    *out = {hit.z, hit.c, Color{1, 1, 1} - clamped, id, -1};
    return true;
}

// Keeps a fragment that frame fi alone sees at sample sj of pixel pi: in the frame's record of the
// pixel, made for it when missing (so the frame resolves the pixel itself). Its index.
inline int32_t keepFrameFragment(ImageBlock& block, int fi, size_t pi, int sj, const SampleFragment& f, SampleHit*& rec) {
    if (!rec) rec = block.makeRecord(fi, pi);
    block.startFragments();
    return block.addFragment(block.recordFragments(fi, pi) + sj, f);
}

// Whether triangle h of a quad with raster corners x, y (at the sample's time) shows its outside to
// the eye, given which way round such a triangle runs in the grid (Grid::frontWinding): a
// crossing that enters the solid the grid bounds (geom/solid_tree.h). The winding flips exactly
// where a closed surface folds over at its silhouette, so front and back layers are told apart
// sample by sample.
inline bool entersSolid(const float* x, const float* y, const Hit& h, int frontWinding) {
    const float a = (x[h.v1] - x[h.v0]) * (y[h.v2] - y[h.v0]) - (y[h.v1] - y[h.v0]) * (x[h.v2] - x[h.v0]);
    return (a > 0) == (frontWinding > 0);
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

// A grid's opacities at slot k, or null where the slot was shaded opaque (GridShader keeps Oi
// only where some point is see-through).
inline const Color* opacities(const Grid& grid, int k) {
    return grid.Oi[k].size() == size_t(grid.vertexCount()) ? grid.Oi[k].data() : nullptr;
}

// With the hit, the K contributions of lights that cast shadows, interpolated the same way.
template <typename PartAt>
inline void writeShadowed(Color* out, uint8_t* tested, uint8_t stillTested, int K, const Hit& h, PartAt partAt) {
    *tested = stillTested;  // Grid::stillShadows
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

// Whether every sample of pixel pi in frame fi already sees something nearer than zmin. The
// pixel's farthest bound (ImageBlock::farthestBound) says so without reading its hits; a stale one
// (negative: its farthest sample came nearer since) is measured again only when it fails.
inline bool pixelBehind(ImageBlock& block, int fi, size_t pi, float zmin, int S) {
    float& bound = block.farthestBound(fi, pi);
    if (bound < 0 && !(zmin > -bound)) {
        // Up to the first sample that sees nothing (+inf, the farthest there is): in a pixel being
        // filled, each first hit makes the bound stale, and the next quad measures it again.
        const SampleHit* seen = block.hits(fi, pi);
        bound = seen[0].z;
        for (int k = 1; k < S && bound != std::numeric_limits<float>::infinity(); ++k) bound = std::max(bound, seen[k].z);
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

// The raster lens shifts of a quad's corners per unit lens coordinate.
inline void lensShifts(const Camera& camera, const float* z, float* sx, float* sy) {
    for (int c = 0; c < 4; ++c) {
        const float s = camera.lensShift(std::max(z[c], camera.eyePlane()));
        sx[c] = s * camera.ax();
        sy[c] = s * camera.ay();
    }
}

}  // namespace
}  // namespace streyes::sampler
