// Running the streyes executable from a test: exit code and everything it printed.
// Header-only, for the tests in tests/cli/ (which know STREYES_EXE).
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace streyes::test {

struct CliRun {
    int exitCode = -1;
    std::string output;  // stdout and stderr
};

// Runs `streyes ARGS` through the shell. The output holds stdout, and stderr too unless
// `withStderr` is false (then stderr is dropped: for parsing --json output).
inline CliRun runStreyes(const std::string& args, bool withStderr = true) {
    CliRun r;
    std::string cmd = std::string(STREYES_EXE) + " " + args + (withStderr ? " 2>&1" : " 2>/dev/null");
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

}  // namespace streyes::test
