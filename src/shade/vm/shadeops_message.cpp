// Message passing (RI Spec 3.2, section 15.8): surface(), displacement(), atmosphere(),
// incident() and opposite() read a parameter (output or not) of another shader of the primitive
// being shaded. The values are in the peer's frame: the registers it last ran with over this grid,
// or, when it has not run over it yet (a displacement asking the surface, a surface asking its
// atmosphere), its parameters bound without running its body.
#include "shade/vm/frame.h"
#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl {

namespace {

// A peer's parameter of type `from` fits a variable of type `to`: the same shape; colours only
// into colours, point, vector and normal into each other.
bool fits(SlType from, SlType to) {
    if (from.isResizable() || to.isResizable()) return false;  // resizable arrays are not passed
    if (from.isString() != to.isString() || from.elements() != to.elements()) return false;
    if (from.isString()) return true;
    if (from.base == to.base) return true;
    const auto pointLike = [](BaseType b) { return b == BaseType::Point || b == BaseType::Vector || b == BaseType::Normal; };
    return pointLike(from.base) && pointLike(to.base);
}

}  // namespace

const std::string& ShadingVM::peerShaderName(Peer which) const {
    static const std::string none;
    const ShaderInstance* s = peers_[size_t(which)].shader;
    return s ? s->program().name : none;
}

Frame* ShadingVM::peerFrame(Peer which) {
    const PeerShader& peer = peers_[size_t(which)];
    const ShaderProgram& p = peer.shader->program();
    for (auto& f : frames_)
        if (f->prog == &p && f->programId == p.id && f->instance == peer.shader && f->peerGrid == peerGrid_ &&
            f->n == grid_->n)
            return f.get();
    // Not run over this grid: bind its parameters (the frame found is never one running now: the
    // running ones are of other programs, or of this instance over this grid, found above).
    Frame& f = frameFor(p);
    const uint64_t savedRun = f.lastRun;
    runFrame(f, *peer.shader, *grid_, &peer.toCurrent, false);
    f.lastRun = savedRun;
    return &f;
}

bool ShadingVM::readPeer(Exec& x, Peer which, const std::string& name, int dst) {
    if (!peers_[size_t(which)].shader || !grid_) return false;
    const ShaderProgram& p = peers_[size_t(which)].shader->program();
    const ParamInfo* info = p.findParam(name);
    const Register& d = x.reg(dst);
    if (!info || !fits(info->type, d.type)) return false;
    const Frame& f = *peerFrame(which);
    const Register& src = p.regs[size_t(info->reg)];
    if (d.type.isString()) {
        if (src.resizable() || d.resizable()) return false;  // resizable string arrays are not passed
        for (int e = 0; e < d.type.elements(); ++e) x.str(dst, e) = f.strs[size_t(src.slot + e)];
        return true;
    }
    int lane = 0;  // a uniform variable takes the value at the first point that runs
    while (lane + 1 < x.n && !x.mask[lane]) ++lane;
    const RegView out = x.view(dst);
    for (int e = 0; e < d.type.elements(); ++e) {
        const ValueRef v = view(f, info->reg, e);
        for (int c = 0; c < out.comps; ++c) {
            float* o = out.comp(c, e);
            if (!v.varying()) std::fill(o, o + out.w, v.comp[c][0]);
            else if (out.w == 1) o[0] = v.comp[c][lane];
            else std::copy(v.comp[c], v.comp[c] + out.w, o);
        }
    }
    return true;
}

namespace ops {

// a0 = flag, a1 = name, a2 = the variable's copy, a3 = which peer.
void message(Exec& x, const Instr& in) {
    float* flag = x.ptr(in.a[0]);
    flag[0] = x.vm.readPeer(x, Peer(in.a[3]), x.str(in.a[1]), in.a[2]) ? 1.0f : 0.0f;
}

}  // namespace ops

}  // namespace streyes::sl
