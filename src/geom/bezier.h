// Bicubic patches in Bezier form: Bernstein evaluation, conversion from RenderMan's bases, and
// de Casteljau subdivision.
//
// Every bicubic patch streyes renders is turned into Bezier form, whatever basis it was given
// in (b-spline, catmull-rom, hermite, a matrix), because a Bezier patch lies inside the convex
// hull of its 16 control points and de Casteljau's construction gives the control points of
// any part of it: a bound that shrinks as the patch is split. Control points are stored row by
// row, u fastest: cp[j * 4 + i] is control point i along u in row j along v.
#pragma once

#include <array>

#include "streyes/scene.h"
#include "streyes/vecmath.h"

namespace streyes {

using BezierPatch = std::array<Vec3f, 16>;
using Matrix4x4 = std::array<double, 16>;  // row-major

// C with Bezier control values Q = C * G, for control values G given in `basis`.
Matrix4x4 basisToBezier(const BasisDesc& basis);

// The Bezier form of a 4x4 patch of control points g (u fastest) given in the bases whose
// basisToBezier matrices are cu (along u) and cv (along v).
BezierPatch patchToBezier(const Matrix4x4& cu, const Matrix4x4& cv, const Vec3d g[16]);

// The Bezier patch through 16 surface points sampled at u, v in {0, 1/3, 2/3, 1}
// (samples[j * 4 + i] at u = i/3, v = j/3): exact for any bicubic polynomial patch.
BezierPatch fitBezier(const Vec3d samples[16]);

// The four cubic Bernstein polynomials at t and their derivatives (exactly 0 and 1 at the ends).
void bernstein(double t, double b[4], double db[4]);

// Position and first derivatives at (u, v), in double precision.
void evalBezier(const BezierPatch& cp, double u, double v, Vec3d* P, Vec3d* dPdu, Vec3d* dPdv);

// de Casteljau at the parameter midpoint: the halves along u (axis 0) or v (axis 1).
void splitBezier(const BezierPatch& cp, int axis, BezierPatch& lo, BezierPatch& hi);

// The control points of the part of the patch over [u0, u1] x [v0, v1] (within [0, 1]^2).
BezierPatch bezierSubPatch(const BezierPatch& cp, double u0, double u1, double v0, double v1);

// Box around the control points: it contains the patch (convex hull property).
Bounds3f bezierBound(const BezierPatch& cp);

}  // namespace streyes
