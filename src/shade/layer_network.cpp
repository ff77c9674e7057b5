#include "shade/layer_network.h"

#include <algorithm>

namespace streyes {

namespace {

// A layer's variable: its parameter's declaration, or a predefined variable's.
struct VarInfo {
    bool found = false;
    sl::Global global = sl::Global::Count;
    sl::SlType type;
    sl::Detail detail = sl::Detail::Uniform;
};

VarInfo lookUp(const sl::ShaderProgram& p, const std::string& name) {
    VarInfo v;
    if (const sl::ParamInfo* info = p.findParam(name)) {
        v.found = true;
        v.type = info->type;
        v.detail = info->detail;
        return v;
    }
    const sl::Global g = sl::findGlobal(name);
    if (g != sl::Global::Count) {
        v.found = true;
        v.global = g;
        v.type = sl::globalInfo(g).type;
        v.detail = sl::globalInfo(g).detail;
    }
    return v;
}

}  // namespace

std::shared_ptr<const LayerNetwork> bindLayerNetwork(const ShaderNetwork& net, sl::ShaderType type,
                                                     std::vector<std::shared_ptr<const sl::ShaderInstance>> layers,
                                                     Log& log) {
    auto out = std::make_shared<LayerNetwork>();
    out->layers = std::move(layers);
    using G = sl::Global;
    out->carried = type == sl::ShaderType::Displacement ? std::vector<G>{G::P, G::N}
                   : type == sl::ShaderType::Imager     ? std::vector<G>{G::Ci, G::Oi, G::alpha}
                                                        : std::vector<G>{G::Ci, G::Oi};
    for (const ShaderConnection& c : net.connections) {
        const sl::ShaderProgram& from = out->layers[size_t(c.from)]->program();
        const sl::ShaderProgram& to = out->layers[size_t(c.to)]->program();
        const std::string what = "ConnectShaderLayers " + net.names[size_t(c.from)] + "." + c.fromVar + " -> " +
                                 net.names[size_t(c.to)] + "." + c.toVar;
        auto skip = [&](const std::string& why) { log.lenient("connect:" + what, c.loc, what + ": " + why + ": not connected"); };
        const VarInfo src = lookUp(from, c.fromVar), dst = lookUp(to, c.toVar);
        if (!src.found) {
            skip("shader \"" + from.name + "\" (" + from.path + ") has no parameter \"" + c.fromVar +
                 "\" and it is no predefined variable");
            continue;
        }
        if (!dst.found) {
            skip("shader \"" + to.name + "\" (" + to.path + ") has no parameter \"" + c.toVar +
                 "\" and it is no predefined variable");
            continue;
        }
        const bool sameType = src.type == dst.type || (src.type.isPointLike() && dst.type.isPointLike());
        const bool supported = src.type.isFloat() || src.type.isTriple() || src.type.is(sl::BaseType::String);
        if (!sameType || !supported) {
            skip(c.fromVar + " is a " + src.type.name() + ", " + c.toVar + " a " + dst.type.name() +
                 (sameType ? " (only float, colour, point-like and string values connect)" : ""));
            continue;
        }
        if (src.detail == sl::Detail::Varying && dst.detail == sl::Detail::Uniform && dst.global == sl::Global::Count) {
            skip(c.fromVar + " varies over the surface; shader \"" + to.name + "\" declares " + c.toVar + " uniform");
            continue;
        }
        LayerNetwork::Link l;
        l.from = c.from;
        l.to = c.to;
        l.fromName = c.fromVar;
        l.toName = c.toVar;
        l.fromGlobal = src.global;
        l.toGlobal = dst.global;
        l.type = dst.type;
        l.string = src.type.isString();
        out->links.push_back(std::move(l));
    }
    // In order of their source layer, connections of one layer in the file's order: a stable
    // insertion sort over a handful of links (std::stable_sort's temporary buffer trips the
    // sanitizer's new/delete pairing in the clang build).
    std::vector<LayerNetwork::Link>& links = out->links;
    for (size_t i = 1; i < links.size(); ++i)
        for (size_t j = i; j > 0 && links[j].from < links[j - 1].from; --j) std::swap(links[j], links[j - 1]);
    return out;
}

bool connectsViewValues(const LayerNetwork& net) {
    using G = sl::Global;
    for (const LayerNetwork::Link& l : net.links) {
        switch (l.fromGlobal) {
            case G::Count:  // a parameter: an output the analysis checked, or an input it takes as given
            case G::Cs: case G::Os: case G::Ci: case G::Oi: case G::alpha:
            case G::s: case G::t: case G::u: case G::v: case G::du: case G::dv: case G::time:
                break;
            default: return true;
        }
    }
    return false;
}

void LayerNetworkRunner::run(sl::ShadingVM& vm, const LayerNetwork& net, sl::ShadingGrid& grid,
                               const std::vector<sl::LightRef>& lights) {
    const auto savedGlobals = grid.globals;
    const std::vector<sl::Primvar>* savedPrimvars = grid.primvars;
    const size_t n = size_t(grid.n);
    const size_t layers = net.layers.size();
    if (primvars_.size() < layers) primvars_.resize(layers);
    for (size_t i = 0; i < layers; ++i) {
        primvars_[i].clear();
        if (savedPrimvars) primvars_[i].assign(savedPrimvars->begin(), savedPrimvars->end());
    }
    if (values_.size() < net.links.size()) values_.resize(net.links.size());
    if (strings_.size() < net.links.size()) strings_.resize(net.links.size());
    if (carried_.size() < net.carried.size()) carried_.resize(net.carried.size());
    carriedViews_.assign(net.carried.size(), sl::ValueRef{});
    last_ = &net;

    // The value `v` copied into `dst` (comps x n, or comps when uniform): a view of it.
    auto keep = [n](const sl::ValueRef& v, int comps, std::vector<float>& dst) {
        const size_t w = v.varying() ? n : 1;
        dst.resize(size_t(comps) * w);
        for (int c = 0; c < comps; ++c)
            for (size_t i = 0; i < w; ++i) dst[size_t(c) * w + i] = v.at(v.comp[c] ? c : 0, int(i));
        sl::ValueRef r;
        for (int c = 0; c < comps; ++c) r.comp[c] = dst.data() + size_t(c) * w;
        r.stride = v.varying() ? 1 : 0;
        return r;
    };

    size_t link = 0;
    for (size_t i = 0; i < layers; ++i) {
        grid.primvars = &primvars_[i];
        vm.run(*net.layers[i], grid, lights);
        if (i + 1 == layers) break;
        // What this layer leaves for the next (Ci and Oi, or P and N ...), then its connections'
        // values. A result the layer did not touch is its input, kept as it is.
        for (size_t c = 0; c < net.carried.size(); ++c) {
            const sl::Global g = net.carried[c];
            const sl::ValueRef r = vm.result(g);
            if (!r.valid()) continue;
            carriedViews_[c] = keep(r, sl::globalInfo(g).type.comps(), carried_[c]);
            grid.set(g, carriedViews_[c]);
        }
        for (; link < net.links.size() && net.links[link].from == int(i); ++link) {
            const LayerNetwork::Link& l = net.links[link];
            sl::Primvar pv;
            pv.name = l.toName;
            pv.type = l.type;
            if (l.string) {
                strings_[link] = vm.paramStrings(l.fromName);
                pv.strings = strings_[link];
                primvars_[size_t(l.to)].push_back(std::move(pv));
                continue;
            }
            const sl::ValueRef v = l.fromGlobal != sl::Global::Count ? vm.result(l.fromGlobal) : vm.param(l.fromName);
            if (!v.valid()) continue;  // a predefined variable the surface has no value of
            const sl::ValueRef kept = keep(v, l.type.comps(), values_[link]);
            if (l.toGlobal != sl::Global::Count) {
                grid.set(l.toGlobal, kept);
            } else {
                pv.value = kept;
                primvars_[size_t(l.to)].push_back(std::move(pv));
            }
        }
    }
    grid.globals = savedGlobals;
    grid.primvars = savedPrimvars;
}

sl::ValueRef LayerNetworkRunner::result(const sl::ShadingVM& vm, sl::Global g) const {
    if (last_ && !last_->layers.empty() && last_->layers.back()->program().globalReg[size_t(g)] < 0)
        for (size_t c = 0; c < last_->carried.size() && c < carriedViews_.size(); ++c)
            if (last_->carried[c] == g && carriedViews_[c].valid()) return carriedViews_[c];
    return vm.result(g);
}

}  // namespace streyes
