/*
 * Implicit field plug-ins for Blobby (opcode 1004), the interface PRMan's "Implicit Field Plugins"
 * application note documents, as far as streyes uses it.
 *
 * A plug-in is a shared object found on Option "searchpath" "procedural" (or
 * STREYES_PROCEDURALPATH), exporting with C linkage
 *
 *     ImplicitField *ImplicitFieldNew(int nfloat, const RtFloat *float0, const RtFloat *float1,
 *                                     int nstring, const RtString *string);
 *
 * called once per 1004 instruction with its float and string arguments (float0 and float1 are the
 * values at shutter open and close: streyes draws a Blobby's first key, and passes it as both).
 * The object it returns fills `bbox` (xmin xmax ymin ymax zmin zmax, object space) in its
 * constructor: the field is taken as 0 outside it. streyes calls Eval (the field at an object-space
 * point; it is added to the other leaves' through the Blobby's code, and the surface is where the
 * total is 27/64) and deletes the object when the Blobby is drawn; calls come from one thread at a
 * time for one object. PRMan's own ImplicitField.h declares these first, in this order, and further
 * virtual functions after them (GradientEval, Range, Motion, ...): a plug-in built against
 * PRMan's header loads here too. streyes samples the field and finds the level by bisection, so it
 * never asks for the gradient or the range.
 */
#ifndef STREYES_IMPLICIT_FIELD_H
#define STREYES_IMPLICIT_FIELD_H

#include "ri.h"

class ImplicitField {
  public:
    RtBound bbox;  // where the field may not be 0, in object space: set by the constructor

    ImplicitField() : bbox{0, 0, 0, 0, 0, 0} {}
    ImplicitField(const ImplicitField&) = delete;
    ImplicitField& operator=(const ImplicitField&) = delete;
    virtual ~ImplicitField() {}

    // The field at object-space point p.
    virtual RtFloat Eval(const RtPoint p) = 0;
};

extern "C" {
typedef ImplicitField* (*ImplicitFieldNewFunction)(int nfloat, const RtFloat* float0, const RtFloat* float1,
                                                   int nstring, const RtString* string);
}

#endif
