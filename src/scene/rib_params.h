// Parameter declarations: what class, type and array size a parameter name stands for.
//
// A parameter list names each value ("Kd" 0.5); the name must be declared (predeclared, by
// Declare, or inline as "uniform float Kd"), and the declaration says how to read the values.
// The lists themselves are read by RibParser::readParams (rib_params.cpp).
#pragma once

#include <map>
#include <string>

#include "streyes/scene.h"

namespace streyes {

// A parameter's declared storage: "uniform color", "varying float[2]", ...
struct RibParamDecl {
    ParamClass cls = ParamClass::Uniform;
    ParamType type = ParamType::Float;
    int arraySize = 1;
};

// Parse "[class] type[n] name" (an inline declaration) or "[class] type[n]" (Declare's second
// argument, withName = false). Returns an empty string on success, else what is wrong.
std::string parseRibDeclaration(const std::string& text, bool withName, RibParamDecl* decl, std::string* name);

// The names declared before any Declare: RenderMan's standard ones and those streyes reads.
std::map<std::string, RibParamDecl> predeclaredParams();

// RIB spellings, for messages: "color", "varying" (defined in params.cpp).
const char* paramTypeName(ParamType type);
const char* paramClassName(ParamClass cls);

}  // namespace streyes
