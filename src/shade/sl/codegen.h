// Code generation: a checked shader becomes a ShaderProgram.
//
// Storage classes are inferred here. Parameters, predefined variables and variables declared
// uniform or varying keep what they say; other variables start uniform and become varying
// when a varying value is assigned to them or they are assigned under varying control flow.
// Since that can change what came before (a loop's condition reading the variable becomes
// varying), the generator then starts again from scratch with that variable varying; details
// only ever go from uniform to varying, so this ends. User functions are inlined at each call,
// so each call gets the storage classes its arguments imply.
#pragma once

#include <algorithm>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "shade/sl/builtins.h"
#include "shade/sl/checker.h"
#include "shade/sl/optimize.h"
#include "shade/vm/program.h"

namespace streyes::sl {

// Generates `out` from `checked` (which the generator annotates no further). Storage-class
// errors (a varying value assigned to a uniform variable) throw InputError.
// With options.optimize, constants are folded and dead code removed (optimize.h).
void generateCode(const CheckedShader& checked, ShaderProgram& out, const BackendOptions& options = {});

class CodeGen {
  public:
    CodeGen(const CheckedShader& checked, ShaderProgram& out, const BackendOptions& options = {})
        : cs_(checked), prog_(out), options_(options) {}
    void generate();

  private:
    struct Restart {};  // thrown when an inferred variable turned varying

    // An expression's value: a register, and whether it is a temporary to give back.
    struct Val {
        int reg = -1;
        SlType type;
        Detail detail = Detail::Uniform;
        bool temp = false;
        bool varying() const { return detail == Detail::Varying; }
    };
    struct Var {
        int reg = -1;
        SlType type;
        Detail detail = Detail::Uniform;
        bool inferred = false;  // may turn varying
        bool explicitUniform = false;
        std::string key;        // inference key: the call path and the declaration
        std::string name;
        int varyingAtDecl = 0;  // varying nesting where it was declared: assignments at that
        int maskedAtDecl = 0;   // nesting keep it uniform
        bool varying() const { return detail == Detail::Varying; }
    };
    struct Func {
        const FunctionDef* def = nullptr;  // null: the shader body
        std::string path;                  // inline path (call sites)
        std::map<const Symbol*, Var*> vars;
        Var* ret = nullptr;
        int funcLevel = -1;                // mask depth of its Func level, or -1 if none
        int entryDepth = 0;
        int varyingAtEntry = 0;
        int maskedAtEntry = 0;
        std::vector<int> returnJumps;      // uniform returns: jumps to the end
    };
    struct Loop {
        int level = -1;           // mask depth of its level, or -1 when it has none
        bool illuminance = false;
        int varyingAtEntry = 0;   // varying nesting in its body: a break there is uniform
        int maskedAtEntry = 0;
        std::vector<int> breakJumps, continueJumps;
    };

    void reset();
    void emitAll();

    // Registers and constants.
    int newReg(SlType t, Detail d, const std::string& name = "");
    Val temp(SlType t, Detail d);
    void release(const Val& v);
    Val constFloat(float v);
    Val constFloats(SlType t, const std::vector<float>& v);
    Val constString(const std::string& s);
    Val global(Global g);
    int emit(OpFn fn, std::initializer_list<int32_t> args, bool varying);
    int extraSpan(const std::vector<int32_t>& regs);
    // Points operand `slot` of instruction `at` at `target`, a jump target (a label).
    void patch(int at, int slot, int target) {
        prog_.code[size_t(at)].a[slot] = target;
        lastLabel_ = std::max(lastLabel_, target);
    }
    int label() {  // here, as a jump target
        lastLabel_ = std::max(lastLabel_, here());
        return here();
    }
    int here() const { return int(prog_.code.size()); }
    void setLoc(const SourceLoc& loc);

    // Variables.
    Var* declareVar(const Symbol* s, Detail declared, bool hasDetail);
    Var* lookup(const Symbol* s);
    bool masked() const { return varyingNest_ > 0 || maskedNest_ > 0; }
    // Stores v into variable var (promoting it); handles inference, masks and errors.
    void store(Var& var, Val v, const SourceLoc& loc);
    void storeElement(Var& var, Val index, Val v, const SourceLoc& loc);
    void assignTo(const Expr& lhs, Val v, const SourceLoc& loc);
    void makeVarying(Var& var);

    // Expressions (codegen_expr.cpp).
    Val gen(const Expr& e);
    Val genBinary(const Expr& e);
    Val genAssign(const Expr& e, bool needValue);
    Val genCast(const Expr& e);
    Val genCall(const Expr& e);
    Val genBuiltin(const Expr& e);
    Val genSpecial(const Expr& e, const Builtin& b);
    Val genTexture(const Expr& e, const Builtin& b);
    Val genRay(const Expr& e, const Builtin& b);
    Val genUserCall(const Expr& e);
    Val genArrayCall(const Expr& e);  // arraylength, resize, push, pop of resizable arrays
    Val convert(Val v, SlType to);
    Val toSpace(Val v, const std::string& space, const SourceLoc& loc);
    Val arith(OpFn fn, Val a, Val b, SlType result);

    // Statements (codegen_stmt.cpp).
    void genStmt(const Stmt& s);
    void genDecl(const VarDecl& d);
    void initResizable(Var& v, const Declarator& dc);
    void genIf(const Stmt& s);
    void genLoop(const Stmt& s);
    void genBreak(const Stmt& s);
    void genReturn(const Stmt& s);
    void genIlluminance(const Stmt& s);
    void genIlluminate(const Stmt& s);
    void genParams();
    void pushLevel() { prog_.maxMaskDepth = std::max(prog_.maxMaskDepth, ++depth_); }
    void popLevel() { --depth_; }
    Val condition(const Expr& e);

    const CheckedShader& cs_;
    ShaderProgram& prog_;
    BackendOptions options_;
    std::set<std::string> varyingKeys_;  // survives restarts
    // Per attempt:
    std::vector<std::unique_ptr<Var>> varStore_;
    std::map<std::pair<int, int>, std::vector<int>> freeTemps_;  // (type code, detail) -> regs
    std::map<std::vector<float>, int> floatConsts_;
    std::map<std::string, int> stringConsts_;
    std::vector<Func*> funcs_;    // inline stack; funcs_[0] is the shader body
    std::vector<Loop*> loops_;
    int depth_ = 0;               // mask depth at this point of the code
    int varyingNest_ = 0;         // enclosing varying conditions and loops (callers' included)
    int maskedNest_ = 0;          // reasons points may be off besides those (breaks, returns)
    const SourceLoc* loc_ = nullptr;
    int lastLabel_ = -1;          // the last position a jump lands on
    // Generating a value for a variable declared uniform: random() gives one number for the
    // grid there (`uniform color c = random();`, as RenderMan's compilers have it).
    bool uniformContext_ = false;
    Val genFor(const Expr& e, const Var& target);
};

}  // namespace streyes::sl
