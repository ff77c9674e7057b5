// A diced grid of micropolygons: (nu+1) x (nv+1) vertices, each at the body's t0 and t1.
//
// A micropolygon is the bilinear quad between four neighbouring vertices; its corners move
// linearly from t0 to t1. Grids are reused from body to body within a bucket, so the vectors
// keep their capacity and dicing allocates nothing once warm.
#pragma once

#include <cstdint>
#include <vector>

#include "streyes/vecmath.h"

namespace streyes {

struct Material;

// Grid::stillShadows: the light slots whose "no moving occluder" bit it has, and the value of a
// grid whose shadows are folded into its colour (every bit set: no other value has them all).
constexpr int kUnblockedSlots = 6;
constexpr unsigned kUnblockedBits = (1u << kUnblockedSlots) - 1u;
constexpr uint8_t kFoldedShadows = 0xFF;

struct Grid {
    int nu = 0, nv = 0;           // micropolygons along u and v
    double t0 = 0, t1 = 0;        // time span, in frames
    bool openEnd = false;         // [t0, t1): a sample exactly at t1 belongs to the next piece
    bool moving = false;          // when false only the [0] arrays are filled
    const Material* material = nullptr;
    uint64_t primitiveId = 0;     // the body's primitive: breaks exact depth ties
    float u0 = 0, u1 = 1, v0 = 0, v1 = 1;  // the body's parameter rectangle (Body::uv)
    bool flatShading = false;
    // The leaf of a solid this grid bounds (Material::solid), -1: none; and which way round a
    // micropolygon's triangle runs in raster space where its outside faces the eye (+1: the
    // signed area of (0, 1, 2) is positive there, -1: negative). Set by the bucket after dicing.
    int solid = -1;
    int frontWinding = 1;
    // Matte 1 (Material::matte): a holdout. Sampled as opaque whatever its Oi, its hits tagged
    // (raster/image_block.h kMatteBit) so that resolving gives them colour 0 and alpha 0.
    bool matte = false;
    // A level of detail's dissolve (Material::dissolveLo/Hi): only this share of a frame's samples
    // sees the grid. [0, 1): every sample.
    float dissolveLo = 0, dissolveHi = 1;
    bool dissolves() const { return dissolveLo > 0 || dissolveHi < 1; }
    const float* primvarCorners = nullptr;  // the body's (Body::primvarCorners)

    std::vector<Vec3f> P[2];      // camera-space positions at t0, t1
    std::vector<Vec3f> N[2];      // geometric normals (not normalised)
    std::vector<Color> Cs;        // surface colour per vertex
    // Micropolygons cut away by a trim curve (nu x nv, u fastest; non-zero: not rasterized).
    // Empty when none is: every dice starts it empty (Body::startGrid); resize() keeps it, as a
    // still grid made moving to be shaded at both ends is the same grid.
    std::vector<uint8_t> hole;
    // Where a dicer does not space vertices evenly over the body's parameter rectangle (a curved
    // body's sides follow its neighbours' lattices to stay crack-free): each vertex's fraction
    // of the rectangle in u and in v, which u, v and the primitive variables are evaluated at.
    // Empty: evenly spaced. Every dice starts them empty (Body::startGrid).
    std::vector<float> paramU, paramV;
    std::vector<Color> Ci[2];     // shaded colour at t0, t1 (written by the shading stage)
    // Shaded opacity at t0, t1 (RenderMan's Oi; Ci is premultiplied by it). Empty for a slot
    // shaded opaque (the usual case): the rasterizer reads a missing slot as Oi = 1. Written by the
    // shading stage for materials that can be transparent (Opacity < 1, Shading Language surfaces).
    std::vector<Color> Oi[2];
    // Lights that cast shadows: their contribution per vertex (shadowSlots colours a vertex, at
    // t0 and t1), kept out of Ci for the per-sample shadow test. Set shadowSlots before dicing.
    int shadowSlots = 0;
    std::vector<Color> Cl[2];
    // Bit 0: Cl[0] already carries the shadow of the occluders that stand still through the shot
    // (a still grid under still lights, tested once per vertex: trace.h, occludeStillVertices),
    // and its samples' own shadow rays test only the moving occluders. Bit k + 1: no moving
    // occluder can come between the grid and light slot k's light (no ray at all; slots 0 to
    // kUnblockedSlots - 1). 0: neither. kFoldedShadows: every shadow was decided at the vertices
    // for the whole shot and added into Ci (Cl zero): its samples need no shadow pass.
    uint8_t stillShadows = 0;
    // Where not empty: stillShadows for the samples of each frame frameShadowsFirst + i (bits for
    // the lights no moving body can shadow in that frame), which they take instead (stillShadowsOf).
    std::vector<uint8_t> frameShadows;
    int frameShadowsFirst = 0;
    // Where a frame's value is kFoldedShadows: Ci[0] with the parts added, the colour of that
    // frame's samples (as a grid folded in every frame has it in Ci).
    std::vector<Color> CiFolded;
    uint8_t stillShadowsOf(int frame) const {
        const long i = long(frame) - frameShadowsFirst;
        return i >= 0 && i < long(frameShadows.size()) ? frameShadows[size_t(i)] : stillShadows;
    }

    // Output variables (util/aov.h) per vertex at t0, t1: aovCount floats each, laid out as the
    // render's AovLayout; empty when no display asks for one. Set aovCount before dicing.
    int aovCount = 0;
    std::vector<float> aov[2];

    int vertexCount() const { return (nu + 1) * (nv + 1); }
    int index(int i, int j) const { return j * (nu + 1) + i; }  // i along u, j along v
    void resize(int nu_, int nv_, bool moving_) {
        nu = nu_;
        nv = nv_;
        moving = moving_;
        size_t n = size_t(vertexCount());
        for (int k = 0; k < (moving ? 2 : 1); ++k) {
            P[k].resize(n);
            N[k].resize(n);
            Ci[k].resize(n);
            if (shadowSlots) Cl[k].resize(n * size_t(shadowSlots));
            if (aovCount) aov[k].resize(n * size_t(aovCount));
        }
        Cs.resize(n);
    }
};

}  // namespace streyes
