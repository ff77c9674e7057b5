// Semantic checks of a parsed shader: names resolve to declarations, expressions have types
// (with RenderMan's conversions: a float promotes to any triple or matrix; point, vector and
// normal convert freely), calls resolve to a user function or a standard one (overloads by
// argument types, then by the type the context wants, as in `color noise(P)`), and statements
// appear where they may. Storage classes (uniform/varying) are the code generator's: it infers
// them, since they depend on how functions are called.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "shade/sl/ast.h"

namespace streyes::sl {

enum class SymbolKind { Global, Param, Local, FuncParam };

struct Symbol {
    std::string name;
    SymbolKind kind = SymbolKind::Local;
    SlType type;
    bool hasDetail = false;  // declared uniform or varying
    Detail detail = Detail::Varying;
    bool output = false;     // an output parameter (shader or function)
    Global global = Global::Count;
    int param = -1;          // shader parameter index
    int formal = -1;         // function parameter position
    FunctionDef* owner = nullptr;  // the function declaring it (null: the shader)
    Declarator* decl = nullptr;
    SourceLoc loc;
};

struct CheckedShader {
    Module module;
    std::vector<std::unique_ptr<Symbol>> symbols;
    std::vector<Symbol*> params;                  // the shader's parameters, in order
    std::array<Symbol*, kGlobalCount> globals{};  // predefined variables
};

// Checks `module`; errors throw InputError naming file:line:column.
CheckedShader checkShader(Module module);

// How costly using a `from` where a `to` is wanted is: 0 the same, 1 point/vector/normal
// interchanged, 2 a float promoted; -1 not allowed.
int conversionCost(SlType from, SlType to);

}  // namespace streyes::sl
