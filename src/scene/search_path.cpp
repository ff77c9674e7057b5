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

}  // namespace streyes
