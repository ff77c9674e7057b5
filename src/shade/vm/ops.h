// The interpreter's operations: each is a function over the whole grid. The code generator
// picks them; operands are in Instr::a (a[0] the destination unless said otherwise; -1 for an
// operand left out). "extra" operands are a[1] = first index into ShaderProgram::extra,
// a[2] = count.
#pragma once

#include "shade/vm/exec.h"

namespace streyes::sl::ops {

#define STREYES_SL_OP(name) void name(Exec& x, const Instr& in)

// ---- Control and moves (shadeops_control.cpp) ----
STREYES_SL_OP(jmp);            // a0 target
STREYES_SL_OP(loopBack);       // a0 loop top, a1 loop end: jumps back, or out past the budget
STREYES_SL_OP(jmpIfZero);      // a0 uniform cond, a1 target
STREYES_SL_OP(jmpIfNone);      // a0 target: no point runs
STREYES_SL_OP(maskIf);         // a0 varying cond: push, mask &= cond
STREYES_SL_OP(maskElse);       // a0 cond: mask = saved & !cond
STREYES_SL_OP(maskPop);        // pop one level
STREYES_SL_OP(loopBegin);      // push a loop level
STREYES_SL_OP(loopCond);       // a0 cond: mask &= cond
STREYES_SL_OP(loopContinueMerge);  // points that continued run again
STREYES_SL_OP(loopBreak);      // a0 loops out: points that run leave the loop
STREYES_SL_OP(loopContinue);   // a0 loops out
STREYES_SL_OP(funcBegin);      // push a function level (for returns under varying conditions)
STREYES_SL_OP(funcReturn);     // points that run leave the function (or the shader)
STREYES_SL_OP(unwind);         // a0 depth: pop down to that level
STREYES_SL_OP(mov);            // a0 = a1 (arrays whole; a float into a triple: all components)
STREYES_SL_OP(movm);           // a0 = a1 where the mask is on
STREYES_SL_OP(floatToMatrix);  // a0 = a1 * identity
STREYES_SL_OP(triple);         // a0 = (a1, a2, a3)
STREYES_SL_OP(matrix16);       // a0 = extra[16] floats

// ---- Arithmetic, logic, math functions (shadeops_math.cpp) ----
STREYES_SL_OP(neg);
STREYES_SL_OP(add);
STREYES_SL_OP(sub);
STREYES_SL_OP(mul);
STREYES_SL_OP(div);            // x / 0 = 0 (counted)
STREYES_SL_OP(matMul);         // matrix product
STREYES_SL_OP(matDiv);         // a1 * inverse(a2)
STREYES_SL_OP(logNot);
STREYES_SL_OP(logAnd);
STREYES_SL_OP(logOr);
STREYES_SL_OP(eq);             // all components equal (floats, triples, matrices)
STREYES_SL_OP(ne);
STREYES_SL_OP(lt);
STREYES_SL_OP(gt);
STREYES_SL_OP(le);
STREYES_SL_OP(ge);
STREYES_SL_OP(select);         // a0 = a1 ? a2 : a3, per point
STREYES_SL_OP(aref);           // a0 = a1[a2]  (index clamped into the array)
STREYES_SL_OP(aset);           // a0[a1] = a2 where the mask is on
// ---- Resizable arrays (shadeops_arrays.cpp): the length is uniform, one a grid ----
STREYES_SL_OP(alen);           // a0 = arraylength(a1)
STREYES_SL_OP(aresize);        // resize(a0, a1): keeps the first min(old, new) elements, new ones 0
STREYES_SL_OP(apush);          // a0 one element longer (0); a1 = its index (the caller stores into it)
STREYES_SL_OP(apop);           // a0 = a1's last element, then a1 one shorter (empty: 0, warned once)
STREYES_SL_OP(alike);          // a0 (resizable) as long as a1, before a whole-array move
STREYES_SL_OP(sin_);
STREYES_SL_OP(cos_);
STREYES_SL_OP(tan_);
STREYES_SL_OP(asin_);          // argument clamped to [-1, 1]
STREYES_SL_OP(acos_);
STREYES_SL_OP(atan1);
STREYES_SL_OP(atan2_);
STREYES_SL_OP(radians);
STREYES_SL_OP(degrees);
STREYES_SL_OP(pow_);           // NaN or infinity: 0 (counted)
STREYES_SL_OP(exp_);
STREYES_SL_OP(sqrt_);          // sqrt(x < 0) = 0 (counted)
STREYES_SL_OP(inversesqrt);    // x <= 0: 0 (counted)
STREYES_SL_OP(log1);           // log(x <= 0) = 0 (counted)
STREYES_SL_OP(log2_);          // log(x, base)
STREYES_SL_OP(mod);            // a - b * floor(a / b); mod(a, 0) = 0 (counted)
STREYES_SL_OP(abs_);
STREYES_SL_OP(sign);
STREYES_SL_OP(floor_);
STREYES_SL_OP(ceil_);
STREYES_SL_OP(round_);
STREYES_SL_OP(min_);
STREYES_SL_OP(max_);
STREYES_SL_OP(clamp);
STREYES_SL_OP(mix);
STREYES_SL_OP(step);
STREYES_SL_OP(smoothstep);
STREYES_SL_OP(spline);         // a0 dst, extra: basis string reg (or -1), value, knots...
STREYES_SL_OP(splineArray);    // a0 dst, a1 basis string (or -1), a2 value, a3 knot array

// ---- Geometry and matrices (shadeops_geom.cpp) ----
STREYES_SL_OP(dot);
STREYES_SL_OP(cross);
STREYES_SL_OP(length);
STREYES_SL_OP(normalize);      // of a zero vector: zero
STREYES_SL_OP(distance);
STREYES_SL_OP(faceforward);    // a0 = faceforward(a1 N, a2 I, a3 Nref)
STREYES_SL_OP(reflect);
STREYES_SL_OP(refract);        // total internal reflection: 0
STREYES_SL_OP(fresnel);        // extra: I, N, eta, Kr, Kt [, R, T] (outputs written whole)
STREYES_SL_OP(comp);           // a0 = component a2 of a1 (triples)
STREYES_SL_OP(setcomp);        // a0 (a copy of a1) with component a2 set to a3
STREYES_SL_OP(mcomp);          // a0 = a1[a2][a3]
STREYES_SL_OP(msetcomp);       // a0 (a copy of a1) with [a2][a3] = a4
STREYES_SL_OP(xform);          // a0 = a1 moved from space a2 (-1: current) to a3 (-1: current),
                               // or by matrix a4 (after space a2 to current when both are
                               // given); a5: 0 point, 1 vector, 2 normal
STREYES_SL_OP(spaceMatrix);    // a0 = matrix from space a1 to current (matrix "space" ...) times a2
STREYES_SL_OP(depth);
STREYES_SL_OP(ptlined);        // a0 = distance from a3 to the segment a1-a2
STREYES_SL_OP(rotatePoint);    // a0 = a1 rotated by a2 radians about the line a3-a4
STREYES_SL_OP(determinant);
STREYES_SL_OP(translateM);     // a0 = a1 followed by a translation by a2
STREYES_SL_OP(rotateM);        // a0 = a1 followed by a rotation by a2 radians about axis a3
STREYES_SL_OP(scaleM);         // a0 = a1 followed by a scale by a2

// ---- Colour (shadeops_color.cpp) ----
STREYES_SL_OP(ctransform);     // a0 = a3 from colour space a1 (-1: rgb) to a2

// ---- Noise (shadeops_noise.cpp) ----
STREYES_SL_OP(noise);          // a0 = noise(a1 [, a2])
STREYES_SL_OP(pnoise);         // a0 = pnoise(a1 [, a2], period a3 [, a4])
STREYES_SL_OP(cellnoise);      // a0 = cellnoise(a1 [, a2])
STREYES_SL_OP(random);         // a0 = random(): per point and call

// ---- Lights (shadeops_illum.cpp) ----
STREYES_SL_OP(illumBegin);     // a0 category (-1), a1 P, a2 axis (-1), a3 angle (-1), a4 end target
STREYES_SL_OP(illumNext);      // same operands; a4 = the body's start
STREYES_SL_OP(illuminate);     // a0 from, a1 axis (-1), a2 angle (-1), a3 end target: pushes a level
STREYES_SL_OP(solar);          // a0 axis (-1), a1 angle (-1), a2 end target: pushes a level
// The lighting functions take the surface's P last (where the lights shine).
STREYES_SL_OP(ambient);        // a0 = ambient(), a1 P
STREYES_SL_OP(diffuse);        // a0 = diffuse(a1 N), a2 P
STREYES_SL_OP(specular);       // a0 = specular(a1 N, a2 V, a3 roughness), a4 P
STREYES_SL_OP(specularbrdf);   // a0 = specularbrdf(a1 L, a2 N, a3 V, a4 roughness)
STREYES_SL_OP(phong);          // a0 = phong(a1 N, a2 V, a3 size), a4 P
STREYES_SL_OP(lightsource);    // a0 = 1 if the current light has parameter a1, copied into a2

// ---- Message passing (shadeops_message.cpp) ----
STREYES_SL_OP(message);        // a0 = 1 if peer a3 (Peer) has parameter a1 fitting a2 (then copied)

// ---- Derivatives (shadeops_deriv.cpp) ----
STREYES_SL_OP(Du);
STREYES_SL_OP(Dv);
STREYES_SL_OP(Deriv);          // a0 = Du(a1)/Du(a2) + Dv(a1)/Dv(a2); a zero denominator's term is 0
STREYES_SL_OP(area);
STREYES_SL_OP(calculatenormal);
STREYES_SL_OP(filterstep);     // a0 = filterstep(a1 edge, a2 s1 [, a3 s2]), a4 width (-1: 1)

// ---- Strings (shadeops_string.cpp) ----
STREYES_SL_OP(printf_);        // extra: format, args...
STREYES_SL_OP(format);         // a0 dst; extra: format, args...
STREYES_SL_OP(concat);         // a0 dst; extra: strings...
STREYES_SL_OP(match);          // a0 = 1 if regular expression a1 is found in a2
STREYES_SL_OP(smov);           // a0 = a1 (strings, arrays whole)
STREYES_SL_OP(streq);
STREYES_SL_OP(strne);
STREYES_SL_OP(saref);          // a0 = a1[a2], uniform index
STREYES_SL_OP(saset);          // a0[a1] = a2, uniform index

// ---- Texture maps (shadeops_tmap.cpp) ----
// a0 dst; extra: name, channel (reg or -1), coordinate count k, k coordinate regs, then
// option pairs (name string reg, value reg).
STREYES_SL_OP(texture);
STREYES_SL_OP(environment);
STREYES_SL_OP(shadow);

// ---- Ray tracing (shadeops_trace.cpp) ----
// a0 dst; extra: positional count k, k regs (P then N, R or the far point; occlusion's samples
// last), then option pairs (name string reg, value reg).
STREYES_SL_OP(occlusion);
// occlusion(mapname, ...): as occlusion with the map name's string reg before the count
// (shadeops_occlmap.cpp); "raytrace" or "" runs occlusion.
STREYES_SL_OP(occlusionmap);
STREYES_SL_OP(indirectdiffuse);
STREYES_SL_OP(trace);
STREYES_SL_OP(transmission);
// a0 = 1 where the ray hit (varying); extra: category, P, dir, angle, samples, sample, then
// (name string reg, reg) pairs: outputs ("surface:Ci" ...) written, options read (shadeops_gather.cpp).
STREYES_SL_OP(gather);

// ---- Point clouds and bake files (shadeops_bake.cpp) ----
// a0 = 1 where a point was written; extra: file, display channels, P, N, then (name, value) pairs.
STREYES_SL_OP(bake3d);
// a0 = 1 where the cloud was read; extra: file, P, N, then (name, output copy) pairs.
STREYES_SL_OP(texture3d);
// extra: file, s, t, value.
STREYES_SL_OP(bake);

// ---- The renderer's state (shadeops_info.cpp) ----
// a0 = 1 when found and the variable a2 can hold it (then written), else 0 (a2 left alone).
STREYES_SL_OP(option);         // a1 name
STREYES_SL_OP(attribute);      // a1 name
STREYES_SL_OP(rendererinfo);   // a1 name
STREYES_SL_OP(rayinfo);        // a1 name: "depth", "type"
STREYES_SL_OP(textureinfo);    // a1 map, a2 field, a3 variable
STREYES_SL_OP(shadername);     // a0 = the running shader's name (a1 -1), or the grid's a1 shader's

#undef STREYES_SL_OP

}  // namespace streyes::sl::ops
