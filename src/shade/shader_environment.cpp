#include "shade/shader_environment.h"

#include <algorithm>

#include "shade/vm/vm.h"

namespace streyes {

void ShaderEnvironments::add(const std::string& name, std::shared_ptr<const sl::ShaderInstance> shader) {
    named_.push_back({name, std::move(shader)});
}

bool ShaderEnvironments::lookup(const std::string& name, int channels, const sl::DirectionQuery& q,
                                float* const* out) const {
    auto it = std::find_if(named_.begin(), named_.end(), [&](const Named& n) { return n.name == name; });
    if (it == named_.end()) return false;
    if (q.n <= 0) return true;
    // A shader VM belongs to one thread; lookups come from every worker (and from inside another
    // VM's run: this one is its own).
    thread_local std::unique_ptr<sl::ShadingVM> vm;
    if (!vm) vm = std::make_unique<sl::ShadingVM>();
    static const float white[3] = {1, 1, 1};
    sl::ShadingGrid g;
    g.n = q.n;
    const sl::ValueRef r = sl::ValueRef::soa(q.R[0], q.R[1], q.R[2]);
    g.set(sl::Global::I, r);
    g.set(sl::Global::P, r);
    g.set(sl::Global::Cs, sl::ValueRef::uniform(white, 3));
    g.set(sl::Global::Os, sl::ValueRef::uniform(white, 3));
    g.time = q.time;
    vm->run(*it->shader, g);
    const sl::ValueRef ci = vm->result(sl::Global::Ci);
    for (int c = 0; c < std::min(channels, 4); ++c)
        for (int i = 0; i < q.n; ++i) out[c][i] = c == 3 ? 1.0f : ci.valid() ? ci.at(c, i) : 0.0f;
    return true;
}

}  // namespace streyes
