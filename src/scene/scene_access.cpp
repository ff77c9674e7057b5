// What a scene may reach outside itself for (streyes/scene_access.h): the process's policy, and
// the one check every file a scene asks to write goes through.
#include "streyes/scene_access.h"

#include <filesystem>
#include <mutex>

namespace streyes {

namespace {
std::mutex accessMutex;
SceneAccess access;  // guarded by accessMutex
}  // namespace

void setSceneAccess(const SceneAccess& a) {
    std::lock_guard<std::mutex> lock(accessMutex);
    access = a;
}

SceneAccess sceneAccess() {
    std::lock_guard<std::mutex> lock(accessMutex);
    return access;
}

void checkSceneWrite(const std::string& request, const std::string& name, const SourceLoc& loc,
                     const std::string& base) {
    namespace fs = std::filesystem;
    const SceneAccess a = sceneAccess();
    if (a.writeFolder.empty()) return;
    const std::string what = request + " \"" + name + "\"";
    const std::string by = a.safe ? "--safe" : "this render";
    const std::string inside = "a scene may write only inside " + a.writeFolder;
    const std::string trust = a.safe ? ", or render without --safe only if you trust the scene" : "";
    const fs::path given(name);
    if (given.is_absolute())
        throw InputError(loc, what + ": " + by + " refuses an absolute path (" + inside + "): give a relative name" +
                                  trust);
    for (const fs::path& part : given)
        if (part == "..")
            throw InputError(loc, what + ": " + by + " refuses a path with \"..\" (" + inside +
                                      "): give a name without it" + trust);
    // Where it would land, symbolic links followed as far as the path exists: a link inside the
    // folder that points out of it does not let a scene out.
    std::error_code ec;
    const fs::path target = fs::absolute(base.empty() ? given : fs::path(base) / given, ec).lexically_normal();
    fs::path real = fs::weakly_canonical(target, ec);
    if (ec) real = target;
    fs::path root = fs::weakly_canonical(fs::absolute(a.writeFolder, ec), ec);
    if (ec) root = fs::absolute(a.writeFolder).lexically_normal();
    const fs::path rel = real.lexically_relative(root);
    const bool outside = rel.empty() || *rel.begin() == ".." || rel == ".";
    if (outside)
        throw InputError(loc, what + " would write '" + real.string() + "': " + by + " refuses it (" + inside + ")" +
                                  (a.safe ? ": give --safe-dir a folder that holds it" + trust : std::string()));
}

}  // namespace streyes
