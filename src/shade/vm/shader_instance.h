// A shader instance: a compiled shader and the parameter values a scene gave it (RIB's
// Surface "plastic" "float Ks" [.5]). Values are type-checked against the shader's
// declarations when they are set; what is not set keeps its default.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shade/vm/program.h"

namespace streyes::sl {

class ShaderInstance {
  public:
    explicit ShaderInstance(ProgramPtr program);

    const ShaderProgram& program() const { return *program_; }
    const ProgramPtr& programPtr() const { return program_; }

    // Sets parameter `name` to `values` given as `type` (the RIB declaration: "float Ks" gives
    // float; BaseType::Void takes the parameter's own type). Point, vector and normal values
    // are in "shader" space, as RIB gives them; the interpreter moves them to current space.
    // A name the shader lacks, a type that differs (point, vector and normal match each
    // other), or a wrong number of values is an InputError at `loc`.
    void set(const std::string& name, SlType type, const std::vector<float>& values, const SourceLoc& loc = {});
    void setStrings(const std::string& name, const std::vector<std::string>& values, const SourceLoc& loc = {});
    // Parses a RIB parameter declaration ("uniform float Ks", "color specularcolor", "Ks") and sets it.
    void setDeclared(const std::string& declaration, const std::vector<float>& values, const SourceLoc& loc = {});

    struct Value {
        int param = -1;
        std::vector<float> floats;  // comps x elements, element-major
        std::vector<std::string> strings;
    };
    // The value set for parameter index `param`, or null (its default applies).
    const Value* value(int param) const;
    // Unique to this instance and its values (a new one at each set): what the interpreter keys
    // results on that it keeps from grid to grid (an address alone may come back with other values).
    uint64_t revision() const { return revision_; }

  private:
    Value& slot(int param);
    ProgramPtr program_;
    std::vector<Value> values_;
    uint64_t revision_;
};

// Parses "[uniform|varying|constant|vertex|facevarying] type[n] name" (the type optional):
// what RIB's inline declarations say. Returns false when it is not such a declaration.
bool parseDeclaration(const std::string& declaration, SlType* type, std::string* name);

}  // namespace streyes::sl
