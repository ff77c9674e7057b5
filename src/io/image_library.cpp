#include "io/image_library.h"

#include <dlfcn.h>
#include <unistd.h>

#include <filesystem>
#include <mutex>

#include "streyes/error.h"

#ifndef STREYES_MODULE_DIR  // the installed module's folder (CMake gives it)
#define STREYES_MODULE_DIR ""
#endif
#ifndef STREYES_MODULE_RELATIVE_DIR  // the same, relative to the installed executable's
#define STREYES_MODULE_RELATIVE_DIR "../lib/streyes"
#endif

namespace streyes {

namespace {

const char* kModule = "libstreyes_oiio.so";

// Where the module may be: beside the running program (the build tree), the installed library
// folder relative to it (bin/../lib/streyes), the installed folder itself, then the loader's path.
std::vector<std::string> candidates() {
    namespace fs = std::filesystem;
    std::vector<std::string> c;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        c.push_back((exe.parent_path() / kModule).string());
        c.push_back((exe.parent_path() / STREYES_MODULE_RELATIVE_DIR / kModule).lexically_normal().string());
    }
    if (std::string(STREYES_MODULE_DIR).size()) c.push_back(std::string(STREYES_MODULE_DIR) + "/" + kModule);
    c.push_back(kModule);
    return c;
}

const ImageLibrary* load() {
    std::string tried, why;
    for (const std::string& path : candidates()) {
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* e = dlerror();
            if (why.empty() && e && std::filesystem::exists(path)) why = e;  // there, but broken
            tried += (tried.empty() ? "" : ", ") + path;
            continue;
        }
        auto entry = reinterpret_cast<const ImageLibrary* (*)()>(dlsym(handle, "streyesImageLibrary"));
        if (entry) return entry();
        why = path + " has no streyesImageLibrary";
    }
    throw RenderError("cannot load the image library module (" + std::string(kModule) + ", needed for images other " +
                      "than EXR frames and for contact sheets): looked in " + tried + (why.empty() ? "" : "; " + why) +
                      " (reinstall streyes, or build the streyes_oiio target)");
}

}  // namespace

const ImageLibrary& imageLibrary() {
    static std::once_flag once;
    static const ImageLibrary* library = nullptr;
    static std::string failure;
    std::call_once(once, [] {
        try {
            library = load();
        } catch (const RenderError& e) {
            failure = e.what();
        }
    });
    if (!library) throw RenderError(failure);
    return *library;
}

}  // namespace streyes
