// The interpreter's state while one program runs over one grid, as its operations see it, and
// the loops every operation is written with. Internal to shade/vm.
//
// Registers are structure of arrays: component c of element e of a varying register is the n
// floats at vary + (slot + e * comps + c) * n; a uniform register keeps one float per component.
// Operations compute on every point (inactive points too: their values are never stored into
// variables) and respect the mask only where it matters: stores into variables, counting
// sanitised results, and calls with side effects (texture lookups, printf, lights).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "shade/vm/program.h"
#include "shade/vm/shading_grid.h"

namespace streyes::sl {

class ShadingVM;
struct Frame;
struct ShadeStats;

// One register seen by an operation: `w` is the number of points it holds (1 or n).
struct RegView {
    float* p = nullptr;
    int w = 1;
    int comps = 1;
    int elems = 1;
    bool varying = false;
    // Component c (of element e): w floats.
    float* comp(int c, int e = 0) const { return p + (std::size_t(e) * std::size_t(comps) + std::size_t(c)) * std::size_t(w); }
    // Point i of component c, reading a uniform register's single value for every point.
    float at(int c, int i) const { return comp(c)[varying ? i : 0]; }
};

// The elements of one resizable array register (an unsized parameter or local, SlType::
// kResizable) over one grid: `length` elements, one per grid (uniform), laid out as a fixed
// register's (element e, component c: w floats at (e * comps + c) * w), so growing appends
// floats and never moves what is there. `data` only grows (doubling, by resize/push, once per
// instruction and grid, never per point) and is kept between grids: no allocation once the
// shader has run at its largest. A string array's elements are `strings` (uniform, as every
// string), kept likewise.
struct ResizableArray {
    int length = 0;
    std::vector<float> data;
    std::vector<std::string> strings;
    // Makes room for `elems` elements of `floatsPerElement` floats; false (nothing changed)
    // past kMaxFloats, the bound on one array (256 MiB) that keeps a runaway resize from
    // exhausting memory.
    static constexpr std::size_t kMaxFloats = std::size_t(1) << 26;
    bool reserve(std::size_t elems, std::size_t floatsPerElement) {
        const std::size_t need = elems * floatsPerElement;
        if (floatsPerElement != 0 && elems > kMaxFloats / floatsPerElement) return false;
        if (data.size() < need) data.resize(std::max(need, std::min(kMaxFloats, 2 * data.size())));
        return true;
    }
};

struct Exec {
    ShadingVM& vm;
    Frame& frame;
    const ShaderProgram& prog;
    const ShadingGrid& grid;
    ShadeStats& stats;
    float* uni = nullptr;
    float* vary = nullptr;
    std::string* strs = nullptr;
    ResizableArray* arrays = nullptr;  // the frame's resizable arrays, by Register::slot
    int n = 0;
    uint8_t* mask = nullptr;  // the current mask: 1 where a point runs
    int active = 0;           // points whose mask is 1
    int pc = 0;
    // Loop iterations of this run (every while and for loop's back edges), against the VM's
    // budget: past it, each loop ends at its next turn.
    uint64_t loopIterations = 0, loopBudget = 0;

    Exec(ShadingVM& v, Frame& f, const ShaderProgram& p, const ShadingGrid& g, ShadeStats& s)
        : vm(v), frame(f), prog(p), grid(g), stats(s) {}

    const Register& reg(int r) const { return prog.regs[std::size_t(r)]; }
    bool varying(int r) const { return reg(r).varying(); }
    int width(int r) const { return varying(r) ? n : 1; }
    float* ptr(int r) const {
        const Register& g = reg(r);
        if (g.resizable()) return arrays[g.slot].data.data();
        return g.varying() ? vary + std::size_t(g.slot) * std::size_t(n) : uni + g.slot;
    }
    // Elements of register r now: a resizable array's current length, else its type's.
    int elements(int r) const {
        const Register& g = reg(r);
        return g.resizable() ? arrays[g.slot].length : g.type.elements();
    }
    RegView view(int r) const {
        const Register& g = reg(r);
        return {ptr(r), g.varying() ? n : 1, g.type.comps(), elements(r), g.varying()};
    }
    std::string& str(int r, int e = 0) const {
        const Register& g = reg(r);
        return g.resizable() ? arrays[g.slot].strings[std::size_t(e)] : strs[g.slot + e];
    }
    bool allOn() const { return active == n; }
    const int32_t* extra(int begin) const { return prog.extra.data() + begin; }
    const SourceLoc* loc(const Instr& in) const { return in.loc >= 0 ? &prog.locs[std::size_t(in.loc)] : nullptr; }
    // Counts a sanitised result at point i (only points that run count).
    void sanitised(int count) const;
    // An array index of a point that runs was outside [0, length): counted, and warned once a
    // place in the shader. The caller clamps it.
    void indexOutOfRange(const Instr& in, int arrayReg, float index) const;
};

// Sets resizable array register r's length (new elements 0); false, leaving it, when the
// array would pass ResizableArray::kMaxFloats (shadeops_arrays.cpp).
bool setLength(Exec& x, int r, int elems);

// Statistics of a VM, cumulative until reset.
struct ShadeStats {
    uint64_t grids = 0;        // runs of a program (lights included)
    uint64_t points = 0;       // points shaded (the surface's n per run)
    uint64_t instructions = 0; // instructions executed
    uint64_t laneOps = 0;      // sum over instructions of their width (1 uniform, n varying)
    uint64_t sanitised = 0;    // results replaced by 0: division by zero, sqrt or log of a
                               // negative, NaN or infinity reaching an output
    uint64_t unknownSpaces = 0;   // transforms to or from a space nobody defined (identity used)
    uint64_t textureErrors = 0;   // lookups the TextureSource refused (fill used)
    uint64_t lightRuns = 0;       // light shader runs
    uint64_t lightReuses = 0;     // light results taken from an earlier grid instead of a run
                                  // (ShadingVM: lights whose results do not depend on the point)
    uint64_t indicesClamped = 0;  // array reads and writes whose index was outside the array for
                                  // some point that ran (clamped): one a grid and instruction
    uint64_t loopsStopped = 0;    // runs whose loops went past the iteration budget
    uint64_t raysMissing = 0;     // ray-traced calls made without a RaySource (no-hit values used)
};

// ---- Loops every operation is written with ------------------------------------------------------

// d[i] = f(a[i]) for the w points of d, a broadcast when uniform.
template <class F>
inline void loop1(int w, float* d, const float* a, bool av, F f) {
    if (av) {
        for (int i = 0; i < w; ++i) d[i] = f(a[i]);
    } else {
        float x = f(a[0]);
        for (int i = 0; i < w; ++i) d[i] = x;
    }
}

template <class F>
inline void loop2(int w, float* d, const float* a, bool av, const float* b, bool bv, F f) {
    if (av && bv) {
        for (int i = 0; i < w; ++i) d[i] = f(a[i], b[i]);
    } else if (av) {
        float y = b[0];
        for (int i = 0; i < w; ++i) d[i] = f(a[i], y);
    } else if (bv) {
        float x = a[0];
        for (int i = 0; i < w; ++i) d[i] = f(x, b[i]);
    } else {
        float r = f(a[0], b[0]);
        for (int i = 0; i < w; ++i) d[i] = r;
    }
}

template <class F>
inline void loop3(int w, float* d, const float* a, bool av, const float* b, bool bv, const float* c, bool cv, F f) {
    if (av && bv && cv) {
        for (int i = 0; i < w; ++i) d[i] = f(a[i], b[i], c[i]);
    } else {
        for (int i = 0; i < w; ++i) d[i] = f(a[av ? i : 0], b[bv ? i : 0], c[cv ? i : 0]);
    }
}

// Component-wise over a destination of any number of components; an operand with fewer
// components (a float beside a color) is broadcast.
template <class F>
inline void map1(Exec& x, const Instr& in, F f) {
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]);
    const int nc = d.comps * d.elems;
    for (int c = 0; c < nc; ++c) loop1(d.w, d.p + std::size_t(c) * d.w, a.p + std::size_t(a.comps * a.elems > 1 ? c : 0) * a.w, a.varying, f);
}

template <class F>
inline void map2(Exec& x, const Instr& in, F f) {
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]), b = x.view(in.a[2]);
    const int nc = d.comps * d.elems;
    for (int c = 0; c < nc; ++c)
        loop2(d.w, d.p + std::size_t(c) * d.w, a.p + std::size_t(a.comps * a.elems > 1 ? c : 0) * a.w, a.varying,
              b.p + std::size_t(b.comps * b.elems > 1 ? c : 0) * b.w, b.varying, f);
}

template <class F>
inline void map3(Exec& x, const Instr& in, F f) {
    RegView d = x.view(in.a[0]), a = x.view(in.a[1]), b = x.view(in.a[2]), e = x.view(in.a[3]);
    const int nc = d.comps * d.elems;
    for (int c = 0; c < nc; ++c)
        loop3(d.w, d.p + std::size_t(c) * d.w, a.p + std::size_t(a.comps > 1 ? c : 0) * a.w, a.varying,
              b.p + std::size_t(b.comps > 1 ? c : 0) * b.w, b.varying, e.p + std::size_t(e.comps > 1 ? c : 0) * e.w,
              e.varying, f);
}

// Counts the points that run where bad(i) holds (a uniform destination counts once).
template <class Bad>
inline int countBad(const Exec& x, int w, Bad bad) {
    int k = 0;
    if (w == 1) return bad(0) && x.active > 0 ? 1 : 0;
    for (int i = 0; i < w; ++i) k += (x.mask[i] && bad(i)) ? 1 : 0;
    return k;
}

inline float finiteOr0(float v) { return std::isfinite(v) ? v : 0.0f; }

// A triple of a register at point i.
struct V3 {
    float x, y, z;
};
inline V3 load3(const RegView& r, int i) {
    int k = r.varying ? i : 0;
    if (r.comps == 1) {
        float v = r.p[k];
        return {v, v, v};
    }
    return {r.p[k], r.p[std::size_t(r.w) + std::size_t(k)], r.p[2 * std::size_t(r.w) + std::size_t(k)]};
}
inline void store3(const RegView& r, int i, V3 v) {
    r.p[i] = v.x;
    r.p[std::size_t(r.w) + std::size_t(i)] = v.y;
    r.p[2 * std::size_t(r.w) + std::size_t(i)] = v.z;
}
inline float dot3(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 sub3(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 add3(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 mul3(V3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline V3 cross3(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline V3 normalize3(V3 a) {
    float l2 = dot3(a, a);
    if (!(l2 > 0) || !std::isfinite(l2)) return {0, 0, 0};
    return mul3(a, 1.0f / std::sqrt(l2));
}

// For each point of a destination of width w: a uniform destination computes point 0 only.
template <class F>
inline void forPoints(int w, F f) {
    for (int i = 0; i < w; ++i) f(i);
}

}  // namespace streyes::sl
