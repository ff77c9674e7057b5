#include "scene/sequence_equal.h"

#include <algorithm>

#include "scene/blobby_cut.h"

namespace streyes {

namespace {

bool sameBasis(const BasisDesc& a, const BasisDesc& b) { return a.m == b.m && a.step == b.step; }

bool sameColors(const ColorPrimvar& a, const ColorPrimvar& b) { return a.cls == b.cls && a.values == b.values; }

bool samePrimitive(const PrimitiveDesc& a, const PrimitiveDesc& b) {
    if (a.times.size() != b.times.size()) return false;
    if (a.times.size() > 1 && a.times != b.times) return false;  // one key: its time means nothing
    if (!sameTransform(a.objectToWorld, b.objectToWorld)) return false;
    if (!sameParams(a.primvars, b.primvars)) return false;
    if (a.attributes == b.attributes) return true;
    return a.attributes && b.attributes && sameAttributes(*a.attributes, *b.attributes);
}

bool sameAttributesPtr(const AttributesPtr& a, const AttributesPtr& b) {
    return a == b || (a && b && sameAttributes(*a, *b));
}

}  // namespace

bool sameTransform(const MotionTransform& a, const MotionTransform& b) {
    if (a.isStatic() != b.isStatic()) return false;
    if (a.isStatic()) return a.keys().front() == b.keys().front();
    return a.times() == b.times() && a.keys() == b.keys();
}

bool sameParams(const ParamList& a, const ParamList& b) {
    if (a.params.size() != b.params.size()) return false;
    for (size_t i = 0; i < a.params.size(); ++i) {
        const Param &p = a.params[i], &q = b.params[i];
        if (p.name != q.name || p.type != q.type || p.cls != q.cls || p.arraySize != q.arraySize || p.nums != q.nums ||
            p.strings != q.strings)
            return false;
    }
    return true;
}

static bool sameDetail(const std::shared_ptr<const LevelOfDetail>& a, const std::shared_ptr<const LevelOfDetail>& b) {
    return a == b || (a && b && a->hasBound == b->hasBound && a->bound.lo == b->bound.lo && a->bound.hi == b->bound.hi &&
                      sameTransform(a->boundToWorld, b->boundToWorld) && a->range == b->range);
}

bool sameAttributes(const Attributes& a, const Attributes& b) {
    auto sameShader = [](const ShaderDesc& x, const ShaderDesc& y) {
        return x.name == y.name && sameParams(x.params, y.params) && sameTransform(x.shaderToWorld, y.shaderToWorld);
    };
    auto sameNetwork = [&](const ShaderNetwork& x, const ShaderNetwork& y) {
        if (x.layers.size() != y.layers.size() || x.names != y.names || x.connections.size() != y.connections.size())
            return false;
        for (size_t i = 0; i < x.layers.size(); ++i)
            if (!sameShader(x.layers[i], y.layers[i])) return false;
        for (size_t i = 0; i < x.connections.size(); ++i) {
            const ShaderConnection &c = x.connections[i], &d = y.connections[i];
            if (c.from != d.from || c.to != d.to || c.fromVar != d.fromVar || c.toVar != d.toVar) return false;
        }
        return true;
    };
    return a.color == b.color && a.opacity == b.opacity && sameShader(a.surface, b.surface) &&
           sameNetwork(a.surfaceLayers, b.surfaceLayers) && sameNetwork(a.displacementLayers, b.displacementLayers) &&
           sameShader(a.displacement, b.displacement) && sameShader(a.atmosphere, b.atmosphere) &&
           sameShader(a.interior, b.interior) && sameShader(a.exterior, b.exterior) &&
           a.displacementBound == b.displacementBound && a.displacementBoundSpace == b.displacementBoundSpace &&
           sameTransform(a.displacementBoundToWorld, b.displacementBoundToWorld) &&
           a.shadingRate == b.shadingRate && a.motionFactor == b.motionFactor && a.lights == b.lights && sameParams(a.user, b.user) &&
           sameBasis(a.uBasis, b.uBasis) && sameBasis(a.vBasis, b.vBasis) &&  // trim: NuPatchDesc compares its own copy
           a.twoSided == b.twoSided && a.solid == b.solid && a.orientation == b.orientation && a.smoothShading == b.smoothShading &&
           sameDetail(a.detail, b.detail);
}

bool sameLight(const LightDesc& a, const LightDesc& b) {
    return a.type == b.type && sameParams(a.params, b.params) && sameTransform(a.lightToWorld, b.lightToWorld) &&
           a.castsShadows == b.castsShadows && a.area == b.area && a.areaPatches == b.areaPatches &&
           sameTransform(a.areaToWorld, b.areaToWorld);
}

bool sameData(const BilinearPatchDesc& a, const BilinearPatchDesc& b) {
    if (a.times.size() != b.times.size() || (a.times.size() > 1 && a.times != b.times)) return false;
    if (a.P != b.P || a.hasCs != b.hasCs || (a.hasCs && a.Cs != b.Cs) || !sameParams(a.primvars, b.primvars)) return false;
    return sameTransform(a.objectToWorld, b.objectToWorld) && sameAttributesPtr(a.attributes, b.attributes);
}

bool sameObject(const std::shared_ptr<const Scene>& a, const std::shared_ptr<const Scene>& b);

bool sameData(const ProceduralDesc& a, const ProceduralDesc& b) {
    return a.kind == b.kind && a.args == b.args && a.directory == b.directory && a.proceduralPath == b.proceduralPath &&
           a.archivePath == b.archivePath && a.bound.lo == b.bound.lo &&
           a.bound.hi == b.bound.hi && sameTransform(a.objectToWorld, b.objectToWorld) &&
           sameAttributesPtr(a.attributes, b.attributes) && sameObject(a.object, b.object) &&
           std::equal(a.objectAttributes.begin(), a.objectAttributes.end(), b.objectAttributes.begin(),
                      b.objectAttributes.end(), [](const auto& x, const auto& y) {
                          return sameAttributesPtr(x.first, y.first) && sameAttributesPtr(x.second, y.second);
                      });
}

bool sameData(const PatchMeshDesc& a, const PatchMeshDesc& b) {
    return a.bicubic == b.bicubic && a.nu == b.nu && a.nv == b.nv && a.uPeriodic == b.uPeriodic &&
           a.vPeriodic == b.vPeriodic && sameBasis(a.uBasis, b.uBasis) && sameBasis(a.vBasis, b.vBasis) &&
           a.P == b.P && sameColors(a.Cs, b.Cs) && samePrimitive(a, b);
}

bool sameData(const SubdivisionMeshDesc& a, const SubdivisionMeshDesc& b) {
    return a.faceSizes == b.faceSizes && a.faceVertices == b.faceVertices && a.vertexCount == b.vertexCount &&
           a.creaseEdges == b.creaseEdges && a.creaseSharpness == b.creaseSharpness && a.corners == b.corners &&
           a.cornerSharpness == b.cornerSharpness && a.holes == b.holes &&
           a.interpolateBoundary == b.interpolateBoundary && a.P == b.P && sameColors(a.Cs, b.Cs) &&
           samePrimitive(a, b);
}

bool sameData(const QuadricDesc& a, const QuadricDesc& b) {
    return a.kind == b.kind && a.params == b.params && sameColors(a.Cs, b.Cs) && samePrimitive(a, b);
}

bool sameData(const PolygonMeshDesc& a, const PolygonMeshDesc& b) {
    return a.request == b.request && a.polygons == b.polygons && a.P == b.P && sameColors(a.Cs, b.Cs) &&
           (a.deferred == b.deferred || (a.deferred && b.deferred && *a.deferred == *b.deferred)) &&
           samePrimitive(a, b);
}

bool sameData(const CurvesDesc& a, const CurvesDesc& b) {
    return a.cubic == b.cubic && a.periodic == b.periodic && sameBasis(a.basis, b.basis) && a.nvertices == b.nvertices &&
           a.P == b.P && a.widthClass == b.widthClass && a.width == b.width && a.normalClass == b.normalClass &&
           a.N == b.N && sameColors(a.Cs, b.Cs) && samePrimitive(a, b);
}

bool sameData(const PointsDesc& a, const PointsDesc& b) {
    return a.P == b.P && a.width == b.width && sameColors(a.Cs, b.Cs) && samePrimitive(a, b);
}

static bool sameTrim(const std::shared_ptr<const TrimLoops>& a, const std::shared_ptr<const TrimLoops>& b) {
    if (a == b) return true;
    if (!a || !b || a->loops.size() != b->loops.size()) return false;
    for (size_t l = 0; l < a->loops.size(); ++l) {
        if (a->loops[l].size() != b->loops[l].size()) return false;
        for (size_t c = 0; c < a->loops[l].size(); ++c) {
            const TrimCurveDesc &x = a->loops[l][c], &y = b->loops[l][c];
            if (x.order != y.order || x.knot != y.knot || x.tmin != y.tmin || x.tmax != y.tmax || x.u != y.u ||
                x.v != y.v || x.w != y.w)
                return false;
        }
    }
    return true;
}

bool sameData(const NuPatchDesc& a, const NuPatchDesc& b) {
    return a.nu == b.nu && a.uorder == b.uorder && a.nv == b.nv && a.vorder == b.vorder && a.uknot == b.uknot &&
           a.vknot == b.vknot && a.umin == b.umin && a.umax == b.umax && a.vmin == b.vmin && a.vmax == b.vmax &&
           a.P == b.P && a.w == b.w && sameColors(a.Cs, b.Cs) && sameTrim(a.trim, b.trim) && samePrimitive(a, b);
}

// An instance's object (ObjectBegin): each frame defines its own, so compare what they hold.
bool sameObject(const std::shared_ptr<const Scene>& a, const std::shared_ptr<const Scene>& b) {
    if (a == b) return true;
    if (!a || !b) return false;
    auto same = [](const auto& x, const auto& y) {
        if (x.size() != y.size()) return false;
        for (size_t i = 0; i < x.size(); ++i)
            if (!sameData(x[i], y[i])) return false;
        return true;
    };
    return same(a->patches, b->patches) && same(a->procedurals, b->procedurals) && same(a->patchMeshes, b->patchMeshes) &&
           same(a->subdivisionMeshes, b->subdivisionMeshes) && same(a->quadrics, b->quadrics) &&
           same(a->polygonMeshes, b->polygonMeshes) && same(a->curves, b->curves) && same(a->points, b->points) &&
           same(a->nuPatches, b->nuPatches);
}

bool stillWithinFrame(const BilinearPatchDesc& p) { return p.P.size() == 1 && p.objectToWorld.isStatic(); }
bool stillWithinFrame(const ProceduralDesc& p) { return p.objectToWorld.isStatic(); }
bool stillWithinFrame(const PrimitiveDesc& p) { return p.times.size() <= 1 && p.objectToWorld.isStatic(); }

}  // namespace streyes
