// Jumps, the mask stack (varying if, loops, break, continue, return) and moves.
#include <cstring>

#include "shade/vm/frame.h"
#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

void jmp(Exec& x, const Instr& in) { x.pc = in.a[0]; }

// A while or for loop's turn: back to its top, or (past the run's iteration budget) out.
void loopBack(Exec& x, const Instr& in) {
    if (++x.loopIterations <= x.loopBudget) {
        x.pc = in.a[0];
        return;
    }
    if (x.loopIterations == x.loopBudget + 1) {
        ++x.stats.loopsStopped;
        x.vm.warnOnce(x, in, "loop",
                      "loops ran more than " + std::to_string(x.loopBudget) +
                          " turns on one grid (a loop that never ends?): each loop now ends at its next turn; "
                          "the shader's results on this grid are what it had then");
    }
    x.pc = in.a[1];
}

void jmpIfZero(Exec& x, const Instr& in) {
    if (x.ptr(in.a[0])[0] == 0.0f) x.pc = in.a[1];
}

void jmpIfNone(Exec& x, const Instr& in) {
    if (x.active == 0) x.pc = in.a[0];
}

void maskIf(Exec& x, const Instr& in) {
    Frame& f = x.frame;
    const int d = f.depth + 1;
    const uint8_t* below = f.mask(d - 1);
    uint8_t* m = f.mask(d);
    RegView c = x.view(in.a[0]);
    for (int i = 0; i < x.n; ++i) m[i] = below[i] & uint8_t(c.at(0, i) != 0.0f);
    setLevel(x, d);
}

void maskElse(Exec& x, const Instr& in) {
    Frame& f = x.frame;
    const int d = f.depth;
    const uint8_t* below = f.mask(d - 1);
    uint8_t* m = f.mask(d);
    RegView c = x.view(in.a[0]);
    for (int i = 0; i < x.n; ++i) m[i] = below[i] & uint8_t(c.at(0, i) == 0.0f);
    setLevel(x, d);
}

void maskPop(Exec& x, const Instr&) { setLevel(x, x.frame.depth - 1); }

void loopBegin(Exec& x, const Instr&) {
    Frame& f = x.frame;
    const int d = f.depth + 1;
    std::memcpy(f.mask(d), f.mask(d - 1), size_t(x.n));
    std::memset(f.cont(d), 0, size_t(x.n));
    setLevel(x, d);
}

void funcBegin(Exec& x, const Instr& in) { loopBegin(x, in); }

void loopCond(Exec& x, const Instr& in) {
    RegView c = x.view(in.a[0]);
    for (int i = 0; i < x.n; ++i) x.mask[i] &= uint8_t(c.at(0, i) != 0.0f);
    recount(x);
}

void loopContinueMerge(Exec& x, const Instr&) {
    Frame& f = x.frame;
    uint8_t* c = f.cont(f.depth);
    for (int i = 0; i < x.n; ++i) {
        x.mask[i] |= c[i];
        c[i] = 0;
    }
    recount(x);
}

namespace {

// The points that run leave every level from `level` up (and the continue sets above it).
void leave(Exec& x, int level, uint8_t* remember) {
    Frame& f = x.frame;
    const int top = f.depth;
    for (int i = 0; i < x.n; ++i) {
        if (!x.mask[i]) continue;
        if (remember) remember[i] = 1;
        for (int d = std::max(level, 0); d <= top; ++d) {
            f.mask(d)[i] = 0;
            if (d > level) f.cont(d)[i] = 0;
        }
    }
}

}  // namespace

// a0: the loop's level; a1: 1 for an illuminance loop, whose C marks points that broke.
void loopBreak(Exec& x, const Instr& in) {
    leave(x, in.a[0], in.a[1] ? x.frame.cont(in.a[0]) : nullptr);
    recount(x);
}

void loopContinue(Exec& x, const Instr& in) {
    // An illuminance loop's next light starts from the level below: nothing to remember.
    leave(x, in.a[0], in.a[1] ? nullptr : x.frame.cont(in.a[0]));
    recount(x);
}

void funcReturn(Exec& x, const Instr& in) {
    leave(x, in.a[0], nullptr);
    recount(x);
}

void unwind(Exec& x, const Instr& in) { setLevel(x, in.a[0]); }

// ---- Moves -------------------------------------------------------------------------------------

void mov(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), s = x.view(in.a[1]);
    const int nd = d.comps * d.elems, ns = s.comps * s.elems;
    for (int c = 0; c < nd; ++c) {
        float* out = d.p + size_t(c) * size_t(d.w);
        const float* src = s.p + size_t(ns == nd ? c : (c % ns)) * size_t(s.w);
        if (s.varying && d.varying) {
            if (out != src) std::memcpy(out, src, sizeof(float) * size_t(d.w));
        } else {
            const float v = src[0];
            for (int i = 0; i < d.w; ++i) out[i] = v;
        }
    }
}

void movm(Exec& x, const Instr& in) {
    if (x.allOn()) return mov(x, in);
    RegView d = x.view(in.a[0]), s = x.view(in.a[1]);
    const int nd = d.comps * d.elems, ns = s.comps * s.elems;
    const uint8_t* m = x.mask;
    for (int c = 0; c < nd; ++c) {
        float* out = d.p + size_t(c) * size_t(d.w);
        const float* src = s.p + size_t(ns == nd ? c : (c % ns)) * size_t(s.w);
        if (s.varying) {
            for (int i = 0; i < d.w; ++i) out[i] = m[i] ? src[i] : out[i];
        } else {
            const float v = src[0];
            for (int i = 0; i < d.w; ++i) out[i] = m[i] ? v : out[i];
        }
    }
}

void floatToMatrix(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]), s = x.view(in.a[1]);
    for (int c = 0; c < 16; ++c) {
        float* out = d.comp(c);
        if (c % 5 == 0) loop1(d.w, out, s.p, s.varying, [](float v) { return v; });
        else
            for (int i = 0; i < d.w; ++i) out[i] = 0;
    }
}

void triple(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]);
    for (int c = 0; c < 3; ++c) {
        RegView s = x.view(in.a[1 + c]);
        loop1(d.w, d.comp(c), s.p, s.varying, [](float v) { return v; });
    }
}

void matrix16(Exec& x, const Instr& in) {
    RegView d = x.view(in.a[0]);
    const int32_t* regs = x.extra(in.a[1]);
    for (int c = 0; c < 16; ++c) {
        RegView s = x.view(regs[c]);
        loop1(d.w, d.comp(c), s.p, s.varying, [](float v) { return v; });
    }
}

}  // namespace streyes::sl::ops
