#include "shade/vm/program.h"

#include <atomic>
#include <cstdio>

#include "shade/vm/shading_grid.h"

namespace streyes::sl {

// ---- Types ------------------------------------------------------------------------------------------

const char* baseTypeName(BaseType b) {
    switch (b) {
        case BaseType::Void: return "void";
        case BaseType::Float: return "float";
        case BaseType::Color: return "color";
        case BaseType::Point: return "point";
        case BaseType::Vector: return "vector";
        case BaseType::Normal: return "normal";
        case BaseType::Matrix: return "matrix";
        case BaseType::String: return "string";
    }
    return "?";
}

std::string SlType::name() const {
    std::string s = baseTypeName(base);
    if (arrayLen > 0) s += "[" + std::to_string(arrayLen) + "]";
    if (arrayLen == kResizable) s += "[]";
    return s;
}

const char* detailName(Detail d) { return d == Detail::Uniform ? "uniform" : "varying"; }

const char* shaderTypeName(ShaderType t) {
    switch (t) {
        case ShaderType::Surface: return "surface";
        case ShaderType::Displacement: return "displacement";
        case ShaderType::Light: return "light";
        case ShaderType::Volume: return "volume";
        case ShaderType::Imager: return "imager";
    }
    return "?";
}

const GlobalInfo& globalInfo(Global g) {
    static const GlobalInfo table[kGlobalCount] = {
        {"P", BaseType::Point, Detail::Varying, true},       {"N", BaseType::Normal, Detail::Varying, true},
        {"Ng", BaseType::Normal, Detail::Varying, false},    {"I", BaseType::Vector, Detail::Varying, true},
        {"E", BaseType::Point, Detail::Uniform, false},      {"Cs", BaseType::Color, Detail::Varying, true},
        {"Os", BaseType::Color, Detail::Varying, true},      {"Ci", BaseType::Color, Detail::Varying, true},
        {"Oi", BaseType::Color, Detail::Varying, true},      {"s", BaseType::Float, Detail::Varying, true},
        {"t", BaseType::Float, Detail::Varying, true},       {"u", BaseType::Float, Detail::Varying, true},
        {"v", BaseType::Float, Detail::Varying, true},       {"du", BaseType::Float, Detail::Varying, false},
        {"dv", BaseType::Float, Detail::Varying, false},     {"dPdu", BaseType::Vector, Detail::Varying, true},
        {"dPdv", BaseType::Vector, Detail::Varying, true},   {"dPdtime", BaseType::Vector, Detail::Varying, false},
        {"time", BaseType::Float, Detail::Uniform, false},   {"dtime", BaseType::Float, Detail::Uniform, false},
        {"L", BaseType::Vector, Detail::Varying, true},      {"Cl", BaseType::Color, Detail::Varying, true},
        {"Ol", BaseType::Color, Detail::Varying, true},      {"Ps", BaseType::Point, Detail::Varying, false},
        {"alpha", BaseType::Float, Detail::Varying, true},   {"ncomps", BaseType::Float, Detail::Uniform, false},
        {"Ns", BaseType::Normal, Detail::Varying, false},
    };
    return table[int(g)];
}

Global findGlobal(const std::string& name) {
    for (int g = 0; g < kGlobalCount; ++g)
        if (name == globalInfo(Global(g)).name) return Global(g);
    return Global::Count;
}

const char* spaceName(Space s) {
    static const char* names[kSpaceCount] = {"current", "camera", "world", "object", "shader", "screen", "raster", "NDC"};
    return names[int(s)];
}

// ---- Programs ---------------------------------------------------------------------------------------

const ParamInfo* ShaderProgram::findParam(const std::string& n) const {
    int i = paramIndex(n);
    return i < 0 ? nullptr : &params[size_t(i)];
}

int ShaderProgram::paramIndex(const std::string& n) const {
    for (size_t i = 0; i < params.size(); ++i)
        if (params[i].name == n) return int(i);
    return -1;
}

void ShaderProgram::finish() {
    static std::atomic<uint64_t> nextId{1};
    id = nextId++;
    uniformFloats = varyingArrays = stringSlots = resizableArrays = 0;
    for (Register& r : regs) {
        if (r.resizable()) {
            r.slot = resizableArrays++;
        } else if (r.type.isString()) {
            r.slot = stringSlots;
            stringSlots += r.type.elements();
        } else if (r.varying()) {
            r.slot = varyingArrays;
            varyingArrays += r.floats();
        } else {
            r.slot = uniformFloats;
            uniformFloats += r.floats();
        }
    }
}

std::string ShaderProgram::dump() const {
    std::string out = std::string(shaderTypeName(type)) + " " + name + "\n";
    char buf[256];
    for (size_t i = 0; i < regs.size(); ++i) {
        const Register& r = regs[i];
        std::snprintf(buf, sizeof buf, "  r%zu %s %s %s%s\n", i, detailName(r.detail), r.type.name().c_str(),
                      r.name.c_str(), r.constant >= 0 ? " (constant)" : "");
        out += buf;
    }
    for (size_t i = 0; i < code.size(); ++i) {
        const Instr& in = code[i];
        std::snprintf(buf, sizeof buf, "%4zu%s %-16s %d %d %d %d %d %d\n", i, int(i) == bodyBegin ? ">" : " ",
                      opName(in.fn), in.a[0], in.a[1], in.a[2], in.a[3], in.a[4], in.a[5]);
        out += buf;
    }
    return out;
}

}  // namespace streyes::sl
