#include "shade/scene_queries.h"

#include "bodies/material.h"

namespace streyes {

bool queryValueOf(const Param& p, sl::QueryValue& out) {
    out = {};
    switch (p.type) {
        case ParamType::Float:
        case ParamType::Integer: out.type = sl::BaseType::Float; break;
        case ParamType::Color: out.type = sl::BaseType::Color; break;
        case ParamType::Point:
        case ParamType::Vector:
        case ParamType::Normal: out.type = sl::BaseType::Point; break;
        case ParamType::Matrix: out.type = sl::BaseType::Matrix; break;
        case ParamType::String:
            out = sl::QueryValue::string("");
            out.strings = p.strings;
            out.count = int(p.strings.size());
            return out.count > 0;
        case ParamType::HPoint: return false;
    }
    const int comps = sl::SlType::compsOf(out.type);
    out.floats.assign(p.nums.begin(), p.nums.end());
    out.count = int(p.nums.size()) / comps;
    return out.count > 0;
}

OptionValues::OptionValues(const Scene& scene) {
    const CameraDesc& c = scene.camera;
    const RenderSettings& s = scene.settings;
    // RI Spec 3.2, section 15.8: the options every renderer answers.
    const float format[3] = {float(c.xres), float(c.yres), float(c.pixelAspect)};
    values_["Format"] = sl::QueryValue::numbers({format[0], format[1], format[2]});
    values_["DeviceResolution"] = values_["Format"];
    const double frameAspect = c.frameAspect > 0 ? c.frameAspect : double(c.xres) * c.pixelAspect / double(c.yres);
    values_["FrameAspectRatio"] = sl::QueryValue::numbers({float(frameAspect)});
    values_["CropWindow"] = sl::QueryValue::numbers({0, 1, 0, 1});  // the whole frame unless a CropWindow (below)
    if (c.depthOfField())
        values_["DepthOfField"] = sl::QueryValue::numbers({float(c.fstop), float(c.focalLength), float(c.focalDistance)});
    else
        values_["DepthOfField"] = sl::QueryValue::numbers({1e38f, 0, 0});  // a pinhole: fstop RI_INFINITY
    values_["Shutter"] = sl::QueryValue::numbers({float(s.shutterOpen), float(s.shutterClose)});
    values_["Clipping"] = sl::QueryValue::numbers({float(c.nearClip), float(c.farClip)});
    // Option "category" "name" values the scene keeps, as "category:name".
    for (const Param& p : s.options.params) {
        sl::QueryValue v;
        if (queryValueOf(p, v)) values_[p.name] = std::move(v);
    }
}

const sl::QueryValue* OptionValues::find(const std::string& name) const {
    auto it = values_.find(name);
    return it == values_.end() ? nullptr : &it->second;
}

bool SceneQueries::option(const std::string& name, sl::QueryValue& out) const {
    const sl::QueryValue* v = options_ ? options_->find(name) : nullptr;
    if (!v) return false;
    out = *v;
    return true;
}

bool SceneQueries::attribute(const std::string& name, sl::QueryValue& out) const {
    if (!attributes_) return false;
    const Attributes& a = *attributes_;
    // RI Spec 3.2, section 15.8.
    if (name == "ShadingRate") out = sl::QueryValue::numbers({float(a.shadingRate)});
    else if (name == "Sides") out = sl::QueryValue::numbers({a.twoSided ? 2.0f : 1.0f});
    else if (name == "Matte") out = sl::QueryValue::numbers({isMatte(a) ? 1.0f : 0.0f});
    else if (name == "GeometricApproximation:motionfactor") out = sl::QueryValue::numbers({float(a.motionFactor)});
    else if (name == "displacementbound:sphere") out = sl::QueryValue::numbers({float(a.displacementBound)});
    else if (name == "displacementbound:coordinatesystem") out = sl::QueryValue::string(a.displacementBoundSpace);
    else if (const Param* p = a.user.find(name)) return queryValueOf(*p, out);
    else return false;
    return true;
}

}  // namespace streyes
