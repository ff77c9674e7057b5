// What the caller gives the interpreter for one grid: the point count and shape, the
// predefined variables' values, the named spaces, the primitive variables, and the lights.
//
// Values are views of the caller's arrays (ValueRef), never copied by the caller: structure of
// arrays (stride 1), arrays of Vec3f (stride 3) or one value for every point (stride 0).
// Everything is in "current" space, which is camera space in streyes.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "shade/vm/state_queries.h"
#include "shade/vm/types.h"
#include "streyes/error.h"
#include "streyes/transform.h"
#include "streyes/vecmath.h"

namespace streyes::sl {

// Component c of point i is comp[c][i * stride]; stride 0: one value for all points.
struct ValueRef {
    const float* comp[3] = {nullptr, nullptr, nullptr};
    int stride = 0;

    bool valid() const { return comp[0] != nullptr; }
    bool varying() const { return stride != 0; }
    float at(int c, int i) const { return comp[c][std::ptrdiff_t(i) * stride]; }
    Vec3f vec(int i) const { return {at(0, i), at(1, i), at(2, i)}; }

    static ValueRef uniform(const float* v, int comps = 1) {
        ValueRef r;
        for (int c = 0; c < comps && c < 3; ++c) r.comp[c] = v + c;
        return r;
    }
    static ValueRef uniform(const Vec3f& v) { return {{&v.x, &v.y, &v.z}, 0}; }
    static ValueRef soa(const float* x, const float* y = nullptr, const float* z = nullptr) {
        return {{x, y, z}, 1};
    }
    static ValueRef aos(const Vec3f* v) { return {{&v->x, &v->y, &v->z}, 3}; }
};

// The standard named spaces. "current" and "camera" are the identity in streyes.
enum class Space : uint8_t { Current, Camera, World, Object, Shader, Screen, Raster, NDC, Count };
constexpr int kSpaceCount = int(Space::Count);
const char* spaceName(Space s);

struct NamedSpace {
    std::string name;
    Matrix4 toCurrent;  // from this space to current space (points are row vectors: p * M)
};

// A primitive variable bound by name to the shader parameter of that name (it overrides the
// instance's value and the default). Point-like values must already be in current space.
struct Primvar {
    std::string name;
    SlType type;                  // must equal the parameter's (point, vector, normal mix freely)
    ValueRef value;               // floats and triples; stride 0 for constant and uniform ones
    std::vector<std::string> strings;  // string parameters
    const float* matrix = nullptr;     // 16 floats for a matrix parameter
    SourceLoc loc;                // named by errors (type mismatch)
};

// One grid of a batch shaded in one run (GridShader::shadeSlots): its points are [offset,
// offset + (nu + 1) * (nv + 1)) of the batch, u fastest. Derivatives difference within it only.
struct ShadingGridPart {
    int offset = 0;
    int nu = 0, nv = 0;
};

struct ShadingGrid {
    int n = 0;           // points
    int nu = 0, nv = 0;  // micropolygons: n == (nu + 1) * (nv + 1), u fastest. 0 0: no shape,
                         // derivatives are 0 (points from a ray tracer, say).
    std::array<ValueRef, kGlobalCount> globals{};
    // From each standard space to current space; Current and Camera are not read.
    std::array<Matrix4, kSpaceCount> toCurrent{};
    const std::vector<NamedSpace>* coordinateSystems = nullptr;  // user spaces (CoordinateSystem)
    const std::vector<Primvar>* primvars = nullptr;
    bool flipNormals = false;  // calculatenormal gives Dv(P) ^ Du(P): orientation vs. handedness
    unsigned seed = 0;         // random() is a hash of (seed, point, call)
    float nearClip = 0, farClip = 1;  // camera-space depths where depth() is 0 and 1
    const StateQueries* state = nullptr;  // what option() and attribute() read (none: they give 0)
    double time = 0;  // the shading time in frames, exactly (the `time` global is a float): rays go then
    // rayinfo(): how the points came to be shaded. Depth 0 and "camera" for what the eye sees;
    // a ray's hits: its depth (1 for rays from those) and "specular" (trace) or "diffuse".
    int rayDepth = 0;
    const char* rayType = "camera";
    // Several small grids shaded in one run: their shapes, in order, covering the n points (nu
    // and nv are then 0). Null: one grid of nu x nv. Only programs batchProgramSafe() accepts may
    // run over such a grid: their values at a point depend on its own grid's data alone.
    const ShadingGridPart* parts = nullptr;
    int partCount = 0;

    void set(Global g, ValueRef v) { globals[size_t(g)] = v; }
    void setSpace(Space s, const Matrix4& m) { toCurrent[size_t(s)] = m; }
    // A grid of nu x nv micropolygons.
    void setShape(int nu_, int nv_) { nu = nu_; nv = nv_; n = (nu + 1) * (nv + 1); }
};

class ShaderInstance;

// A light as a surface's illuminance loops see it: its shader instance and its own "shader"
// space (and "object" space, the same) at the shading time.
struct LightRef {
    LightRef() = default;
    LightRef(const ShaderInstance* s, const Matrix4& m) : shader(s), toCurrent(m) {}
    // One point of an area light: N is the light's surface normal there (current space), and
    // what it gives is weighted by `weight` (1 / the number of points).
    LightRef(const ShaderInstance* s, const Matrix4& m, Vec3f n, float w)
        : shader(s), toCurrent(m), normal(n), hasNormal(true), weight(w) {}

    const ShaderInstance* shader = nullptr;
    Matrix4 toCurrent;
    Vec3f normal{0, 0, 0};
    bool hasNormal = false;
    float weight = 1;
};

}  // namespace streyes::sl
