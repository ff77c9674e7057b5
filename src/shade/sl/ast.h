// The syntax tree of a Shading Language source. The parser builds it; the checker annotates
// each expression with its type and what its names and calls refer to; the code generator
// walks it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "shade/vm/types.h"
#include "streyes/error.h"

namespace streyes::sl {

struct Builtin;
struct FunctionDef;
struct Symbol;

enum class ExprKind {
    Number,    // number
    String,    // text
    Name,      // text; symbol
    Call,      // text(args); builtin or function; channel: name[c] on a texture's first argument
    Unary,     // op args[0]: "-", "!"
    Binary,    // args[0] op args[1]: + - * / ^ . == != < > <= >= && ||
    Assign,    // args[0] op args[1]: = += -= *= /=
    Ternary,   // args[0] ? args[1] : args[2]
    Cast,      // castType ["space"] args[0]: a typecast, or a constructor with a space
    Tuple,     // ( args... ): 3 (a triple) or 16 (a matrix) values, typed by context
    Index,     // args[0][args[1]]
    ArrayInit  // { args... }: array initialisers
};

struct Expr {
    ExprKind kind;
    SourceLoc loc;
    std::string text;            // name, operator, string value, or the space of a Cast
    double number = 0;
    SlType castType;             // Cast
    std::vector<std::unique_ptr<Expr>> args;
    std::unique_ptr<Expr> channel;  // Call: texture("name"[channel], ...)

    // Filled by the checker.
    SlType type;                 // result type (void for calls of void functions)
    Symbol* symbol = nullptr;    // Name; also the target of an Assign's Name
    const Builtin* builtin = nullptr;
    FunctionDef* function = nullptr;

    Expr(ExprKind k, SourceLoc l) : kind(k), loc(std::move(l)) {}
};
using ExprPtr = std::unique_ptr<Expr>;

// A declared name: `float a = 1, b[3];` has two declarators.
struct Declarator {
    std::string name;
    SourceLoc loc;
    int arrayLen = 0;  // > 0: array
    ExprPtr init;      // may be null; an ArrayInit for arrays
    std::string initText;  // the initialiser as written (parameter defaults, for describe)
    Symbol* symbol = nullptr;  // filled by the checker
};

struct VarDecl {
    SourceLoc loc;
    BaseType base = BaseType::Float;
    bool hasDetail = false;  // uniform or varying written
    Detail detail = Detail::Varying;
    bool output = false;
    bool isExtern = false;
    std::vector<Declarator> decls;
};

enum class StmtKind {
    Block, Expr, Decl, If, While, For, Break, Continue, Return, Illuminance, Illuminate, Solar, Empty
};

struct Stmt {
    StmtKind kind;
    SourceLoc loc;
    std::vector<std::unique_ptr<Stmt>> body;  // Block: statements; If: then [, else]; loops: the body
    ExprPtr expr;                             // Expr, Return (may be null), If/While cond
    ExprPtr init, step;                       // For (each may be null); For's cond is expr
    std::vector<ExprPtr> args;                // Illuminance / Illuminate / Solar arguments
    VarDecl decl;                             // Decl
    int level = 1;                            // Break / Continue: how many loops out

    Stmt(StmtKind k, SourceLoc l) : kind(k), loc(std::move(l)) {}
};
using StmtPtr = std::unique_ptr<Stmt>;

struct FunctionDef {
    std::string name;
    SourceLoc loc;
    SlType returnType;  // void for procedures
    std::vector<VarDecl> formals;
    StmtPtr body;
};

struct ShaderDef {
    ShaderType type = ShaderType::Surface;
    std::string name;
    SourceLoc loc;
    std::vector<VarDecl> formals;
    StmtPtr body;
};

struct Module {
    std::vector<std::unique_ptr<FunctionDef>> functions;
    std::unique_ptr<ShaderDef> shader;
};

}  // namespace streyes::sl
