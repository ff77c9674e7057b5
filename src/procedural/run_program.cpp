#include "procedural/run_program.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>

extern char** environ;

namespace streyes {

std::vector<std::string> splitCommandLine(const std::string& commandLine) {
    std::vector<std::string> words;
    std::istringstream in(commandLine);
    std::string w;
    while (in >> w) words.push_back(w);
    return words;
}

std::string findProgram(const std::string& name) {
    auto runnable = [](const std::string& p) {
        struct stat st {};
        return stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(p.c_str(), X_OK) == 0;
    };
    if (name.empty()) return "";
    if (name.find('/') != std::string::npos) return runnable(name) ? name : "";
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path ? path : "/usr/bin:/bin");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        std::string p = (dir.empty() ? std::string(".") : dir) + "/" + name;
        if (runnable(p)) return p;
    }
    return "";
}

namespace {

// One running helper program.
class Child {
  public:
    Child(const std::string& commandLine, const SourceLoc& loc) : commandLine_(commandLine) {
        // A program that dies while we write to it must not kill the renderer with SIGPIPE.
        static std::once_flag ignorePipe;
        std::call_once(ignorePipe, [] { signal(SIGPIPE, SIG_IGN); });
        std::vector<std::string> argv = splitCommandLine(commandLine);
        if (argv.empty()) throw InputError(loc, "RunProgram: no program given");
        if (findProgram(argv[0]).empty())
            throw InputError(loc, "RunProgram: cannot run '" + argv[0] +
                                      "': no such program (give a path, or put it on PATH)");
        int in[2], out[2];
        if (pipe(in) != 0 || pipe(out) != 0) throw InputError(loc, std::string("RunProgram: pipe: ") + std::strerror(errno));
        posix_spawn_file_actions_t fa;
        posix_spawn_file_actions_init(&fa);
        posix_spawn_file_actions_adddup2(&fa, in[0], 0);
        posix_spawn_file_actions_adddup2(&fa, out[1], 1);
        for (int fd : {in[0], in[1], out[0], out[1]}) posix_spawn_file_actions_addclose(&fa, fd);
        std::vector<char*> args;
        for (std::string& a : argv) args.push_back(a.data());
        args.push_back(nullptr);
        int rc = posix_spawnp(&pid_, args[0], &fa, nullptr, args.data(), environ);
        posix_spawn_file_actions_destroy(&fa);
        close(in[0]);
        close(out[1]);
        toChild_ = in[1];
        fromChild_ = out[0];
        fcntl(toChild_, F_SETFD, FD_CLOEXEC);
        fcntl(fromChild_, F_SETFD, FD_CLOEXEC);
        if (rc != 0) {
            close(toChild_);
            close(fromChild_);
            throw InputError(loc, "RunProgram: cannot run '" + argv[0] + "': " + std::strerror(rc));
        }
    }
    ~Child() { finish(); }

    bool alive() const { return pid_ > 0; }

    // One request and its answer; false when the program ended (the answer is what it wrote).
    std::string request(const std::string& line, const SourceLoc& loc, double timeout) {
        if (!writeAll(line)) return failed(loc, "", "it stopped reading its input");
        std::string answer;
        char buf[65536];
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
        while (true) {
            const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
            if (left <= 0) {
                kill(pid_, SIGKILL);
                finish();
                throw InputError(loc, "RunProgram '" + commandLine_ + "' did not answer within " +
                                          std::to_string(int(timeout)) + " s");
            }
            pollfd p{fromChild_, POLLIN, 0};
            int r = poll(&p, 1, int(std::min(left, 1.0) * 1000) + 1);
            if (r < 0 && errno == EINTR) continue;
            if (r <= 0) continue;
            ssize_t n = read(fromChild_, buf, sizeof buf);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;  // the program closed its output
            answer.append(buf, size_t(n));
            if (answer.back() == '\377') {
                answer.pop_back();
                return answer;
            }
        }
        return failed(loc, answer, "");
    }

  private:
    bool writeAll(const std::string& s) {
        size_t done = 0;
        while (done < s.size()) {
            ssize_t n = write(toChild_, s.data() + done, s.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) return false;
            done += size_t(n);
        }
        return true;
    }

    // The program ended: its answer counts when it exited cleanly, else it is an error.
    std::string failed(const SourceLoc& loc, const std::string& answer, const std::string& why) {
        int status = finish();
        if (why.empty() && WIFEXITED(status) && WEXITSTATUS(status) == 0) return answer;
        // A program that ended before reading its request (why: "it stopped reading") also says how
        // it ended, when that was not cleanly.
        std::string how = why;
        if (how.empty() || !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
            const std::string end = WIFEXITED(status) ? "it exited with status " + std::to_string(WEXITSTATUS(status))
                                                      : "it was killed by signal " + std::to_string(WTERMSIG(status));
            how = how.empty() ? end : how + "; " + end;
        }
        throw InputError(loc, "RunProgram '" + commandLine_ + "' failed: " + how + " (its messages, if any, are above)");
    }

    int finish() {
        int status = 0;
        if (toChild_ >= 0) close(toChild_);
        if (fromChild_ >= 0) close(fromChild_);
        toChild_ = fromChild_ = -1;
        if (pid_ > 0) {
            while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
            }
            pid_ = -1;
        }
        return status;
    }

    std::string commandLine_;
    pid_t pid_ = -1;
    int toChild_ = -1, fromChild_ = -1;
};

// Running programs by command line; requests to one program are serialised.
struct Programs {
    std::mutex mutex;
    std::map<std::string, std::shared_ptr<std::pair<std::mutex, std::unique_ptr<Child>>>> byCommand;
};

Programs& programs() {
    static Programs p;
    return p;
}

std::string formatDetail(double detail) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", std::isfinite(detail) ? detail : 1e30);
    return buf;
}

}  // namespace

std::string runProgramRequest(const std::string& commandLine, double detail, const std::string& datablock,
                              const SourceLoc& loc, double timeoutSeconds) {
    std::shared_ptr<std::pair<std::mutex, std::unique_ptr<Child>>> slot;
    {
        std::lock_guard<std::mutex> lock(programs().mutex);
        auto& s = programs().byCommand[commandLine];
        if (!s) s = std::make_shared<std::pair<std::mutex, std::unique_ptr<Child>>>();
        slot = s;
    }
    std::lock_guard<std::mutex> lock(slot->first);
    if (!slot->second || !slot->second->alive()) slot->second = std::make_unique<Child>(commandLine, loc);
    // The datablock goes on one line: newlines in it would end the request early.
    std::string block = datablock;
    for (char& c : block)
        if (c == '\n') c = ' ';
    return slot->second->request(formatDetail(detail) + " " + block + "\n", loc, timeoutSeconds);
}

}  // namespace streyes
