#include "scene/search_path.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

namespace streyes {

std::string expandSearchPath(const std::string& spec, const std::string& previous) {
    std::string out;
    for (char c : spec) {
        if (c == '&') out += previous;
        else out += c;
    }
    return out;
}

std::vector<std::string> searchPathFolders(const std::string& path, const std::string& directory) {
    std::vector<std::string> folders;
    size_t start = 0;
    while (start <= path.size()) {
        size_t end = path.find(':', start);
        if (end == std::string::npos) end = path.size();
        std::string f = path.substr(start, end - start);
        if (f == "@") f = directory.empty() ? "." : directory;
        if (!f.empty()) folders.push_back(f);
        start = end + 1;
    }
    return folders;
}

std::vector<std::string> environmentSearchPath(const char* variable) {
    std::vector<std::string> folders;
    const char* value = std::getenv(variable);
    if (!value) return folders;
    const std::string path = value;
    for (size_t start = 0; start <= path.size();) {
        const size_t end = std::min(path.find(':', start), path.size());
        if (end > start) folders.push_back(path.substr(start, end - start));
        start = end + 1;
    }
    return folders;
}

std::string findOnSearchPath(const std::string& name, const std::string& path, const std::string& directory,
                             const std::vector<std::string>& suffixes) {
    namespace fs = std::filesystem;
    std::error_code ec;
    for (const std::string& folder : searchPathFolders(path, directory)) {
        const fs::path p = fs::path(folder) / name;
        if (fs::is_regular_file(p, ec)) return p.string();
        for (const std::string& s : suffixes) {
            const fs::path q = fs::path(folder) / (name + s);
            if (fs::is_regular_file(q, ec)) return q.string();
        }
    }
    return "";
}

std::string findPluginFile(const std::string& name, const std::string& path, const std::string& directory) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (name.empty()) return "";
    if (name.find('/') == std::string::npos) {
        const std::string found = findOnSearchPath(name, path, directory, {".so"});
        if (!found.empty()) return found;
        for (const std::string& folder : environmentSearchPath(kProceduralPathVariable)) {
            const std::string inEnv = findOnSearchPath(name, folder, "", {".so"});
            if (!inEnv.empty()) return inEnv;
        }
        return "";
    }
    std::vector<std::string> candidates;
    if (fs::path(name).is_relative() && !directory.empty()) candidates.push_back((fs::path(directory) / name).string());
    candidates.push_back(name);
    for (const std::string& c : candidates)
        for (const std::string& p : {c, c + ".so"})
            if (fs::is_regular_file(p, ec)) return p;
    return "";
}

std::string pluginSearchDescription(const std::string& name, const std::string& path, const std::string& directory) {
    if (name.find('/') != std::string::npos) return "beside this file or from the current folder";
    std::string where;
    for (const std::string& f : searchPathFolders(path, directory)) where += (where.empty() ? "in " : ", ") + f;
    for (const std::string& f : environmentSearchPath(kProceduralPathVariable))
        where += ", " + f + " (" + kProceduralPathVariable + ")";
    return where;
}

}  // namespace streyes
