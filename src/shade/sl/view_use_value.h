// The lattice of view_use.cpp's analysis: what a value is with respect to the view (invariant, a
// point or vector that follows the camera, or view-dependent), whether it can tell a surface's
// facing, and where it first read the view. Internal to the analysis.
#pragma once

#include <cstdint>
#include <vector>

#include "shade/sl/ast.h"

namespace streyes::sl::viewuse {

enum class Kind : uint8_t { Invariant, Point, Vector, View };
// What a value is, where the facing rules need it: the renderer's N or Ng (normalized or
// negated), I (normalized or negated), or a dot product of the two.
enum class Shape : uint8_t { None, Normal, Incident, NdotI };

struct Value {
    Kind kind = Kind::Invariant;
    bool facing = false;
    Shape shape = Shape::None;
    // Where a view value first read the view, and how (for the result's message).
    const SourceLoc* where = nullptr;
    const char* what = nullptr;

    bool operator==(const Value& o) const { return kind == o.kind && facing == o.facing && shape == o.shape; }
    bool operator!=(const Value& o) const { return !(*this == o); }
};

inline Value of(Kind k, bool facing = false, Shape shape = Shape::None) { return Value{k, facing, shape, nullptr, nullptr}; }

inline Value view(const SourceLoc& loc, const char* what, bool facing = false) {
    return Value{Kind::View, facing, Shape::None, &loc, what};
}

// A view value made from `a` and `b`: it keeps the first origin it has.
inline Value viewFrom(const SourceLoc& loc, const char* what, const Value& a, const Value& b = {}) {
    if (a.kind == Kind::View && a.where) return Value{Kind::View, a.facing || b.facing, Shape::None, a.where, a.what};
    if (b.kind == Kind::View && b.where) return Value{Kind::View, a.facing || b.facing, Shape::None, b.where, b.what};
    return view(loc, what, a.facing || b.facing);
}

// Either value, at different points or on different paths.
inline Value join(const Value& a, const Value& b) {
    Value r;
    r.facing = a.facing || b.facing;
    r.shape = a.shape == b.shape ? a.shape : Shape::None;
    r.kind = a.kind == b.kind ? a.kind : Kind::View;
    if (r.kind == Kind::View) {
        const Value& src = a.kind == Kind::View && a.where ? a : b;
        r.where = src.where;
        r.what = src.what;
    }
    return r;
}

// A value computed where `ctl` decides whether it is: view when the decision is.
inline Value under(Value v, const Value& ctl, const SourceLoc& loc) {
    v.facing = v.facing || ctl.facing;
    if (ctl.kind != Kind::Invariant && v.kind != Kind::View) {
        v.kind = Kind::View;
        v.shape = Shape::None;
        v.where = ctl.where ? ctl.where : &loc;
        v.what = ctl.where ? ctl.what : "assigned under a condition that reads the view";
    }
    return v;
}

inline bool allInvariant(const std::vector<Value>& v) {
    for (const Value& x : v)
        if (x.kind != Kind::Invariant) return false;
    return true;
}

inline bool anyFacing(const std::vector<Value>& v) {
    for (const Value& x : v)
        if (x.facing) return true;
    return false;
}

// A pure function of its arguments: invariant when they all are.
inline Value pure(const std::vector<Value>& args, const SourceLoc& loc, const char* what) {
    if (allInvariant(args)) return of(Kind::Invariant, anyFacing(args));
    for (const Value& a : args)
        if (a.kind == Kind::View && a.where) return viewFrom(loc, what, a);
    return view(loc, what, anyFacing(args));
}

}  // namespace streyes::sl::viewuse
