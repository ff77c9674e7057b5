// Shared pieces of the streyes command line: usage errors and argument parsing.
// Each command lives in its own file (render_command.cpp, ...) and is dispatched by main.cpp.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace streyes::cli {

// Bad usage: printed with the usage text, exit code 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A whole number in [lo, hi] for option `opt`, or a UsageError naming both.
long parseInt(const std::string& opt, const std::string& value, long lo, long hi);
// A real number in [lo, hi].
double parseReal(const std::string& opt, const std::string& value, double lo, double hi);

extern const char* kUsage;

int renderCommand(const std::vector<std::string>& args);

}  // namespace streyes::cli
