// The Shading Language compiler's entry points and the shader cache the renderer uses.
//
//   ShaderCache cache;                          // searchpath "shaders" by default
//   ProgramPtr plastic = cache.get("plastic");  // compiled once per file and modification time
//   ShaderInstance inst(plastic);
//   inst.setDeclared("float Ks", {0.8f}, loc);  // RIB's Surface "plastic" "float Ks" [.8]
//
// A bad shader throws InputError whose message starts "file:line:column:".
#pragma once

#include <filesystem>
#include <iosfwd>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "shade/sl/optimize.h"
#include "shade/sl/preprocess.h"
#include "shade/vm/program.h"

namespace streyes::sl {

// Compiles `source` (preprocessed first: #include looks in `file`'s folder, then along
// options.includePath); `file` names it in errors and in ShaderProgram::path.
// `backend` turns the backend's optimisations off (tests compare the plain program's grids).
ProgramPtr compileShader(const std::string& source, const std::string& file = "<string>",
                         const PreprocessOptions& options = {}, const BackendOptions& backend = {});
// Compiles the file at `path` (InputError when it cannot be read).
ProgramPtr compileShaderFile(const std::string& path, const PreprocessOptions& options = {},
                             const BackendOptions& backend = {});

// Compiled shaders by name, found along a search path, each compiled once per file path and
// modification time of the file and of every file it #included (an edited file or header is
// compiled again); a shader's #include <name> and the headers its folder lacks are looked for
// along the same search path. Thread-safe: many threads may ask at once; programs are immutable
// and shared.
class ShaderCache {
  public:
    explicit ShaderCache(std::vector<std::string> searchPath = {"shaders"});
    // RIB's Option "searchpath" "shader": folders separated by ':'; '&' stands for the path
    // before, '@' for the default (the path the cache was made with).
    void setSearchPath(const std::string& colonSeparated);
    // Folders searched after the path's (STREYES_SHADERPATH's: the environment's after the scene's).
    void appendSearchPath(const std::vector<std::string>& folders);
    std::vector<std::string> searchPath() const;
    // `name` is "plastic", "plastic.sl", or a path. Not found, or a bad shader: InputError (at
    // `requestedAt` when not found: the RIB line that asked).
    ProgramPtr get(const std::string& name, const SourceLoc& requestedAt = {});
    // The file `name` resolves to, or "" when there is none.
    std::string find(const std::string& name) const;
    size_t compiledCount() const;  // compilations so far (cache misses)

  private:
    struct Entry {
        std::vector<std::filesystem::file_time_type> mtimes;  // of program->sources, in order
        std::vector<std::string> searchPath;                  // the includes were found along
        ProgramPtr program;
    };
    mutable std::mutex mutex_;
    std::vector<std::string> default_;  // what '@' stands for: the path the cache was made with
    std::vector<std::string> path_;
    std::map<std::string, Entry> byPath_;
    size_t compiled_ = 0;
};

// sloinfo: checks the shader at `path` (its #includes found as `options` says) and prints its
// type, name and parameters (with storage class, type and default) to `out`, its warnings to
// `err`. Returns 0, or 2 after printing the error to `err`.
int describeShader(const std::string& path, std::ostream& out, std::ostream& err, const PreprocessOptions& options = {});

}  // namespace streyes::sl
