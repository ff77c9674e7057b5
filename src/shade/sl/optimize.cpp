#include "shade/sl/optimize.h"

#include <cmath>

#include "shade/vm/frame.h"
#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl {

namespace {

bool folds(OpFn fn) {
    for (OpFn f : {ops::add, ops::sub, ops::mul, ops::div, ops::neg, ops::lt, ops::gt, ops::le, ops::ge, ops::eq, ops::ne,
                   ops::logAnd, ops::logOr, ops::logNot, ops::dot, ops::cross})
        if (fn == f) return true;
    return false;
}

// Operations with no effect but writing a[0] from registers a[1..]: dropped when nothing reads
// a[0]. (Operations that count something, x / 0 or an index out of range, stay: their counts
// and warnings are part of what a run reports.)
bool pure(OpFn fn) {
    for (OpFn f : {ops::mov, ops::movm, ops::triple, ops::floatToMatrix, ops::neg, ops::add, ops::sub, ops::mul, ops::lt, ops::gt,
                   ops::le, ops::ge, ops::eq, ops::ne, ops::logAnd, ops::logOr, ops::logNot, ops::select, ops::sin_,
                   ops::cos_, ops::radians, ops::degrees, ops::abs_, ops::sign, ops::floor_, ops::ceil_, ops::round_,
                   ops::min_, ops::max_, ops::clamp, ops::mix, ops::step, ops::smoothstep, ops::dot, ops::cross,
                   ops::length, ops::normalize, ops::distance, ops::faceforward, ops::reflect, ops::comp})
        if (fn == f) return true;
    return false;
}

bool isConstant(const ShaderProgram& p, int r) {
    return r >= 0 && p.regs[size_t(r)].constant >= 0 && !p.regs[size_t(r)].type.isString();
}

// A temporary or a local variable: nothing outside the program's own instructions reads it
// (predefined variables and parameters are read by the renderer, lights and message passing).
bool isLocal(const Register& r) { return r.global < 0 && r.param < 0 && r.constant < 0; }

// The operands of instruction `in` that are jump targets (instruction indices).
std::vector<int> targetSlots(OpFn fn) {
    if (fn == ops::jmp || fn == ops::jmpIfNone) return {0};
    if (fn == ops::jmpIfZero) return {1};
    if (fn == ops::loopBack) return {0, 1};
    if (fn == ops::illumBegin || fn == ops::illumNext) return {4};
    if (fn == ops::illuminate) return {3};
    if (fn == ops::solar) return {2};
    return {};
}

}  // namespace

bool foldConstant(const ShaderProgram& p, OpFn fn, SlType result, int a, int b, std::vector<float>* out) {
    if (!folds(fn) || result.isString() || result.isArray() || !isConstant(p, a) || (b >= 0 && !isConstant(p, b)))
        return false;
    // A program of three uniform registers (result, a, b), run by the operation itself.
    ShaderProgram mini;
    Register d;
    d.type = result;
    mini.regs.push_back(d);
    for (int r : {a, b}) {
        if (r < 0) continue;
        Register c = p.regs[size_t(r)];
        c.constant = -1;
        mini.regs.push_back(c);
    }
    mini.finish();
    Frame frame;
    frame.n = 1;
    frame.arena.assign(size_t(mini.uniformFloats), 0.0f);
    for (size_t k = 1; k < mini.regs.size(); ++k) {
        const Register& src = p.regs[size_t(k == 1 ? a : b)];
        for (int f = 0; f < src.floats(); ++f)
            frame.arena[size_t(mini.regs[k].slot + f)] = p.constFloats[size_t(src.constant + f)];
    }
    ShadingVM vm;
    ShadingGrid grid;
    grid.n = 1;
    ShadeStats stats;
    Exec x(vm, frame, mini, grid, stats);
    x.uni = frame.arena.data();
    x.vary = x.uni + mini.uniformFloats;
    x.n = 1;
    uint8_t on = 1;
    x.mask = &on;
    x.active = 1;
    Instr in;
    in.fn = fn;
    in.a[0] = 0;
    in.a[1] = 1;
    in.a[2] = b >= 0 ? 2 : -1;
    fn(x, in);
    if (stats.sanitised != 0) return false;
    out->assign(frame.arena.begin() + mini.regs[0].slot, frame.arena.begin() + mini.regs[0].slot + mini.regs[0].floats());
    for (float v : *out)
        if (!std::isfinite(v)) return false;
    return true;
}

int removeDeadCode(ShaderProgram& p) {
    const size_t nc = p.code.size(), nr = p.regs.size(), words = (nr + 63) / 64;
    // Registers whose every write stays: read by the renderer after the run (predefined
    // variables, parameters) or through `extra` (operand lists, read by ops this pass does not
    // look into).
    std::vector<uint8_t> pinned(nr, 0);
    for (size_t r = 0; r < nr; ++r) pinned[r] = !isLocal(p.regs[r]);
    for (int32_t r : p.extra)
        if (r >= 0 && size_t(r) < nr) pinned[size_t(r)] = 1;
    using Set = std::vector<uint64_t>;
    auto has = [](const Set& s, int r) { return (s[size_t(r) / 64] >> (r % 64)) & 1; };
    auto add = [](Set& s, int r) { s[size_t(r) / 64] |= uint64_t(1) << (r % 64); };
    auto reg = [&](int32_t r) { return r >= 0 && size_t(r) < nr; };
    std::vector<uint8_t> keep(nc, 1);
    int removed = 0;
    for (bool again = true; again;) {
        again = false;
        // Liveness over the control flow (fall through, and each jump's targets), to a fixed
        // point. A pure operation writes every point of its destination (kills it); any other
        // operation, masked moves included, reads all its operands and kills nothing.
        std::vector<Set> liveIn(nc + 1, Set(words, 0));
        for (size_t r = 0; r < nr; ++r)
            if (pinned[r]) add(liveIn[nc], int(r));
        for (bool changed = true; changed;) {
            changed = false;
            for (size_t i = nc; i-- > 0;) {
                const Instr& in = p.code[i];
                Set live(words, 0);
                auto join = [&](int32_t t) {
                    if (t < 0 || size_t(t) > nc) return;
                    for (size_t w = 0; w < words; ++w) live[w] |= liveIn[size_t(t)][w];
                };
                if (in.fn != ops::jmp) join(int32_t(i + 1));
                for (int slot : targetSlots(in.fn)) join(in.a[slot]);
                if (keep[i]) {
                    // A masked move keeps the old value where the mask is off: it reads it.
                    if (pure(in.fn) && in.fn != ops::movm) {
                        if (reg(in.a[0])) live[size_t(in.a[0]) / 64] &= ~(uint64_t(1) << (in.a[0] % 64));
                        for (int s2 = 1; s2 < 6; ++s2)
                            if (reg(in.a[s2])) add(live, in.a[s2]);
                    } else {
                        for (int s2 = 0; s2 < 6; ++s2)
                            if (reg(in.a[s2])) add(live, in.a[s2]);
                    }
                }
                if (live != liveIn[i]) {
                    liveIn[i] = std::move(live);
                    changed = true;
                }
            }
        }
        for (size_t i = 0; i < nc; ++i) {
            const Instr& in = p.code[i];
            if (!keep[i] || !pure(in.fn) || !reg(in.a[0]) || pinned[size_t(in.a[0])]) continue;
            // Live after i: what its successors need.
            bool needed = in.fn != ops::jmp && has(liveIn[i + 1], in.a[0]);
            for (int slot : targetSlots(in.fn))
                if (in.a[slot] >= 0 && size_t(in.a[slot]) <= nc && has(liveIn[size_t(in.a[slot])], in.a[0])) needed = true;
            if (needed) continue;
            keep[i] = 0;
            ++removed;
            again = true;
        }
    }
    if (removed == 0) return 0;
    // Old index -> new index (an instruction removed: the next one kept).
    std::vector<int> to(nc + 1, 0);
    int next = 0;
    for (size_t i = 0; i < p.code.size(); ++i) {
        to[i] = next;
        next += keep[i];
    }
    to[p.code.size()] = next;
    auto remap = [&](int32_t& t) {
        if (t >= 0 && size_t(t) <= p.code.size()) t = to[size_t(t)];
    };
    std::vector<Instr> code;
    code.reserve(size_t(next));
    for (size_t i = 0; i < p.code.size(); ++i) {
        if (!keep[i]) continue;
        Instr in = p.code[i];
        for (int s : targetSlots(in.fn)) remap(in.a[s]);
        code.push_back(in);
    }
    p.code = std::move(code);
    for (ParamInfo& info : p.params) {
        remap(info.initBegin);
        remap(info.initEnd);
    }
    remap(p.bodyBegin);
    return removed;
}

}  // namespace streyes::sl
