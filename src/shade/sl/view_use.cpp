#include "shade/sl/view_use.h"

#include <map>
#include <optional>

#include "shade/sl/builtins.h"
#include "shade/sl/view_use_value.h"
#include "shade/vm/ray_source.h"

namespace streyes::sl {

namespace {

using namespace viewuse;

enum class SpaceClass { Current, Still, Other };

// "world", "object" and "shader" stay with the world (the renderer checks the shader's own
// transform); "current" and "camera" are current space; the rest (screen, raster, NDC, named
// coordinate systems, a name known only at run time) are taken to follow the camera.
SpaceClass spaceClass(const std::string& s) {
    if (s == "current" || s == "camera") return SpaceClass::Current;
    if (s == "world" || s == "object" || s == "shader") return SpaceClass::Still;
    return SpaceClass::Other;
}

SpaceClass spaceClass(const Expr* e) {
    return e && e->kind == ExprKind::String ? spaceClass(e->text) : SpaceClass::Other;
}

class Analysis {
  public:
    explicit Analysis(const CheckedShader& cs) : cs_(cs) {}

    ViewUseResult run() {
        const ShaderDef& sh = *cs_.module.shader;
        ctl_.push_back(of(Kind::Invariant));
        // Parameters: a value the renderer sets (RIB, primitive variables: point-like ones taken
        // from shader or object space to current) or the default, whichever the instance has.
        for (const Symbol* p : cs_.params) {
            const Declarator& dc = *p->decl;
            Value def = dc.init ? eval(*dc.init) : of(Kind::Invariant);
            const bool pointLike = p->type.element().isPointLike();
            Value set = of(pointLike ? (p->type.base == BaseType::Point ? Kind::Point : Kind::Vector) : Kind::Invariant);
            // A zero vector default is the same in every space (a zero point is the eye).
            if (pointLike && p->type.base != BaseType::Point && dc.init && isZeroValue(*dc.init)) def = set;
            Value v = join(set, def);
            if (v.kind == Kind::View && !v.where) v = view(dc.loc, "the parameter's default reads the view");
            state_[p] = v;
        }
        if (sh.body) exec(*sh.body);
        ViewUseResult r;
        if (giveUp_) {
            r.use = ViewUse::Reads;
            r.why = giveUpLoc_.str() + ": " + giveUpWhy_;
            return r;
        }
        bool facing = false;
        auto need = [&](const Value& v, Kind k, const char* name) {
            facing = facing || v.facing;
            if (v.kind == k || r.use == ViewUse::Reads) return;
            r.use = ViewUse::Reads;
            r.why = (v.where ? v.where->str() + ": " + std::string(v.what ? v.what : "reads the view") + " (reaches " +
                                   name + ")"
                             : std::string(name) + " is not a world-still value");
        };
        r.use = ViewUse::None;
        auto global = [&](Global g) { return get(cs_.globals[size_t(g)], g); };
        switch (sh.type) {
            case ShaderType::Surface:
            case ShaderType::Volume:
                need(global(Global::Ci), Kind::Invariant, "Ci");
                need(global(Global::Oi), Kind::Invariant, "Oi");
                break;
            case ShaderType::Displacement:
                need(global(Global::P), Kind::Point, "P");
                need(global(Global::N), Kind::Vector, "N");
                break;
            case ShaderType::Light:
                need(global(Global::Cl), Kind::Invariant, "Cl");
                need(global(Global::Ol), Kind::Invariant, "Ol");
                // The direction the surface's illuminance sees: from a world-still point, or
                // along a world-still axis.
                if (lightL_) need(*lightL_, Kind::Vector, "L");
                if (assignsL_) need(global(Global::L), Kind::Vector, "L");
                break;
            case ShaderType::Imager:
                r.use = ViewUse::Reads;
                r.why = sh.loc.str() + ": an imager runs on each frame";
                return r;
        }
        for (const Symbol* p : cs_.params)
            if (p->output) need(get(p), Kind::Invariant, p->name.c_str());
        if (r.use == ViewUse::None && facing) r.use = ViewUse::FacingOnly;
        return r;
    }

  private:
    using State = std::map<const Symbol*, Value>;

    // A predefined variable's value when the shader starts.
    Value initialGlobal(Global g) const {
        const ShaderType type = cs_.module.shader->type;
        switch (g) {
            case Global::P:
            case Global::Ps: return of(Kind::Point);
            case Global::N:
            case Global::Ng:
            case Global::Ns: return of(Kind::Vector, false, Shape::Normal);
            case Global::dPdu:
            case Global::dPdv: return of(Kind::Vector);
            case Global::I: {
                Value v = view(cs_.module.shader->loc, "I (the direction from the eye)");
                v.shape = Shape::Incident;
                return v;
            }
            case Global::E: return view(cs_.module.shader->loc, "E (the eye)");
            case Global::dPdtime: return view(cs_.module.shader->loc, "dPdtime (motion in current space)");
            // A light's L is the direction it shines along (illuminate and solar set it); a
            // surface's is its lights' inside illuminance (set there).
            case Global::L:
                return type == ShaderType::Light ? of(Kind::Vector)
                                                 : view(cs_.module.shader->loc, "L outside illuminance");
            default: return of(Kind::Invariant);  // Cs, Os, Ci, Oi, Cl, Ol, s, t, u, v, du, dv, time, ...
        }
    }

    Value initial(const Symbol* s) const {
        if (s->kind == SymbolKind::Global) return initialGlobal(s->global);
        return of(Kind::Invariant);  // locals start at zero; parameters are set in run()
    }

    Value get(const Symbol* s, Global g = Global::Count) const {
        if (!s) return initialGlobal(g);
        auto it = state_.find(s);
        return it != state_.end() ? it->second : initial(s);
    }

    State joinStates(const State& a, const State& b) const {
        State out = a;
        for (auto& [sym, v] : b) {
            auto it = out.find(sym);
            out[sym] = join(it != out.end() ? it->second : initial(sym), v);
        }
        for (auto& [sym, v] : out)
            if (!b.count(sym)) v = join(v, initial(sym));
        return out;
    }

    Value ctl() const { return join(join(ctl_.back(), loopExit_), funcExit_); }

    void giveUp(const SourceLoc& loc, const char* why) {
        if (giveUp_) return;
        giveUp_ = true;
        giveUpLoc_ = loc;
        giveUpWhy_ = why;
    }

    // ---- Statements -------------------------------------------------------------------------

    void exec(const Stmt& s) {
        if (giveUp_) return;
        switch (s.kind) {
            case StmtKind::Block:
                for (const StmtPtr& b : s.body) exec(*b);
                break;
            case StmtKind::Expr:
                if (s.expr) eval(*s.expr);
                break;
            case StmtKind::Decl:
                for (const Declarator& dc : s.decl.decls) {
                    if (!dc.symbol || s.decl.isExtern) continue;
                    if (dc.init) state_[dc.symbol] = under(eval(*dc.init), ctl(), dc.loc);
                    else state_[dc.symbol] = join(get(dc.symbol), under(of(Kind::Invariant), ctl(), dc.loc));
                }
                break;
            case StmtKind::If: {
                const Value c = eval(*s.expr);
                ctl_.push_back(join(ctl(), c));
                const State before = state_;
                exec(*s.body[0]);
                State taken = state_;
                state_ = before;
                if (s.body.size() > 1) exec(*s.body[1]);
                state_ = joinStates(taken, state_);
                ctl_.pop_back();
                break;
            }
            case StmtKind::While:
            case StmtKind::For: loop(s); break;
            case StmtKind::Break:
            case StmtKind::Continue: loopExit_ = join(loopExit_, ctl()); break;
            case StmtKind::Return:
                if (s.expr) {
                    const Value v = under(eval(*s.expr), ctl(), s.loc);
                    if (!returns_.empty()) returns_.back() = returns_.back() ? join(*returns_.back(), v) : v;
                }
                funcExit_ = join(funcExit_, ctl());
                break;
            case StmtKind::Illuminance: illuminance(s); break;
            case StmtKind::Illuminate:
            case StmtKind::Solar: illuminate(s); break;
            case StmtKind::Empty: break;
        }
    }

    // Runs `body` until nothing it assigns changes: every iteration count at once.
    template <typename Body>
    void fixedPoint(const SourceLoc& loc, Body&& body) {
        const Value savedExit = loopExit_;
        for (int round = 0;; ++round) {
            if (round == 32) {  // cannot happen on the finite lattice; be safe
                giveUp(loc, "a loop's analysis did not settle");
                break;
            }
            const State before = state_;
            const Value exitBefore = loopExit_;
            body();
            state_ = joinStates(before, state_);
            if (state_ == before && loopExit_ == exitBefore) break;
        }
        loopExit_ = savedExit;
    }

    void loop(const Stmt& s) {
        if (s.init) eval(*s.init);
        fixedPoint(s.loc, [&] {
            const Value c = s.expr ? eval(*s.expr) : of(Kind::Invariant);
            ctl_.push_back(join(ctl(), c));
            exec(*s.body[0]);
            if (s.step) eval(*s.step);
            ctl_.pop_back();
        });
    }

    // A cone (axis, angle): which lights or points it admits is world-still when the axis is a
    // world-still vector and the angle invariant.
    Value cone(const Value& axis, const Value& angle, const SourceLoc& loc) {
        Value c = of(Kind::Invariant, axis.facing || angle.facing);
        if (axis.kind != Kind::Vector || angle.kind != Kind::Invariant)
            c = viewFrom(loc, "a cone whose axis or angle reads the view", axis, angle);
        return c;
    }

    void illuminance(const Stmt& s) {
        const size_t first = !s.args.empty() && s.args[0]->type.isString() ? 1 : 0;
        if (s.args.size() <= first) {
            giveUp(s.loc, "illuminance without a position");
            return;
        }
        std::vector<Value> a;
        for (const ExprPtr& e : s.args) a.push_back(eval(*e));
        const Value pos = a[first];
        Value c = of(Kind::Invariant, pos.facing);
        if (pos.kind != Kind::Point) c = viewFrom(s.loc, "illuminance from a point that is not world-still", pos);
        if (a.size() > first + 2) c = join(c, cone(a[first + 1], a[first + 2], s.loc));
        const Symbol* L = cs_.globals[size_t(Global::L)];
        const Symbol* Cl = cs_.globals[size_t(Global::Cl)];
        const Symbol* Ol = cs_.globals[size_t(Global::Ol)];
        // Each light's L (from the point towards it) and Cl; whether a light is still in world,
        // and what its own shader reads, the renderer combines (SceneShaders::bind).
        fixedPoint(s.loc, [&] {
            ctl_.push_back(join(ctl(), c));
            if (L) state_[L] = under(of(Kind::Vector, pos.facing), c, s.loc);
            if (Cl) state_[Cl] = under(of(Kind::Invariant), c, s.loc);
            if (Ol) state_[Ol] = under(of(Kind::Invariant), c, s.loc);
            exec(*s.body[0]);
            ctl_.pop_back();
        });
    }

    void illuminate(const Stmt& s) {
        std::vector<Value> a;
        for (const ExprPtr& e : s.args) a.push_back(eval(*e));
        Value L = of(Kind::Vector);
        Value c = of(Kind::Invariant);
        if (s.kind == StmtKind::Solar) {
            if (a.size() < 2) L = view(s.loc, "solar() without an axis");
            else {
                c = cone(a[0], a[1], s.loc);
                L = a[0].kind == Kind::Vector ? of(Kind::Vector, a[0].facing)
                                              : viewFrom(s.loc, "solar along an axis that is not world-still", a[0]);
            }
        } else if (a.empty()) {
            L = view(s.loc, "illuminate() without a position");
        } else {
            L = a[0].kind == Kind::Point ? of(Kind::Vector, a[0].facing)
                                         : viewFrom(s.loc, "illuminate from a point that is not world-still", a[0]);
            if (a.size() > 2) c = cone(a[1], a[2], s.loc);
        }
        ctl_.push_back(join(ctl(), c));
        lightL_ = lightL_ ? join(*lightL_, under(L, ctl(), s.loc)) : under(L, ctl(), s.loc);
        if (const Symbol* l = cs_.globals[size_t(Global::L)]) state_[l] = under(L, ctl(), s.loc);
        const State before = state_;
        exec(*s.body[0]);
        state_ = joinStates(before, state_);  // points outside the cone keep what they had
        ctl_.pop_back();
    }

    // ---- Expressions ------------------------------------------------------------------------

    void assign(const Expr& target, Value v, const SourceLoc& loc) {
        if (target.kind == ExprKind::Name && target.symbol) {
            if (target.symbol->kind == SymbolKind::Global && target.symbol->global == Global::L) assignsL_ = true;
            state_[target.symbol] = under(v, ctl(), loc);
            return;
        }
        if (target.kind == ExprKind::Index) {  // one element: the array is either
            const Value index = eval(*target.args[1]);
            const Expr* base = target.args[0].get();
            if (base->kind == ExprKind::Name && base->symbol) {
                const Symbol* sym = base->symbol;
                state_[sym] = join(get(sym), under(under(v, index, loc), ctl(), loc));
                return;
            }
        }
        giveUp(loc, "an assignment the analysis does not follow");
    }

    Value eval(const Expr& e) {
        // Calls are analysed at each call site and loops to a fixed point: a budget keeps nested
        // calls and loops from taking long (then: Reads).
        if (++steps_ > kStepBudget) giveUp(e.loc, "the shader is too large to analyse");
        if (giveUp_) return view(e.loc, "not analysed");
        switch (e.kind) {
            case ExprKind::Number:
            case ExprKind::String: return of(Kind::Invariant);
            case ExprKind::Name: return e.symbol ? get(e.symbol) : view(e.loc, "an unresolved name");
            case ExprKind::Call: return call(e);
            case ExprKind::Unary: {
                Value a = eval(*e.args[0]);
                if (e.text == "!") return a.kind == Kind::Invariant ? a : viewFrom(e.loc, "not of a view value", a);
                // Negation keeps vectors, and the shapes the facing rules look for.
                if (a.kind == Kind::Point) return view(e.loc, "a negated point (a point about the eye)", a.facing);
                return a;
            }
            case ExprKind::Binary: return binary(e);
            case ExprKind::Assign: {
                Value v = eval(*e.args[1]);
                if (e.text != "=") {
                    const Value old = eval(*e.args[0]);
                    v = arith(e.text.substr(0, 1), old, v, *e.args[0], *e.args[1], e.loc);
                }
                assign(*e.args[0], v, e.loc);
                return v;
            }
            case ExprKind::Ternary: {
                const Value c = eval(*e.args[0]);
                const Value a = eval(*e.args[1]), b = eval(*e.args[2]);
                return under(join(a, b), c, e.loc);
            }
            case ExprKind::Cast: return cast(e);
            case ExprKind::Tuple:
            case ExprKind::ArrayInit: {
                std::vector<Value> a;
                for (const ExprPtr& x : e.args) a.push_back(eval(*x));
                if (e.kind == ExprKind::ArrayInit) {
                    Value r = a.empty() ? of(Kind::Invariant) : a[0];
                    for (const Value& x : a) r = join(r, x);
                    return r;
                }
                // (x, y, z) in current space: a point or vector fixed to the camera.
                return pure(a, e.loc, "a tuple of values that read the view");
            }
            case ExprKind::Index: {
                const Value base = eval(*e.args[0]), index = eval(*e.args[1]);
                return under(base, index, e.loc);
            }
        }
        return view(e.loc, "an expression the analysis does not know");
    }

    // 0, (0, 0, 0), vector (0, 0, 0), vector 0: a value zero in every component (no space).
    static bool isZeroValue(const Expr& e) {
        if (e.kind == ExprKind::Tuple) {
            for (const ExprPtr& a : e.args)
                if (!isZero(*a)) return false;
            return true;
        }
        if (e.kind == ExprKind::Cast && e.text.empty()) return isZeroValue(*e.args[0]);
        return isZero(e);
    }

    static bool isZero(const Expr& e) {
        if (e.kind == ExprKind::Number) return e.number == 0;
        if (e.kind == ExprKind::Unary && e.text == "-") return isZero(*e.args[0]);
        return false;
    }

    Value binary(const Expr& e) {
        const Value a = eval(*e.args[0]), b = eval(*e.args[1]);
        const std::string& op = e.text;
        const bool facing = a.facing || b.facing;
        if (op == "&&" || op == "||")
            return a.kind == Kind::Invariant && b.kind == Kind::Invariant ? of(Kind::Invariant, facing)
                                                                          : viewFrom(e.loc, "a condition", a, b);
        if (op == "==" || op == "!=" || op == "<" || op == ">" || op == "<=" || op == ">=") {
            // The sign of N.I: which side faces the eye.
            if ((a.shape == Shape::NdotI && isZero(*e.args[1])) || (b.shape == Shape::NdotI && isZero(*e.args[0])))
                return of(Kind::Invariant, true);
            return a.kind == Kind::Invariant && b.kind == Kind::Invariant
                       ? of(Kind::Invariant, facing)
                       : viewFrom(e.loc, "a comparison of values that are not invariant", a, b);
        }
        return arith(op, a, b, *e.args[0], *e.args[1], e.loc);
    }

    static bool isFloat(const Expr& e) { return e.type.base == BaseType::Float && e.type.arrayLen == 0; }

    Value arith(const std::string& op, const Value& a, const Value& b, const Expr& ea, const Expr& eb,
                const SourceLoc& loc) {
        const bool facing = a.facing || b.facing;
        const Kind ka = a.kind, kb = b.kind;
        if (op == ".") {
            if ((a.shape == Shape::Normal && b.shape == Shape::Incident) ||
                (a.shape == Shape::Incident && b.shape == Shape::Normal)) {
                Value v = viewFrom(loc, "N.I", a, b);
                v.shape = Shape::NdotI;
                return v;
            }
            if (ka == Kind::Vector && kb == Kind::Vector) return of(Kind::Invariant, facing);
            if (ka == Kind::Invariant && kb == Kind::Invariant) return of(Kind::Invariant, facing);
            return viewFrom(loc, "a dot product with a value that reads the view", a, b);
        }
        if (ka == Kind::View || kb == Kind::View) return viewFrom(loc, "reads the view", a, b);
        if (ka == Kind::Invariant && kb == Kind::Invariant) return of(Kind::Invariant, facing);
        if (op == "^" && ka == Kind::Vector && kb == Kind::Vector) return of(Kind::Vector, facing);
        if (op == "+") {
            if ((ka == Kind::Point && kb == Kind::Vector) || (ka == Kind::Vector && kb == Kind::Point))
                return of(Kind::Point, facing);
            if (ka == Kind::Vector && kb == Kind::Vector) return of(Kind::Vector, facing);
        }
        if (op == "-") {
            if (ka == Kind::Point && kb == Kind::Point) return of(Kind::Vector, facing);
            if (ka == Kind::Point && kb == Kind::Vector) return of(Kind::Point, facing);
            if (ka == Kind::Vector && kb == Kind::Vector) return of(Kind::Vector, facing);
        }
        if (op == "*") {
            if (ka == Kind::Vector && kb == Kind::Invariant && isFloat(eb)) return of(Kind::Vector, facing);
            if (kb == Kind::Vector && ka == Kind::Invariant && isFloat(ea)) return of(Kind::Vector, facing);
        }
        if (op == "/" && ka == Kind::Vector && kb == Kind::Invariant && isFloat(eb)) return of(Kind::Vector, facing);
        return view(loc, "arithmetic that mixes current-space values with others", facing);
    }

    Value cast(const Expr& e) {
        Value a = eval(*e.args[0]);
        const SlType to = e.castType;
        const SlType from = e.args[0]->type;
        if (!to.isPointLike()) {
            // To a float or colour: the components of a point or vector read the view.
            if (a.kind == Kind::Point || a.kind == Kind::Vector)
                return view(e.loc, "a component of a current-space point or vector", a.facing);
            if (to.isMatrix() && !e.text.empty() && spaceClass(e.text) != SpaceClass::Current)
                return a.kind == Kind::View ? a : view(e.loc, "a matrix of a space that moves against the camera", a.facing);
            return a;  // colour spaces, a float cast
        }
        if (!from.isPointLike() && a.kind != Kind::Invariant) return viewFrom(e.loc, "reads the view", a);
        if (e.text.empty()) return a;
        switch (spaceClass(e.text)) {
            case SpaceClass::Current: return a;
            case SpaceClass::Still:
                if (a.kind == Kind::Invariant) return of(to.base == BaseType::Point ? Kind::Point : Kind::Vector, a.facing);
                return viewFrom(e.loc, "a current-space value read as given in another space", a);
            case SpaceClass::Other: break;
        }
        return view(e.loc, "a value given in a space that follows the camera (screen, raster, NDC, named)", a.facing);
    }

    Value call(const Expr& e) {
        if (e.function) return userCall(e);
        if (!e.builtin && !e.args.empty() && e.args[0]->kind == ExprKind::Name && e.args[0]->symbol &&
            (e.text == "arraylength" || e.text == "resize" || e.text == "push" || e.text == "pop"))
            return arrayCall(e);
        if (!e.builtin) return view(e.loc, "a call the analysis does not know");
        const Builtin& b = *e.builtin;
        std::vector<Value> a;
        for (const ExprPtr& x : e.args) a.push_back(eval(*x));
        if (e.channel) a.push_back(eval(*e.channel));
        const bool facing = anyFacing(a);
        const std::string& n = b.name;
        auto k = [&](size_t i) { return i < a.size() ? a[i].kind : Kind::View; };
        auto same = [&](Kind want) {
            for (const Value& x : a)
                if (x.kind != want) return false;
            return true;
        };
        switch (b.special) {
            case Special::Ray:
                // Its output options ("occlusion", "environmentcolor") are what the rays meet too.
                {
                    size_t i = b.name == "occlusion" && !e.args.empty() && e.args[0]->type.isString() ? 1 : 0;
                    while (i < e.args.size() && !e.args[i]->type.isString()) ++i;  // the positional arguments
                    for (; i + 1 < e.args.size(); i += 2)
                        if (e.args[i]->kind == ExprKind::String && isRayOutputOption(b.name, e.args[i]->text))
                            assign(*e.args[i + 1], view(e.loc, "a ray (what it meets may move)"), e.loc);
                }
                return view(e.loc, "a ray (what it meets may move)");
            case Special::PointCloud:
                // texture3d's variables: what a file holds near the point (taken as reading the
                // view, conservatively: a cloud may hold anything).
                if (n == "texture3d")
                    for (size_t i = 4; i < e.args.size(); i += 2)
                        assign(*e.args[i], view(e.loc, "a point cloud lookup"), e.loc);
                return of(Kind::Invariant);
            case Special::Lightsource:
                if (a.size() > 1) assign(*e.args[1], view(e.loc, "a value passed from another shader"), e.loc);
                return view(e.loc, "a value passed from another shader");
            case Special::Query: {
                // Options, attributes and renderer information are the render's (the same in
                // every frame, shade/scene_queries.h); a map's information may differ by frame.
                const size_t out = n == "textureinfo" ? 2 : 1;
                const Value v = n != "textureinfo" ? of(Kind::Invariant) : view(e.loc, "textureinfo (maps may differ by frame)");
                if (out < e.args.size()) assign(*e.args[out], v, e.loc);
                return v;
            }
            case Special::SetComp: {
                std::vector<Value> rest(a.begin() + 1, a.end());
                const Value v = a[0].kind == Kind::Invariant && allInvariant(rest)
                                    ? of(Kind::Invariant, facing)
                                    : view(e.loc, "a component of a current-space value set", facing);
                assign(*e.args[0], v, e.loc);
                return of(Kind::Invariant);
            }
            case Special::Fresnel: {
                // fresnel(I, N, eta, Kr, Kt [, R, T]): I and N world-still vectors, eta invariant.
                const bool ok = k(0) == Kind::Vector && k(1) == Kind::Vector && k(2) == Kind::Invariant;
                const bool inv = k(0) == Kind::Invariant && k(1) == Kind::Invariant && k(2) == Kind::Invariant;
                for (size_t i = 3; i < e.args.size(); ++i) {
                    Value v = ok || inv ? of(i < 5 || inv ? Kind::Invariant : Kind::Vector, facing)
                                        : viewFrom(e.loc, "fresnel of vectors that read the view", a[0], a[1]);
                    assign(*e.args[i], v, e.loc);
                }
                return of(Kind::Invariant);
            }
            case Special::Faceforward: {
                // faceforward(N, I): +-N by the sign of Ng.I (the code generator's reference).
                const Value ng = get(cs_.globals[size_t(Global::Ng)], Global::Ng);
                if (k(0) != Kind::Vector && k(0) != Kind::Invariant)
                    return viewFrom(e.loc, "faceforward of a vector that reads the view", a[0]);
                if (k(0) == Kind::Vector && a[1].shape == Shape::Incident && ng.shape == Shape::Normal)
                    return of(Kind::Vector, true, a[0].shape);
                if (k(0) == Kind::Vector && k(1) == Kind::Vector && ng.kind == Kind::Vector)
                    return of(Kind::Vector, facing || ng.facing, a[0].shape);
                return viewFrom(e.loc, "faceforward by a direction that reads the view", a[1], a[0]);
            }
            case Special::Transform: return transform(e, b, a);
            case Special::Shadow: {
                // A lookup at a current-space point: the renderer takes it to the map's world.
                for (size_t i = 0; i < e.args.size(); ++i) {
                    const bool point = e.args[i]->type.base == BaseType::Point && e.args[i]->type.arrayLen == 0;
                    if (point ? a[i].kind != Kind::Point : a[i].kind != Kind::Invariant)
                        return viewFrom(e.loc, "a shadow lookup at a point that is not world-still", a[i]);
                }
                return of(Kind::Invariant, facing);
            }
            default: break;
        }
        if (n == "random") return view(e.loc, "random()");
        if (n == "specular" || n == "phong") return view(e.loc, "a highlight (reads I)");
        if (n == "ambient") return of(Kind::Invariant);
        if (n == "diffuse") {
            // Lights seen from P (its current value) along a world-still normal.
            const Value p = get(cs_.globals[size_t(Global::P)], Global::P);
            if (k(0) == Kind::Vector && p.kind == Kind::Point) return of(Kind::Invariant, facing || p.facing);
            return viewFrom(e.loc, "diffuse of a normal that is not world-still", a[0], p);
        }
        if (n == "length") {
            if (k(0) == Kind::Vector || k(0) == Kind::Invariant) return of(Kind::Invariant, facing);
            return viewFrom(e.loc, "length of a value that reads the view", a[0]);
        }
        if (n == "normalize") {
            // A direction keeps its class and shape (N's, I's); a point's is the direction from
            // the eye.
            if (k(0) == Kind::Point) return view(e.loc, "the direction of a point from the eye", facing);
            return a[0];
        }
        if (n == "faceforward" && a.size() == 3) {  // faceforward(N, I, Nref): +-N by the sign of Nref.I
            if (k(0) == Kind::Vector && a[1].shape == Shape::Incident && a[2].shape == Shape::Normal &&
                k(2) == Kind::Vector)
                return of(Kind::Vector, true, a[0].shape);
            if (k(0) == Kind::Vector && k(1) == Kind::Vector && k(2) == Kind::Vector) return of(Kind::Vector, facing, a[0].shape);
            return pure(a, e.loc, "faceforward by a direction that reads the view");
        }
        if (n == "distance" || n == "ptlined") {
            if (same(Kind::Point) || same(Kind::Invariant)) return of(Kind::Invariant, facing);
            return pure(a, e.loc, "a distance between points that are not world-still");
        }
        if (n == "area") {
            if (k(0) == Kind::Point || k(0) == Kind::Invariant) return of(Kind::Invariant, facing);
            return viewFrom(e.loc, "area of a value that is not a world-still point", a[0]);
        }
        if (n == "calculatenormal") {
            if (k(0) == Kind::Point) return of(Kind::Vector, facing);
            return pure(a, e.loc, "calculatenormal of a value that is not a world-still point");
        }
        if (n == "depth") return pure(a, e.loc, "depth()");
        if (n == "Du" || n == "Dv" || n == "Deriv") {
            const bool byInvariant = a.size() < 2 || k(1) == Kind::Invariant;
            if (byInvariant && (k(0) == Kind::Point || k(0) == Kind::Vector)) return of(Kind::Vector, facing);
            return pure(a, e.loc, "a derivative of a value that reads the view");
        }
        if (n == "reflect" || n == "refract") {
            if (k(0) == Kind::Vector && k(1) == Kind::Vector && (a.size() < 3 || k(2) == Kind::Invariant))
                return of(Kind::Vector, facing);
            return pure(a, e.loc, "a reflection or refraction of a direction that reads the view");
        }
        if (n == "mix" && a.size() == 3) {
            if (isFloat(*e.args[2]) && k(2) == Kind::Invariant && k(0) == k(1) &&
                (k(0) == Kind::Point || k(0) == Kind::Vector))
                return of(k(0), facing);
            return pure(a, e.loc, "mix of values that read the view");
        }
        if (n == "rotate" && b.ret.base == BaseType::Point) {
            if (k(0) == Kind::Point && k(1) == Kind::Invariant && k(2) == Kind::Point && k(3) == Kind::Point)
                return of(Kind::Point, facing);
            return pure(a, e.loc, "rotate about points that are not world-still");
        }
        // The rest are functions of their arguments alone (maths, noise, comp, splines, strings,
        // colour spaces, texture and environment lookups by invariant coordinates).
        return pure(a, e.loc, n == "noise" || n == "pnoise" || n == "cellnoise" ? "noise of a current-space value"
                              : b.special == Special::Comp || n == "comp"   ? "a component of a current-space value"
                                                                              : "a function of values that read the view");
    }

    Value transform(const Expr& e, const Builtin& b, const std::vector<Value>& a) {
        if (a.size() < 2) return pure(a, e.loc, "a transform");
        const Value x = a.back();
        const bool facing = anyFacing(a);
        const bool point = b.index == 0;
        // The forms: (to, x), (from, to, x), (m, x), (from, m, x).
        const Expr* e0 = e.args[0].get();
        if (e.args.size() == 2 && e0->type.isMatrix() == false) {
            if (e0->kind != ExprKind::String) return view(e.loc, "a transform to a space named at run time", facing);
            return through(SpaceClass::Current, spaceClass(e0), x, point, e.loc, facing);
        }
        if (e.args.size() == 3 && !e.args[1]->type.isMatrix()) {
            if (e0->kind != ExprKind::String || e.args[1]->kind != ExprKind::String)
                return view(e.loc, "a transform between spaces named at run time", facing);
            return through(spaceClass(e0), spaceClass(e.args[1].get()), x, point, e.loc, facing);
        }
        // (from, m, x): x taken from `from` to current space, then through m.
        if (e.args.size() == 3 && (e0->kind != ExprKind::String || e0->text != "current"))
            return view(e.loc, "a transform from a named space through a matrix", facing);
        // Through a matrix: invariant only of invariants.
        return pure(a, e.loc, "a transform by a matrix of a value that reads the view");
    }

    Value through(SpaceClass from, SpaceClass to, const Value& x, bool point, const SourceLoc& loc, bool facing) {
        const Kind cov = point ? Kind::Point : Kind::Vector;
        if (from == SpaceClass::Current && to == SpaceClass::Current) return x;
        if (from == SpaceClass::Current && to == SpaceClass::Still) {
            if (x.kind == cov) return of(Kind::Invariant, facing);
            return viewFrom(loc, "a transform of a value that is not world-still", x);
        }
        if (from == SpaceClass::Still && to == SpaceClass::Current) {
            if (x.kind == Kind::Invariant) return of(cov, facing);
            return viewFrom(loc, "a current-space value read as given in another space", x);
        }
        if (from == SpaceClass::Still && to == SpaceClass::Still) {
            if (x.kind == Kind::Invariant) return of(Kind::Invariant, facing);
            return viewFrom(loc, "a current-space value read as given in another space", x);
        }
        return view(loc, "a transform to or from a space that follows the camera (screen, raster, NDC, named)", facing);
    }

    // A resizable array's length and elements: resize and push join what they are given into
    // the array (as an element's assignment does); arraylength and pop read it.
    Value arrayCall(const Expr& e) {
        const Symbol* sym = e.args[0]->symbol;
        const Value arr = get(sym);
        if (e.text == "resize" || e.text == "push") {
            state_[sym] = join(arr, under(eval(*e.args[1]), ctl(), e.loc));
            return of(Kind::Invariant);
        }
        return arr;
    }

    Value userCall(const Expr& e) {
        const FunctionDef& f = *e.function;
        if (depth_ >= 32) {
            giveUp(e.loc, "functions nested too deep to analyse");
            return view(e.loc, "a call too deep");
        }
        std::vector<Value> a;
        for (const ExprPtr& x : e.args) a.push_back(eval(*x));
        std::vector<std::pair<const Symbol*, bool>> formals;  // symbol, output
        for (const VarDecl& d : f.formals)
            for (const Declarator& dc : d.decls) formals.push_back({dc.symbol, d.output});
        for (size_t i = 0; i < formals.size() && i < a.size(); ++i)
            if (formals[i].first) state_[formals[i].first] = a[i];
        ++depth_;
        const Value savedExit = funcExit_;
        funcExit_ = of(Kind::Invariant);
        returns_.push_back(std::nullopt);
        if (f.body) exec(*f.body);
        Value r = returns_.back().value_or(of(Kind::Invariant));
        returns_.pop_back();
        funcExit_ = savedExit;
        --depth_;
        for (size_t i = 0; i < formals.size() && i < e.args.size(); ++i)
            if (formals[i].second && formals[i].first) assign(*e.args[i], get(formals[i].first), e.loc);
        return r;
    }

    const CheckedShader& cs_;
    State state_;
    std::vector<Value> ctl_;
    Value loopExit_, funcExit_;  // the conditions under which a loop or function was left early
    std::vector<std::optional<Value>> returns_;  // what each function being analysed returns, joined
    std::optional<Value> lightL_;                 // the L of every illuminate and solar, joined
    int depth_ = 0;
    static constexpr long kStepBudget = 1000000;
    long steps_ = 0;
    bool assignsL_ = false;
    bool giveUp_ = false;
    SourceLoc giveUpLoc_;
    const char* giveUpWhy_ = "";
};

}  // namespace

ViewUseResult analyzeViewUse(const CheckedShader& shader) {
    if (!shader.module.shader) return {};
    return Analysis(shader).run();
}

}  // namespace streyes::sl
