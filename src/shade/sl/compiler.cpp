#include "shade/sl/compiler.h"

#include <fstream>
#include <ostream>
#include <sstream>

#include "shade/sl/checker.h"
#include "shade/sl/codegen.h"
#include "shade/sl/parser.h"
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
        for (int e = 0; e < elems; ++e) {
            ValueRef v = vm.param(info.name, e);
            for (int c = 0; c < comps; ++c) info.defaultFloats.push_back(info.type.isMatrix() ? v.comp[0][c] : v.at(c, 0));
        }
    }
}

}  // namespace

ProgramPtr compileShader(const std::string& source, const std::string& file) {
    CheckedShader checked = checkShader(parseShader(source, file));
    auto program = std::make_shared<ShaderProgram>();
    program->path = file;
    generateCode(checked, *program);
    program->path = file;
    ProgramPtr shared = program;
    evaluateDefaults(shared);
    return shared;
}

ProgramPtr compileShaderFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot read shader " + path);
    std::stringstream ss;
    ss << in.rdbuf();
    return compileShader(ss.str(), path);
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
    if (path.empty()) {
        std::string dirs;
        for (const std::string& d : searchPath()) dirs += (dirs.empty() ? "" : ":") + d;
        throw InputError(requestedAt, "shader \"" + name + "\" not found (searchpath " + dirs + ")");
    }
    std::error_code ec;
    auto mtime = std::filesystem::last_write_time(path, ec);
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = byPath_.find(path);
    if (it != byPath_.end() && it->second.mtime == mtime) return it->second.program;
    ProgramPtr p = compileShaderFile(path);  // under the lock: each file is compiled once
    ++compiled_;
    byPath_[path] = {mtime, p};
    return p;
}

size_t ShaderCache::compiledCount() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return compiled_;
}

// ---- describeShader ------------------------------------------------------------------------------

int describeShader(const std::string& path, std::ostream& out, std::ostream& err) {
    ProgramPtr p;
    try {
        p = compileShaderFile(path);
    } catch (const InputError& e) {
        err << e.report() << "\n";
        return 2;
    }
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
