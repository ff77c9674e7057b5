// Param and ParamList: typed RIB parameter values and their readers.
//
// The parser has already checked that values match their declared type (numbers for numeric
// types, strings for strings, whole numbers for integers). The readers here check the shape a
// particular use needs, such as "one color", and say so with the parameter's file:line when it
// does not fit.
#include "streyes/scene.h"

#include "scene/rib_params.h"

namespace streyes {

const char* paramTypeName(ParamType type) {
    switch (type) {
    case ParamType::Float: return "float";
    case ParamType::Integer: return "integer";
    case ParamType::String: return "string";
    case ParamType::Point: return "point";
    case ParamType::Vector: return "vector";
    case ParamType::Normal: return "normal";
    case ParamType::Color: return "color";
    case ParamType::HPoint: return "hpoint";
    case ParamType::Matrix: return "matrix";
    }
    return "?";
}

const char* paramClassName(ParamClass cls) {
    switch (cls) {
    case ParamClass::Constant: return "constant";
    case ParamClass::Uniform: return "uniform";
    case ParamClass::Varying: return "varying";
    case ParamClass::Vertex: return "vertex";
    case ParamClass::FaceVarying: return "facevarying";
    }
    return "?";
}

namespace {

// "float", "color[2]": the declared type as it would be written in RIB.
std::string declaredType(const Param& p) {
    std::string s = paramTypeName(p.type);
    if (p.arraySize != 1) s += "[" + std::to_string(p.arraySize) + "]";
    return s;
}

size_t valueCount(const Param& p) { return p.type == ParamType::String ? p.strings.size() : p.nums.size(); }

[[noreturn]] void wrongShape(const Param& p, const std::string& expected) {
    throw InputError(p.loc, "parameter '" + p.name + "' must be " + expected + ", but it is declared " +
                                declaredType(p) + " with " + std::to_string(valueCount(p)) +
                                (valueCount(p) == 1 ? " value" : " values"));
}

}  // namespace

int Param::componentsPerItem() const {
    int perElement = 1;
    switch (type) {
    case ParamType::Float:
    case ParamType::Integer:
    case ParamType::String: perElement = 1; break;
    case ParamType::Point:
    case ParamType::Vector:
    case ParamType::Normal:
    case ParamType::Color: perElement = 3; break;
    case ParamType::HPoint: perElement = 4; break;
    case ParamType::Matrix: perElement = 16; break;
    }
    return perElement * arraySize;
}

const Param* ParamList::find(const std::string& name) const {
    for (const Param& p : params)
        if (p.name == name) return &p;
    return nullptr;
}

double ParamList::getFloat(const std::string& name, double fallback) const {
    const Param* p = find(name);
    if (!p) return fallback;
    if ((p->type != ParamType::Float && p->type != ParamType::Integer) || p->nums.size() != 1)
        wrongShape(*p, "one float");
    return p->nums[0];
}

Color ParamList::getColor(const std::string& name, Color fallback) const {
    const Param* p = find(name);
    if (!p) return fallback;
    if (p->type != ParamType::Color || p->nums.size() != 3) wrongShape(*p, "one color (3 numbers)");
    return Color(float(p->nums[0]), float(p->nums[1]), float(p->nums[2]));
}

Vec3d ParamList::getPoint(const std::string& name, Vec3d fallback) const {
    const Param* p = find(name);
    if (!p) return fallback;
    bool threeD = p->type == ParamType::Point || p->type == ParamType::Vector || p->type == ParamType::Normal;
    if (threeD && p->nums.size() == 3) return {p->nums[0], p->nums[1], p->nums[2]};
    if (p->type == ParamType::HPoint && p->nums.size() == 4) {
        double w = p->nums[3];
        if (w == 0) throw InputError(p->loc, "parameter '" + p->name + "' has w = 0: it is a point at infinity");
        return {p->nums[0] / w, p->nums[1] / w, p->nums[2] / w};
    }
    wrongShape(*p, "one point (3 numbers)");
}

std::string ParamList::getString(const std::string& name, const std::string& fallback) const {
    const Param* p = find(name);
    if (!p) return fallback;
    if (p->type != ParamType::String || p->strings.size() != 1) wrongShape(*p, "one string");
    return p->strings[0];
}

}  // namespace streyes
