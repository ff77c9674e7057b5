/* A plug-in that calls an Ri function streyes does not have (RiBlobby): it cannot be loaded. */
#include <ri.h>

RtVoid RiBlobby(RtInt nleaf, RtInt ncode, RtInt code[], RtInt nflt, RtFloat flt[], RtInt nstr, RtString str[], ...);

RtPointer ConvertParameters(RtString paramstr) { return (RtPointer)paramstr; }

RtVoid Subdivide(RtPointer data, RtFloat detail) {
    (void)data;
    (void)detail;
    RiBlobby(0, 0, 0, 0, 0, 0, 0, RI_NULL);
}

RtVoid Free(RtPointer data) { (void)data; }
