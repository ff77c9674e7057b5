#include "shade/sl/compiler.h"

#include <fstream>
#include <ostream>
#include <sstream>

#include "shade/sl/checker.h"
#include "shade/sl/codegen.h"
#include "shade/sl/parser.h"
#include "shade/sl/view_use.h"
#include "shade/vm/vm.h"

namespace streyes::sl {

namespace {

// Parameter defaults as values: the defaults' code run over one point with every space the
// identity (what describe prints; the renderer recomputes them per grid).
void evaluateDefaults(const ProgramPtr& program) {
    ShaderProgram& p = const_cast<ShaderProgram&>(*program);  // still private to the compiler
    ShaderInstance instance(program);
    ShadingGrid grid;
    grid.n = 1;
    ShadingVM vm;
    vm.bindParams(instance, grid);
    for (ParamInfo& info : p.params) {
        if (info.type.isString()) {
            info.defaultStrings = vm.paramStrings(info.name);
            continue;
        }
        const int comps = info.type.comps(), elems = info.type.elements();
        info.defaultFloats.clear();
        for (int e = 0; info.type.isResizable() || e < elems; ++e) {  // resizable: as long as its default
            ValueRef v = vm.param(info.name, e);
            if (!v.valid()) break;
            for (int c = 0; c < comps; ++c) info.defaultFloats.push_back(info.type.isMatrix() ? v.comp[0][c] : v.at(c, 0));
        }
    }
}

}  // namespace

ProgramPtr compileShader(const std::string& source, const std::string& file, const PreprocessOptions& options,
                         const BackendOptions& backend) {
    PreprocessedSource pp = preprocess(source, file, options);
    auto program = std::make_shared<ShaderProgram>();
    try {
        CheckedShader checked = checkShader(parseShader(pp));
        program->path = file;
        generateCode(checked, *program, backend);
        const ViewUseResult use = analyzeViewUse(checked);
        program->viewUse = use.use;
        program->viewUseWhy = use.why;
    } catch (const InputError& e) {
        // An error at a token a macro made: say which call of the macro it is about.
        const std::string site = pp.expansionOf(e.loc);
        if (site.empty()) throw;
        throw InputError(e.loc, e.message + " (" + site + ")");
    }
    program->path = file;
    program->sources = std::move(pp.files);
    for (auto& [loc, what] : pp.warnings) program->warnings.push_back({loc, what});
    ProgramPtr shared = program;
    evaluateDefaults(shared);
    return shared;
}

ProgramPtr compileShaderFile(const std::string& path, const PreprocessOptions& options, const BackendOptions& backend) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot read shader " + path);
    std::stringstream ss;
    ss << in.rdbuf();
    return compileShader(ss.str(), path, options, backend);
}

// ---- ShaderCache ---------------------------------------------------------------------------------

ShaderCache::ShaderCache(std::vector<std::string> searchPath) : default_(searchPath), path_(std::move(searchPath)) {}

void ShaderCache::setSearchPath(const std::string& spec) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> before = path_, out;
    std::string item;
    std::istringstream in(spec);
    while (std::getline(in, item, ':')) {
        if (item == "&") out.insert(out.end(), before.begin(), before.end());
        else if (item == "@") out.insert(out.end(), default_.begin(), default_.end());
        else if (!item.empty()) out.push_back(item);
    }
    path_ = out;
}

void ShaderCache::appendSearchPath(const std::vector<std::string>& folders) {
    std::lock_guard<std::mutex> lock(mutex_);
    path_.insert(path_.end(), folders.begin(), folders.end());
}

std::vector<std::string> ShaderCache::searchPath() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return path_;
}

std::string ShaderCache::find(const std::string& name) const {
    namespace fs = std::filesystem;
    std::vector<std::string> dirs = searchPath();
    auto candidates = [&](const fs::path& base) {
        std::vector<fs::path> c{base};
        if (base.extension() != ".sl") c.push_back(fs::path(base.string() + ".sl"));
        return c;
    };
    std::error_code ec;
    if (name.find('/') != std::string::npos) {
        for (const fs::path& p : candidates(name))
            if (fs::is_regular_file(p, ec)) return p.string();
        return "";
    }
    for (const std::string& d : dirs)
        for (const fs::path& p : candidates(fs::path(d) / name))
            if (fs::is_regular_file(p, ec)) return p.string();
    return "";
}

ProgramPtr ShaderCache::get(const std::string& name, const SourceLoc& requestedAt) {
    std::string path = find(name);
    const std::vector<std::string> dirs = searchPath();
    if (path.empty()) {
        std::string list;
        for (const std::string& d : dirs) list += (list.empty() ? "" : ":") + d;
        throw InputError(requestedAt, "shader \"" + name + "\" not found (searchpath " + list + ")");
    }
    auto mtimes = [](const std::vector<std::string>& files) {
        std::vector<std::filesystem::file_time_type> t;
        for (const std::string& f : files) {
            std::error_code ec;
            t.push_back(std::filesystem::last_write_time(f, ec));
        }
        return t;
    };
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = byPath_.find(path);
    // The same file and headers, unchanged, found along the same path: the same program.
    if (it != byPath_.end() && it->second.searchPath == dirs && it->second.mtimes == mtimes(it->second.program->sources))
        return it->second.program;
    PreprocessOptions options;
    options.includePath = dirs;
    ProgramPtr p = compileShaderFile(path, options);  // under the lock: each file is compiled once
    ++compiled_;
    byPath_[path] = {mtimes(p->sources), dirs, p};
    return p;
}

size_t ShaderCache::compiledCount() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return compiled_;
}

// ---- describeShader ------------------------------------------------------------------------------

int describeShader(const std::string& path, std::ostream& out, std::ostream& err, const PreprocessOptions& options) {
    ProgramPtr p;
    try {
        p = compileShaderFile(path, options);
    } catch (const InputError& e) {
        err << e.report() << "\n";
        return 2;
    }
    for (const ShaderProgram::Warning& w : p->warnings) err << w.str() << "\n";
    out << shaderTypeName(p->type) << " \"" << p->name << "\"\n";
    for (const ParamInfo& info : p->params) {
        out << "    \"" << info.name << "\" \"" << (info.output ? "output " : "") << detailName(info.detail) << " "
            << info.type.name() << "\"\n\t\tDefault value: ";
        if (info.type.isString()) {
            for (size_t i = 0; i < info.defaultStrings.size(); ++i) out << (i ? " " : "") << '"' << info.defaultStrings[i] << '"';
        } else {
            const bool many = info.defaultFloats.size() > 1;
            if (many) out << "[";
            for (size_t i = 0; i < info.defaultFloats.size(); ++i) out << (i ? " " : "") << info.defaultFloats[i];
            if (many) out << "]";
        }
        // The expression as written, when it says more than the value (radians(30), a space).
        if (info.defaultText.find_first_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ(") != std::string::npos &&
            !info.type.isString())
            out << "  (" << info.defaultText << ")";
        out << "\n";
    }
    return 0;
}

}  // namespace streyes::sl
