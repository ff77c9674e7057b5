// Can a shader's results change when only the camera moves? A dataflow analysis over the checked
// syntax tree (issue 48): a grid still in world under a moving camera is shaded once for a block
// of frames only when its shaders' results cannot.
//
// Shading runs in camera ("current") space, so the analysis gives each value one of:
//   invariant  the same whatever the camera (numbers, parameters, Cs, s, t, u, v, a point taken
//              to "world", "object" or "shader" space, dot products and lengths of vectors...);
//   point      a world-still point in current space: P, Ps, a point from "world" space, P + v;
//   vector     a world-still direction in current space: N, Ng, dPdu, dPdv, L in illuminance,
//              P - Q, sums, scaling by invariant floats, normalize, cross, Du(P), reflect(v, N);
//   view       anything else: I, E, dPdtime, values given in current, camera, screen, raster
//              or NDC space, a component of a point or vector (xcomp(P)), noise(P), specular(),
//              random(), rays, message passing (lightsource()) and textureinfo().
// Each value also carries `facing`: it depends on the view only through the sign of N.I or Ng.I
// (faceforward(N, I), or N.I compared with 0), of the renderer's N and Ng.
// A value assigned under a condition takes the condition's class (a branch on zcomp(P) makes what
// it assigns view); loops and illuminance are iterated to a fixed point; break, continue and
// return raise the class of everything after them in their loop or function; user functions are
// analysed at each call with their arguments' classes. The results must be: Ci, Oi, Cl, Ol and
// output parameters invariant; a displacement's P a point and N a vector.
//
// The rules for dot, length, distance, area, normalize and cross hold only for a rigid camera
// (rotation and translation): the renderer checks the camera (SceneShaders) and treats a scaling
// or shearing one as reading the view. Whether the lights a surface reads are still in world is
// the renderer's too (SceneShaders::bind).
#pragma once

#include <string>

#include "shade/sl/checker.h"
#include "shade/vm/program.h"

namespace streyes::sl {

struct ViewUseResult {
    ViewUse use = ViewUse::Reads;
    std::string why;  // Reads: "file:line:col: what" of the first value that reads the view
};

// Analyses a checked shader (after checkShader). Never throws on a valid tree.
ViewUseResult analyzeViewUse(const CheckedShader& shader);

}  // namespace streyes::sl
