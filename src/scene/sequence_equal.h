// Whether two frames' descriptions of a primitive are the same data: what the sequence reader
// (streyes/sequence.h) asks before it lets a primitive's run go on. Places in the input (loc) and
// lifetimes are not data; everything the renderer reads is.
#pragma once

#include "streyes/scene.h"

namespace streyes {

bool sameTransform(const MotionTransform& a, const MotionTransform& b);
bool sameParams(const ParamList& a, const ParamList& b);
bool sameAttributes(const Attributes& a, const Attributes& b);
bool sameLight(const LightDesc& a, const LightDesc& b);

// Same data (attributes compared by sameAttributes).
bool sameData(const BilinearPatchDesc& a, const BilinearPatchDesc& b);
bool sameData(const ProceduralDesc& a, const ProceduralDesc& b);
bool sameData(const PatchMeshDesc& a, const PatchMeshDesc& b);
bool sameData(const SubdivisionMeshDesc& a, const SubdivisionMeshDesc& b);
bool sameData(const QuadricDesc& a, const QuadricDesc& b);
bool sameData(const CurvesDesc& a, const CurvesDesc& b);
bool sameData(const PointsDesc& a, const PointsDesc& b);
bool sameData(const PolygonMeshDesc& a, const PolygonMeshDesc& b);
bool sameData(const NuPatchDesc& a, const NuPatchDesc& b);

// Does the primitive stand still within its frame (no motion keys of its own or of its transform)?
bool stillWithinFrame(const BilinearPatchDesc& p);
bool stillWithinFrame(const ProceduralDesc& p);
bool stillWithinFrame(const PrimitiveDesc& p);

}  // namespace streyes
