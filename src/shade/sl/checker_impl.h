// The Shading Language checker's internals, shared by checker.cpp (declarations, statements and
// expressions) and checker_calls.cpp (the calls with rules of their own: texture, ray, point-cloud,
// gather, spline, format and filterstep). Only those two include it.
#pragma once

#include <cctype>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "shade/sl/builtins.h"
#include "shade/sl/checker.h"

namespace streyes::sl::detail {

// What a gather output holds (void: not one streyes gives).
inline SlType gatherOutputType(const std::string& name) {
    if (name == "surface:Ci" || name == "surface:Oi") return BaseType::Color;
    if (name == "surface:P" || name == "ray:origin") return BaseType::Point;
    if (name == "surface:N") return BaseType::Normal;
    if (name == "ray:direction") return BaseType::Vector;
    if (name == "ray:length") return BaseType::Float;
    return BaseType::Void;
}

inline bool isIdentifier(const std::string& s) {
    if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
    for (char c : s)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
    return true;
}

inline const std::set<std::string> kTextureOptions = {"blur", "sblur", "tblur", "width", "swidth", "twidth",
                                               "fill", "filter", "samples", "bias"};
// The ray-traced functions' options: those read (floats, and the environment map's name), then
// PRMan's and Aqsis's others, accepted and ignored (docs/SCENE-FORMAT.md says which).
inline const std::set<std::string> kRayFloatOptions = {"samples", "maxdist", "coneangle", "bias", "adaptive",
                                                "minsamples", "maxvariation", "maxerror", "maxpixeldist",
                                                "falloff", "falloffmode", "samplebase", "blur", "pointbased", "microbufres",
                                                "maxsolidangle", "clamp", "sortbleeding", "hitsides"};
inline const std::set<std::string> kRayStringOptions = {"environmentmap", "environmentspace", "label", "subset",
                                                 "distribution", "hitmode", "filename", "hitsides", "coordsystem"};

class Checker {
  public:
    explicit Checker(CheckedShader& out) : out_(out) {}

    void run() {
        Module& m = out_.module;
        for (auto& f : m.functions) functions_[f->name].push_back(f.get());
        ShaderDef& s = *m.shader;
        shaderType_ = s.type;
        // Predefined variables: the outermost scope of the shader and of every function.
        scopes_.emplace_back();
        for (int g = 0; g < kGlobalCount; ++g) {
            const GlobalInfo& gi = globalInfo(Global(g));
            Symbol* sym = newSymbol(gi.name, SymbolKind::Global, gi.type, s.loc);
            sym->hasDetail = true;
            sym->detail = gi.detail;
            sym->global = Global(g);
            out_.globals[size_t(g)] = sym;
            scopes_.back()[gi.name] = sym;
        }
        // Parameters, each default seeing the parameters before it.
        scopes_.emplace_back();
        for (VarDecl& d : s.formals) {
            if (d.isExtern) fail(d.loc, "'extern' is not for parameters");
            for (Declarator& dc : d.decls) {
                SlType t(d.base, dc.arrayLen);
                if (d.base == BaseType::Void) fail(dc.loc, "a parameter cannot be void");
                checkInit(dc, t);
                Symbol* sym = declare(dc, SymbolKind::Param, t, d);
                sym->param = int(out_.params.size());
                out_.params.push_back(sym);
            }
        }
        shaderScopeDepth_ = scopes_.size();
        function_ = nullptr;
        checkStmt(*s.body);
        scopes_.resize(1);
        for (auto& f : m.functions) checkFunction(*f);
    }

  private:
    [[noreturn]] void fail(const SourceLoc& loc, const std::string& what) const { throw InputError(loc, what); }

    Symbol* newSymbol(const std::string& name, SymbolKind kind, SlType type, const SourceLoc& loc) {
        auto s = std::make_unique<Symbol>();
        s->name = name;
        s->kind = kind;
        s->type = type;
        s->loc = loc;
        s->owner = function_;
        out_.symbols.push_back(std::move(s));
        return out_.symbols.back().get();
    }

    Symbol* declare(Declarator& dc, SymbolKind kind, SlType type, const VarDecl& d) {
        auto& scope = scopes_.back();
        if (scope.count(dc.name)) fail(dc.loc, "'" + dc.name + "' is already declared in this scope");
        Symbol* sym = newSymbol(dc.name, kind, type, dc.loc);
        sym->hasDetail = d.hasDetail;
        sym->detail = d.hasDetail ? d.detail : (kind == SymbolKind::Param ? Detail::Uniform : Detail::Varying);
        if (kind == SymbolKind::Param) sym->hasDetail = true;  // parameters are uniform unless said varying
        sym->output = d.output;
        sym->decl = &dc;
        dc.symbol = sym;
        scope[dc.name] = sym;
        return sym;
    }

    Symbol* lookup(const std::string& name) const {
        for (auto it = scopes_.rbegin(); it != scopes_.rend(); ++it) {
            auto f = it->find(name);
            if (f != it->end()) return f->second;
        }
        return nullptr;
    }

    void checkFunction(FunctionDef& f) {
        function_ = &f;
        scopes_.emplace_back();
        int pos = 0;
        for (VarDecl& d : f.formals) {
            if (d.base == BaseType::Void) fail(d.loc, "a parameter cannot be void");
            for (Declarator& dc : d.decls) {
                if (dc.init) fail(dc.loc, "function parameters have no default values");
                Symbol* sym = declare(dc, SymbolKind::FuncParam, SlType(d.base, dc.arrayLen), d);
                sym->formal = pos++;
            }
        }
        loopDepth_ = 0;
        checkStmt(*f.body);
        scopes_.pop_back();
        function_ = nullptr;
    }

    void checkInit(Declarator& dc, SlType t) {
        if (!dc.init) return;
        if (dc.init->kind == ExprKind::ArrayInit) {
            if (!t.isArray()) fail(dc.init->loc, "'" + dc.name + "' is not an array: no {...} initialiser");
            if (!t.isResizable() && int(dc.init->args.size()) != t.arrayLen)
                fail(dc.init->loc, "'" + dc.name + "' has " + std::to_string(t.arrayLen) + " elements, the initialiser " +
                                       std::to_string(dc.init->args.size()));
            for (auto& e : dc.init->args) expectType(*e, t.element(), "an element of '" + dc.name + "'");
            dc.init->type = t;
            return;
        }
        expectType(*dc.init, t, "'" + dc.name + "'");
    }

    // Checks `e` where a `want` is needed (assignment, initialiser, argument, return).
    void expectType(Expr& e, SlType want, const std::string& what) {
        SlType got = check(e, want);
        if (e.kind == ExprKind::Tuple && flexibleTuple(e, want)) return;
        if (conversionCost(got, want) < 0)
            fail(e.loc, "cannot use a " + got.name() + " as " + what + " (" + want.name() + ")");
    }

    // An untyped tuple (a, b, c) takes the triple type its context wants.
    bool flexibleTuple(Expr& e, SlType want) {
        if (e.kind != ExprKind::Tuple) return false;
        if ((e.args.size() == 3 && want.isTriple()) || (e.args.size() == 16 && want.isMatrix())) {
            e.type = want;
            return true;
        }
        return false;
    }

    int argCost(const Expr& e, SlType want) const {
        if (e.kind == ExprKind::Tuple &&
            ((e.args.size() == 3 && want.isTriple()) || (e.args.size() == 16 && want.isMatrix())))
            return e.type == want ? 0 : 1;
        return conversionCost(e.type, want);
    }

    // ---- Statements ----

    void checkStmt(Stmt& s) {
        switch (s.kind) {
            case StmtKind::Block:
                scopes_.emplace_back();
                for (auto& b : s.body) checkStmt(*b);
                scopes_.pop_back();
                break;
            case StmtKind::Expr: check(*s.expr, SlType()); break;
            case StmtKind::Empty: break;
            case StmtKind::Decl: checkDecl(s.decl); break;
            case StmtKind::If:
                checkCond(*s.expr);
                for (auto& b : s.body) checkScoped(*b);
                break;
            case StmtKind::While:
            case StmtKind::For:
                if (s.init) check(*s.init, SlType());
                if (s.expr) checkCond(*s.expr);
                if (s.step) check(*s.step, SlType());
                ++loopDepth_;
                checkScoped(*s.body[0]);
                --loopDepth_;
                break;
            case StmtKind::Break:
            case StmtKind::Continue:
                if (s.level > loopDepth_)
                    fail(s.loc, std::string(s.kind == StmtKind::Break ? "break" : "continue") +
                                    (loopDepth_ == 0 ? " outside a loop" : " out of more loops than enclose it"));
                break;
            case StmtKind::Return:
                if (!function_) {
                    if (s.expr) fail(s.expr->loc, "a shader returns no value");
                } else if (function_->returnType.isVoid()) {
                    if (s.expr) fail(s.expr->loc, "'" + function_->name + "' returns no value (void)");
                } else {
                    if (!s.expr) fail(s.loc, "'" + function_->name + "' must return a " + function_->returnType.name());
                    expectType(*s.expr, function_->returnType, "the value of '" + function_->name + "'");
                }
                break;
            case StmtKind::Illuminance: checkIlluminance(s); break;
            case StmtKind::Illuminate:
            case StmtKind::Solar: checkIlluminate(s); break;
        }
    }

    void checkScoped(Stmt& s) {
        scopes_.emplace_back();
        checkStmt(s);
        scopes_.pop_back();
    }

    void checkCond(Expr& e) {
        SlType t = check(e, SlType());
        if (!t.isFloat()) fail(e.loc, "a condition must be a float or a comparison, not a " + t.name());
    }

    void checkDecl(VarDecl& d) {
        if (d.base == BaseType::Void) fail(d.loc, "a variable cannot be void");
        for (Declarator& dc : d.decls) {
            SlType t(d.base, dc.arrayLen);
            if (d.isExtern) {
                // extern names a variable of the shader: a parameter or a predefined one.
                Symbol* target = nullptr;
                for (Symbol* p : out_.params)
                    if (p->name == dc.name) target = p;
                if (!target) {
                    Global g = findGlobal(dc.name);
                    if (g != Global::Count) target = out_.globals[size_t(g)];
                }
                if (!target) fail(dc.loc, "extern '" + dc.name + "' names no shader parameter or predefined variable");
                if (target->type != t)
                    fail(dc.loc, "extern '" + dc.name + "' is declared " + t.name() + ", the shader's is " +
                                     target->type.name());
                if (dc.init) fail(dc.loc, "an extern declaration has no initialiser");
                dc.symbol = target;
                scopes_.back()[dc.name] = target;
                continue;
            }
            checkInit(dc, t);
            declare(dc, SymbolKind::Local, t, d);
        }
    }

    void checkIlluminance(Stmt& s) {
        if (!function_ && shaderType_ != ShaderType::Surface && shaderType_ != ShaderType::Volume)
            fail(s.loc, "illuminance is only for surface and volume shaders");
        size_t n = s.args.size();
        size_t first = 0;
        if (n >= 1) {
            check(*s.args[0], SlType());
            if (s.args[0]->type.isString()) first = 1;
        }
        size_t rest = n - first;
        if (rest != 1 && rest != 3)
            fail(s.loc, "illuminance takes ([category,] position [, axis, angle]), not " + std::to_string(n) + " arguments");
        for (size_t i = first; i < n; ++i) {
            SlType want = i == first ? SlType(BaseType::Point) : i == first + 1 ? SlType(BaseType::Vector) : SlType(BaseType::Float);
            expectType(*s.args[i], want, "an illuminance argument");
        }
        ++loopDepth_;  // break and continue apply to the loop over lights
        checkScoped(*s.body[0]);
        --loopDepth_;
    }

    void checkIlluminate(Stmt& s) {
        const bool solar = s.kind == StmtKind::Solar;
        const char* name = solar ? "solar" : "illuminate";
        if (!function_ && shaderType_ != ShaderType::Light) fail(s.loc, std::string(name) + " is only for light shaders");
        size_t n = s.args.size();
        size_t ok1 = solar ? 0 : 1, ok2 = solar ? 2 : 3;
        if (n != ok1 && n != ok2)
            fail(s.loc, solar ? "solar takes () or (axis, angle)" : "illuminate takes (position) or (position, axis, angle)");
        for (size_t i = 0; i < n; ++i) {
            size_t k = solar ? i + 1 : i;
            SlType want = k == 0 ? SlType(BaseType::Point) : k == 1 ? SlType(BaseType::Vector) : SlType(BaseType::Float);
            expectType(*s.args[i], want, std::string("a ") + name + " argument");
        }
        checkScoped(*s.body[0]);
    }

    // ---- Expressions ----

    SlType check(Expr& e, SlType want) {
        e.type = checkExpr(e, want);
        return e.type;
    }

    SlType checkExpr(Expr& e, SlType want) {
        switch (e.kind) {
            case ExprKind::Number: return BaseType::Float;
            case ExprKind::String: return BaseType::String;
            case ExprKind::Name: {
                Symbol* s = lookup(e.text);
                if (!s && e.text == "PI") {  // the one predefined constant
                    e.kind = ExprKind::Number;
                    e.number = 3.14159265358979323846;
                    return BaseType::Float;
                }
                if (!s) fail(e.loc, "undefined variable '" + e.text + "'");
                e.symbol = s;
                return s->type;
            }
            case ExprKind::Tuple: {
                for (auto& a : e.args) expectType(*a, BaseType::Float, "a tuple value");
                if (e.args.size() == 16) return BaseType::Matrix;
                return want.isTriple() ? want.base : BaseType::Point;
            }
            case ExprKind::ArrayInit: fail(e.loc, "{...} only initialises an array in its declaration");
            case ExprKind::Index: {
                SlType base = check(*e.args[0], SlType());
                if (!base.isArray()) fail(e.loc, "only arrays can be indexed, not a " + base.name());
                expectType(*e.args[1], BaseType::Float, "an index");
                return base.element();
            }
            case ExprKind::Unary: {
                SlType t = check(*e.args[0], SlType());
                if (e.text == "!") {
                    if (!t.isFloat()) fail(e.loc, "'!' needs a float or a comparison, not a " + t.name());
                    return t;
                }
                if (!(t.isFloat() || t.isTriple() || t.isMatrix())) fail(e.loc, "cannot negate a " + t.name());
                return t;
            }
            case ExprKind::Binary: return checkBinary(e);
            case ExprKind::Assign: return checkAssign(e);
            case ExprKind::Ternary: {
                checkCond(*e.args[0]);
                SlType a = check(*e.args[1], want), b = check(*e.args[2], want);
                if (a == b) return a;
                if (a.isFloat() && (b.isTriple() || b.isMatrix())) return b;
                if (b.isFloat() && (a.isTriple() || a.isMatrix())) return a;
                if (a.isPointLike() && b.isPointLike()) return a;
                if (flexibleTuple(*e.args[1], b)) return b;
                if (flexibleTuple(*e.args[2], a)) return a;
                fail(e.loc, "the two sides of ?: differ: " + a.name() + " and " + b.name());
            }
            case ExprKind::Cast: return checkCast(e);
            case ExprKind::Call: return checkCall(e, want);
        }
        return SlType();
    }

    SlType checkBinary(Expr& e) {
        SlType a = check(*e.args[0], SlType()), b = check(*e.args[1], SlType());
        // An untyped tuple beside a typed triple takes its type.
        if (e.args[0]->kind == ExprKind::Tuple && b.isTriple()) a = e.args[0]->type = b;
        if (e.args[1]->kind == ExprKind::Tuple && a.isTriple()) b = e.args[1]->type = a;
        SlType r = binaryType(e.text, a, b);
        if (r.isVoid()) fail(e.loc, "'" + e.text + "' cannot take a " + a.name() + " and a " + b.name());
        return r;
    }

  public:
    // The result of a op b, or void when they do not go together.
    static SlType binaryType(const std::string& op, SlType a, SlType b) {
        if (a.isArray() || b.isArray()) return SlType();
        if (op == "&&" || op == "||") return a.isFloat() && b.isFloat() ? SlType(BaseType::Float) : SlType();
        if (op == "==" || op == "!=") {
            if (a.isString() || b.isString()) return a == b ? SlType(BaseType::Float) : SlType();
            if (a == b || conversionCost(a, b) >= 0 || conversionCost(b, a) >= 0) return BaseType::Float;
            return SlType();
        }
        if (op == "<" || op == ">" || op == "<=" || op == ">=")
            return a.isFloat() && b.isFloat() ? SlType(BaseType::Float) : SlType();
        if (op == ".") return a.isPointLike() && b.isPointLike() ? SlType(BaseType::Float) : SlType();
        if (op == "^") return a.isPointLike() && b.isPointLike() ? SlType(BaseType::Vector) : SlType();
        // + - * /
        if (a.isString() || b.isString() || a.isVoid() || b.isVoid()) return SlType();
        if (a.isMatrix() || b.isMatrix()) {
            if (a.isMatrix() && b.isMatrix()) return BaseType::Matrix;
            if ((op == "*" || op == "/") && (a.isFloat() || b.isFloat())) return BaseType::Matrix;
            return SlType();
        }
        if (a.isFloat()) return b;
        if (b.isFloat()) return a;
        if (a.base == BaseType::Color || b.base == BaseType::Color) return a == b ? a : SlType();
        // point-like with point-like
        if (op == "-" && a.base == BaseType::Point && b.base == BaseType::Point) return BaseType::Vector;
        if (op == "+" || op == "-") {
            if (a.base == BaseType::Point || b.base == BaseType::Point) return BaseType::Point;
            if (a == b) return a;
            return BaseType::Vector;
        }
        return a;
    }

  private:
    SlType checkAssign(Expr& e) {
        Expr& lhs = *e.args[0];
        Expr* var = &lhs;
        if (lhs.kind == ExprKind::Index) var = lhs.args[0].get();
        if (var->kind != ExprKind::Name) fail(lhs.loc, "only a variable or an array element can be assigned to");
        SlType lt = check(lhs, SlType());
        checkWritable(*var->symbol, lhs.loc);
        e.symbol = var->symbol;
        if (e.text == "=") {
            if (e.args[1]->kind == ExprKind::ArrayInit) fail(e.args[1]->loc, "{...} only initialises an array in its declaration");
            expectType(*e.args[1], lt, "the value of '" + var->symbol->name + "'");
            return lt;
        }
        SlType rt = check(*e.args[1], lt);
        if (e.args[1]->kind == ExprKind::Tuple && lt.isTriple()) rt = e.args[1]->type = lt;
        SlType r = binaryType(e.text.substr(0, 1), lt, rt);
        if (r.isVoid() || conversionCost(r, lt) < 0)
            fail(e.loc, "'" + e.text + "' cannot take a " + lt.name() + " and a " + rt.name());
        return lt;
    }

    void checkWritable(const Symbol& s, const SourceLoc& loc) const {
        if (s.kind == SymbolKind::Global && !globalInfo(s.global).writable)
            fail(loc, "'" + s.name + "' is read-only");
        if (s.kind == SymbolKind::FuncParam && !s.output)
            fail(loc, "'" + s.name + "' is a parameter of '" + s.owner->name + "' not declared output: it cannot be assigned");
    }

    SlType checkCast(Expr& e) {
        SlType to = e.castType;
        Expr& arg = *e.args[0];
        if (!e.text.empty() && !(to.isTriple() || to.isMatrix()))
            fail(e.loc, "only colors, points, vectors, normals and matrices take a space name");
        SlType from;
        if (arg.kind == ExprKind::Tuple) {
            check(arg, to);
            if (arg.args.size() == 3 && !to.isTriple()) fail(e.loc, "a 3-tuple makes a color, point, vector or normal, not a " + to.name());
            if (arg.args.size() == 16 && !to.isMatrix()) fail(e.loc, "a 16-tuple makes a matrix, not a " + to.name());
            arg.type = to;
            return to;
        }
        from = check(arg, to);
        if (from == to || (from.isFloat() && (to.isTriple() || to.isMatrix())) || (from.isTriple() && to.isTriple()))
            return to;
        fail(e.loc, "cannot make a " + to.name() + " from a " + from.name());
    }

    // ---- Calls ----

    SlType checkCall(Expr& e, SlType want) {
        auto uf = functions_.find(e.text);
        if (uf == functions_.end() && e.text == "arraylength") return checkArrayLength(e);
        if (uf == functions_.end() && (e.text == "resize" || e.text == "push" || e.text == "pop")) return checkResizing(e);
        const auto& builtins = findBuiltins(e.text);
        if (uf == functions_.end() && builtins.empty()) fail(e.loc, "unknown function '" + e.text + "'");
        // texture("name"[channel], ...): the channel comes off the name.
        if (!builtins.empty() && (builtins[0]->special == Special::Texture || builtins[0]->special == Special::Environment ||
                                  builtins[0]->special == Special::Shadow)) {
            if (!e.args.empty() && e.args[0]->kind == ExprKind::Index) {
                ExprPtr ix = std::move(e.args[0]);
                e.channel = std::move(ix->args[1]);
                e.args[0] = std::move(ix->args[0]);
            }
        }
        for (auto& a : e.args) {
            if (a->kind == ExprKind::ArrayInit) fail(a->loc, "{...} only initialises an array in its declaration");
            check(*a, SlType());
        }
        if (uf != functions_.end()) return checkUserCall(e, uf->second);
        const Builtin* b = builtins[0];
        switch (b->special) {
            case Special::Texture:
            case Special::Environment:
            case Special::Shadow: return checkTexture(e, want);
            case Special::Ray: return checkRay(e);
            case Special::Gather: return checkGather(e);
            case Special::PointCloud: return checkPointCloud(e);
            case Special::Bake: {
                if (e.args.size() != 4) fail(e.loc, "bake takes (string file, float s, float t, value)");
                if (!e.args[0]->type.isString()) fail(e.args[0]->loc, "bake's first argument is a file name (a string)");
                expectType(*e.args[1], BaseType::Float, "bake's s");
                expectType(*e.args[2], BaseType::Float, "bake's t");
                const SlType v = e.args[3]->type;
                if (v.isArray() || !(v.isFloat() || v.isTriple()))
                    fail(e.args[3]->loc, "bake writes a float or a color (or point, vector, normal), not a " + v.name());
                e.builtin = b;
                return BaseType::Void;
            }
            case Special::Spline: return checkSpline(e);
            case Special::Printf:
            case Special::Format:
            case Special::Concat: return checkFormat(e);
            case Special::Lightsource: {
                if (e.args.size() != 2 || !e.args[0]->type.isString())
                    fail(e.loc, "lightsource takes (string name, output variable)");
                requireVariable(*e.args[1], "lightsource's second argument");
                e.builtin = b;
                return BaseType::Float;
            }
            case Special::Message: {
                if (e.args.size() != 2 || !e.args[0]->type.isString())
                    fail(e.loc, e.text + " takes (string name, output variable): another shader's parameter");
                if (e.args[0]->kind == ExprKind::String && !isIdentifier(e.args[0]->text))
                    fail(e.args[0]->loc, e.text + "(\"" + e.args[0]->text +
                                             "\", ...): a parameter name is an identifier (letters, digits, _)");
                requireVariable(*e.args[1], e.text + "'s second argument");
                e.builtin = b;
                return BaseType::Float;
            }
            case Special::Query: {
                const size_t names = b->name == "textureinfo" ? 2 : 1;
                bool ok = e.args.size() == names + 1;
                for (size_t i = 0; ok && i < names; ++i) ok = e.args[i]->type.isString();
                if (!ok)
                    fail(e.loc, e.text + (names == 2 ? " takes (string map, string name, output variable)"
                                                     : " takes (string name, output variable)"));
                requireVariable(*e.args.back(), e.text + "'s last argument");
                e.builtin = b;
                return BaseType::Float;
            }
            case Special::Filterstep: return checkFilterstep(e);
            default: break;
        }
        return resolveBuiltin(e, builtins, want);
    }

    // arraylength(a): a fixed array's length is known here, so the call is that number; a
    // resizable one's is read at run time (the code generator's alen).
    SlType checkArrayLength(Expr& e) {
        if (e.args.size() != 1) fail(e.loc, "arraylength takes one array");
        const SlType t = check(*e.args[0], SlType());
        if (!t.isArray()) fail(e.args[0]->loc, "arraylength of a " + t.name() + ", not an array");
        if (t.isResizable()) {
            if (e.args[0]->kind != ExprKind::Name) fail(e.args[0]->loc, "arraylength takes an array variable");
            e.number = -1;
            return BaseType::Float;
        }
        e.kind = ExprKind::Number;
        e.number = t.arrayLen;
        e.args.clear();
        return BaseType::Float;
    }

    // resize(a, n), push(a, v), pop(a): only on arrays declared without a length (RSL 2's
    // resizable arrays), written as variables.
    SlType checkResizing(Expr& e) {
        const size_t want = e.text == "pop" ? 1 : 2;
        if (e.args.size() != want)
            fail(e.loc, e.text + (e.text == "resize" ? " takes (array, float length)"
                                  : e.text == "push" ? " takes (array, value)"
                                                     : " takes (array)"));
        Expr& a = *e.args[0];
        const SlType t = check(a, SlType());
        if (a.kind != ExprKind::Name) fail(a.loc, e.text + "'s first argument must be an array variable (it is changed)");
        if (!t.isArray()) fail(a.loc, e.text + " needs an array, not the " + t.name() + " '" + a.text + "'");
        if (!t.isResizable())
            fail(a.loc, e.text + " of '" + a.text + "', a " + t.name() +
                            " of fixed length: only arrays declared without a length (" + baseTypeName(t.base) + " " +
                            a.text + "[]) can be resized, pushed onto or popped");
        checkWritable(*a.symbol, a.loc);
        if (e.text == "resize") expectType(*e.args[1], BaseType::Float, "resize's length");
        if (e.text == "push") {
            if (e.args[1]->kind == ExprKind::ArrayInit) fail(e.args[1]->loc, "push takes one element, not {...}");
            expectType(*e.args[1], t.element(), "the value pushed onto '" + a.text + "'");
        }
        return e.text == "pop" ? t.element() : SlType(BaseType::Void);
    }

    void requireVariable(Expr& a, const std::string& what) {
        Expr* v = &a;
        if (v->kind == ExprKind::Index) v = v->args[0].get();
        if (v->kind != ExprKind::Name) fail(a.loc, what + " must be a variable (it is written)");
        checkWritable(*v->symbol, a.loc);
    }

    SlType resolveBuiltin(Expr& e, const std::vector<const Builtin*>& cands, SlType want) {
        const Builtin* best = nullptr;
        int bestCost = 1 << 30;
        for (const Builtin* b : cands) {
            size_t na = e.args.size();
            if (na < b->args.size() || (na > b->args.size() && !b->varargs)) continue;
            int cost = 0;
            for (size_t i = 0; i < na && cost >= 0; ++i) {
                SlType t = i < b->args.size() ? b->args[i] : b->args.back();
                int c = argCost(*e.args[i], t);
                cost = c < 0 ? -1 : cost + c;
            }
            if (cost < 0) continue;
            // The context's wanted type breaks ties (and beats promotions of the arguments).
            if (!want.isVoid()) cost = cost * 4 + (b->ret == want ? 0 : conversionCost(b->ret, want) >= 0 ? 1 : 3);
            if (cost < bestCost) {
                best = b;
                bestCost = cost;
            }
        }
        if (!best) fail(e.loc, "no form of '" + e.text + "' takes (" + argTypes(e) + ")");
        for (size_t i = 0; i < e.args.size(); ++i) {
            SlType t = i < best->args.size() ? best->args[i] : best->args.back();
            flexibleTuple(*e.args[i], t);
            if (best->outputs & (1u << i)) requireVariable(*e.args[i], "argument " + std::to_string(i + 1) + " of " + e.text);
        }
        e.builtin = best;
        return best->ret;
    }

    std::string argTypes(const Expr& e) const {
        std::string s;
        for (size_t i = 0; i < e.args.size(); ++i) s += (i ? ", " : "") + e.args[i]->type.name();
        return s;
    }

    SlType checkUserCall(Expr& e, const std::vector<FunctionDef*>& fns) {
        FunctionDef* best = nullptr;
        int bestCost = 1 << 30;
        for (FunctionDef* f : fns) {
            std::vector<SlType> params;
            for (const VarDecl& d : f->formals)
                for (const Declarator& dc : d.decls) params.push_back(SlType(d.base, dc.arrayLen));
            if (params.size() != e.args.size()) continue;
            int cost = 0;
            for (size_t i = 0; i < params.size() && cost >= 0; ++i) {
                int c = argCost(*e.args[i], params[i]);
                cost = c < 0 ? -1 : cost + c;
            }
            if (cost >= 0 && cost < bestCost) {
                best = f;
                bestCost = cost;
            }
        }
        if (!best) {
            size_t count = 0;
            for (const VarDecl& d : fns[0]->formals) count += d.decls.size();
            if (fns.size() == 1 && count != e.args.size())
                fail(e.loc, "'" + e.text + "' takes " + std::to_string(count) + " argument" + (count == 1 ? "" : "s") +
                                ", not " + std::to_string(e.args.size()));
            fail(e.loc, "no form of '" + e.text + "' takes (" + argTypes(e) + ")");
        }
        size_t i = 0;
        for (const VarDecl& d : best->formals)
            for (const Declarator& dc : d.decls) {
                flexibleTuple(*e.args[i], SlType(d.base, dc.arrayLen));
                if (d.output) requireVariable(*e.args[i], "'" + dc.name + "' (an output parameter of " + e.text + ")");
                ++i;
            }
        e.function = best;
        return best->returnType;
    }

    // The calls with their own rules (checker_calls.cpp).
    SlType checkTexture(Expr& e, SlType want);
    SlType checkRay(Expr& e);
    SlType checkPointCloud(Expr& e);
    SlType checkGather(Expr& e);
    SlType checkSpline(Expr& e);
    SlType checkFormat(Expr& e);
    SlType checkFilterstep(Expr& e);

    CheckedShader& out_;
    std::map<std::string, std::vector<FunctionDef*>> functions_;
    std::vector<std::map<std::string, Symbol*>> scopes_;
    size_t shaderScopeDepth_ = 0;
    FunctionDef* function_ = nullptr;
    ShaderType shaderType_ = ShaderType::Surface;
    int loopDepth_ = 0;
};

}  // namespace streyes::sl::detail
