// Information functions (RI Spec 3.2, section 15.8): option(), attribute(), rendererinfo(),
// textureinfo(), shadername(); PRMan's rayinfo(). Each answers once per grid (the values are uniform) and writes
// the shader's variable only when the value fits it.
#include <cstdlib>

#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

#ifndef STREYES_VERSION
#define STREYES_VERSION "0.0.0"
#endif

namespace streyes::sl::ops {

namespace {

bool sameKind(BaseType var, BaseType value) {
    auto pointLike = [](BaseType b) { return b == BaseType::Point || b == BaseType::Vector || b == BaseType::Normal; };
    return var == value || (pointLike(var) && pointLike(value));
}

// Writes `v` into register `reg` (every point of a varying one): 1 when it fits, else 0 and
// the register is left as it was.
float store(Exec& x, int reg, const QueryValue& v) {
    const SlType type = x.reg(reg).type;
    if (!sameKind(type.base, v.type) || v.count < 1) return 0;
    if (type.isArray() ? type.arrayLen < v.count : v.count != 1) return 0;
    if (type.isString()) {
        if (int(v.strings.size()) < v.count) return 0;
        for (int e = 0; e < v.count; ++e) x.str(reg, e) = v.strings[size_t(e)];
        return 1;
    }
    const int comps = type.comps();
    if (int(v.floats.size()) < v.count * comps) return 0;
    RegView d = x.view(reg);
    for (int e = 0; e < v.count; ++e)
        for (int c = 0; c < comps; ++c) {
            float* out = d.comp(c, e);
            const float value = v.floats[size_t(e * comps + c)];
            for (int i = 0; i < d.w; ++i) out[i] = value;
        }
    return 1;
}

QueryValue version() {
    QueryValue v = QueryValue::numbers({0, 0, 0, 0});
    const std::string s = STREYES_VERSION;
    size_t at = 0;
    for (int k = 0; k < 3 && at < s.size(); ++k) {
        v.floats[size_t(k)] = float(std::atoi(s.c_str() + at));
        at = s.find('.', at);
        if (at == std::string::npos) break;
        ++at;
    }
    return v;
}

}  // namespace

void option(Exec& x, const Instr& in) {
    QueryValue v;
    const StateQueries* q = x.grid.state;
    x.ptr(in.a[0])[0] = q && q->option(x.str(in.a[1]), v) ? store(x, in.a[2], v) : 0.0f;
}

void attribute(Exec& x, const Instr& in) {
    QueryValue v;
    const StateQueries* q = x.grid.state;
    x.ptr(in.a[0])[0] = q && q->attribute(x.str(in.a[1]), v) ? store(x, in.a[2], v) : 0.0f;
}

// rayinfo(): the ray that brought the grid to be shaded (PRMan's "depth" and "type").
void rayinfo(Exec& x, const Instr& in) {
    const std::string& name = x.str(in.a[1]);
    float found = 0;
    if (name == "depth") found = store(x, in.a[2], QueryValue::numbers({float(x.grid.rayDepth)}));
    else if (name == "type") found = store(x, in.a[2], QueryValue::string(x.grid.rayType ? x.grid.rayType : "camera"));
    x.ptr(in.a[0])[0] = found;
}

// The renderer's name and version: never another renderer's.
void rendererinfo(Exec& x, const Instr& in) {
    const std::string& name = x.str(in.a[1]);
    float found = 0;
    if (name == "renderer") found = store(x, in.a[2], QueryValue::string("streyes"));
    else if (name == "version") found = store(x, in.a[2], version());
    else if (name == "versionstring") found = store(x, in.a[2], QueryValue::string(STREYES_VERSION));
    x.ptr(in.a[0])[0] = found;
}

void textureinfo(Exec& x, const Instr& in) {
    QueryValue v;
    TextureSource* t = x.vm.textureSource();
    x.ptr(in.a[0])[0] = t && t->textureInfo(x.str(in.a[1]), x.str(in.a[2]), v) ? store(x, in.a[3], v) : 0.0f;
}

// shadername(): the running shader's name; shadername(type): the grid's shader of that type
// ("surface", "displacement", "atmosphere"; the running shader's own type names it), else "".
void shadername(Exec& x, const Instr& in) {
    if (in.a[1] < 0) {
        x.str(in.a[0]) = x.prog.name;
        return;
    }
    const std::string& type = x.str(in.a[1]);
    std::string name;
    if (type == shaderTypeName(x.prog.type) || (type == "lightsource" && x.prog.type == ShaderType::Light))
        name = x.prog.name;
    else if (type == "surface")
        name = x.vm.peerShaderName(Peer::Surface);
    else if (type == "displacement")
        name = x.vm.peerShaderName(Peer::Displacement);
    else if (type == "atmosphere")
        name = x.vm.peerShaderName(Peer::Atmosphere);
    x.str(in.a[0]) = name;
}

}  // namespace streyes::sl::ops
