// Which programs may run over a batch of grids (ShadingGrid::parts) and give every point the
// value it has when its grid is shaded alone, bit for bit (internal to shade/vm and its callers).
#pragma once

#include <exception>

#include "shade/vm/program.h"

namespace streyes::sl {

// True when every derivative (Du, Dv, Deriv, area, calculatenormal, filterstep) comes before the
// first varying control flow or light statement, where every point runs: under a mask, a
// derivative reads neighbours that did not run, which hold what an earlier run left there, and
// an earlier run of a batch is not the one of the grid alone. Every other operation computes a
// point from that point's operands, but for those gridWideOp names.
bool batchProgramSafe(const ShaderProgram& p);

// An operation that reads the point's index in the run or the grid's seed, or hands the run's
// points to something outside as a set (random, textures, shadows, rays, gather, point clouds,
// message passing, printf's output order). A run over a batch refuses it when it executes
// (ShadingVM throws BatchRefused; the caller shades the grids one by one): a light's shadow()
// under `if (shadowname != "")` never runs without a map, and its light batches.
bool gridWideOp(OpFn fn);

struct BatchRefused : std::exception {
    const char* what() const noexcept override { return "a grid-wide operation in a batched run"; }
};

}  // namespace streyes::sl
