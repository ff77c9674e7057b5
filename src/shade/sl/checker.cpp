// The Shading Language checker's entry point; the checker itself is in checker_impl.h (declarations,
// statements, expressions) and checker_calls.cpp (the calls with rules of their own).
#include "shade/sl/checker.h"

#include "shade/sl/checker_impl.h"

namespace streyes::sl {

int conversionCost(SlType from, SlType to) {
    if (from == to) return 0;
    // A resizable array (an unsized formal, or a local or parameter being assigned) takes an
    // array of any length of its element type.
    if (to.isResizable() && from.isArray() && from.base == to.base) return 1;
    if (from.isArray() || to.isArray()) return -1;
    if (from.isPointLike() && to.isPointLike()) return 1;
    if (from.isFloat() && (to.isTriple() || to.isMatrix())) return 2;
    return -1;
}

CheckedShader checkShader(Module module) {
    CheckedShader out;
    out.module = std::move(module);
    detail::Checker c(out);
    c.run();
    return out;
}

}  // namespace streyes::sl
