#include "bodies/material.h"

namespace streyes {

bool isMatte(const Attributes& a) {
    const Param* p = a.user.find("streyes:matte");
    return p && !p->nums.empty() && p->nums[0] != 0;
}

namespace {

// Attribute "cull" NAME 0: the cull is off (PRMan's default is 1, on).
bool cullOff(const Attributes& a, const char* name) {
    const Param* p = a.user.find(std::string("cull:") + name);
    return p && !p->nums.empty() && p->nums[0] == 0;
}

}  // namespace

Material makeMaterial(const Attributes& a, Facing facing) {
    Material m;
    using O = Attributes::Orientation;
    if (facing != Facing::Camera) {
        // "outside" and "inside" follow the primitive's coordinate system; "lh" is camera space's
        // handedness (no flip), "rh" the other.
        const bool mirrored = facing == Facing::Mirrored;
        m.flipNormals = a.orientation == O::Outside   ? mirrored
                        : a.orientation == O::Inside  ? !mirrored
                                                      : a.orientation == O::RightHanded;
        m.oneSided = !a.twoSided && a.solid < 0;
        m.solid = a.solid;
    }
    m.smoothShading = a.smoothShading;
    m.matte = isMatte(a);
    m.shadeHidden = cullOff(a, "hidden");
    m.shadeBackFacing = cullOff(a, "backfacing");
    m.Cs = a.color;
    m.Os = a.opacity;
    m.shadingRate = float(a.shadingRate);
    m.motionFactor = float(a.motionFactor);
    m.lights = a.lights;
    m.attributes = &a;
    const ParamList& p = a.surface.params;
    const std::string& name = a.surface.name;
    if (name == "constant") {
        m.kind = SurfaceKind::Constant;
    } else if (name == "matte") {
        m.kind = SurfaceKind::Matte;
        m.Ka = float(p.getFloat("Ka", 1));
        m.Kd = float(p.getFloat("Kd", 1));
    } else if (name == "plastic") {
        m.kind = SurfaceKind::Plastic;
        m.Ka = float(p.getFloat("Ka", 1));
        m.Kd = float(p.getFloat("Kd", 0.5));
        m.Ks = float(p.getFloat("Ks", 0.5));
        m.roughness = float(p.getFloat("roughness", 0.1));
        m.specularColor = p.getColor("specularcolor", {1, 1, 1});
    } else {
        m.kind = SurfaceKind::Default;
    }
    // The built-in shading (shade/shading.cpp) as it reads the view: constant not at all; matte
    // through faceforward(N, I) alone (then N.L with the lights'); plastic through its highlight
    // (H = L + V) and defaultsurface through |N.I|. A camera-facing primitive's N is the
    // camera's. The binder raises this for lights moving in world and for shaders.
    m.viewUse = m.kind == SurfaceKind::Constant                              ? ViewUse::None
                : m.kind == SurfaceKind::Matte && facing != Facing::Camera ? ViewUse::FacingOnly
                                                                           : ViewUse::Reads;
    return m;
}

float dicingRate(const Body& body, const RasterMeasure& m, double exposure) {
    if (const float rate = body.latticeRate(); rate > 0) return rate;
    const Material* material = body.material();
    if (!material) return 1.0f;
    if (!body.moving() || !(material->motionFactor > 0)) return material->shadingRate;
    const double span = body.time().t1 - body.time().t0;
    return motionDicingRate(material->shadingRate, material->motionFactor,
                            span > 0 ? double(m.motion) * exposure / span : 0.0);
}

}  // namespace streyes
