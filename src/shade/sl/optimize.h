// The code generator's backend optimisations: constant folding (an operation whose operands
// are all constants is computed once, at compile time, by the interpreter's own operation, so
// the value is the one the VM would compute bit for bit) and dead-code removal (pure operations
// whose results, temporaries or local variables, nothing reads are dropped, and jump targets
// moved to match).
//
// BackendOptions::optimize = false compiles the plain program (tests compare the two).
#pragma once

#include <vector>

#include "shade/vm/program.h"

namespace streyes::sl {

struct BackendOptions {
    bool optimize = true;  // constant folding and dead-code removal
};

// The value of `fn` (an arithmetic, comparison or logical operation, or dot or cross) on the
// constant registers a and b (b -1 for a unary operation) of `p`, into a uniform result of type
// `result`: its floats in *out, and true. False when fn is not one that folds, an operand is not
// a constant, or the VM would sanitise or count something (x / 0), so that it still does.
bool foldConstant(const ShaderProgram& p, OpFn fn, SlType result, int a, int b, std::vector<float>* out);

// Removes the pure instructions whose results (temporaries, local variables) no instruction reads, until none is
// left; remaps jump targets, parameter default ranges and bodyBegin. Returns how many it
// removed. Call before finish().
int removeDeadCode(ShaderProgram& p);

}  // namespace streyes::sl
