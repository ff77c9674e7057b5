// Where occlusion(), indirectdiffuse(), trace() and transmission() get their values: an
// interface the renderer implements with its spacetime ray tracer (trace/shader_rays.h) and
// tests replace with a double. Shading sits below ray tracing in the layers; the tracer reaches
// the interpreter downwards through this, as textures do through TextureSource.
//
// One call covers every active point of a grid (one virtual call per call site and grid, never
// per point). Arrays are structure of arrays, n long; the source writes each active point's
// result (the rest are ignored). Rays are cast at `time`, the time the grid is shaded at, so
// what a shader sees through them is what exists at that instant.
#pragma once

#include <cstdint>
#include <limits>
#include <string>

namespace streyes::sl {

// The named arguments of a ray-traced call, uniform over the grid (taken at the first point
// that runs, like texture options).
struct RayOptions {
    float samples = 0;  // rays per point; 0: the function's default (one for trace, 16 otherwise)
    float maxdist = std::numeric_limits<float>::infinity();  // hits farther away do not count
    float coneangle = -1;     // half-angle of the cone about D; < 0: the function's default (pi/2; trace 0)
    float bias = -1;          // rays start this far from P; < 0: the source's default
    std::string environmentmap;  // what a ray that hits nothing sees (indirectdiffuse); "": black
    // "environmentspace": current-space directions times this (row vectors, row-major; its 3 x 3
    // part) are the map's directions. Identity without the option: the map is in current space,
    // as environment() takes what it is given.
    float environmentFromCurrent[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    bool uniform = false;     // gather's "distribution" "uniform": directions uniform in solid angle (else cosine)
    const std::string* shader = nullptr;  // the calling shader's name, for warnings
};

// The named arguments a call writes (output variables, after PRMan): indirectdiffuse()'s
// "occlusion" (float: the occlusion the same samples give) and occlusion()'s "environmentcolor"
// (color: the environment map the occluders let through, as a sum over all the samples, so that
// a constant map c gives c (1 - occlusion)).
inline bool isRayOutputOption(const std::string& function, const std::string& name) {
    return (function == "indirectdiffuse" && name == "occlusion") || (function == "occlusion" && name == "environmentcolor");
}

struct RayQuery {
    int n = 0;
    const uint8_t* active = nullptr;  // nullptr: every point
    // P: where rays start. D: occlusion and indirectdiffuse, the normal the hemisphere is about;
    // trace, the direction; transmission, the point rays go to.
    const float* P[3] = {};
    const float* D[3] = {};
    double time = 0;     // in frames
    unsigned seed = 0;   // the grid's (its primitive's): with each point's P and the call site,
                         // what picks its sample directions
    uint32_t site = 0;   // the call site in the program, so two calls at a point sample differently
};

// What one gather() sample gives each active point (arrays n long; nullptr: not wanted).
struct GatherHits {
    uint8_t* hit = nullptr;            // 1 where the ray hit something (always written)
    float* dir[3] = {};                // the ray's unit direction (always written)
    float* Ci[3] = {};                 // the nearest hit's colour, shaded by its own shader
    float* Oi[3] = {};                 // and opacity
    float* P[3] = {};                  // where it is
    float* N[3] = {};                  // its normal
    float* length = nullptr;           // its distance from P
};

class RaySource {
  public:
    virtual ~RaySource() = default;
    // The fraction of the cone about D (cosine-weighted) in which a ray from P hits something
    // within maxdist: 0 open, 1 covered, into out[0]. out[1..3], when not null: the call's
    // "environmentcolor", the environment map in the directions of the same rays that hit
    // nothing, summed and divided by all the rays (black without a map).
    virtual void occlusion(const RayOptions& o, const RayQuery& q, float* const* out) = 0;
    // The light arriving at P over the cone about D, cosine-weighted and normalised (a uniform
    // white surrounding gives 1): hits shaded, misses the environment map in their direction
    // (or black without one). out[0..2] the colour; out[3], when not null, the share of the
    // same rays that hit something within maxdist (the call's "occlusion" output).
    virtual void indirectdiffuse(const RayOptions& o, const RayQuery& q, float* const* out) = 0;
    // The colour seen from P along D (the nearest hit, shaded; black when nothing is hit or the
    // ray depth is spent), averaged over `samples` rays in the cone about D.
    virtual void trace(const RayOptions& o, const RayQuery& q, float* const* out) = 0;
    // The light that gets from P to D through what lies between: the product of (1 - opacity)
    // of each surface crossed (1 when nothing is).
    virtual void transmission(const RayOptions& o, const RayQuery& q, float* const* out) = 0;
    // Sample `sample` of o.samples of a gather() loop: one ray a point in the cone of half-angle
    // o.coneangle about D (cosine-weighted, or uniform with o.uniform), its nearest hit within
    // maxdist. The default traces nothing: every ray misses, along D.
    virtual void gather(const RayOptions& o, const RayQuery& q, int sample, const GatherHits& out) {
        (void)o;
        (void)sample;
        missAll(q, out);
    }
    static void missAll(const RayQuery& q, const GatherHits& out) {
        for (int i = 0; i < q.n; ++i) {
            out.hit[i] = 0;
            for (int c = 0; c < 3; ++c) out.dir[c][i] = q.D[c][i];
        }
    }
};

}  // namespace streyes::sl
