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

// The command whose options are being read, for a usage error's last lines: its name ("render",
// "farm submit") and synopsis; set by CommandLine (command_line.h), empty before a command is known.
struct UsageContext {
    std::string command, synopsis;
};
UsageContext& usageContext();

// A whole number in [lo, hi] for option `opt`, or a UsageError naming both.
long parseInt(const std::string& opt, const std::string& value, long lo, long hi);
// A real number in [lo, hi].
double parseReal(const std::string& opt, const std::string& value, double lo, double hi);
// A frame range "A-B" or a single frame "A" (A may be negative: "-3-5").
void parseFrameRange(const std::string& opt, const std::string& value, int* first, int* last);
// The frames of a #### pattern: every frame of the range when given (the caller checks that the
// files exist), else those on disk (InputError when there are none).
std::vector<int> selectFrames(const std::string& pattern, bool hasRange, int first, int last);

// The commands, for `streyes --help` and a usage error before a command is known.
extern const char* kUsage;

int renderCommand(const std::vector<std::string>& args);

// `streyes compare A B`: error of B against the reference A (compare_command.cpp).
int compareCommand(const std::vector<std::string>& args);

// `streyes sheet PATTERN -o FILE`: frames laid out on one contact sheet (sheet_command.cpp).
int sheetCommand(const std::vector<std::string>& args);

// `streyes shader FILE.sl`: checks shaders and prints their parameters (shader_command.cpp).
int shaderCommand(const std::vector<std::string>& args);

// `streyes catrib FILE.rib ... -o OUT`: RIB written again as ASCII, binary or gzip (catrib_command.cpp).
int catribCommand(const std::vector<std::string>& args);

// `streyes farm submit|status|gather`: a shot on a Slurm cluster (farm_command.cpp, docs/FARM.md).
int farmCommand(const std::vector<std::string>& args);

}  // namespace streyes::cli
