/* A plug-in whose Subdivide makes a bad call: a sphere with a radius that is not a number (its
 * third call), after two good ones. */
#include <math.h>
#include <ri.h>

RtPointer ConvertParameters(RtString paramstr) { return (RtPointer)paramstr; }

RtVoid Subdivide(RtPointer data, RtFloat detail) {
    (void)data;
    (void)detail;
    RiAttributeBegin();
    RiSphere(1, -1, 1, 360, RI_NULL);
    RiSphere(NAN, -1, 1, 360, RI_NULL);
    RiAttributeEnd();
}

RtVoid Free(RtPointer data) { (void)data; }
