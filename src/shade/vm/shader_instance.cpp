#include "shade/vm/shader_instance.h"

#include <atomic>
#include <sstream>

#include "shade/vm/exec.h"

namespace streyes::sl {

namespace {
uint64_t nextRevision() {
    static std::atomic<uint64_t> counter{0};
    return ++counter;
}
}  // namespace

ShaderInstance::ShaderInstance(ProgramPtr program) : program_(std::move(program)), revision_(nextRevision()) {}

const ShaderInstance::Value* ShaderInstance::value(int param) const {
    for (const Value& v : values_)
        if (v.param == param) return &v;
    return nullptr;
}

ShaderInstance::Value& ShaderInstance::slot(int param) {
    for (Value& v : values_)
        if (v.param == param) return v;
    values_.push_back({param, {}, {}});
    return values_.back();
}

namespace {

int findParam(const ShaderProgram& p, const std::string& name, const SourceLoc& loc) {
    int k = p.paramIndex(name);
    if (k < 0) {
        std::string known;
        for (const ParamInfo& i : p.params) known += (known.empty() ? "" : ", ") + i.name;
        throw InputError(loc, std::string(shaderTypeName(p.type)) + " shader \"" + p.name + "\" has no parameter \"" +
                                  name + "\"" + (known.empty() ? " (it has none)" : " (it has " + known + ")"));
    }
    return k;
}

}  // namespace

void ShaderInstance::set(const std::string& name, SlType type, const std::vector<float>& values, const SourceLoc& loc) {
    const ShaderProgram& p = *program_;
    const int k = findParam(p, name, loc);
    const ParamInfo& info = p.params[size_t(k)];
    const std::string what = "parameter \"" + name + "\" of shader \"" + p.name + "\" is " + detailName(info.detail) +
                             " " + info.type.name();
    if (info.type.isString()) throw InputError(loc, what + ": give it a string");
    if (type.base != BaseType::Void) {
        const bool same = type.base == info.type.base || (SlType(type.base).isPointLike() && info.type.element().isPointLike());
        if (!same) throw InputError(loc, what + ", not " + baseTypeName(type.base));
        if (type.arrayLen != 0 && type.arrayLen != info.type.arrayLen && !info.type.isResizable())
            throw InputError(loc, what + ", not " + type.name());
    }
    const size_t want = size_t(info.type.comps() * info.type.elements());
    if (info.type.isResizable()) {  // declared without a length: as many elements as given
        const size_t comps = size_t(info.type.comps());
        if (values.size() % comps != 0)
            throw InputError(loc, what + ": it takes " + std::to_string(comps) + " values an element, not " +
                                      std::to_string(values.size()) + " in all");
        if (values.size() > ResizableArray::kMaxFloats)
            throw InputError(loc, what + ": " + std::to_string(values.size()) + " values are more than an array holds (2^26)");
    } else if (values.size() != want)
        throw InputError(loc, what + ": it takes " + std::to_string(want) + " value" + (want == 1 ? "" : "s") + ", not " +
                                  std::to_string(values.size()));
    Value& v = slot(k);
    v.floats = values;
    v.strings.clear();
    revision_ = nextRevision();
}

void ShaderInstance::setStrings(const std::string& name, const std::vector<std::string>& values, const SourceLoc& loc) {
    const ShaderProgram& p = *program_;
    const int k = findParam(p, name, loc);
    const ParamInfo& info = p.params[size_t(k)];
    if (!info.type.isString())
        throw InputError(loc, "parameter \"" + name + "\" of shader \"" + p.name + "\" is " + info.type.name() + ", not string");
    if (info.type.isResizable()) {  // declared without a length: as many strings as given
        if (values.size() > ResizableArray::kMaxFloats)
            throw InputError(loc, "parameter \"" + name + "\" of shader \"" + p.name + "\": " + std::to_string(values.size()) +
                                      " strings are more than an array holds (2^26)");
    } else if (values.size() != size_t(info.type.elements()))
        throw InputError(loc, "parameter \"" + name + "\" of shader \"" + p.name + "\" takes " +
                                  std::to_string(info.type.elements()) + " string(s), not " + std::to_string(values.size()));
    Value& v = slot(k);
    v.strings = values;
    v.floats.clear();
    revision_ = nextRevision();
}

bool parseDeclaration(const std::string& declaration, SlType* type, std::string* name) {
    std::istringstream in(declaration);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    if (words.empty()) return false;
    size_t i = 0;
    static const char* classes[] = {"uniform", "varying", "constant", "vertex", "facevarying", "facevertex"};
    for (const char* c : classes)
        if (i < words.size() && words[i] == c) ++i;
    *type = SlType();
    if (words.size() - i == 2) {
        std::string t = words[i];
        int len = 0;
        size_t br = t.find('[');
        if (br != std::string::npos) {
            len = std::atoi(t.c_str() + br + 1);
            t = t.substr(0, br);
        }
        static const std::pair<const char*, BaseType> types[] = {
            {"float", BaseType::Float},   {"color", BaseType::Color},   {"point", BaseType::Point},
            {"vector", BaseType::Vector}, {"normal", BaseType::Normal}, {"matrix", BaseType::Matrix},
            {"string", BaseType::String}, {"hpoint", BaseType::Point},  {"integer", BaseType::Float}};
        bool found = false;
        for (const auto& [n, b] : types)
            if (t == n) {
                *type = SlType(b, len);
                found = true;
            }
        if (!found) return false;
        ++i;
    }
    if (words.size() - i != 1) return false;
    *name = words[i];
    return true;
}

void ShaderInstance::setDeclared(const std::string& declaration, const std::vector<float>& values, const SourceLoc& loc) {
    SlType type;
    std::string name;
    if (!parseDeclaration(declaration, &type, &name)) throw InputError(loc, "bad parameter declaration \"" + declaration + "\"");
    set(name, type, values, loc);
}

}  // namespace streyes::sl
