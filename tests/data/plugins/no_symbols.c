/* A shared object that is not a procedural plug-in: it exports ConvertParameters only. */
#include <ri.h>

RtPointer ConvertParameters(RtString paramstr) { return (RtPointer)paramstr; }
