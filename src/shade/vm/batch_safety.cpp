#include "shade/vm/batch_safety.h"

#include "shade/vm/ops.h"

namespace streyes::sl {

namespace {

template <size_t N>
bool oneOf(OpFn fn, const OpFn (&set)[N]) {
    for (OpFn f : set)
        if (f == fn) return true;
    return false;
}

}  // namespace

bool gridWideOp(OpFn fn) {
    static const OpFn kGridWide[] = {
        ops::random,      ops::texture,   ops::environment,  ops::shadow,   ops::occlusion,
        ops::occlusionmap, ops::indirectdiffuse, ops::trace, ops::transmission, ops::gather,
        ops::bake3d,      ops::texture3d, ops::bake,         ops::lightsource, ops::message,
        ops::printf_,
    };
    return oneOf(fn, kGridWide);
}

bool batchProgramSafe(const ShaderProgram& p) {
    static const OpFn kMasks[] = {
        ops::jmpIfNone, ops::maskIf,  ops::maskElse,   ops::maskPop,     ops::loopBegin,  ops::loopCond,
        ops::loopContinueMerge, ops::loopBreak, ops::loopContinue, ops::funcBegin, ops::funcReturn,
        ops::unwind,    ops::illumBegin, ops::illumNext, ops::illuminate, ops::solar,
    };
    static const OpFn kDerivatives[] = {ops::Du, ops::Dv, ops::Deriv, ops::area, ops::calculatenormal, ops::filterstep};
    bool masked = false;
    for (const Instr& in : p.code) {
        if (oneOf(in.fn, kMasks)) masked = true;
        else if (masked && oneOf(in.fn, kDerivatives)) return false;
    }
    return true;
}

}  // namespace streyes::sl
