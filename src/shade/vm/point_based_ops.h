// Point-based occlusion() and indirectdiffuse() (shadeops_pointbased.cpp), reached from the
// ray-traced operations (shadeops_trace.cpp) when the call names a point cloud.
#pragma once

#include "shade/vm/exec.h"

namespace streyes::sl::ops {

// True when the call is point-based ("filename" names a cloud and "pointbased" is not 0): then
// its destination holds the result (0 where the cloud cannot be read, warned once). False: the
// call is left to the ray tracer.
bool pointBasedCall(Exec& x, const Instr& in, bool indirect);

}  // namespace streyes::sl::ops
