#include "procedural/dynamic_load.h"

#include <dlfcn.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>

#include "scene/ri_stream.h"
#include "scene/search_path.h"
#include "streyes/rib.h"

namespace streyes {

namespace {

using ConvertFn = RtPointer (*)(RtString);
using SubdivideFn = RtVoid (*)(RtPointer, RtFloat);
using FreeFn = RtVoid (*)(RtPointer);

// A loaded plug-in; unloaded when the last generator using it goes.
struct Plugin {
    std::string path;
    void* handle = nullptr;
    ConvertFn convert = nullptr;
    SubdivideFn subdivide = nullptr;
    FreeFn free = nullptr;
    ~Plugin() {
        if (handle) dlclose(handle);
    }
};

struct Plugins {
    std::mutex mutex;
    std::map<std::string, std::weak_ptr<Plugin>> byPath;
};
Plugins& plugins() {
    static Plugins p;
    return p;
}

std::shared_ptr<Plugin> loadPlugin(const std::string& path, const SourceLoc& loc) {
    // The plug-in calls the program's Ri functions: they must all be linked in (ri_stream.h).
    static const int linked = riApiFunctionCount();
    (void)linked;
    std::lock_guard<std::mutex> lock(plugins().mutex);
    std::weak_ptr<Plugin>& slot = plugins().byPath[std::filesystem::absolute(path).lexically_normal().string()];
    if (std::shared_ptr<Plugin> p = slot.lock()) return p;
    auto p = std::make_shared<Plugin>();
    p->path = path;
    dlerror();
    p->handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!p->handle) {
        const char* why = dlerror();
        throw InputError(loc, "DynamicLoad: cannot load the plug-in '" + path + "': " + (why ? why : "unknown error") +
                                  " (build it as a shared object for this machine; it may call only the Ri functions "
                                  "of include/ri.h, which a program linking streyes exports)");
    }
    p->convert = reinterpret_cast<ConvertFn>(dlsym(p->handle, "ConvertParameters"));
    p->subdivide = reinterpret_cast<SubdivideFn>(dlsym(p->handle, "Subdivide"));
    p->free = reinterpret_cast<FreeFn>(dlsym(p->handle, "Free"));
    std::string missing;
    if (!p->convert) missing += " ConvertParameters";
    if (!p->subdivide) missing += " Subdivide";
    if (!p->free) missing += " Free";
    if (!missing.empty())
        throw InputError(loc, "DynamicLoad: the plug-in '" + path + "' does not export" + missing +
                                  " (a procedural plug-in exports ConvertParameters, Subdivide and Free with C "
                                  "linkage: extern \"C\" in C++; see include/ri.h)");
    slot = p;
    return p;
}

// What a plug-in's children inherit from the procedural that made them: where names are looked
// up, and what keeps the code of the function procedurals they hold loaded.
struct Lineage {
    std::string directory, proceduralPath = kDefaultSearchPath, archivePath = kDefaultSearchPath;
    std::shared_ptr<const void> keep;  // the plug-in, if any
};

class FunctionGenerator;

// One expansion: `subdivide` runs with a fresh stream current on this thread; the stream's RIB
// becomes the children. Errors name the procedural and the call at fault.
void expandThroughStream(const ExpandContext& ctx, const std::string& what, const Lineage& lineage,
                         const std::function<void()>& subdivide, ProceduralOutput& out);

// RiProcedural with a function of the program's (or a plug-in's) own.
class FunctionGenerator final : public ProceduralGenerator {
  public:
    FunctionGenerator(std::shared_ptr<RiFunctionProcedural> f, Lineage lineage)
        : lineage_(std::move(lineage)), f_(std::move(f)) {}
    std::string describe() const override { return "RiProcedural function " + f_->id; }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const float detail = float(std::min(ctx.detail, double(RI_INFINITY)));
        expandThroughStream(ctx, "RiProcedural function", lineage_, [&] { f_->subdivide(f_->data, detail); }, out);
    }

  private:
    Lineage lineage_;                          // keeps the plug-in the function is in loaded...
    std::shared_ptr<RiFunctionProcedural> f_;  // ...until after this (declared later) is freed
};

// Procedural "DynamicLoad" ["name" "parameters"] with a plug-in.
class PluginGenerator final : public ProceduralGenerator {
  public:
    PluginGenerator(std::shared_ptr<Plugin> plugin, std::string name, RtPointer data, Lineage lineage)
        : plugin_(std::move(plugin)), name_(std::move(name)), data_(data), lineage_(std::move(lineage)) {
        lineage_.keep = plugin_;
    }
    ~PluginGenerator() override { plugin_->free(data_); }
    std::string describe() const override { return "DynamicLoad '" + name_ + "'"; }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const float detail = float(std::min(ctx.detail, double(RI_INFINITY)));
        expandThroughStream(ctx, describe(), lineage_, [&] { plugin_->subdivide(data_, detail); }, out);
    }

  private:
    std::shared_ptr<Plugin> plugin_;
    std::string name_;
    RtPointer data_;
    Lineage lineage_;
};

void expandThroughStream(const ExpandContext& ctx, const std::string& what, const Lineage& lineage,
                         const std::function<void()>& subdivide, ProceduralOutput& out) {
    RiStream stream(what);
    {
        RiStreamScope scope(&stream);
        subdivide();
    }
    if (!stream.error().empty()) throw InputError(ctx.loc, what + ": a bad call in Subdivide: " + stream.error());
    Scene& scene = out.scene;
    try {
        scene = parseRibFragment(stream.text(), what + " calls", ctx.objectToWorld, ctx.attributes, *ctx.log, ctx.read);
    } catch (const InputError& e) {
        // The stream holds one request a line: line n is the n-th call.
        throw InputError(ctx.loc, what + ": a bad call in Subdivide: call " + std::to_string(e.loc.line) + ": " +
                                      e.message);
    }
    if (!scene.lights.empty()) {
        ctx.log->warnOnce("procedural-lights", ctx.loc, "lights declared by a procedural are ignored");
        scene.lights.clear();
    }
    std::vector<ProceduralDesc> kept;
    for (ProceduralDesc& p : scene.procedurals) {
        p.directory = lineage.directory;
        p.proceduralPath = lineage.proceduralPath;
        p.archivePath = lineage.archivePath;
        auto f = p.kind == kRiFunctionKind && p.args.size() == 1 ? stream.functions().find(p.args[0])
                                                                 : stream.functions().end();
        if (f == stream.functions().end()) {
            kept.push_back(std::move(p));
            continue;
        }
        GeneratedProcedural g;
        g.generator = std::make_shared<FunctionGenerator>(f->second, lineage);
        g.desc = std::move(p);
        out.procedurals.push_back(std::move(g));
    }
    scene.procedurals = std::move(kept);
}

Lineage lineageOf(const ProceduralDesc& desc) {
    Lineage l;
    l.directory = desc.directory;
    l.proceduralPath = desc.proceduralPath;
    l.archivePath = desc.archivePath;
    return l;
}

}  // namespace

std::string findPlugin(const std::string& name, const ProceduralDesc& desc) {
    return findPluginFile(name, desc.proceduralPath, desc.directory);
}

std::shared_ptr<const ProceduralGenerator> makePluginGenerator(const ProceduralDesc& desc) {
    const std::string& name = desc.args.at(0);
    const std::string path = findPlugin(name, desc);
    if (path.empty()) {
        const std::string where = pluginSearchDescription(name, desc.proceduralPath, desc.directory);
        throw InputError(desc.loc, "DynamicLoad: no plug-in '" + name + "' (looked for '" + name + "' and '" + name +
                                       ".so' " + where +
                                       "); give its path, or add its folder with Option \"searchpath\" \"procedural\" "
                                       "[\"folder:&\"] or " + kProceduralPathVariable +
                                       "; the built-in generators are \"forest\" and \"tree\"");
    }
    std::shared_ptr<Plugin> plugin = loadPlugin(path, desc.loc);
    const std::string params = desc.args.size() > 1 ? desc.args[1] : "";
    RtPointer data = plugin->convert(params.c_str());
    return std::make_shared<PluginGenerator>(std::move(plugin), name, data, lineageOf(desc));
}

std::shared_ptr<const ProceduralGenerator> makeFunctionGenerator(const ProceduralDesc& desc) {
    std::shared_ptr<RiFunctionProcedural> f = desc.args.size() == 1 ? findRiFunction(desc.args[0]) : nullptr;
    if (!f)
        throw InputError(desc.loc, std::string("Procedural \"") + kRiFunctionKind +
                                       "\" names a function procedural that no RI session holds (only RiProcedural "
                                       "writes these)");
    return std::make_shared<FunctionGenerator>(std::move(f), lineageOf(desc));
}

}  // namespace streyes
