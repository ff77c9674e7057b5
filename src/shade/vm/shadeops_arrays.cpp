// Resizable arrays (SlType::kResizable): arraylength, resize, push and pop at run time, and
// the length a whole-array assignment or a parameter's value gives. The length is one value a
// grid; the elements live in the frame's ResizableArray stores (exec.h), which grow here, once
// an instruction and grid at most (doubling), never per point.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl {

bool setLength(Exec& x, int r, int elems) {
    const Register& g = x.reg(r);
    ResizableArray& a = x.arrays[g.slot];
    if (elems < 0) elems = 0;
    if (g.type.isString()) {  // one string an element, under the same bound; new ones ""
        if (std::size_t(elems) > ResizableArray::kMaxFloats) return false;
        if (a.strings.size() < std::size_t(elems)) a.strings.resize(std::max(std::size_t(elems), 2 * a.strings.size()));
        for (int e = a.length; e < elems; ++e) a.strings[std::size_t(e)].clear();
        a.length = elems;
        return true;
    }
    const std::size_t w = g.varying() ? std::size_t(x.n) : 1;
    const std::size_t perElement = std::size_t(g.type.comps()) * w;
    if (!a.reserve(std::size_t(elems), perElement)) return false;
    // New elements start at 0 (the storage holds what earlier grids left).
    if (elems > a.length)
        std::fill(a.data.begin() + std::ptrdiff_t(std::size_t(a.length) * perElement),
                  a.data.begin() + std::ptrdiff_t(std::size_t(elems) * perElement), 0.0f);
    a.length = elems;
    return true;
}

namespace {

void tooLong(Exec& x, const Instr& in, double want) {
    char shown[32];
    std::snprintf(shown, sizeof shown, "%g", want);
    const Register& r = x.reg(in.a[0]);
    x.vm.warnOnce(x, in, "resize",
                  std::string("array '") + r.name + "' cannot hold " + shown +
                      " elements (the bound is 2^26 floats over the grid): its length is left at " +
                      std::to_string(x.elements(in.a[0])) + " (warned once here)");
}

}  // namespace

namespace ops {

void alen(Exec& x, const Instr& in) { x.ptr(in.a[0])[0] = float(x.elements(in.a[1])); }

void aresize(Exec& x, const Instr& in) {
    const float f = x.ptr(in.a[1])[0];
    // A negative or NaN length is 0; a fraction is dropped (as an index is).
    const double want = f >= 1.0f ? std::floor(double(f)) : 0.0;
    if (want > double(ResizableArray::kMaxFloats) || !setLength(x, in.a[0], int(want))) tooLong(x, in, want);
}

void apush(Exec& x, const Instr& in) {
    const int len = x.elements(in.a[0]);
    if (!setLength(x, in.a[0], len + 1)) {
        tooLong(x, in, double(len) + 1);
        x.ptr(in.a[1])[0] = -1.0f;  // the element store that follows writes nowhere
        return;
    }
    x.ptr(in.a[1])[0] = float(len);
}

void apop(Exec& x, const Instr& in) {
    const bool isString = x.reg(in.a[1]).type.isString();
    const int len = x.elements(in.a[1]);
    if (len == 0) {
        if (x.active > 0) {
            ++x.stats.indicesClamped;
            const Register& r = x.reg(in.a[1]);
            x.vm.warnOnce(x, in, "pop", "pop of '" + r.name + "', which is empty: " + (isString ? "\"\"" : "0") +
                                            " (warned once here; other grids may do it too)");
        }
        if (isString) {
            x.str(in.a[0]).clear();
            return;
        }
        RegView d = x.view(in.a[0]);
        for (int c = 0; c < d.comps; ++c) std::fill(d.comp(c), d.comp(c) + d.w, 0.0f);
        return;
    }
    if (isString) {
        x.str(in.a[0]) = x.str(in.a[1], len - 1);
        setLength(x, in.a[1], len - 1);
        return;
    }
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]);
    for (int c = 0; c < d.comps; ++c) {
        const float* s = a.comp(c, len - 1);
        for (int i = 0; i < d.w; ++i) d.comp(c)[i] = s[a.varying ? i : 0];
    }
    setLength(x, in.a[1], len - 1);
}

void alike(Exec& x, const Instr& in) {
    // Shorter or as long: never past the bound (the source holds as many already).
    setLength(x, in.a[0], x.elements(in.a[1]));
}

}  // namespace ops
}  // namespace streyes::sl
