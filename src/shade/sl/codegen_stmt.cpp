// Code generation of statements: declarations, uniform control flow as jumps, varying control
// flow under the mask stack, and the light statements.
#include "shade/sl/codegen.h"
#include "shade/vm/ops.h"

namespace streyes::sl {

namespace {

// Does `s` hold a break or continue that leaves the loop whose body it is (`inner` loops deep)?
bool leavesLoop(const Stmt& s, int inner) {
    if ((s.kind == StmtKind::Break || s.kind == StmtKind::Continue) && s.level > inner) return true;
    bool loop = s.kind == StmtKind::While || s.kind == StmtKind::For || s.kind == StmtKind::Illuminance;
    for (const auto& b : s.body)
        if (leavesLoop(*b, inner + (loop ? 1 : 0))) return true;
    return false;
}

}  // namespace

void CodeGen::genStmt(const Stmt& s) {
    setLoc(s.loc);
    switch (s.kind) {
        case StmtKind::Block:
            for (const auto& b : s.body) genStmt(*b);
            break;
        case StmtKind::Expr:
            if (s.expr->kind == ExprKind::Assign) genAssign(*s.expr, false);
            else release(gen(*s.expr));
            break;
        case StmtKind::Empty: break;
        case StmtKind::Decl: genDecl(s.decl); break;
        case StmtKind::If: genIf(s); break;
        case StmtKind::While:
        case StmtKind::For: genLoop(s); break;
        case StmtKind::Break:
        case StmtKind::Continue: genBreak(s); break;
        case StmtKind::Return: genReturn(s); break;
        case StmtKind::Illuminance: genIlluminance(s); break;
        case StmtKind::Illuminate:
        case StmtKind::Solar: genIlluminate(s); break;
    }
}

void CodeGen::genDecl(const VarDecl& d) {
    if (d.isExtern) return;  // the checker bound the name to the shader's variable
    for (const Declarator& dc : d.decls) {
        Var* v = declareVar(dc.symbol, d.detail, d.hasDetail);
        setLoc(dc.loc);
        if (prog_.regs[size_t(v->reg)].resizable()) {
            initResizable(*v, dc);
        } else if (dc.init && dc.init->kind == ExprKind::ArrayInit) {
            for (size_t k = 0; k < dc.init->args.size(); ++k)
                storeElement(*v, constFloat(float(k)), genFor(*dc.init->args[k], *v), dc.loc);
        } else if (dc.init) {
            store(*v, genFor(*dc.init, *v), dc.loc);
        } else if (v->type.isString()) {
            emit(ops::smov, {v->reg, constString("").reg}, false);
        } else {
            // Variables start at zero, so that a shader never reads what the last grid left.
            emit(ops::mov, {v->reg, constFloat(0).reg}, v->detail == Detail::Varying);
        }
    }
}

// A resizable array's declaration: its length set (0, or its initialiser's) wherever it is
// declared, so that a loop's next turn starts it afresh; then its elements.
void CodeGen::initResizable(Var& v, const Declarator& dc) {
    if (dc.init && dc.init->kind != ExprKind::ArrayInit) {
        store(v, genFor(*dc.init, v), dc.loc);
        return;
    }
    const size_t count = dc.init ? dc.init->args.size() : 0;
    emit(ops::aresize, {v.reg, constFloat(float(count)).reg}, false);
    for (size_t k = 0; k < count; ++k) storeElement(v, constFloat(float(k)), genFor(*dc.init->args[k], v), dc.loc);
}

void CodeGen::genIf(const Stmt& s) {
    Val c = gen(*s.expr);
    setLoc(s.loc);
    const bool hasElse = s.body.size() > 1;
    if (!c.varying()) {
        int skip = emit(ops::jmpIfZero, {c.reg, -1}, false);
        release(c);
        genStmt(*s.body[0]);
        if (hasElse) {
            int over = emit(ops::jmp, {-1}, false);
            patch(skip, 1, label());
            genStmt(*s.body[1]);
            patch(over, 0, label());
        } else {
            patch(skip, 1, label());
        }
        return;
    }
    if (hasElse && !c.temp) {  // the else branch reads the condition again: keep it from changing
        Val t = temp(BaseType::Float, Detail::Varying);
        emit(ops::mov, {t.reg, c.reg}, true);
        c = t;
    }
    emit(ops::maskIf, {c.reg}, true);
    pushLevel();
    int none = emit(ops::jmpIfNone, {-1}, false);
    ++varyingNest_;
    genStmt(*s.body[0]);
    if (hasElse) {
        patch(none, 0, label());
        setLoc(s.loc);
        emit(ops::maskElse, {c.reg}, true);
        none = emit(ops::jmpIfNone, {-1}, false);
        genStmt(*s.body[1]);
    }
    --varyingNest_;
    patch(none, 0, label());
    emit(ops::maskPop, {}, true);
    popLevel();
    release(c);
}

void CodeGen::genLoop(const Stmt& s) {
    if (s.init) {
        if (s.init->kind == ExprKind::Assign) genAssign(*s.init, false);
        else release(gen(*s.init));
    }
    setLoc(s.loc);
    const bool exits = leavesLoop(*s.body[0], 0);
    // Is the condition varying? Generate it once to see, then throw that code away.
    bool varyingCond = false;
    if (s.expr) {
        int mark = here();
        auto temps = freeTemps_;
        Val c = gen(*s.expr);
        varyingCond = c.varying();
        prog_.code.resize(size_t(mark));
        freeTemps_ = temps;
    }
    Loop loop;
    const int saveVarying = varyingNest_, saveMasked = maskedNest_;
    if (varyingCond || exits) {
        emit(ops::loopBegin, {}, true);
        pushLevel();
        loop.level = depth_;
    }
    int top = label();
    std::vector<int> exitJumps;
    if (s.expr) {
        Val c = gen(*s.expr);
        setLoc(s.loc);
        if (c.varying()) {
            emit(ops::loopCond, {c.reg}, true);
            exitJumps.push_back(emit(ops::jmpIfNone, {-1}, false));
        } else {
            exitJumps.push_back(emit(ops::jmpIfZero, {c.reg, -1}, false));
            if (exits) exitJumps.push_back(emit(ops::jmpIfNone, {-1}, false));
        }
        release(c);
    } else if (exits) {
        exitJumps.push_back(emit(ops::jmpIfNone, {-1}, false));
    }
    if (varyingCond) ++varyingNest_;
    if (exits) ++maskedNest_;
    loop.varyingAtEntry = varyingNest_;
    loop.maskedAtEntry = maskedNest_;
    loops_.push_back(&loop);
    genStmt(*s.body[0]);
    loops_.pop_back();
    int cont = label();
    for (int j : loop.continueJumps) patch(j, 0, cont);
    if (loop.level >= 0) emit(ops::loopContinueMerge, {}, true);
    if (s.step) {
        if (s.step->kind == ExprKind::Assign) genAssign(*s.step, false);
        else release(gen(*s.step));
    }
    varyingNest_ = saveVarying;
    maskedNest_ = saveMasked;
    setLoc(s.loc);
    const int back = emit(ops::loopBack, {top, -1}, false);  // counts the turn against the budget
    int end = label();
    patch(back, 1, end);
    for (int j : exitJumps) patch(j, prog_.code[size_t(j)].fn == ops::jmpIfZero ? 1 : 0, end);
    for (int j : loop.breakJumps) patch(j, 0, end);
    if (loop.level >= 0) {
        emit(ops::maskPop, {}, true);
        popLevel();
    }
}

void CodeGen::genBreak(const Stmt& s) {
    Loop& loop = *loops_[loops_.size() - size_t(s.level)];
    const bool isBreak = s.kind == StmtKind::Break;
    const bool uniform = !loop.illuminance && varyingNest_ == loop.varyingAtEntry && maskedNest_ == loop.maskedAtEntry;
    if (uniform) {
        // Every point still in the loop leaves: a jump, after dropping inner mask levels.
        if (depth_ > loop.level && loop.level >= 0) emit(ops::unwind, {loop.level}, false);
        (isBreak ? loop.breakJumps : loop.continueJumps).push_back(emit(ops::jmp, {-1}, false));
        return;
    }
    emit(isBreak ? ops::loopBreak : ops::loopContinue, {loop.level, loop.illuminance ? 1 : 0}, true);
}

void CodeGen::genReturn(const Stmt& s) {
    Func& f = *funcs_.back();
    if (s.expr) store(*f.ret, gen(*s.expr), s.loc);
    setLoc(s.loc);
    const Stmt* body = f.def ? f.def->body.get() : cs_.module.shader->body.get();
    if (body->kind == StmtKind::Block && !body->body.empty() && body->body.back().get() == &s) return;  // falls off the end
    const bool uniform = varyingNest_ == f.varyingAtEntry && maskedNest_ == f.maskedAtEntry;
    if (uniform) {
        int level = f.def ? f.funcLevel : 0;
        if (level < 0) level = f.entryDepth;
        if (depth_ > level) emit(ops::unwind, {level}, false);
        f.returnJumps.push_back(emit(ops::jmp, {-1}, false));
        return;
    }
    emit(ops::funcReturn, {f.def ? f.funcLevel : 0}, true);
    ++maskedNest_;  // the rest of the function runs for the points that did not return
}

void CodeGen::genIlluminance(const Stmt& s) {
    prog_.usesLights = true;
    size_t first = s.args[0]->type.isString() ? 1 : 0;
    std::vector<Val> held;
    int cat = -1, axis = -1, angle = -1;
    if (first) {
        held.push_back(gen(*s.args[0]));
        cat = held.back().reg;
    }
    held.push_back(convert(gen(*s.args[first]), BaseType::Point));
    int P = held.back().reg;
    if (s.args.size() > first + 1) {
        held.push_back(convert(gen(*s.args[first + 1]), BaseType::Vector));
        axis = held.back().reg;
        held.push_back(convert(gen(*s.args[first + 2]), BaseType::Float));
        angle = held.back().reg;
    }
    setLoc(s.loc);
    global(Global::L);  // the loop sets L and Cl for each light
    global(Global::Cl);
    Loop loop;
    loop.illuminance = true;
    int begin = emit(ops::illumBegin, {cat, P, axis, angle, -1}, true);
    pushLevel();
    loop.level = depth_;
    int body = label();
    ++varyingNest_;
    loop.varyingAtEntry = varyingNest_;
    loop.maskedAtEntry = maskedNest_;
    loops_.push_back(&loop);
    genStmt(*s.body[0]);
    loops_.pop_back();
    --varyingNest_;
    setLoc(s.loc);
    emit(ops::illumNext, {cat, P, axis, angle, body}, true);
    popLevel();
    patch(begin, 4, label());
    for (const Val& v : held) release(v);
}

void CodeGen::genIlluminate(const Stmt& s) {
    prog_.illuminates = true;
    const bool solar = s.kind == StmtKind::Solar;
    std::vector<Val> held;
    for (size_t i = 0; i < s.args.size(); ++i) {
        size_t k = solar ? i + 1 : i;
        held.push_back(convert(gen(*s.args[i]), k == 0 ? SlType(BaseType::Point) : k == 1 ? SlType(BaseType::Vector)
                                                                                       : SlType(BaseType::Float)));
    }
    setLoc(s.loc);
    global(Global::L);
    global(Global::Cl);
    global(Global::Ps);
    if (solar && s.args.empty()) global(Global::N);
    int at;
    if (solar) {
        at = emit(ops::solar, {held.empty() ? -1 : held[0].reg, held.empty() ? -1 : held[1].reg, -1}, true);
    } else {
        at = emit(ops::illuminate, {held[0].reg, held.size() > 1 ? held[1].reg : -1, held.size() > 1 ? held[2].reg : -1, -1}, true);
    }
    pushLevel();
    ++varyingNest_;
    genStmt(*s.body[0]);
    --varyingNest_;
    patch(at, solar ? 2 : 3, label());
    emit(ops::maskPop, {}, true);
    popLevel();
    for (const Val& v : held) release(v);
}

// Parameters: a register each, and the code computing its default (run only when neither the
// instance nor a primitive variable gives a value).
void CodeGen::genParams() {
    for (Symbol* p : cs_.params) {
        Var* v = declareVar(p, p->detail, true);
        prog_.regs[size_t(v->reg)].param = int(prog_.params.size());
        ParamInfo info;
        info.name = p->name;
        info.type = p->type;
        info.detail = v->detail;
        info.output = p->output;
        info.reg = v->reg;
        info.loc = p->loc;
        const Declarator& dc = *p->decl;
        info.defaultText = dc.initText;
        info.initBegin = here();
        setLoc(dc.loc);
        if (prog_.regs[size_t(v->reg)].resizable()) {
            initResizable(*v, dc);
        } else if (dc.init->kind == ExprKind::ArrayInit) {
            for (size_t k = 0; k < dc.init->args.size(); ++k)
                storeElement(*v, constFloat(float(k)), genFor(*dc.init->args[k], *v), dc.loc);
        } else {
            store(*v, genFor(*dc.init, *v), dc.init->loc);
        }
        info.initEnd = label();
        prog_.params.push_back(info);
    }
}

}  // namespace streyes::sl
