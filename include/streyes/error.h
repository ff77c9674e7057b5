// Errors and warnings that name where in the input they come from.
//
// InputError is bad input (a malformed scene, a bad option): the CLI prints it as
// "file:line: error: what" and exits 2. RenderError is a failure while rendering or writing
// (an unwritable folder, a full disk): exit 1. Warnings go through a Log so that tests can
// capture them and so that each kind of warning is said once, not once per body.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace streyes {

// A place in the input. `file` is shared: thousands of locations point at one string.
struct SourceLoc {
    std::shared_ptr<const std::string> file;
    int line = 0;
    int column = 0;  // 1-based; 0 when unknown (RIB locations carry lines only)
    // Binary RIB, where lines mean little: the byte the token or request starts at, counted in the
    // (decompressed) stream; -1 for text.
    long long offset = -1;
    // "scene.rib:12" ("shader.sl:12:5" with a column, "scene.rib, byte 1234" in binary RIB), or ""
    // when unknown.
    std::string str() const;
};

class InputError : public std::runtime_error {
  public:
    InputError(const SourceLoc& loc, const std::string& what);
    explicit InputError(const std::string& what) : std::runtime_error(what), message(what) {}
    SourceLoc loc;
    std::string message;  // without the location
    // "file:line: error: message" (or "streyes: error: message" without a location)
    std::string report() const;
};

class RenderError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Thread-safe sink for warnings. `warnOnce` keys on a category string so that, say, an
// unsupported request warns the first time only.
class Log {
  public:
    void warn(const SourceLoc& loc, const std::string& what);
    void warnOnce(const std::string& key, const SourceLoc& loc, const std::string& what);
    // What the peers (PRMan, Aqsis) warn about and render without: a request streyes does not
    // know or leaves out, one in the wrong block, a parameter a shader does not have, an option
    // or attribute that changes the picture elsewhere. Said once per key, like warnOnce; under
    // setStrict(true) (streyes render --strict) an InputError instead, so that a pipeline can
    // refuse a scene whose picture would lack something it asks for.
    void lenient(const std::string& key, const SourceLoc& loc, const std::string& what);
    void setStrict(bool s) { strict_ = s; }
    bool strict() const { return strict_; }
    void info(const std::string& what);
    std::vector<std::string> warnings() const;
    void setQuiet(bool q) { quiet_ = q; }  // quiet: keep warnings, do not print them
    void setEcho(bool e) { echo_ = e; }    // echo: print to stderr as they come (CLI)

  private:
    mutable std::mutex mutex_;
    std::vector<std::string> warnings_;
    std::set<std::string> said_;
    bool quiet_ = false;
    bool echo_ = false;
    std::atomic<bool> strict_{false};
};

}  // namespace streyes
