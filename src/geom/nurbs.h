// Non-uniform rational B-splines: the knot span of a parameter, the basis functions and their
// derivatives (Cox-de Boor, Piegl & Tiller's triangular scheme), a rational surface's point and
// exact first derivatives, and the Bezier control net of any sub-rectangle (blossoms), whose hull
// is the conservative bound of a piece.
//
// Why the bound holds: over one knot span the surface is a rational tensor Bezier patch; its
// control points over a sub-rectangle [a, b] x [c, d] of the span are the blossoms of the
// homogeneous surface at (a^(p-i) b^i, c^(q-j) d^j), each a convex combination of the span's
// homogeneous control points (every de Boor weight lies in [0, 1] for arguments inside the
// span). With positive weights the projected Bezier points then have positive weights too, and a
// rational Bezier patch with positive weights lies in the convex hull of its projected points.
// The union over the spans the rectangle meets bounds it, and shrinks with the rectangle.
#pragma once

#include <vector>

#include "streyes/vecmath.h"

namespace streyes {

// A homogeneous point: (x w, y w, z w) and w.
struct HPoint {
    Vec3d p;
    double w = 1;
};

// Past this many spans in a rectangle its bound is the box of the spans' control points (the
// Bezier nets cost ~300 blends a span, bicubic); pieces within fewer spans get their nets.
constexpr int kMaxBezierSpans = 16;

// Orders above this are refused when read (scratch arrays are fixed, so evaluation allocates nothing).
constexpr int kMaxNurbsOrder = 32;

// The span s (order - 1 <= s < n) with knots[s] <= t < knots[s + 1]; t at or past the end of the
// range takes the last non-empty span. Knots hold n + order values.
int nurbsSpan(const double* knots, int n, int order, double t);
// The `order` basis functions non-zero on span s at t (N[r] is N_{s-order+1+r}) and, when dN is
// given, their first derivatives.
void nurbsBasis(const double* knots, int order, int s, double t, double* N, double* dN);

// A rational B-spline surface over camera-space control points (u fastest), with its knots and
// weights; the points belong to one motion key.
struct NurbsSurface {
    int nu = 0, uorder = 0, nv = 0, vorder = 0;
    const double* uknot = nullptr;
    const double* vknot = nullptr;
    const double* w = nullptr;      // nu * nv, positive
    const Vec3d* P = nullptr;       // nu * nv, the points (not multiplied by their weights)

    // Point and first derivatives at (u, v) of the knot range.
    void evaluate(double u, double v, Vec3d* S, Vec3d* Su, Vec3d* Sv) const;
    // The box of the projected Bezier control points of every span's part of [u0, u1] x [v0, v1]
    // (over more than kMaxBezierSpans spans, the box of their control points).
    Bounds3d bound(double u0, double u1, double v0, double v1) const;
    // The homogeneous control points (x w, y w, z w, w) of the curve u = c (in v, nv of them), or
    // of v = c (in u): boundary curves, to find seams and collapsed sides.
    void isoCurve(bool alongV, double c, std::vector<HPoint>* out) const;
};

// A rational B-spline curve in the (u, v) plane (a trim curve), as a polyline.
void nurbsCurvePolyline(int n, int order, const double* knot, double tmin, double tmax, const double* u,
                        const double* v, const double* w, int stepsPerSpan, std::vector<Vec2<double>>* out);

}  // namespace streyes
