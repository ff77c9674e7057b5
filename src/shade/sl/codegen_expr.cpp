// Code generation of expressions and calls (standard functions and inlined user functions).
#include <cstdio>

#include "shade/sl/codegen.h"
#include "shade/vm/ops.h"
#include "shade/vm/ray_source.h"

namespace streyes::sl {

namespace {
std::string pathKey(const void* p) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "/%p", p);
    return buf;
}
}  // namespace

CodeGen::Val CodeGen::gen(const Expr& e) {
    setLoc(e.loc);
    switch (e.kind) {
        case ExprKind::Number: return constFloat(float(e.number));
        case ExprKind::String: return constString(e.text);
        case ExprKind::Name: {
            Var* v = lookup(e.symbol);
            Val r;
            r.reg = v->reg;
            r.type = v->type;
            r.detail = v->detail;
            return r;
        }
        case ExprKind::Tuple: {
            std::vector<Val> vals;
            Detail d = Detail::Uniform;
            for (auto& a : e.args) {
                vals.push_back(gen(*a));
                d = join(d, vals.back().detail);
            }
            setLoc(e.loc);
            Val t = temp(e.type, d);
            if (vals.size() == 16) {
                std::vector<int32_t> regs;
                for (const Val& v : vals) regs.push_back(v.reg);
                emit(ops::matrix16, {t.reg, extraSpan(regs), 16}, t.varying());
            } else {
                emit(ops::triple, {t.reg, vals[0].reg, vals[1].reg, vals[2].reg}, t.varying());
            }
            for (const Val& v : vals) release(v);
            return t;
        }
        case ExprKind::Index: {
            Val base = gen(*e.args[0]);
            Val index = gen(*e.args[1]);
            setLoc(e.loc);
            if (base.type.isString()) {
                if (index.varying()) throw InputError(e.loc, "string arrays take uniform indices");
                Val t = temp(BaseType::String, Detail::Uniform);
                emit(ops::saref, {t.reg, base.reg, index.reg}, false);
                release(index);
                return t;
            }
            Val t = temp(base.type.element(), join(base.detail, index.detail));
            emit(ops::aref, {t.reg, base.reg, index.reg}, t.varying());
            release(base);
            release(index);
            return t;
        }
        case ExprKind::Unary: {
            Val a = gen(*e.args[0]);
            const OpFn fn = e.text == "!" ? ops::logNot : ops::neg;
            std::vector<float> folded;
            if (options_.optimize && foldConstant(prog_, fn, e.type, a.reg, -1, &folded)) return constFloats(e.type, folded);
            Val t = temp(e.type, a.detail);
            emit(fn, {t.reg, a.reg}, t.varying());
            release(a);
            return t;
        }
        case ExprKind::Binary: return genBinary(e);
        case ExprKind::Assign: return genAssign(e, true);
        case ExprKind::Ternary: {
            if (e.type.isString() || e.type.isArray())
                throw InputError(e.loc, "?: between strings or arrays is not supported");
            Val c = gen(*e.args[0]);
            Val a = convert(gen(*e.args[1]), e.type);
            Val b = convert(gen(*e.args[2]), e.type);
            Val t = temp(e.type, join(c.detail, join(a.detail, b.detail)));
            emit(ops::select, {t.reg, c.reg, a.reg, b.reg}, t.varying());
            release(c);
            release(a);
            release(b);
            return t;
        }
        case ExprKind::Cast: return genCast(e);
        case ExprKind::Call: return genCall(e);
        case ExprKind::ArrayInit: break;
    }
    throw InputError(e.loc, "{...} only initialises an array in its declaration");
}

CodeGen::Val CodeGen::arith(OpFn fn, Val a, Val b, SlType result) {
    // Constant operands: the value now, once (constants are not temporaries: nothing to release).
    std::vector<float> folded;
    if (options_.optimize && foldConstant(prog_, fn, result, a.reg, b.reg, &folded)) return constFloats(result, folded);
    Val t = temp(result, join(a.detail, b.detail));
    emit(fn, {t.reg, a.reg, b.reg}, t.varying());
    release(a);
    release(b);
    return t;
}

namespace {
OpFn arithOp(char op, bool matrices) {
    switch (op) {
        case '+': return ops::add;
        case '-': return ops::sub;
        case '*': return matrices ? ops::matMul : ops::mul;
        default: return matrices ? ops::matDiv : ops::div;
    }
}
}  // namespace

CodeGen::Val CodeGen::genBinary(const Expr& e) {
    Val a = gen(*e.args[0]);
    Val b = gen(*e.args[1]);
    setLoc(e.loc);
    const std::string& op = e.text;
    if (op == "==" || op == "!=") {
        if (a.type.isString()) return arith(op == "==" ? ops::streq : ops::strne, a, b, BaseType::Float);
        return arith(op == "==" ? ops::eq : ops::ne, a, b, BaseType::Float);
    }
    if (op == "<") return arith(ops::lt, a, b, BaseType::Float);
    if (op == ">") return arith(ops::gt, a, b, BaseType::Float);
    if (op == "<=") return arith(ops::le, a, b, BaseType::Float);
    if (op == ">=") return arith(ops::ge, a, b, BaseType::Float);
    if (op == "&&") return arith(ops::logAnd, a, b, BaseType::Float);
    if (op == "||") return arith(ops::logOr, a, b, BaseType::Float);
    if (op == ".") return arith(ops::dot, a, b, BaseType::Float);
    if (op == "^") return arith(ops::cross, a, b, BaseType::Vector);
    return arith(arithOp(op[0], a.type.isMatrix() && b.type.isMatrix()), a, b, e.type);
}

CodeGen::Val CodeGen::genFor(const Expr& e, const Var& target) {
    const bool save = uniformContext_;
    uniformContext_ = !target.varying() && !target.inferred;
    Val v = gen(e);
    uniformContext_ = save;
    return v;
}

CodeGen::Val CodeGen::genAssign(const Expr& e, bool needValue) {
    const Expr& lhs = *e.args[0];
    Val v;
    if (e.text == "=") {
        const Expr& base = lhs.kind == ExprKind::Index ? *lhs.args[0] : lhs;
        v = base.kind == ExprKind::Name ? genFor(*e.args[1], *lookup(base.symbol)) : gen(*e.args[1]);
    } else {
        Val cur = gen(lhs);
        Val rhs = gen(*e.args[1]);
        setLoc(e.loc);
        bool matrices = cur.type.isMatrix() && rhs.type.isMatrix();
        SlType r = cur.type;
        v = arith(arithOp(e.text[0], matrices), cur, rhs, r.isFloat() && rhs.type.isTriple() ? rhs.type : r);
    }
    setLoc(e.loc);
    assignTo(lhs, v, e.loc);
    if (!needValue) return Val{};
    return gen(lhs);
}

CodeGen::Val CodeGen::genCast(const Expr& e) {
    Val v = gen(*e.args[0]);
    setLoc(e.loc);
    v = convert(v, e.castType);
    if (!e.text.empty()) v = toSpace(v, e.text, e.loc);
    return v;
}

// A value given in space `space` (a constructor such as point "world" (0,0,0) or color "hsv"
// (h,s,v)) as it is in current space (rgb for colours).
CodeGen::Val CodeGen::toSpace(Val v, const std::string& space, const SourceLoc& loc) {
    setLoc(loc);
    Val name = constString(space);
    Val t = temp(v.type, v.detail);
    if (v.type.base == BaseType::Color) {
        emit(ops::ctransform, {t.reg, name.reg, constString("rgb").reg, v.reg}, t.varying());
    } else if (v.type.isMatrix()) {
        emit(ops::spaceMatrix, {t.reg, name.reg, v.reg}, t.varying());
    } else {
        int kind = v.type.base == BaseType::Point ? 0 : v.type.base == BaseType::Vector ? 1 : 2;
        emit(ops::xform, {t.reg, v.reg, name.reg, -1, -1, kind}, t.varying());
    }
    release(v);
    return t;
}

CodeGen::Val CodeGen::genCall(const Expr& e) {
    if (e.function) return genUserCall(e);
    if (!e.builtin) return genArrayCall(e);
    return genBuiltin(e);
}

// The length of a resizable array is one value a grid: resize, push and pop change it for
// every point, so they are refused under varying conditions (as a uniform variable's store is).
CodeGen::Val CodeGen::genArrayCall(const Expr& e) {
    const Expr& arrayArg = *e.args.at(0);
    Var* var = lookup(arrayArg.symbol);
    const bool resizable = prog_.regs[size_t(var->reg)].resizable();
    setLoc(e.loc);
    if (e.text == "arraylength") {
        if (!resizable) return constFloat(float(var->type.elements()));  // an unsized formal given a fixed array
        Val t = temp(BaseType::Float, Detail::Uniform);
        emit(ops::alen, {t.reg, var->reg}, false);
        return t;
    }
    if (!resizable)  // an unsized output formal, given an array of fixed length at this call
        throw InputError(arrayArg.loc, e.text + " of '" + arrayArg.text + "', here a " + var->type.name() +
                                           " of fixed length: pass an array declared without a length (" +
                                           baseTypeName(var->type.base) + " a[])");
    if (varyingNest_ > var->varyingAtDecl)
        throw InputError(e.loc, e.text + " of '" + arrayArg.text +
                                    "' under a varying condition: an array's length is one value for the whole grid "
                                    "(move the call out of the varying if or loop, or store into an element there)");
    if (e.text == "resize") {
        Val n = convert(gen(*e.args[1]), BaseType::Float);
        if (n.varying()) throw InputError(e.args[1]->loc, "resize's length is one value for the whole grid: give a uniform one");
        setLoc(e.loc);
        emit(ops::aresize, {var->reg, n.reg}, false);
        release(n);
        return Val{};
    }
    if (e.text == "push") {
        Val v = gen(*e.args[1]);
        setLoc(e.loc);
        Val index = temp(BaseType::Float, Detail::Uniform);
        emit(ops::apush, {var->reg, index.reg}, false);
        storeElement(*var, index, v, e.loc);
        return Val{};
    }
    Val t = temp(var->type.element(), var->detail);  // pop
    emit(ops::apop, {t.reg, var->reg}, t.varying());
    return t;
}

CodeGen::Val CodeGen::genBuiltin(const Expr& e) {
    const Builtin& b = *e.builtin;
    if (b.lights) prog_.usesLights = true;
    if (b.special != Special::None) return genSpecial(e, b);
    std::vector<Val> args;
    Detail d = b.varying && !(uniformContext_ && b.op == ops::random) ? Detail::Varying : Detail::Uniform;
    for (size_t i = 0; i < e.args.size(); ++i) {
        Val v = convert(gen(*e.args[i]), i < b.args.size() ? b.args[i] : b.args.back());
        d = join(d, v.detail);
        args.push_back(v);
    }
    setLoc(e.loc);
    // The derivative of a uniform value is zero.
    if ((b.op == ops::Du || b.op == ops::Dv || b.op == ops::Deriv) && !args[0].varying()) {
        for (const Val& v : args) release(v);
        return constFloats(b.ret, std::vector<float>(size_t(b.ret.comps()), 0.0f));
    }
    std::vector<int32_t> operands;
    Val dst;
    if (!b.ret.isVoid()) dst = temp(b.ret, d);
    operands.push_back(dst.reg);
    if (b.op == ops::pnoise && args.size() == 2) {  // pnoise(x, period): no second coordinate
        operands.insert(operands.end(), {args[0].reg, -1, args[1].reg, -1});
    } else {
        for (const Val& v : args) operands.push_back(v.reg);
    }
    if (b.lights) operands.push_back(global(Global::P).reg);  // where the lights shine
    int at = emit(b.op, {}, d == Detail::Varying);
    for (size_t k = 0; k < operands.size() && k < 6; ++k) prog_.code[size_t(at)].a[k] = operands[k];
    for (const Val& v : args) release(v);
    return dst;
}

CodeGen::Val CodeGen::genSpecial(const Expr& e, const Builtin& b) {
    auto genAll = [&](size_t from, size_t to, Detail& d) {
        std::vector<Val> v;
        for (size_t i = from; i < to; ++i) {
            v.push_back(gen(*e.args[i]));
            d = join(d, v.back().detail);
        }
        setLoc(e.loc);
        return v;
    };
    Detail d = b.varying ? Detail::Varying : Detail::Uniform;
    switch (b.special) {
        case Special::MinMax: {
            std::vector<Val> v = genAll(0, e.args.size(), d);
            Val r = convert(v[0], b.ret);
            for (size_t i = 1; i < v.size(); ++i) r = arith(b.op, r, convert(v[i], b.ret), b.ret);
            return r;
        }
        case Special::Comp: {
            Val v = gen(*e.args[0]);
            Val t = temp(BaseType::Float, v.detail);
            emit(ops::comp, {t.reg, v.reg, constFloat(float(b.index)).reg}, t.varying());
            release(v);
            return t;
        }
        case Special::SetComp: {
            std::vector<Val> v = genAll(0, e.args.size(), d);
            Val t = temp(v[0].type, d);
            if (b.index >= 0) {
                emit(ops::setcomp, {t.reg, v[0].reg, constFloat(float(b.index)).reg, v[1].reg}, t.varying());
            } else if (v[0].type.isMatrix()) {
                emit(ops::msetcomp, {t.reg, v[0].reg, v[1].reg, v[2].reg, v[3].reg}, t.varying());
            } else {
                emit(ops::setcomp, {t.reg, v[0].reg, v[1].reg, v[2].reg}, t.varying());
            }
            for (size_t i = 1; i < v.size(); ++i) release(v[i]);
            assignTo(*e.args[0], t, e.loc);
            return Val{};
        }
        case Special::Faceforward: {
            std::vector<Val> v = genAll(0, 2, d);
            Val ng = global(Global::Ng);
            Val t = temp(b.ret, join(d, ng.detail));
            emit(ops::faceforward, {t.reg, v[0].reg, v[1].reg, ng.reg}, t.varying());
            for (const Val& x : v) release(x);
            return t;
        }
        case Special::Transform: {
            std::vector<Val> v = genAll(0, e.args.size(), d);
            Val t = temp(b.ret, d);
            int from = -1, to = -1, mat = -1;
            const Val& src = v.back();
            if (v.size() == 3 && v[1].type.isMatrix()) {
                from = v[0].reg;
                mat = v[1].reg;
            } else if (v.size() == 3) {
                from = v[0].reg;
                to = v[1].reg;
            } else if (v[0].type.isMatrix()) {
                mat = v[0].reg;
            } else {
                to = v[0].reg;
            }
            emit(ops::xform, {t.reg, src.reg, from, to, mat, b.index}, t.varying());
            for (const Val& x : v) release(x);
            return t;
        }
        case Special::CTransform: {
            std::vector<Val> v = genAll(0, e.args.size(), d);
            Val t = temp(BaseType::Color, d);
            int from = v.size() == 3 ? v[0].reg : -1;
            int to = v.size() == 3 ? v[1].reg : v[0].reg;
            emit(ops::ctransform, {t.reg, from, to, v.back().reg}, t.varying());
            for (const Val& x : v) release(x);
            return t;
        }
        case Special::Fresnel: {
            std::vector<Val> in = genAll(0, 3, d);
            Val eta = convert(in[2], BaseType::Float);
            std::vector<Val> outs;
            for (size_t i = 3; i < e.args.size(); ++i) outs.push_back(temp(i < 5 ? SlType(BaseType::Float) : SlType(BaseType::Vector), d));
            std::vector<int32_t> regs = {in[0].reg, in[1].reg, eta.reg};
            for (const Val& o : outs) regs.push_back(o.reg);
            emit(ops::fresnel, {-1, extraSpan(regs), int(regs.size())}, d == Detail::Varying);
            release(in[0]);
            release(in[1]);
            release(eta);
            for (size_t i = 0; i < outs.size(); ++i) assignTo(*e.args[3 + i], outs[i], e.args[3 + i]->loc);
            return Val{};
        }
        case Special::Spline: {
            size_t first = e.args[0]->type.isString() ? 1 : 0;
            std::vector<Val> v = genAll(0, e.args.size(), d);
            Val t = temp(b.ret, d);
            int basis = first ? v[0].reg : -1;
            if (v.back().type.isArray()) {
                emit(ops::splineArray, {t.reg, basis, v[first].reg, v[first + 1].reg}, t.varying());
            } else {
                std::vector<int32_t> regs = {basis};
                for (size_t i = first; i < v.size(); ++i) regs.push_back(convert(v[i], i == first ? SlType(BaseType::Float) : b.ret).reg);
                emit(ops::spline, {t.reg, extraSpan(regs), int(regs.size())}, t.varying());
            }
            for (const Val& x : v) release(x);
            return t;
        }
        case Special::Filterstep: {
            size_t k = 0;
            while (k < e.args.size() && !e.args[k]->type.isString()) ++k;
            std::vector<Val> v = genAll(0, k, d);
            Val width = k < e.args.size() ? gen(*e.args[k + 1]) : Val{};
            setLoc(e.loc);
            Val t = temp(BaseType::Float, Detail::Varying);
            emit(ops::filterstep, {t.reg, v[0].reg, v[1].reg, k == 3 ? v[2].reg : -1, width.reg}, true);
            for (const Val& x : v) release(x);
            release(width);
            return t;
        }
        case Special::Lightsource: {
            Val name = gen(*e.args[0]);
            Val cur = gen(*e.args[1]);
            setLoc(e.loc);
            Val copy = temp(cur.type, Detail::Varying);
            emit(ops::mov, {copy.reg, cur.reg}, true);
            release(cur);
            Val flag = temp(BaseType::Float, Detail::Uniform);
            emit(ops::lightsource, {flag.reg, name.reg, copy.reg}, true);
            assignTo(*e.args[1], copy, e.loc);
            return flag;
        }
        case Special::Message: {
            // As the queries: a copy written when the other shader has the parameter and it fits,
            // then stored back (a miss leaves the variable as it was).
            Val name = gen(*e.args[0]);
            Val cur = gen(*e.args[1]);
            setLoc(e.loc);
            // Another shader's value may vary: a variable that may turn varying takes it so; one
            // declared uniform takes the value at the first point that runs.
            const Expr& target = e.args[1]->kind == ExprKind::Index ? *e.args[1]->args[0] : *e.args[1];
            const Var* var = lookup(target.symbol);
            const bool varying = !cur.type.isString() && (cur.varying() || (var && var->inferred));
            Val copy = temp(cur.type, varying ? Detail::Varying : cur.detail);
            emit(cur.type.isString() ? ops::smov : ops::mov, {copy.reg, cur.reg}, copy.varying());
            release(cur);
            Val flag = temp(BaseType::Float, Detail::Uniform);
            emit(ops::message, {flag.reg, name.reg, copy.reg, b.index}, false);
            release(name);
            assignTo(*e.args[1], copy, e.loc);
            return flag;
        }
        case Special::Gather: {
            // extra: category, P, dir, angle, samples, sample, then (name, register) pairs; an
            // output's register is a copy of its variable the op writes where the ray hit (the
            // direction and origin everywhere), stored back after.
            std::vector<Val> held;
            auto keep = [&](Val v) {
                held.push_back(v);
                return v.reg;
            };
            std::vector<int32_t> regs;
            static const BaseType kinds[] = {BaseType::String, BaseType::Point, BaseType::Vector, BaseType::Float,
                                             BaseType::Float, BaseType::Float};
            for (size_t k = 0; k < 6; ++k) regs.push_back(keep(convert(gen(*e.args[k]), kinds[k])));
            std::vector<std::pair<const Expr*, Val>> outputs;
            for (size_t k = 6; k + 1 < e.args.size(); k += 2) {
                regs.push_back(keep(gen(*e.args[k])));
                if (e.args[k]->text.find(':') == std::string::npos) {
                    regs.push_back(keep(gen(*e.args[k + 1])));
                    continue;
                }
                Val cur = gen(*e.args[k + 1]);
                Val copy = temp(cur.type, Detail::Varying);
                emit(ops::mov, {copy.reg, cur.reg}, true);
                release(cur);
                regs.push_back(copy.reg);
                outputs.emplace_back(e.args[k + 1].get(), copy);
            }
            setLoc(e.loc);
            Val hit = temp(BaseType::Float, Detail::Varying);
            emit(ops::gather, {hit.reg, extraSpan(regs), int(regs.size())}, true);
            for (const Val& v : held) release(v);
            for (auto& [target, copy] : outputs) assignTo(*target, copy, e.loc);
            return hit;
        }
        case Special::Query: {
            // The value is the grid's: a copy of the variable is written when the value fits it,
            // then stored back (so a miss leaves the variable as it was).
            std::vector<Val> names;
            for (size_t i = 0; i + 1 < e.args.size(); ++i) names.push_back(gen(*e.args[i]));
            Val cur = gen(*e.args.back());
            setLoc(e.loc);
            Val copy = temp(cur.type, cur.detail);
            emit(cur.type.isString() ? ops::smov : ops::mov, {copy.reg, cur.reg}, copy.varying());
            release(cur);
            Val flag = temp(BaseType::Float, Detail::Uniform);
            if (names.size() == 2) emit(b.op, {flag.reg, names[0].reg, names[1].reg, copy.reg}, false);
            else emit(b.op, {flag.reg, names[0].reg, copy.reg}, false);
            for (const Val& v : names) release(v);
            assignTo(*e.args.back(), copy, e.loc);
            return flag;
        }
        case Special::Printf:
        case Special::Format:
        case Special::Concat: {
            std::vector<Val> v = genAll(0, e.args.size(), d);
            std::vector<int32_t> regs;
            for (const Val& x : v) regs.push_back(x.reg);
            Val t;
            if (b.special != Special::Printf) t = temp(BaseType::String, Detail::Uniform);
            emit(b.op, {t.reg, extraSpan(regs), int(regs.size())}, d == Detail::Varying);
            for (const Val& x : v) release(x);
            return t;
        }
        case Special::Texture:
        case Special::Environment:
        case Special::Shadow: return genTexture(e, b);
        case Special::Ray: return genRay(e, b);
        case Special::PointCloud: {
            // extra: file, [display channels], P, N, then (name, register) pairs; texture3d's
            // channels are copies of their variables the op writes where it found the cloud,
            // stored back after.
            const bool bake = b.name == "bake3d";
            const size_t positional = bake ? 4 : 3;
            std::vector<Val> held;
            auto keep = [&](Val v) {
                held.push_back(v);
                return v.reg;
            };
            std::vector<int32_t> regs;
            for (size_t k = 0; k < positional; ++k) {
                const BaseType want = k + 2 < positional ? BaseType::String : k + 1 < positional ? BaseType::Point : BaseType::Normal;
                regs.push_back(keep(want == BaseType::String ? gen(*e.args[k]) : convert(gen(*e.args[k]), want)));
            }
            std::vector<std::pair<const Expr*, Val>> outputs;
            for (size_t k = positional; k + 1 < e.args.size(); k += 2) {
                regs.push_back(keep(gen(*e.args[k])));
                const Expr& v = *e.args[k + 1];
                const bool option = e.args[k]->kind == ExprKind::String &&
                                    (e.args[k]->text == "coordsystem" || e.args[k]->text == "filterradius" ||
                                     e.args[k]->text == "filterscale" || e.args[k]->text == "maxdepth");
                if (bake || option || v.type.isString()) {
                    regs.push_back(keep(gen(v)));
                    continue;
                }
                Val cur = gen(v);
                Val copy = temp(cur.type, Detail::Varying);
                emit(ops::mov, {copy.reg, cur.reg}, true);
                release(cur);
                regs.push_back(copy.reg);
                outputs.emplace_back(&v, copy);
            }
            setLoc(e.loc);
            Val flag = temp(BaseType::Float, Detail::Varying);
            emit(b.op, {flag.reg, extraSpan(regs), int(regs.size())}, true);
            for (const Val& v : held) release(v);
            for (auto& [target, copy] : outputs) assignTo(*target, copy, e.loc);
            return flag;
        }
        case Special::Bake: {
            std::vector<Val> held;
            std::vector<int32_t> regs;
            held.push_back(gen(*e.args[0]));
            held.push_back(convert(gen(*e.args[1]), BaseType::Float));
            held.push_back(convert(gen(*e.args[2]), BaseType::Float));
            held.push_back(gen(*e.args[3]));
            for (const Val& v : held) regs.push_back(v.reg);
            setLoc(e.loc);
            emit(b.op, {-1, extraSpan(regs), int(regs.size())}, true);
            for (const Val& v : held) release(v);
            return Val{};
        }
        default: break;
    }
    throw InputError(e.loc, "internal error: unhandled function " + b.name);
}

CodeGen::Val CodeGen::genTexture(const Expr& e, const Builtin& b) {
    std::vector<Val> held;
    auto keep = [&](Val v) {
        held.push_back(v);
        return v.reg;
    };
    std::vector<int32_t> regs;
    regs.push_back(keep(gen(*e.args[0])));
    regs.push_back(e.channel ? keep(convert(gen(*e.channel), BaseType::Float)) : -1);
    size_t i = 1;
    std::vector<int32_t> coords;
    while (i < e.args.size() && !e.args[i]->type.isString()) {
        SlType want = b.special == Special::Texture ? SlType(BaseType::Float)
                      : b.special == Special::Shadow ? SlType(BaseType::Point) : SlType(BaseType::Vector);
        coords.push_back(keep(convert(gen(*e.args[i]), want)));
        ++i;
    }
    if (b.special == Special::Texture && coords.empty()) {  // texture(name): at (s, t)
        coords.push_back(global(Global::s).reg);
        coords.push_back(global(Global::t).reg);
    }
    regs.push_back(int32_t(coords.size()));
    regs.insert(regs.end(), coords.begin(), coords.end());
    for (; i + 1 < e.args.size(); i += 2) {
        regs.push_back(keep(gen(*e.args[i])));
        regs.push_back(keep(gen(*e.args[i + 1])));
    }
    setLoc(e.loc);
    Val t = temp(b.ret, Detail::Varying);
    emit(b.op, {t.reg, extraSpan(regs), int(regs.size())}, true);
    for (const Val& v : held) release(v);
    return t;
}

// extra: the positional count k, k registers (converted to the listed types), option pairs.
CodeGen::Val CodeGen::genRay(const Expr& e, const Builtin& b) {
    std::vector<Val> held;
    auto keep = [&](Val v) {
        held.push_back(v);
        return v.reg;
    };
    // occlusion(mapname, P, N, ...): the map-based form (shadeops_occlmap.cpp), the name first.
    const bool mapForm = b.name == "occlusion" && !e.args.empty() && e.args[0]->type.isString();
    size_t i = mapForm ? 1 : 0;
    const int32_t mapName = mapForm ? keep(gen(*e.args[0])) : -1;
    std::vector<int32_t> positional;
    for (size_t k = 0; i < e.args.size() && !e.args[i]->type.isString(); ++i, ++k)
        positional.push_back(keep(convert(gen(*e.args[i]), b.args[k])));
    std::vector<int32_t> regs{int32_t(positional.size())};
    regs.insert(regs.end(), positional.begin(), positional.end());
    std::vector<std::pair<const Expr*, Val>> outputs;  // output options: varying copies stored back after
    for (; i + 1 < e.args.size(); i += 2) {
        regs.push_back(keep(gen(*e.args[i])));
        if (isRayOutputOption(b.name, e.args[i]->text)) {
            Val cur = gen(*e.args[i + 1]);
            Val copy = temp(cur.type, Detail::Varying);
            emit(ops::mov, {copy.reg, cur.reg}, true);
            release(cur);
            regs.push_back(copy.reg);
            outputs.emplace_back(e.args[i + 1].get(), copy);
            continue;
        }
        regs.push_back(keep(gen(*e.args[i + 1])));
    }
    if (mapForm) regs.insert(regs.begin(), mapName);
    setLoc(e.loc);
    Val t = temp(b.ret, Detail::Varying);
    emit(mapForm ? ops::occlusionmap : b.op, {t.reg, extraSpan(regs), int(regs.size())}, true);
    for (const Val& v : held) release(v);
    for (auto& [target, copy] : outputs) assignTo(*target, copy, e.loc);
    return t;
}

namespace {

bool containsReturn(const Stmt& s) {
    if (s.kind == StmtKind::Return) return true;
    for (const auto& b : s.body)
        if (containsReturn(*b)) return true;
    return false;
}

// A return anywhere but as the body's last statement needs a mask level for the function.
bool hasInnerReturn(const Stmt& body) {
    if (body.kind != StmtKind::Block) return containsReturn(body) && body.kind != StmtKind::Return;
    for (size_t i = 0; i < body.body.size(); ++i) {
        const Stmt& s = *body.body[i];
        bool last = i + 1 == body.body.size();
        if (last && s.kind == StmtKind::Return) continue;
        if (containsReturn(s)) return true;
    }
    return false;
}

}  // namespace

CodeGen::Val CodeGen::genUserCall(const Expr& e) {
    const FunctionDef& f = *e.function;
    for (const Func* fn : funcs_)
        if (fn->def == &f) throw InputError(e.loc, "'" + f.name + "' calls itself (functions are inlined: no recursion)");
    if (funcs_.size() > 64) throw InputError(e.loc, "functions nested too deeply");
    Func ctx;
    ctx.def = &f;
    ctx.path = funcs_.back()->path + pathKey(&e);
    std::vector<Val> held;
    std::vector<std::pair<const Expr*, Var*>> copyBack;  // output arguments that are array elements
    size_t i = 0;
    for (const VarDecl& d : f.formals) {
        for (const Declarator& dc : d.decls) {
            const Expr& arg = *e.args[i++];
            const Symbol* sym = dc.symbol;
            if (d.output) {
                if (conversionCost(arg.type, sym->type) < 0 || conversionCost(arg.type, sym->type) > 1)
                    throw InputError(arg.loc, "output parameter '" + dc.name + "' of " + f.name + " is a " +
                                                  sym->type.name() + ": pass a variable of that type, not a " + arg.type.name());
                if (arg.kind == ExprKind::Name) {
                    ctx.vars[sym] = lookup(arg.symbol);
                    continue;
                }
                // An array element: work on a copy, stored back after the call.
                Val v = gen(arg);
                auto var = std::make_unique<Var>();
                var->reg = newReg(sym->type, Detail::Varying, dc.name);
                emit(ops::mov, {var->reg, v.reg}, true);
                release(v);
                var->type = sym->type;
                var->detail = Detail::Varying;
                var->name = dc.name;
                var->varyingAtDecl = varyingNest_;
                var->maskedAtDecl = maskedNest_;
                ctx.vars[sym] = var.get();
                copyBack.emplace_back(&arg, var.get());
                varStore_.push_back(std::move(var));
                continue;
            }
            Val v = convert(gen(arg), sym->type);
            if (d.hasDetail && d.detail == Detail::Uniform && v.varying())
                throw InputError(arg.loc, "parameter '" + dc.name + "' of " + f.name + " is uniform; the value passed is varying");
            if (d.hasDetail && d.detail == Detail::Varying && !v.varying()) {
                if (v.type.isResizable())
                    throw InputError(arg.loc, "parameter '" + dc.name + "' of " + f.name +
                                                  " is varying; a uniform resizable array cannot be passed to it (declare it varying)");
                Val t = temp(v.type, Detail::Varying);
                emit(ops::mov, {t.reg, v.reg}, true);
                release(v);
                v = t;
            }
            auto var = std::make_unique<Var>();
            var->reg = v.reg;
            var->type = sym->type.isResizable() ? v.type : sym->type;  // an unsized formal: the array passed
            var->detail = v.detail;
            var->name = dc.name;
            ctx.vars[sym] = var.get();
            varStore_.push_back(std::move(var));
            held.push_back(v);
        }
    }
    setLoc(e.loc);
    if (!f.returnType.isVoid()) {
        auto ret = std::make_unique<Var>();
        ret->type = f.returnType;
        ret->name = f.name + " result";
        ret->key = ctx.path + "|return";
        ret->inferred = true;
        ret->detail = varyingKeys_.count(ret->key) ? Detail::Varying : Detail::Uniform;
        ret->reg = newReg(ret->type, ret->detail, ret->name);
        ret->varyingAtDecl = varyingNest_;
        ret->maskedAtDecl = maskedNest_;
        ctx.ret = ret.get();
        varStore_.push_back(std::move(ret));
    }
    ctx.entryDepth = depth_;
    ctx.varyingAtEntry = varyingNest_;
    ctx.maskedAtEntry = maskedNest_;
    std::vector<Loop*> outerLoops;
    outerLoops.swap(loops_);  // break and continue never leave a function
    funcs_.push_back(&ctx);
    if (hasInnerReturn(*f.body)) {
        emit(ops::funcBegin, {}, true);
        pushLevel();
        ctx.funcLevel = depth_;
    }
    genStmt(*f.body);
    int end = label();
    for (int j : ctx.returnJumps) patch(j, 0, end);
    if (ctx.funcLevel >= 0) {
        emit(ops::maskPop, {}, true);
        popLevel();
    }
    maskedNest_ = ctx.maskedAtEntry;
    funcs_.pop_back();
    loops_.swap(outerLoops);
    for (const Val& v : held) release(v);
    for (auto& [arg, var] : copyBack) {
        Val v;
        v.reg = var->reg;
        v.type = var->type;
        v.detail = var->detail;
        assignTo(*arg, v, arg->loc);
    }
    Val r;
    if (ctx.ret) {
        r.reg = ctx.ret->reg;
        r.type = ctx.ret->type;
        r.detail = ctx.ret->detail;
    }
    return r;
}

}  // namespace streyes::sl
