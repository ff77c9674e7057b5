#include "streyes/error.h"

#include <cstdio>

namespace streyes {

std::string SourceLoc::str() const {
    if (!file) return "";
    if (offset >= 0) return *file + ", byte " + std::to_string(offset);
    std::string s = *file + ":" + std::to_string(line);
    return column > 0 ? s + ":" + std::to_string(column) : s;
}

static std::string withLoc(const SourceLoc& loc, const std::string& what) {
    std::string where = loc.str();
    return where.empty() ? what : where + ": " + what;
}

InputError::InputError(const SourceLoc& l, const std::string& what)
    : std::runtime_error(withLoc(l, what)), loc(l), message(what) {}

std::string InputError::report() const {
    std::string where = loc.str();
    return (where.empty() ? std::string("streyes") : where) + ": error: " + message;
}

void Log::warn(const SourceLoc& loc, const std::string& what) {
    std::string msg = withLoc(loc, "warning: " + what);
    std::lock_guard<std::mutex> lock(mutex_);
    warnings_.push_back(msg);
    if (echo_ && !quiet_) std::fprintf(stderr, "%s\n", msg.c_str());
}

void Log::warnOnce(const std::string& key, const SourceLoc& loc, const std::string& what) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!said_.insert(key).second) return;
    }
    warn(loc, what);
}

void Log::lenient(const std::string& key, const SourceLoc& loc, const std::string& what) {
    if (strict_) throw InputError(loc, what + " (an error under --strict)");
    warnOnce(key, loc, what);
}

void Log::info(const std::string& what) {
    if (echo_ && !quiet_) std::fprintf(stderr, "%s\n", what.c_str());
}

std::vector<std::string> Log::warnings() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return warnings_;
}

}  // namespace streyes
