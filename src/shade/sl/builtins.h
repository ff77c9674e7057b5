// The standard library's signatures (RI Spec 3.2, chapter 15): what the checker resolves calls
// against and which interpreter operation (or code-generator rule) each one becomes.
#pragma once

#include <string>
#include <vector>

#include "shade/vm/program.h"

namespace streyes::sl {

// Calls the code generator handles itself rather than as op(dst, args...).
enum class Special {
    None,
    MinMax,       // min/max of two or more: a chain of two-argument operations
    Comp,         // xcomp, ycomp, zcomp: comp with a fixed index (Builtin::index)
    SetComp,      // setxcomp, ..., setcomp: a copy with one component set, stored into arg 0
    Faceforward,  // faceforward(N, I): Nref is Ng
    Transform,    // transform, vtransform, ntransform: space names or matrices
    CTransform,   // ctransform(from, to, c) / ctransform(to, c)
    Fresnel,      // outputs Kr, Kt [, R, T]
    Spline,       // spline([basis,] value, knots...) / spline([basis,] value, array)
    Filterstep,   // filterstep(edge, s1 [, s2] [, "width", w])
    Lightsource,  // lightsource(name, output var): any type
    Message,      // surface, displacement, atmosphere, incident, opposite (name, output var):
                  // another shader's parameter (Builtin::index: which, vm/vm.h Peer)
    Query,        // option, attribute, rendererinfo (name, output var), textureinfo (map, name, var)
    Printf,
    Format,
    Concat,
    Texture,      // texture, environment, shadow: channels, coordinate forms, options
    Environment,
    Shadow,
    Ray,          // occlusion, indirectdiffuse, trace, transmission: positional, then options
    Gather,       // $gather (the parser's lowering of a gather loop): one ray a point; outputs
    PointCloud,   // bake3d (file, channels, P, N, pairs), texture3d (file, P, N, output pairs)
    Bake,         // bake (file, s, t, value)
};

struct Builtin {
    std::string name;
    SlType ret;
    std::vector<SlType> args;
    OpFn op = nullptr;
    Special special = Special::None;
    unsigned outputs = 0;   // bit i: argument i is written (must be a variable)
    bool varargs = false;   // more arguments may follow the listed ones
    bool varying = false;   // varying even from uniform arguments (noise of P is not; random is)
    bool lights = false;    // needs the lights (ambient, diffuse, specular, phong)
    int index = -1;         // Comp / SetComp: the component; Transform: 0 point, 1 vector, 2 normal
};

// Every signature named `name` (empty when there is none), in preference order: when only the
// return type tells two apart, the first is the default (float before color before point).
const std::vector<const Builtin*>& findBuiltins(const std::string& name);

}  // namespace streyes::sl
