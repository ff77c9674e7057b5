// Running the streyes executable from a test: exit code and everything it printed.
// Header-only, for the tests in tests/cli/ (which know STREYES_EXE).
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace streyes::test {

struct CliRun {
    int exitCode = -1;   // -1 when the process did not exit normally (a signal, a crash)
    std::string output;  // stdout and stderr
};

// Runs the shell command `prefix` `streyes ARGS` (the prefix may set a limit, an environment or
// drop privileges: "ulimit -f 4; ", "setpriv ... "). The output holds stdout, and stderr too
// unless `withStderr` is false.
inline CliRun runStreyesWith(const std::string& prefix, const std::string& args, bool withStderr = true) {
    CliRun r;
    std::string cmd = prefix + std::string(STREYES_EXE) + " " + args + (withStderr ? " 2>&1" : " 2>/dev/null");
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
    int status = pclose(p);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// Runs `streyes ARGS` through the shell. The output holds stdout, and stderr too unless
// `withStderr` is false (then stderr is dropped: for parsing --json output).
inline CliRun runStreyes(const std::string& args, bool withStderr = true) { return runStreyesWith("", args, withStderr); }

// Runs `streyes ARGS` with stderr going to the file `stderrPath` (neither a terminal nor a pipe,
// as in a render farm's log) and stdout dropped. Returns the exit code, -1 when it did not exit.
inline int runStreyesLogged(const std::string& args, const std::string& stderrPath) {
    const std::string cmd = std::string(STREYES_EXE) + " " + args + " >/dev/null 2>" + stderrPath;
    const int status = std::system(cmd.c_str());
    return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A run of `streyes ARGS` in folder `cwd`, its address space capped at `addressSpaceBytes` (0: no
// cap) so that a bug that allocates without bound fails there rather than taking the machine's
// memory, with its peak resident memory as wait4 reports it (ru_maxrss). That figure starts from
// the test process's own at the fork (the child's memory before exec counts): an upper bound, for
// checks of gigabytes; `streyes render --stats` reports the render's own peak.
struct MeasuredRun {
    int exitCode = -1;  // -1 when the process did not exit normally (a signal, a crash)
    std::string output;  // stdout and stderr
    long peakResidentBytes = 0;
};
inline MeasuredRun runStreyesMeasured(const std::vector<std::string>& args, const std::string& cwd = "",
                                      unsigned long addressSpaceBytes = 0) {
    MeasuredRun r;
    int fds[2];
    if (pipe(fds) != 0) return r;
    const pid_t pid = fork();
    if (pid == 0) {
        dup2(fds[1], 1);
        dup2(fds[1], 2);
        close(fds[0]);
        close(fds[1]);
        if (!cwd.empty() && chdir(cwd.c_str()) != 0) _exit(126);
        if (addressSpaceBytes > 0) {
            struct rlimit lim {addressSpaceBytes, addressSpaceBytes};
            setrlimit(RLIMIT_AS, &lim);
        }
        std::vector<char*> argv;
        argv.push_back(const_cast<char*>(STREYES_EXE));
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        execv(STREYES_EXE, argv.data());
        _exit(127);
    }
    close(fds[1]);
    char buf[4096];
    ssize_t n;
    while ((n = read(fds[0], buf, sizeof buf)) > 0) r.output.append(buf, size_t(n));
    close(fds[0]);
    int status = 0;
    struct rusage ru {};
    if (pid > 0 && wait4(pid, &status, 0, &ru) == pid) {
        r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        r.peakResidentBytes = ru.ru_maxrss * 1024L;  // Linux reports kilobytes
    }
    return r;
}

inline std::string readFile(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
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
