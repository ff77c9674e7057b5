#include "shade/sl/codegen.h"

#include <cstdio>

#include "shade/vm/ops.h"

namespace streyes::sl {

void generateCode(const CheckedShader& checked, ShaderProgram& out, const BackendOptions& options) {
    CodeGen g(checked, out, options);
    g.generate();
}

void CodeGen::generate() {
    for (;;) {
        reset();
        try {
            emitAll();
            return;
        } catch (const Restart&) {
            // a variable turned varying: start again with it varying (varyingKeys_ grew)
        }
    }
}

void CodeGen::reset() {
    ShaderProgram fresh;
    fresh.path = prog_.path;
    prog_ = std::move(fresh);
    varStore_.clear();
    freeTemps_.clear();
    floatConsts_.clear();
    stringConsts_.clear();
    funcs_.clear();
    loops_.clear();
    depth_ = varyingNest_ = maskedNest_ = 0;
    loc_ = nullptr;
    lastLabel_ = -1;
}

void CodeGen::emitAll() {
    const ShaderDef& s = *cs_.module.shader;
    prog_.type = s.type;
    prog_.name = s.name;
    Func body;
    funcs_.push_back(&body);
    genParams();
    prog_.bodyBegin = here();
    genStmt(*s.body);
    for (int j : body.returnJumps) patch(j, 0, here());
    funcs_.pop_back();
    if (options_.optimize) removeDeadCode(prog_);
    prog_.finish();
}

// ---- Registers and constants ---------------------------------------------------------------------

int CodeGen::newReg(SlType t, Detail d, const std::string& name) {
    Register r;
    r.type = t;
    r.detail = t.isString() ? Detail::Uniform : d;
    r.name = name;
    prog_.regs.push_back(r);
    return int(prog_.regs.size()) - 1;
}

CodeGen::Val CodeGen::temp(SlType t, Detail d) {
    if (t.isString()) d = Detail::Uniform;
    auto key = std::make_pair(int(t.base) + 16 * t.arrayLen, int(d));
    auto& list = freeTemps_[key];
    Val v;
    v.type = t;
    v.detail = d;
    v.temp = true;
    if (!list.empty()) {
        v.reg = list.back();
        list.pop_back();
    } else {
        v.reg = newReg(t, d);
    }
    return v;
}

void CodeGen::release(const Val& v) {
    if (!v.temp || v.reg < 0) return;
    const Register& r = prog_.regs[size_t(v.reg)];
    freeTemps_[std::make_pair(int(r.type.base) + 16 * r.type.arrayLen, int(r.detail))].push_back(v.reg);
}

CodeGen::Val CodeGen::constFloats(SlType t, const std::vector<float>& values) {
    std::vector<float> key = values;
    key.push_back(float(int(t.base)));
    auto it = floatConsts_.find(key);
    int reg;
    if (it != floatConsts_.end()) {
        reg = it->second;
    } else {
        reg = newReg(t, Detail::Uniform);
        prog_.regs[size_t(reg)].constant = int(prog_.constFloats.size());
        prog_.constFloats.insert(prog_.constFloats.end(), values.begin(), values.end());
        floatConsts_[key] = reg;
    }
    Val v;
    v.reg = reg;
    v.type = t;
    return v;
}

CodeGen::Val CodeGen::constFloat(float f) { return constFloats(BaseType::Float, {f}); }

CodeGen::Val CodeGen::constString(const std::string& s) {
    auto it = stringConsts_.find(s);
    int reg;
    if (it != stringConsts_.end()) {
        reg = it->second;
    } else {
        reg = newReg(BaseType::String, Detail::Uniform);
        prog_.regs[size_t(reg)].constant = int(prog_.constStrings.size());
        prog_.constStrings.push_back(s);
        stringConsts_[s] = reg;
    }
    Val v;
    v.reg = reg;
    v.type = BaseType::String;
    return v;
}

CodeGen::Val CodeGen::global(Global g) {
    Var* var = lookup(cs_.globals[size_t(g)]);
    Val v;
    v.reg = var->reg;
    v.type = var->type;
    v.detail = var->detail;
    return v;
}

void CodeGen::setLoc(const SourceLoc& loc) { loc_ = &loc; }

int CodeGen::emit(OpFn fn, std::initializer_list<int32_t> args, bool varying) {
    Instr in;
    in.fn = fn;
    int k = 0;
    for (int32_t a : args) in.a[k++] = a;
    in.varying = varying;
    if (loc_) {
        const SourceLoc* last = prog_.locs.empty() ? nullptr : &prog_.locs.back();
        if (!last || last->line != loc_->line || last->column != loc_->column || last->file != loc_->file)
            prog_.locs.push_back(*loc_);
        in.loc = int(prog_.locs.size()) - 1;
    }
    prog_.code.push_back(in);
    return here() - 1;
}

int CodeGen::extraSpan(const std::vector<int32_t>& regs) {
    int begin = int(prog_.extra.size());
    prog_.extra.insert(prog_.extra.end(), regs.begin(), regs.end());
    return begin;
}

// ---- Variables -----------------------------------------------------------------------------------

namespace {
std::string keyOf(const void* p) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%p", p);
    return buf;
}
}  // namespace

CodeGen::Var* CodeGen::declareVar(const Symbol* s, Detail declared, bool hasDetail) {
    Func& f = *funcs_.back();
    auto v = std::make_unique<Var>();
    v->type = s->type;
    v->name = s->name;
    v->key = f.path + "|" + keyOf(s);
    if (hasDetail || s->type.isString()) {
        v->detail = s->type.isString() ? Detail::Uniform : declared;
        v->explicitUniform = v->detail == Detail::Uniform;
    } else {
        v->inferred = true;
        v->detail = varyingKeys_.count(v->key) ? Detail::Varying : Detail::Uniform;
    }
    v->varyingAtDecl = varyingNest_;
    v->maskedAtDecl = maskedNest_;
    v->reg = newReg(v->type, v->detail, v->name);
    Var* raw = v.get();
    varStore_.push_back(std::move(v));
    f.vars[s] = raw;
    return raw;
}

CodeGen::Var* CodeGen::lookup(const Symbol* s) {
    auto it = funcs_.back()->vars.find(s);
    if (it != funcs_.back()->vars.end()) return it->second;
    it = funcs_.front()->vars.find(s);
    if (it != funcs_.front()->vars.end()) return it->second;
    if (s->kind == SymbolKind::Global) {
        // A predefined variable: its register is made on first use, in the shader's scope.
        const GlobalInfo& gi = globalInfo(s->global);
        auto v = std::make_unique<Var>();
        v->type = gi.type;
        v->name = gi.name;
        v->detail = gi.detail;
        v->explicitUniform = gi.detail == Detail::Uniform;
        v->reg = newReg(gi.type, gi.detail, gi.name);
        prog_.regs[size_t(v->reg)].global = int(s->global);
        prog_.globalReg[int(s->global)] = v->reg;
        Var* raw = v.get();
        varStore_.push_back(std::move(v));
        funcs_.front()->vars[s] = raw;
        return raw;
    }
    throw InputError(s->loc, "internal error: no register for '" + s->name + "'");
}

void CodeGen::makeVarying(Var& var) {
    varyingKeys_.insert(var.key);
    throw Restart{};
}

namespace {
// Operations whose destination may be one of their operands (each point is read whole before
// it is written), so an assignment can write the variable directly.
bool aliasSafe(OpFn fn) {
    using namespace ops;
    static const OpFn safe[] = {neg, add, sub, mul, div, logNot, logAnd, logOr, eq, ne, lt, gt, le, ge, select,
                                sin_, cos_, tan_, asin_, acos_, atan1, atan2_, radians, degrees, pow_, exp_, sqrt_,
                                inversesqrt, log1, log2_, mod, abs_, sign, floor_, ceil_, round_, min_, max_, clamp,
                                mix, step, smoothstep, dot, cross, length, normalize, distance, faceforward, reflect,
                                refract, xform, ctransform, noise, pnoise, cellnoise, matMul, matDiv, triple,
                                floatToMatrix, comp, setcomp, ambient, diffuse, specular, specularbrdf, phong};
    for (OpFn f : safe)
        if (f == fn) return true;
    return false;
}
}  // namespace

void CodeGen::store(Var& var, Val v, const SourceLoc& loc) {
    v = convert(v, var.type);
    if (v.varying() && !var.varying()) {
        if (var.inferred) makeVarying(var);
        throw InputError(loc, "cannot assign a varying value to uniform variable '" + var.name + "'");
    }
    if (!var.varying() && varyingNest_ > var.varyingAtDecl) {
        if (var.inferred) makeVarying(var);
        throw InputError(loc, "cannot assign to uniform variable '" + var.name + "' under a varying condition");
    }
    if (!var.varying() && var.inferred && maskedNest_ > var.maskedAtDecl) makeVarying(var);
    const bool maskedStore = var.varying() && (varyingNest_ > 0 || maskedNest_ > 0);
    // A resizable array takes the length of the array assigned to it (one a grid), then its elements.
    if (prog_.regs[size_t(var.reg)].resizable() && v.reg != var.reg) emit(ops::alike, {var.reg, v.reg}, false);
    if (var.type.isString()) {
        if (v.reg != var.reg) emit(ops::smov, {var.reg, v.reg}, false);
    } else if (maskedStore) {
        emit(ops::movm, {var.reg, v.reg}, true);
    } else if (v.temp && !prog_.code.empty() && prog_.code.back().a[0] == v.reg && aliasSafe(prog_.code.back().fn) &&
               prog_.regs[size_t(v.reg)].detail == var.detail && prog_.regs[size_t(v.reg)].type == var.type &&
               prog_.code.back().fn != ops::movm && lastLabel_ < here()) {
        prog_.code.back().a[0] = var.reg;  // the value was made just now: make it in the variable
    } else if (v.reg != var.reg) {
        emit(ops::mov, {var.reg, v.reg}, var.varying());
    }
    release(v);
}

void CodeGen::storeElement(Var& var, Val index, Val v, const SourceLoc& loc) {
    v = convert(v, var.type.element());
    Detail d = join(index.detail, v.detail);
    if (var.type.isString() && index.varying()) throw InputError(loc, "string arrays take uniform indices");
    if (d == Detail::Varying && !var.varying()) {
        if (var.inferred) makeVarying(var);
        throw InputError(loc, "cannot assign a varying value to an element of uniform array '" + var.name + "'");
    }
    if (!var.varying() && varyingNest_ > var.varyingAtDecl) {
        if (var.inferred) makeVarying(var);
        throw InputError(loc, "cannot assign to uniform array '" + var.name + "' under a varying condition");
    }
    if (!var.varying() && var.inferred && maskedNest_ > var.maskedAtDecl) makeVarying(var);
    emit(var.type.isString() ? ops::saset : ops::aset, {var.reg, index.reg, v.reg}, var.varying());
    release(v);
    release(index);
}

void CodeGen::assignTo(const Expr& lhs, Val v, const SourceLoc& loc) {
    if (lhs.kind == ExprKind::Index) {
        Var* var = lookup(lhs.args[0]->symbol);
        Val index = gen(*lhs.args[1]);
        storeElement(*var, index, v, loc);
        return;
    }
    store(*lookup(lhs.symbol), v, loc);
}

CodeGen::Val CodeGen::convert(Val v, SlType to) {
    if (v.type == to || to.isVoid()) return v;
    if (to.isResizable() && v.type.isArray() && v.type.base == to.base) return v;  // any length: as it is
    if ((v.type.isTriple() && to.isTriple()) || (v.type.isArray() && v.type == to)) {
        v.type = to;
        return v;
    }
    if (v.type.isFloat() && to.isTriple()) {
        Val t = temp(to, v.detail);
        emit(ops::mov, {t.reg, v.reg}, t.varying());
        release(v);
        return t;
    }
    if (v.type.isFloat() && to.isMatrix()) {
        Val t = temp(to, v.detail);
        emit(ops::floatToMatrix, {t.reg, v.reg}, t.varying());
        release(v);
        return t;
    }
    throw InputError(loc_ ? *loc_ : SourceLoc{}, "internal error: cannot convert " + v.type.name() + " to " + to.name());
}

}  // namespace streyes::sl
