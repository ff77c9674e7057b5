// Scene-description helpers for the curved primitives: RenderMan's named bases and the patch
// counts of a PatchMesh.
#include "streyes/scene.h"

namespace streyes {

bool basisFromName(const std::string& name, BasisDesc* out) {
    // RenderMan's RiBezierBasis, RiBSplineBasis, RiCatmullRomBasis, RiHermiteBasis, RiPowerBasis
    // with their standard steps.
    if (name == "bezier") {
        *out = BasisDesc{};
    } else if (name == "b-spline" || name == "bspline") {
        *out = {{-1.0 / 6, 0.5, -0.5, 1.0 / 6, 0.5, -1, 0.5, 0, -0.5, 0, 0.5, 0, 1.0 / 6, 2.0 / 3, 1.0 / 6, 0}, 1};
    } else if (name == "catmull-rom" || name == "catmullrom") {
        *out = {{-0.5, 1.5, -1.5, 0.5, 1, -2.5, 2, -0.5, -0.5, 0, 0.5, 0, 0, 1, 0, 0}, 1};
    } else if (name == "hermite") {
        *out = {{2, 1, -2, 1, -3, -2, 3, -1, 0, 1, 0, 0, 1, 0, 0, 0}, 2};
    } else if (name == "power") {
        *out = {{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, 4};
    } else {
        return false;
    }
    return true;
}

int PatchMeshDesc::uPatches() const {
    if (!bicubic) return uPeriodic ? nu : nu - 1;
    return uPeriodic ? nu / uBasis.step : (nu - 4) / uBasis.step + 1;
}

int PatchMeshDesc::vPatches() const {
    if (!bicubic) return vPeriodic ? nv : nv - 1;
    return vPeriodic ? nv / vBasis.step : (nv - 4) / vBasis.step + 1;
}

int CurvesDesc::segments(size_t curve) const {
    const int n = nvertices[curve];
    if (!cubic) return periodic ? n : n - 1;
    return periodic ? n / basis.step : (n - 4) / basis.step + 1;
}

}  // namespace streyes

namespace streyes {

void setLifetime(Scene& scene, const Lifetime& life) {
    for (BilinearPatchDesc& p : scene.patches) p.life = life;
    for (ProceduralDesc& p : scene.procedurals) p.life = life;
    for (PatchMeshDesc& p : scene.patchMeshes) p.life = life;
    for (SubdivisionMeshDesc& p : scene.subdivisionMeshes) p.life = life;
    for (QuadricDesc& p : scene.quadrics) p.life = life;
    for (PolygonMeshDesc& p : scene.polygonMeshes) p.life = life;
    for (CurvesDesc& p : scene.curves) p.life = life;
    for (PointsDesc& p : scene.points) p.life = life;
    for (NuPatchDesc& p : scene.nuPatches) p.life = life;
}

}  // namespace streyes
