#include "shade/vm/vm.h"

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <cstring>

#include "shade/vm/batch_safety.h"
#include "shade/vm/frame.h"
#include "shade/vm/ops.h"

namespace streyes::sl {

void Exec::sanitised(int count) const { stats.sanitised += uint64_t(count); }

void Exec::indexOutOfRange(const Instr& in, int arrayReg, float index) const {
    ++stats.indicesClamped;
    const Register& r = reg(arrayReg);
    const int len = elements(arrayReg);
    char shown[32];
    std::snprintf(shown, sizeof shown, "%g", double(index));
    const std::string name = r.name.empty() ? "an array" : "'" + r.name + "'";
    if (len == 0) {
        vm.warnOnce(*this, in, "index",
                    std::string("array index ") + shown + " of " + name +
                        ", which is empty: read as 0, written nowhere (warned once here; other points and grids may do it too)");
        return;
    }
    vm.warnOnce(*this, in, "index",
                std::string("array index ") + shown + " is outside " + name + " of " + std::to_string(len) + " (0 to " +
                    std::to_string(len - 1) + "): clamped into it (warned once here; other points and grids may do it too)");
}

void ShadingVM::warnOnce(const Exec& x, const Instr& in, const char* kind, const std::string& what) {
    if (!log_) return;
    const SourceLoc* loc = x.loc(in);
    const SourceLoc at = loc ? *loc : SourceLoc{std::make_shared<const std::string>(x.prog.path), 0, 0};
    log_->warnOnce(std::string("sl:") + kind + ":" + x.prog.path + ":" + at.str(), at,
                   "shader \"" + x.prog.name + "\": " + what);
}

void Frame::prepare(const ProgramPtr& program, int points) {
    const ShaderProgram& p = *program;
    if (prog != &p || programId != p.id) {
        prog = &p;
        programId = p.id;
        constantsLoaded = false;
    }
    if (keep != program) keep = program;
    n = points;
    const size_t need = size_t(p.uniformFloats) + size_t(p.varyingArrays) * size_t(n);
    if (arena.size() < need) arena.resize(need);
    if (strs.size() < size_t(p.stringSlots)) strs.resize(size_t(p.stringSlots));
    // Kept (with their storage) between runs; every run starts each at length 0, its
    // declaration or parameter binding giving it its elements.
    if (arrays.size() < size_t(p.resizableArrays)) arrays.resize(size_t(p.resizableArrays));
    for (ResizableArray& a : arrays) a.length = 0;
    const size_t levels = size_t(p.maxMaskDepth) + 2;
    if (masks.size() < levels * size_t(n)) {
        masks.resize(levels * size_t(n));
        conts.resize(levels * size_t(n));
    }
    if (lightIndex.size() < levels) lightIndex.resize(levels);
    if (!constantsLoaded) {
        // Constants live in the uniform area, whose layout does not depend on n: load once.
        for (const Register& r : p.regs) {
            if (r.constant < 0) continue;
            if (r.type.isString()) {
                strs[size_t(r.slot)] = p.constStrings[size_t(r.constant)];
            } else {
                for (int k = 0; k < r.floats(); ++k) arena[size_t(r.slot + k)] = p.constFloats[size_t(r.constant + k)];
            }
        }
        constantsLoaded = true;
    }
    depth = 0;
}

ShadingVM::ShadingVM() = default;
ShadingVM::~ShadingVM() = default;

void ShadingVM::print(const std::string& s) const {
    if (print_) print_(s);
    else std::fprintf(stderr, "%s", s.c_str());
}

Frame& ShadingVM::frameFor(const ShaderProgram& p) {
    for (auto& f : frames_)
        if (f->prog == &p && f->programId == p.id) {
            f->lastRun = runCount_;
            return *f;
        }
    // A new frame, or (past kMaxFrames) the one unused longest, never one of this run's.
    constexpr size_t kMaxFrames = 32;
    Frame* frame = nullptr;
    if (frames_.size() < kMaxFrames) {
        frames_.push_back(std::make_unique<Frame>());
        frame = frames_.back().get();
    } else {
        for (auto& f : frames_)
            if (f->lastRun != runCount_ && (!frame || f->lastRun < frame->lastRun)) frame = f.get();
        if (!frame) {
            frames_.push_back(std::make_unique<Frame>());
            frame = frames_.back().get();
        }
    }
    frame->prog = nullptr;
    frame->programId = 0;
    frame->lastRun = runCount_;
    return *frame;
}

void ShadingVM::run(const ShaderInstance& shader, const ShadingGrid& grid, const std::vector<LightRef>& lights) {
    ++runCount_;
    grid_ = &grid;
    lights_ = &lights;
    if (lightResults_.size() < lights.size()) lightResults_.resize(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) lightResults_[i].valid = false;
    randomCalls_ = 0;
    currentLight_ = nullptr;
    pointFreeWatch_ = nullptr;  // a light run a refused batch left (batch_safety.h) watches nothing now
    runInstructions_ = 0;
    Frame& f = frameFor(shader.program());
    top_ = &f;
    runFrame(f, shader, grid, &grid.toCurrent[size_t(Space::Shader)]);
    stats_.points += uint64_t(grid.n);
}

void ShadingVM::bindParams(const ShaderInstance& shader, const ShadingGrid& grid) {
    ++runCount_;
    grid_ = &grid;
    static const std::vector<LightRef> none;
    lights_ = &none;
    Frame& f = frameFor(shader.program());
    top_ = &f;
    runFrame(f, shader, grid, &grid.toCurrent[size_t(Space::Shader)], false);
}

void ShadingVM::runFrame(Frame& f, const ShaderInstance& shader, const ShadingGrid& grid, const Matrix4* shaderSpace,
                         bool body) {
    const ShaderProgram& p = shader.program();
    f.prepare(shader.programPtr(), grid.n);
    Exec x(*this, f, p, grid, stats_);
    x.loopBudget = loopBudget_;
    x.uni = f.arena.data();
    x.vary = x.uni + p.uniformFloats;
    x.strs = f.strs.data();
    x.arrays = f.arrays.data();
    x.n = grid.n;
    std::memset(f.mask(0), 1, size_t(grid.n));
    setLevel(x, 0);
    f.instance = &shader;
    f.peerGrid = peerGrid_;
    const Matrix4* savedSpace = shaderSpace_;
    const Matrix4* savedObject = objectSpace_;
    shaderSpace_ = shaderSpace;
    // "object" space is the primitive's: the grid's (a light's own grid holds its shader space).
    objectSpace_ = &grid.toCurrent[size_t(Space::Object)];
    bindGlobals(x, grid);
    bindParamValues(x, shader, grid);
    if (body) {
        execute(x, p.bodyBegin, int(p.code.size()));
        sanitiseOutputs(x);
    }
    shaderSpace_ = savedSpace;
    objectSpace_ = savedObject;
    ++stats_.grids;
}

void ShadingVM::execute(Exec& x, int begin, int end) {
    const Instr* code = x.prog.code.data();
    uint64_t count = 0, lanes = 0;
    x.pc = begin;
    while (x.pc < end) {
        const Instr& in = code[x.pc++];
        if (pointFreeWatch_ == &x.frame && !pointFreeInstr(x, in)) pointFreeWatch_ = nullptr;
        if (x.grid.parts && gridWideOp(in.fn)) throw BatchRefused();  // batch_safety.h
        in.fn(x, in);
        ++count;
        lanes += in.varying ? uint64_t(x.n) : 1u;
        if (instructionBudget_ != 0 && ++runInstructions_ > instructionBudget_) {
            stats_.instructions += count;
            throw InputError("shader \"" + x.prog.name + "\" (" + x.prog.path + ") ran more than " +
                             std::to_string(instructionBudget_) + " instructions over one grid: a loop that never ends?");
        }
    }
    stats_.instructions += count;
    stats_.laneOps += lanes;
}

// ---- Binding ---------------------------------------------------------------------------------------

namespace {

void fill(const RegView& d, float v) {
    for (int c = 0; c < d.comps * d.elems; ++c)
        for (int i = 0; i < d.w; ++i) d.comp(c)[i] = v;
}

void copyIn(const RegView& d, const ValueRef& s, const GridKernels& k) {
    // Triples stored x y z x y z (the renderer's grids): split by the kernel.
    if (d.comps == 3 && d.varying && s.stride == 3 && s.comp[1] == s.comp[0] + 1 && s.comp[2] == s.comp[0] + 2) {
        float* const out[3] = {d.comp(0), d.comp(1), d.comp(2)};
        k.deinterleave3(size_t(d.w), s.comp[0], out);
        return;
    }
    for (int c = 0; c < d.comps && c < 3; ++c) {
        float* out = d.comp(c);
        const float* in = s.comp[c] ? s.comp[c] : s.comp[0];
        if (s.stride == 0) {
            for (int i = 0; i < d.w; ++i) out[i] = in[0];
        } else if (s.stride == 1) {
            std::memcpy(out, in, sizeof(float) * size_t(d.w));
        } else {
            for (int i = 0; i < d.w; ++i) out[i] = in[std::ptrdiff_t(i) * s.stride];
        }
    }
}

// A primitive variable of type `a` can bind a parameter of type `b`.
bool compatible(SlType a, SlType b) {
    return a == b || (a.arrayLen == b.arrayLen && a.element().isPointLike() && b.element().isPointLike());
}

// Moves a point-like value from "shader" space to current space.
void fromShaderSpace(float* v, BaseType b, const Matrix4& m) {
    Vec3d p(v[0], v[1], v[2]), q;
    if (b == BaseType::Point) {
        q = m.point(p);
    } else if (b == BaseType::Vector) {
        q = m.vector(p);
    } else {  // normals: by the inverse transpose
        Matrix4 inv;
        if (!invert(m, &inv)) return;
        q = {inv(0, 0) * p.x + inv(0, 1) * p.y + inv(0, 2) * p.z, inv(1, 0) * p.x + inv(1, 1) * p.y + inv(1, 2) * p.z,
             inv(2, 0) * p.x + inv(2, 1) * p.y + inv(2, 2) * p.z};
    }
    v[0] = float(q.x);
    v[1] = float(q.y);
    v[2] = float(q.z);
}

}  // namespace

void ShadingVM::bindGlobals(Exec& x, const ShadingGrid& g) {
    const ShaderProgram& p = x.prog;
    auto in = [&](Global k) -> const ValueRef& { return g.globals[size_t(k)]; };
    for (int k = 0; k < kGlobalCount; ++k) {
        const int r = p.globalReg[k];
        if (r < 0) continue;
        RegView d = x.view(r);
        const Global gk = Global(k);
        const ValueRef& src = in(gk);
        if (src.valid()) {
            copyIn(d, src, *kernels_);
            continue;
        }
        switch (gk) {
            case Global::N:
            case Global::Ng: {
                const ValueRef& other = in(gk == Global::N ? Global::Ng : Global::N);
                if (other.valid()) copyIn(d, other, *kernels_);
                else fill(d, 0);
                break;
            }
            case Global::I: {
                const ValueRef& P = in(Global::P);
                const ValueRef& E = in(Global::E);
                if (P.valid()) copyIn(d, P, *kernels_);
                else fill(d, 0);
                for (int c = 0; c < 3; ++c) {
                    const float e = E.valid() ? E.at(c, 0) : 0.0f;
                    float* o = d.comp(c);
                    for (int i = 0; i < d.w; ++i) o[i] = o[i] - e;
                }
                break;
            }
            case Global::Ps:
                if (in(Global::P).valid()) copyIn(d, in(Global::P), *kernels_);
                else fill(d, 0);
                break;
            case Global::Ns:  // outside a light: the surface's own normal
                if (in(Global::N).valid()) copyIn(d, in(Global::N), *kernels_);
                else if (in(Global::Ng).valid()) copyIn(d, in(Global::Ng), *kernels_);
                else fill(d, 0);
                break;
            case Global::Oi:
                if (in(Global::Os).valid()) copyIn(d, in(Global::Os), *kernels_);
                else fill(d, 1);
                break;
            case Global::Cs:
            case Global::Os:
            case Global::alpha: fill(d, 1); break;
            case Global::ncomps: fill(d, 3); break;
            case Global::u:
            case Global::v:
            case Global::s:
            case Global::t: {
                // Without values: the grid's own parameterisation (s, t default to u, v).
                const bool alongU = gk == Global::u || gk == Global::s;
                const ValueRef& uv = in(alongU ? Global::u : Global::v);
                if (uv.valid()) {
                    copyIn(d, uv, *kernels_);
                } else if (g.nu > 0 && g.nv > 0) {
                    for (int i = 0; i < d.w; ++i) {
                        int iu = i % (g.nu + 1), iv = i / (g.nu + 1);
                        d.p[i] = alongU ? float(iu) / float(g.nu) : float(iv) / float(g.nv);
                    }
                } else {
                    fill(d, 0);
                }
                break;
            }
            case Global::du: fill(d, g.nu > 0 ? 1.0f / float(g.nu) : 0.0f); break;
            case Global::dv: fill(d, g.nv > 0 ? 1.0f / float(g.nv) : 0.0f); break;
            default: fill(d, 0); break;
        }
    }
}

void ShadingVM::bindParamValues(Exec& x, const ShaderInstance& shader, const ShadingGrid& g) {
    const ShaderProgram& p = x.prog;
    // A string parameter's elements from a value or primitive variable (a resizable one: all of them).
    auto bindStrings = [&](const ParamInfo& info, const std::vector<std::string>& from) {
        if (p.regs[size_t(info.reg)].resizable() && !setLength(x, info.reg, int(from.size())))
            throw InputError("parameter \"" + info.name + "\" of shader \"" + p.name + "\": too many values");
        for (int e = 0; e < x.elements(info.reg) && e < int(from.size()); ++e) x.str(info.reg, e) = from[size_t(e)];
    };
    for (size_t k = 0; k < p.params.size(); ++k) {
        const ParamInfo& info = p.params[k];
        RegView d = x.view(info.reg);
        // A primitive variable of the same name first.
        const Primvar* pv = nullptr;
        if (g.primvars)
            for (const Primvar& v : *g.primvars)
                if (v.name == info.name) pv = &v;
        if (pv) {
            if (!compatible(pv->type, info.type))
                throw InputError(pv->loc, "primitive variable \"" + pv->name + "\" is a " + pv->type.name() +
                                              "; shader \"" + p.name + "\" declares it " + info.type.name());
            if (info.type.isString()) {
                bindStrings(info, pv->strings);
                continue;
            }
            if (info.type.isMatrix()) {
                for (int c = 0; c < 16; ++c)
                    for (int i = 0; i < d.w; ++i) d.comp(c)[i] = pv->matrix ? pv->matrix[c] : (c % 5 == 0 ? 1.0f : 0.0f);
                continue;
            }
            if (pv->value.varying() && !d.varying)
                throw InputError(pv->loc, "primitive variable \"" + pv->name + "\" varies over the surface; shader \"" +
                                              p.name + "\" declares it uniform");
            copyIn(d, pv->value, *kernels_);
            continue;
        }
        if (const ShaderInstance::Value* v = shader.value(int(k))) {
            if (info.type.isString()) {
                bindStrings(info, v->strings);
                continue;
            }
            const int comps = info.type.comps();
            int elems = info.type.elements();
            if (p.regs[size_t(info.reg)].resizable()) {  // sized by the value given
                elems = int(v->floats.size()) / comps;
                if (!setLength(x, info.reg, elems)) throw InputError("parameter \"" + info.name + "\" of shader \"" + p.name + "\": too many values");
                d = x.view(info.reg);
            }
            for (int e = 0; e < elems; ++e) {
                float val[16];
                for (int c = 0; c < comps; ++c) val[c] = v->floats[size_t(e * comps + c)];
                if (info.type.element().isPointLike() && shaderSpace_) fromShaderSpace(val, info.type.base, *shaderSpace_);
                for (int c = 0; c < comps; ++c)
                    for (int i = 0; i < d.w; ++i) d.comp(c, e)[i] = val[c];
            }
            continue;
        }
        execute(x, info.initBegin, info.initEnd);
    }
}

void ShadingVM::sanitiseOutputs(Exec& x) {
    const ShaderProgram& p = x.prog;
    auto clean = [&](int r) {
        if (r < 0 || p.regs[size_t(r)].type.isString()) return;
        RegView d = x.view(r);
        const size_t count = size_t(d.comps) * size_t(d.elems) * size_t(d.w);
        // A float is NaN or infinite when its exponent bits are all ones: test them all at
        // once (vectorised), and replace only when something was found.
        uint32_t any = 0;
        for (size_t i = 0; i < count; ++i) {
            uint32_t bits;
            std::memcpy(&bits, d.p + i, 4);
            any |= uint32_t((bits & 0x7f800000u) == 0x7f800000u);
        }
        if (!any) return;
        for (size_t i = 0; i < count; ++i)
            if (!std::isfinite(d.p[i])) {
                d.p[i] = 0;
                ++stats_.sanitised;
            }
    };
    for (Global g : {Global::Ci, Global::Oi, Global::P, Global::N, Global::L, Global::Cl, Global::Ol, Global::alpha})
        clean(p.globalReg[int(g)]);
    for (const ParamInfo& info : p.params)
        if (info.output) clean(info.reg);
}

// ---- Results ---------------------------------------------------------------------------------------

ValueRef ShadingVM::view(const Frame& f, int reg, int element) const {
    const Register& r = f.prog->regs[size_t(reg)];
    if (r.resizable() && element >= f.arrays[size_t(r.slot)].length) return {};
    const float* base = r.resizable() ? f.arrays[size_t(r.slot)].data.data()
                                      : f.arena.data() + (r.varying() ? size_t(f.prog->uniformFloats) + size_t(r.slot) * size_t(f.n)
                                                                      : size_t(r.slot));
    const size_t w = r.varying() ? size_t(f.n) : 1;
    ValueRef v;
    const int comps = r.type.comps();
    for (int c = 0; c < comps && c < 3; ++c) v.comp[c] = base + (size_t(element) * size_t(comps) + size_t(c)) * w;
    v.stride = r.varying() ? 1 : 0;
    return v;
}

ValueRef ShadingVM::result(Global g) const {
    if (top_ && top_->prog) {
        int r = top_->prog->globalReg[int(g)];
        if (r >= 0) return view(*top_, r);
    }
    return grid_ ? grid_->globals[size_t(g)] : ValueRef{};
}

ValueRef ShadingVM::param(const std::string& name, int element) const {
    if (!top_ || !top_->prog) return {};
    const ParamInfo* info = top_->prog->findParam(name);
    if (!info || info->type.isString() || (!info->type.isResizable() && element >= info->type.elements())) return {};
    return view(*top_, info->reg, element);
}

ValueRef ShadingVM::output(const std::string& name) const {
    if (!top_ || !top_->prog) return {};
    const ParamInfo* info = top_->prog->findParam(name);
    if (!info || !info->output) return {};
    return param(name);
}

std::vector<std::string> ShadingVM::paramStrings(const std::string& name) const {
    std::vector<std::string> out;
    if (!top_ || !top_->prog) return out;
    const ParamInfo* info = top_->prog->findParam(name);
    if (!info || !info->type.isString()) return out;
    const Register& r = top_->prog->regs[size_t(info->reg)];
    if (r.resizable()) {
        const ResizableArray& a = top_->arrays[size_t(r.slot)];
        out.assign(a.strings.begin(), a.strings.begin() + a.length);
        return out;
    }
    for (int e = 0; e < info->type.elements(); ++e) out.push_back(top_->strs[size_t(r.slot + e)]);
    return out;
}

// ---- Spaces ----------------------------------------------------------------------------------------

bool ShadingVM::spaceToCurrent(const std::string& name, float m[16]) {
    const Matrix4* found = nullptr;
    static const Matrix4 identity;
    for (int s = 0; s < kSpaceCount; ++s) {
        if (name != spaceName(Space(s))) continue;
        if (Space(s) == Space::Current || Space(s) == Space::Camera) found = &identity;
        else if (Space(s) == Space::Shader && shaderSpace_) found = shaderSpace_;
        else if (Space(s) == Space::Object && objectSpace_) found = objectSpace_;
        else found = &grid_->toCurrent[size_t(s)];
    }
    if (!found && grid_ && grid_->coordinateSystems)
        for (const NamedSpace& ns : *grid_->coordinateSystems)
            if (ns.name == name) found = &ns.toCurrent;
    if (!found) {
        ++stats_.unknownSpaces;
        for (int k = 0; k < 16; ++k) m[k] = k % 5 == 0 ? 1.0f : 0.0f;
        return false;
    }
    for (int k = 0; k < 16; ++k) m[k] = float(found->m[size_t(k)]);
    return true;
}

bool ShadingVM::currentToSpace(const std::string& name, float m[16]) {
    float f[16];
    bool ok = spaceToCurrent(name, f);
    Matrix4 a, inv;
    for (int k = 0; k < 16; ++k) a.m[size_t(k)] = f[k];
    if (!invert(a, &inv)) inv = Matrix4();
    for (int k = 0; k < 16; ++k) m[k] = float(inv.m[size_t(k)]);
    return ok;
}

// ---- Lights ----------------------------------------------------------------------------------------

const std::vector<LightResult>& ShadingVM::lightsAt(Exec& x, const RegView& P) {
    const size_t n = size_t(x.n);
    for (size_t k = 0; k < lights_->size(); ++k) {
        LightResult& r = lightResults_[k];
        if (r.valid && r.uniform) continue;  // the same for any positions of this run
        bool same = r.valid && r.Ps.size() >= 3 * n;
        for (int c = 0; c < 3 && same; ++c) {
            const float* a = r.Ps.data() + size_t(c) * n;
            if (P.varying) {
                same = std::memcmp(a, P.comp(c), sizeof(float) * n) == 0;
            } else {
                for (size_t i = 0; i < n && same; ++i) same = a[i] == P.comp(c)[0];
            }
        }
        if (!same) runLight(k, P);
    }
    return lightResults_;
}

void ShadingVM::runLight(size_t index, const RegView& P) {
    const LightRef& ref = (*lights_)[index];
    LightResult& res = lightResults_[index];
    const ShaderProgram& lp = ref.shader->program();
    const size_t n = size_t(grid_->n);
    res.Ps.resize(3 * n);  // filled below unless the results are given again
    // The light runs over the surface's points: Ps the surface's, P its own origin.
    lightGrid_ = *grid_;
    lightGrid_.primvars = nullptr;
    for (Global g : {Global::L, Global::Cl, Global::Ol, Global::Ci, Global::Oi, Global::P})
        lightGrid_.globals[size_t(g)] = ValueRef{};
    lightGrid_.set(Global::Ps, ValueRef::soa(res.Ps.data(), res.Ps.data() + n, res.Ps.data() + 2 * n));
    ns_.resize(3 * n);  // filled below if the light runs and reads Ns
    lightGrid_.set(Global::Ns, ValueRef::soa(ns_.data(), ns_.data() + n, ns_.data() + 2 * n));
    Vec3d o = ref.toCurrent.point({0, 0, 0});
    lightOrigin_[0] = float(o.x);
    lightOrigin_[1] = float(o.y);
    lightOrigin_[2] = float(o.z);
    lightGrid_.set(Global::P, ValueRef::uniform(lightOrigin_, 3));
    if (ref.hasNormal) {  // a point of an area light: N and Ng are its surface's
        lightNormal_[0] = ref.normal.x;
        lightNormal_[1] = ref.normal.y;
        lightNormal_[2] = ref.normal.z;
        lightGrid_.set(Global::N, ValueRef::uniform(lightNormal_, 3));
        lightGrid_.set(Global::Ng, ValueRef::uniform(lightNormal_, 3));
    }
    lightGrid_.toCurrent[size_t(Space::Shader)] = ref.toCurrent;
    lightGrid_.toCurrent[size_t(Space::Object)] = ref.toCurrent;
    illuminateFrom = solarAxis = -1;
    // Results an earlier grid's run left that this run would give again.
    const bool keyed = n > 0 && pointFreeKey(lp);
    if (keyed)
        for (const PointFreeLight& e : pointFree_) {
            if (!samePointFree(e, ref)) continue;
            res.ambient = e.ambient;
            // Kept uniform: one value a component, read for every point (LightResult::at).
            res.uniform = true;
            res.L.assign(e.L, e.L + 3);
            res.Cl.assign(e.Cl, e.Cl + 3);
            res.Ln.assign(e.Ln, e.Ln + 3);
            res.lit.assign(1, e.lit);
            res.shader = ref.shader;
            res.nonDiffuse = e.nonDiffuse;
            res.nonSpecular = e.nonSpecular;
            res.category = e.category;
            res.outFloats = e.outFloats;
            res.outStrings = e.outStrings;
            res.outOffset = e.outOffset;
            res.outVarying.assign(lp.params.size(), 0);
            res.valid = true;
            ++stats_.lightReuses;
            return;
        }
    // Its positions, kept to reuse the results while P stays the same.
    res.uniform = false;
    for (int c = 0; c < 3; ++c) {
        float* o = res.Ps.data() + size_t(c) * n;
        if (P.varying) std::memcpy(o, P.comp(c), sizeof(float) * n);
        else std::fill(o, o + n, P.comp(c)[0]);
    }
    // Ns: the surface's normal at Ps, turned to face the eye (against I), as the standard
    // surfaces' Nf is and as Aqsis's lights see it (its envlight example occludes a floor whose
    // N points away from the teapot). (Only for a light that reads Ns.)
    const ValueRef& sn = grid_->globals[size_t(Global::N)];
    const ValueRef& si = grid_->globals[size_t(Global::I)];
    for (size_t i = 0; i < (lp.globalReg[int(Global::Ns)] >= 0 ? n : 0); ++i) {
        const Vec3f v = sn.valid() ? sn.vec(int(i)) : Vec3f{0, 0, 0};
        const float side = si.valid() ? dot(v, si.vec(int(i))) : 0.0f;
        for (int c = 0; c < 3; ++c) ns_[size_t(c) * n + i] = side > 0 ? -v[c] : v[c];
    }
    lit_.assign(n, lp.illuminates ? 0 : 1);
    const LightResult* savedLight = currentLight_;
    currentLight_ = nullptr;
    Frame& f = frameFor(lp);
    const ShadeStats before = stats_;
    const Frame* savedWatch = pointFreeWatch_;
    pointFreeWatch_ = keyed ? &f : nullptr;
    runFrame(f, *ref.shader, lightGrid_, &ref.toCurrent);
    // Point-free: every instruction passed, and nothing was counted (a space nobody defined,
    // a result sanitised ...) that a reuse would not count again.
    const bool pointFree = keyed && pointFreeWatch_ == &f && stats_.sanitised == before.sanitised &&
                           stats_.unknownSpaces == before.unknownSpaces && stats_.textureErrors == before.textureErrors &&
                           stats_.indicesClamped == before.indicesClamped && stats_.loopsStopped == before.loopsStopped &&
                           stats_.raysMissing == before.raysMissing;
    pointFreeWatch_ = savedWatch;
    currentLight_ = savedLight;
    ++stats_.lightRuns;

    // Collect: L towards the light as the surface sees it, Cl, where it reached, outputs.
    res.ambient = !lp.illuminates;
    auto grab = [&](Global g, std::vector<float>& out, float sign) {
        out.resize(3 * n);
        int r = lp.globalReg[int(g)];
        if (r < 0) {
            std::fill(out.begin(), out.end(), 0.0f);
            return;
        }
        ValueRef v = view(f, r);
        for (int c = 0; c < 3; ++c) {
            float* o = out.data() + size_t(c) * n;
            if (v.stride == 1 && sign == 1) {
                std::memcpy(o, v.comp[c], sizeof(float) * n);
            } else {
                for (size_t i = 0; i < n; ++i) o[i] = sign * v.at(c, int(i));
            }
        }
    };
    grab(Global::Cl, res.Cl, 1);
    if (ref.weight != 1)
        for (float& c : res.Cl) c *= ref.weight;
    if (res.ambient) {
        res.L.assign(3 * n, 0.0f);
        res.Ln.assign(3 * n, 0.0f);
    } else {
        grab(Global::L, res.L, -1);
        res.Ln.resize(3 * n);
        const float* const l[3] = {res.L.data(), res.L.data() + n, res.L.data() + 2 * n};
        float* const ln[3] = {res.Ln.data(), res.Ln.data() + n, res.Ln.data() + 2 * n};
        kernels_->normalize(n, l, true, ln);
    }
    res.lit = lit_;
    res.shader = ref.shader;
    res.nonDiffuse = res.nonSpecular = false;
    res.category.clear();
    res.outFloats.clear();
    res.outStrings.clear();
    res.outOffset.assign(lp.params.size(), -1);
    res.outVarying.assign(lp.params.size(), 0);
    for (size_t k = 0; k < lp.params.size(); ++k) {
        const ParamInfo& info = lp.params[k];
        const Register& r = lp.regs[size_t(info.reg)];
        if (info.type.isString()) {
            if (info.name == "__category" && !r.resizable()) res.category = f.strs[size_t(r.slot)];
            if (!info.output || r.resizable()) continue;  // a resizable output: not passed on, as below
            res.outOffset[k] = int(res.outStrings.size());
            for (int e = 0; e < info.type.elements(); ++e) res.outStrings.push_back(f.strs[size_t(r.slot + e)]);
            continue;
        }
        if (r.resizable()) continue;  // a light's resizable output: not passed on (lightsource() misses)
        ValueRef v = view(f, info.reg);
        if (info.type.isFloat() && info.name == "__nondiffuse") res.nonDiffuse = v.at(0, 0) != 0;
        if (info.type.isFloat() && info.name == "__nonspecular") res.nonSpecular = v.at(0, 0) != 0;
        if (!info.output) continue;
        res.outOffset[k] = int(res.outFloats.size());
        res.outVarying[k] = r.varying() ? 1 : 0;
        const size_t count = size_t(r.floats()) * (r.varying() ? n : 1);
        const float* base = v.comp[0];
        res.outFloats.insert(res.outFloats.end(), base, base + count);
    }
    res.valid = true;
    if (pointFree) keepPointFree(ref, lp, res, n);
}

// ---- Lights whose results do not depend on the point -------------------------------------------------

// An instruction that gives every point the same value from uniform operands, reading nothing of
// the grid but uniform registers and the spaces (which key the results), under a mask with every
// point on. Anything else (a varying operand, an operation not listed: noise, texture,
// illuminate from Ps, attribute() ...) makes the run's results the points' own.
bool ShadingVM::pointFreeInstr(const Exec& x, const Instr& in) {
    if (!x.allOn()) return false;
    auto uniformAt = [&](std::initializer_list<int> operands) {
        for (int k : operands)
            if (in.a[k] >= 0 && x.varying(in.a[k])) return false;
        return true;
    };
    const OpFn f = in.fn;
    if (f == ops::mov || f == ops::movm || f == ops::neg || f == ops::logNot) return uniformAt({1});
    if (f == ops::add || f == ops::sub || f == ops::mul || f == ops::div || f == ops::eq || f == ops::ne ||
        f == ops::lt || f == ops::gt || f == ops::le || f == ops::ge || f == ops::logAnd || f == ops::logOr)
        return uniformAt({1, 2});
    if (f == ops::triple) return uniformAt({1, 2, 3});
    if (f == ops::xform) return uniformAt({1, 4});
    if (f == ops::jmpIfZero) return uniformAt({0});
    if (f == ops::solar) return in.a[0] >= 0 && uniformAt({0, 1});
    return f == ops::smov || f == ops::streq || f == ops::strne || f == ops::jmp || f == ops::maskPop;
}

// The uniform predefined variables the light about to run has, as lightGrid_ binds them; false
// when one of them would be derived from the grid's points (not bound: I from P, du from nu ...).
bool ShadingVM::pointFreeKey(const ShaderProgram& lp) {
    pointFreeKey_.clear();
    for (int k = 0; k < kGlobalCount; ++k) {
        const int r = lp.globalReg[k];
        if (r < 0 || lp.regs[size_t(r)].varying()) continue;
        const ValueRef& v = lightGrid_.globals[size_t(k)];
        if (!v.valid()) {
            switch (Global(k)) {
                case Global::N: case Global::Ng: case Global::I: case Global::Ps: case Global::Ns: case Global::Oi:
                case Global::u: case Global::v: case Global::s: case Global::t: case Global::du: case Global::dv:
                    return false;
                default: continue;  // a constant fill (bindGlobals)
            }
        }
        const int comps = std::min(3, lp.regs[size_t(r)].type.comps());
        for (int c = 0; c < comps; ++c) pointFreeKey_.push_back((v.comp[c] ? v.comp[c] : v.comp[0])[0]);
    }
    return true;
}

bool ShadingVM::samePointFree(const PointFreeLight& e, const LightRef& ref) const {
    if (e.shader != ref.shader || e.revision != ref.shader->revision() || e.hasNormal != ref.hasNormal) return false;
    if (std::memcmp(&e.weight, &ref.weight, sizeof(float)) != 0 || std::memcmp(&e.normal, &ref.normal, sizeof(Vec3f)) != 0)
        return false;
    if (std::memcmp(e.toCurrent.m.data(), ref.toCurrent.m.data(), sizeof(double) * 16) != 0) return false;
    if (e.globals.size() != pointFreeKey_.size() ||
        (!e.globals.empty() &&  // memcmp of no bytes may still not be given a null pointer
         std::memcmp(e.globals.data(), pointFreeKey_.data(), sizeof(float) * e.globals.size()) != 0))
        return false;
    for (int s = 0; s < kSpaceCount; ++s)
        if (std::memcmp(e.spaces[size_t(s)].m.data(), lightGrid_.toCurrent[size_t(s)].m.data(), sizeof(double) * 16) != 0)
            return false;
    const size_t named = lightGrid_.coordinateSystems ? lightGrid_.coordinateSystems->size() : 0;
    if (e.named.size() != named) return false;
    for (size_t i = 0; i < named; ++i) {
        const NamedSpace& a = e.named[i];
        const NamedSpace& b = (*lightGrid_.coordinateSystems)[i];
        if (a.name != b.name || std::memcmp(a.toCurrent.m.data(), b.toCurrent.m.data(), sizeof(double) * 16) != 0)
            return false;
    }
    return true;
}

// Keeps a point-free run's results when they are what it says: each the same at every point,
// and no output parameter varying.
void ShadingVM::keepPointFree(const LightRef& ref, const ShaderProgram& lp, const LightResult& res, size_t n) {
    for (const ParamInfo& info : lp.params)
        if (info.output && lp.regs[size_t(info.reg)].varying()) return;
    auto constant = [n](const std::vector<float>& v, float* out) {
        for (size_t c = 0; c < 3; ++c) {
            const float* a = v.data() + c * n;
            for (size_t i = 1; i < n; ++i)
                if (std::memcmp(a + i, a, sizeof(float)) != 0) return false;
            out[c] = a[0];
        }
        return true;
    };
    float L[3], Cl[3], Ln[3];
    if (!constant(res.L, L) || !constant(res.Cl, Cl) || !constant(res.Ln, Ln)) return;
    for (size_t i = 1; i < n; ++i)
        if (res.lit[i] != res.lit[0]) return;
    // A few lights and times a thread meets at once; the oldest goes first. Entries are
    // overwritten in place (no allocation once their vectors have grown).
    constexpr size_t kKept = 16;
    if (pointFree_.size() < kKept) {
        pointFree_.emplace_back();
        pointFreeNext_ = pointFree_.size() - 1;
    }
    PointFreeLight& e = pointFree_[pointFreeNext_];
    pointFreeNext_ = (pointFreeNext_ + 1) % kKept;
    for (int c = 0; c < 3; ++c) e.L[c] = L[c], e.Cl[c] = Cl[c], e.Ln[c] = Ln[c];
    e.shader = ref.shader;
    e.revision = ref.shader->revision();
    e.toCurrent = ref.toCurrent;
    e.normal = ref.normal;
    e.hasNormal = ref.hasNormal;
    e.weight = ref.weight;
    e.spaces = lightGrid_.toCurrent;
    e.named.clear();
    if (lightGrid_.coordinateSystems) e.named.assign(lightGrid_.coordinateSystems->begin(), lightGrid_.coordinateSystems->end());
    e.globals.assign(pointFreeKey_.begin(), pointFreeKey_.end());
    e.ambient = res.ambient;
    e.nonDiffuse = res.nonDiffuse;
    e.nonSpecular = res.nonSpecular;
    e.lit = res.lit[0];
    e.category = res.category;
    e.outFloats.assign(res.outFloats.begin(), res.outFloats.end());
    e.outStrings.assign(res.outStrings.begin(), res.outStrings.end());
    e.outOffset.assign(res.outOffset.begin(), res.outOffset.end());
}

}  // namespace streyes::sl
