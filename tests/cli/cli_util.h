// Running the streyes command in tests: its exit code and output, files in a folder.
#pragma once

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace streyes::test {

struct CliRun {
    int exitCode = -1;   // -1 when the process did not exit normally (a signal, a crash)
    std::string output;  // stdout and stderr
};

// Runs `STREYES_EXE args` through the shell (args may redirect or hold shell syntax), with
// `prefix` before the command (an environment, a privilege drop).
inline CliRun runStreyes(const std::string& args, const std::string& prefix = "") {
    CliRun r;
    std::string cmd = prefix + std::string(STREYES_EXE) + " " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
    int status = pclose(p);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

inline std::string writeFile(const std::string& dir, const std::string& name, const std::string& text) {
    std::string path = dir + "/" + name;
    std::ofstream(path) << text;
    return path;
}

// File names in `dir`, hidden ones included, sorted.
inline std::vector<std::string> listDir(const std::string& dir) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace streyes::test
