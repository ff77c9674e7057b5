// The interpreter's hot per-point loops as SIMD kernels over a grid's points (Highway, compiled
// once per instruction set and chosen at run time, capped as the sample kernels are: capSimd in
// raster/sample_kernels.h), and the plain C++ reference they must match bit for bit.
//
// Same pixels on every machine: each kernel makes exactly the reference's IEEE operations in the
// same order on each lane (add, subtract, multiply, divide, square root and compares are exactly
// rounded on every target; the build has -ffp-contract=off so nothing is fused; no approximate
// reciprocals; pow stays std::pow, point by point). Tails shorter than a vector run the
// reference code. grid_kernels_test.cpp checks every target this CPU runs against the reference.
//
// Operands are component arrays of n floats (a triple: three); `varying` false means one value
// for every point (read at [0]).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace streyes::sl {

// One light's results over the points, as sumLights reads them (vm.h's LightResult).
struct LightLanes {
    const float* Ln[3];   // L normalised
    const float* Cl[3];
    const uint8_t* lit;   // 1 where the light reached the point
    bool varying = true;  // false: one value (Ln, Cl and lit at [0]) for every point
};

struct GridKernels {
    const char* target;  // "SCALAR reference", or Highway's target name
    // out = normalize(a): 0 where |a|^2 is 0, NaN or infinite (exec.h's normalize3).
    void (*normalize)(size_t n, const float* const a[3], bool av, float* const out[3]);
    // out = a . b
    void (*dot)(size_t n, const float* const a[3], bool av, const float* const b[3], bool bv, float* out);
    // out = I . ref < 0 ? N : N * -1
    void (*faceforward)(size_t n, const float* const N[3], bool nv, const float* const I[3], bool iv,
                        const float* const ref[3], bool rv, float* const out[3]);
    // out = b == 0 ? 0 : a / b
    void (*divide)(size_t n, const float* a, bool av, const float* b, bool bv, float* out);
    // The map operations of shadeops_math.cpp, as its scalar lambdas write them:
    // out = a + b, a - b, a * b, std::min(a, b), std::max(a, b).
    void (*add)(size_t n, const float* a, bool av, const float* b, bool bv, float* out);
    void (*sub)(size_t n, const float* a, bool av, const float* b, bool bv, float* out);
    void (*mul)(size_t n, const float* a, bool av, const float* b, bool bv, float* out);
    void (*min)(size_t n, const float* a, bool av, const float* b, bool bv, float* out);
    void (*max)(size_t n, const float* a, bool av, const float* b, bool bv, float* out);
    // out = b == 0 ? 0 : a - b * floor(a / b)
    void (*mod)(size_t n, const float* a, bool av, const float* b, bool bv, float* out);
    // filterstep(edge, s) over a micropolygon (shadeops_deriv.cpp): su and sv are s's changes
    // along u and v at each point (n floats each); w = (|su| + |sv|) * wscale, lo = s - w / 2,
    // hi = s + w / 2, out = hi > lo ? min(1, max(0, (hi - edge) / (hi - lo))) : s < edge ? 0 : 1.
    void (*filterstep)(size_t n, const float* edge, bool ev, const float* s, bool sv_, const float* su,
                       const float* sv, float wscale, float* out);
    // out = a * (1 - t) + b * t
    void (*mix)(size_t n, const float* a, bool av, const float* b, bool bv, const float* t, bool tv, float* out);
    // out = v <= e0 ? 0 : v >= e1 ? 1 : s * s * (3 - 2 * s) with s = (v - e0) / (e1 - e0)
    void (*smoothstep)(size_t n, const float* e0, bool e0v, const float* e1, bool e1v, const float* v, bool vv,
                       float* out);
    // diffuse(): out += Cl * (Ln . N) where lit, not Ln . unitN < cosHalf and not Ln . N <= 0.
    void (*diffuseLight)(size_t n, const LightLanes& l, float cosHalf, const float* const unitN[3],
                         const float* const N[3], bool nv, float* const out[3]);
    // specular()'s base before the power: where lit and Ln . unitN >= cosHalf,
    // max(0, N . normalize(Ln + V)), else -1 (the point takes nothing from this light).
    void (*specularBase)(size_t n, const LightLanes& l, float cosHalf, const float* const unitN[3],
                         const float* const N[3], bool nv, const float* const V[3], bool vv, float* base);
    // out += Cl * t except where t <= 0 (a NaN t is added, as the interpreter always did).
    void (*addLight)(size_t n, const float* const Cl[3], bool clv, const float* t, float* const out[3]);
    // Three component arrays from n triples (x y z x y z ...).
    void (*deinterleave3)(size_t n, const float* xyz, float* const out[3]);
};

// The kernels this CPU runs (the widest instruction set allowed), chosen once.
const GridKernels& gridKernels();
// The plain C++ reference: the interpreter's plain path.
const GridKernels& gridKernelsScalar();
// Every instruction set this CPU runs and this build has kernels for (tests).
std::vector<const GridKernels*> gridKernelsOfEveryTarget();

}  // namespace streyes::sl
