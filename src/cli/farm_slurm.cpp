#include "farm_slurm.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "streyes/error.h"

namespace streyes::farm {

std::string findOnPath(const std::string& program) {
    if (program.find('/') != std::string::npos) return access(program.c_str(), X_OK) == 0 ? program : "";
    const char* path = std::getenv("PATH");
    std::stringstream ss(path ? path : "/usr/bin:/bin");
    std::string dir;
    while (std::getline(ss, dir, ':')) {
        if (dir.empty()) dir = ".";
        const std::string p = dir + "/" + program;
        struct stat st {};
        if (stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(p.c_str(), X_OK) == 0) return p;
    }
    return "";
}

ProgramRun runProgram(const std::vector<std::string>& argv, int timeoutSeconds) {
    ProgramRun r;
    const std::string exe = argv.empty() ? "" : findOnPath(argv[0]);
    if (exe.empty()) return r;
    int out[2], err[2];
    if (pipe(out) != 0) return r;
    if (pipe(err) != 0) {
        close(out[0]);
        close(out[1]);
        return r;
    }
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const pid_t pid = fork();
    if (pid < 0) {
        for (int fd : {out[0], out[1], err[0], err[1]}) close(fd);
        return r;
    }
    if (pid == 0) {
        dup2(out[1], STDOUT_FILENO);
        dup2(err[1], STDERR_FILENO);
        for (int fd : {out[0], out[1], err[0], err[1]}) close(fd);
        const int devnull = open("/dev/null", O_RDONLY);
        if (devnull >= 0) dup2(devnull, STDIN_FILENO);
        execv(exe.c_str(), args.data());
        _exit(127);
    }
    close(out[1]);
    close(err[1]);
    r.started = true;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeoutSeconds);
    pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
    int open = 2;
    while (open > 0) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) {
            r.timedOut = true;
            kill(pid, SIGKILL);
            break;
        }
        const int n = poll(fds, 2, int(std::min<long long>(left.count(), 1000)));
        if (n < 0 && errno != EINTR) break;
        for (int k = 0; k < 2; ++k) {
            if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            char buf[4096];
            const ssize_t got = read(fds[k].fd, buf, sizeof buf);
            if (got > 0) {
                (k == 0 ? r.out : r.err).append(buf, size_t(got));
            } else if (got == 0 || errno != EINTR) {
                close(fds[k].fd);
                fds[k].fd = -1;
                --open;
            }
        }
    }
    for (pollfd& p : fds)
        if (p.fd >= 0) close(p.fd);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

namespace {

std::string trim(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    size_t i = s.find_first_not_of(" \n");
    return i == std::string::npos ? "" : s.substr(i);
}

// What a Slurm command said when it failed: its stderr, else its stdout.
std::string said(const ProgramRun& r) {
    std::string s = trim(r.err.empty() ? r.out : r.err);
    return s.empty() ? "no message" : s;
}

std::string slurmConfNote() {
    const char* conf = std::getenv("SLURM_CONF");
    return conf ? std::string(" (SLURM_CONF=") + conf + ")" : std::string(" (/etc/slurm/slurm.conf; SLURM_CONF unset)");
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream ss(text);
    std::string l;
    while (std::getline(ss, l))
        if (!trim(l).empty()) out.push_back(trim(l));
    return out;
}

std::string field(const std::vector<std::pair<std::string, std::string>>& fields, const std::string& key) {
    for (const auto& [k, v] : fields)
        if (k == key) return v;
    return "";
}

}  // namespace

void checkSlurmReachable() {
    for (const char* program : {"sbatch", "squeue", "scontrol", "sinfo"})
        if (findOnPath(program).empty())
            throw InputError(std::string("Slurm is not installed here: no '") + program +
                             "' on PATH. Install its client commands (Debian: apt-get install slurm-client, or "
                             "slurm-wlm for a whole one-node cluster; tools/slurm-local.sh start DIR starts one), "
                             "or run streyes farm on a machine that submits to your cluster");
    const ProgramRun ping = runProgram({"scontrol", "ping"}, 30);
    if (!ping.started || ping.timedOut || ping.exitCode != 0 || ping.out.find("is UP") == std::string::npos)
        throw InputError("no Slurm controller answers" + slurmConfNote() + ": 'scontrol ping' says: " +
                         (ping.timedOut ? std::string("no answer in 30 s") : said(ping).substr(0, said(ping).find('\n'))) +
                         ". Start slurmctld (tools/slurm-local.sh start DIR for a local one-node cluster) or "
                         "point SLURM_CONF at your cluster's slurm.conf");
}

int ClusterSize::slots(int cpusPerTask) const {
    if (cpusPerTask <= 0) return nodes;
    int n = 0;
    for (int c : cpusPerNode) n += c / cpusPerTask;
    return n;
}

ClusterSize clusterSize(const std::string& partition) {
    std::vector<std::string> args = {"sinfo", "-h", "-N", "-o", "%N|%c|%t|%P"};
    if (!partition.empty()) {
        args.push_back("-p");
        args.push_back(partition);
    }
    const ProgramRun r = runProgram(args, 60);
    if (!r.started || r.exitCode != 0)
        throw InputError("cannot list the cluster's nodes: 'sinfo' says: " + said(r) + slurmConfNote());
    ClusterSize c;
    std::vector<std::string> seen;
    for (const std::string& l : lines(r.out)) {
        std::stringstream ss(l);
        std::string node, cpus, state, part;
        std::getline(ss, node, '|');
        std::getline(ss, cpus, '|');
        std::getline(ss, state, '|');
        std::getline(ss, part, '|');
        const bool isDefault = !part.empty() && part.back() == '*';
        if (isDefault) part.pop_back();
        if (partition.empty() && !isDefault) continue;  // the default partition's nodes only
        c.partition = part;
        bool dup = false;
        for (const std::string& s : seen) dup = dup || s == node;
        if (dup) continue;
        seen.push_back(node);
        // States that take no work: down, drained or draining, failing, not responding ("*" suffix).
        if (!state.empty() && state.back() == '*') continue;
        if (state.rfind("down", 0) == 0 || state.rfind("drain", 0) == 0 || state.rfind("fail", 0) == 0 ||
            state == "maint" || state == "inval" || state == "future" || state == "unk")
            continue;
        c.nodes += 1;
        c.cpusPerNode.push_back(std::max(1, std::atoi(cpus.c_str())));
    }
    if (seen.empty())
        throw InputError(partition.empty() ? "the cluster has no default partition: name one with --partition"
                                           : "no partition '" + partition + "' on this cluster (sinfo lists none): " +
                                                 "see 'sinfo -s' for the partitions there are");
    if (c.nodes == 0)
        throw InputError("no node of partition '" + c.partition +
                         "' can take work (all down, drained or not responding): see 'sinfo -N -p " + c.partition + "'");
    return c;
}

int maxArraySize() {
    const ProgramRun r = runProgram({"scontrol", "show", "config"}, 60);
    for (const std::string& l : lines(r.out))
        if (l.rfind("MaxArraySize", 0) == 0) {
            size_t eq = l.find('=');
            if (eq != std::string::npos) {
                const int n = std::atoi(l.c_str() + eq + 1);
                if (n > 0) return n;
            }
        }
    return 1001;
}

long submitBatch(const std::vector<std::string>& sbatchArgs, const std::string& script) {
    std::vector<std::string> argv = {"sbatch", "--parsable"};
    argv.insert(argv.end(), sbatchArgs.begin(), sbatchArgs.end());
    argv.push_back(script);
    const ProgramRun r = runProgram(argv, 120);
    if (!r.started || r.exitCode != 0) {
        std::string cmd;
        for (const std::string& a : argv) cmd += (cmd.empty() ? "" : " ") + a;
        throw RenderError("sbatch refused the job: " + said(r) + "\n  " + cmd);
    }
    // --parsable: "JOBID" or "JOBID;CLUSTER"
    const std::string out = trim(r.out);
    const long job = std::atol(out.c_str());
    if (job <= 0) throw RenderError("sbatch did not print a job id: '" + out + "'");
    return job;
}

std::vector<int> parseTaskIds(const std::string& text) {
    std::vector<int> ids;
    std::string f = text.substr(0, text.find('%'));
    std::stringstream ss(f);
    std::string part;
    while (std::getline(ss, part, ',')) {
        if (part.empty()) continue;
        size_t dash = part.find('-');
        char* end = nullptr;
        const long a = std::strtol(part.c_str(), &end, 10);
        if (end == part.c_str()) continue;
        long b = a;
        if (dash != std::string::npos) b = std::strtol(part.c_str() + dash + 1, nullptr, 10);
        for (long k = a; k <= b && k - a < 1000000; ++k) ids.push_back(int(k));
    }
    return ids;
}

std::vector<std::pair<std::string, std::string>> parseScontrolLine(const std::string& line) {
    // "Key=value Key=value ...": a word that does not look like Key= continues the value before it
    // (values such as Comment or Command may hold spaces).
    std::vector<std::pair<std::string, std::string>> fields;
    std::stringstream ss(line);
    std::string word;
    while (ss >> word) {
        size_t eq = word.find('=');
        bool key = eq != std::string::npos && eq > 0;
        for (size_t i = 0; key && i < eq; ++i) {
            const char c = word[i];
            key = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '/' || c == ':' || c == '.';
        }
        if (key) fields.emplace_back(word.substr(0, eq), word.substr(eq + 1));
        else if (!fields.empty()) fields.back().second += " " + word;
    }
    return fields;
}

std::vector<TaskState> jobTasks(long job, bool* known) {
    const ProgramRun r = runProgram({"scontrol", "-o", "show", "job", std::to_string(job)}, 60);
    std::vector<TaskState> tasks;
    *known = r.started && r.exitCode == 0;
    if (!*known) return tasks;
    for (const std::string& l : lines(r.out)) {
        const auto f = parseScontrolLine(l);
        if (field(f, "ArrayJobId") != std::to_string(job)) continue;
        TaskState t;
        t.state = field(f, "JobState");
        t.reason = field(f, "Reason");
        t.exitCode = field(f, "ExitCode");
        t.nodes = field(f, "NodeList");
        t.restarts = std::atoi(field(f, "Restarts").c_str());
        // A pending array not yet split into tasks is one record for all of them: "0-3".
        for (int id : parseTaskIds(field(f, "ArrayTaskId"))) {
            t.task = id;
            tasks.push_back(t);
        }
    }
    return tasks;
}

std::string jobComment(long job) {
    const ProgramRun r = runProgram({"scontrol", "-o", "show", "job", std::to_string(job)}, 60);
    if (!r.started || r.exitCode != 0) return "";
    for (const std::string& l : lines(r.out)) {
        const std::string c = field(parseScontrolLine(l), "Comment");
        if (!c.empty() && c != "(null)") return c;
    }
    return "";
}

bool jobActive(long job) {
    const ProgramRun r = runProgram({"squeue", "-h", "-r", "-j", std::to_string(job), "-o", "%i|%T"}, 60);
    if (!r.started || r.exitCode != 0) return false;  // squeue fails for a job it no longer has
    for (const std::string& l : lines(r.out)) {
        const std::string state = l.substr(l.find('|') + 1);
        if (state == "PENDING" || state == "RUNNING" || state == "CONFIGURING" || state == "COMPLETING" ||
            state == "REQUEUED" || state == "RESIZING" || state == "SUSPENDED" || state == "REQUEUE_HOLD" ||
            state == "REQUEUE_FED" || state == "SIGNALING" || state == "STAGE_OUT")
            return true;
    }
    return false;
}

}  // namespace streyes::farm
