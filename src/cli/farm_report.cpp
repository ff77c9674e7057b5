// `streyes farm status | gather`: what a submitted shot has done, read back from its manifest,
// its frames, the tasks' logs and stats, and Slurm (docs/FARM.md).
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>

#include "command_line.h"
#include "commands.h"
#include "farm_plan.h"
#include "farm_slurm.h"
#include "procedural/procedural.h"
#include "render_request.h"
#include "streyes/image_io.h"
#include "streyes/passes.h"
#include "streyes/rib.h"
#include "farm_report.h"

namespace streyes::cli {

using namespace streyes::farm;
namespace fs = std::filesystem;

namespace {

bool isJobId(const std::string& s) {
    return !s.empty() && s.size() < 12 && s.find_first_not_of("0123456789") == std::string::npos;
}

// The manifest a status or gather argument names: a job id (found through the job's comment) or a
// manifest file.
Manifest findManifest(const std::string& arg) {
    if (isJobId(arg) && !fs::exists(arg)) {
        checkSlurmReachable();
        const std::string comment = jobComment(std::atol(arg.c_str()));
        const std::string tag = "streyes-farm:";
        if (comment.rfind(tag, 0) != 0)
            throw InputError("Slurm does not know job " + arg + " as a streyes farm job (it forgets finished jobs " +
                             "after MinJobAge, 300 s by default): give the shot's manifest instead, NAME.farm.json " +
                             "beside its frames");
        const std::string path = comment.substr(tag.size());
        if (!fs::exists(path)) throw InputError("job " + arg + "'s manifest '" + path + "' is gone");
        return Manifest::load(path);
    }
    if (!fs::exists(arg))
        throw InputError("no manifest '" + arg + "': give a job id or the NAME.farm.json that farm submit wrote");
    try {
        return Manifest::load(arg);
    } catch (const std::runtime_error& e) {
        throw InputError(e.what());
    }
}

std::string readTail(const std::string& path, int lines, bool* exists) {
    std::ifstream f(path, std::ios::binary);
    *exists = bool(f);
    if (!f) return "";
    std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    // Progress bars redraw with carriage returns: keep what was last drawn on each line.
    std::vector<std::string> all;
    std::string cur;
    for (char c : text) {
        if (c == '\n') {
            all.push_back(cur);
            cur.clear();
        } else if (c == '\r') {
            cur.clear();
        } else {
            cur += c;
        }
    }
    if (!cur.empty()) all.push_back(cur);
    std::string out;
    for (size_t i = all.size() > size_t(lines) ? all.size() - size_t(lines) : 0; i < all.size(); ++i)
        out += all[i] + "\n";
    return out;
}

// The exit code the batch script logged last ("streyes farm: exit code N"), or INT_MIN when it
// logged none (the task was killed, or runs still).
int loggedExitCode(const std::string& log) {
    std::ifstream f(log, std::ios::binary);
    std::string line;
    int code = INT_MIN;
    const std::string tag = "streyes farm: exit code ";
    while (std::getline(f, line)) {
        size_t at = line.find(tag);
        if (at != std::string::npos) code = std::atoi(line.c_str() + at + tag.size());
        else if (line.find("streyes farm: job ") != std::string::npos) code = INT_MIN;  // a new attempt began
    }
    return code;
}

bool activeState(const std::string& s) {
    return s == "PENDING" || s == "RUNNING" || s == "CONFIGURING" || s == "COMPLETING" || s == "REQUEUED" ||
           s == "RESIZING" || s == "SUSPENDED" || s == "REQUEUE_HOLD" || s == "REQUEUE_FED" || s == "SIGNALING" ||
           s == "STAGE_OUT";
}

// ---- status --------------------------------------------------------------------------------------

struct BlockStatus {
    int index = 0;
    Block block;
    int complete = 0;
    std::vector<int> missing;
    long job = 0;        // the latest submission that ran this block (0: never submitted)
    std::string state;   // Slurm's, or from the log
    std::string source;  // "slurm", "log", "none"
    std::string exitCode, nodes, reason, log;
    int restarts = 0;
    bool failed = false;  // ended, frames still missing
};

// `status` and `gather` take one job or manifest.
std::string oneTarget(const std::vector<std::string>& targets, const std::string& command) {
    if (targets.empty())
        throw UsageError("farm " + command + " needs a job id or a manifest (NAME.farm.json)");
    if (targets.size() > 1)
        throw UsageError("give one job or manifest, not '" + targets[0] + "' and '" + targets[1] + "'");
    return targets[0];
}

}  // namespace

int farmStatus(const std::vector<std::string>& args) {
    CommandLine cl("farm status", "usage: streyes farm status JOB|MANIFEST [--json] [--lines N]",
                   "\nA shot's frames complete and missing (each frame read back), each block's task as Slurm "
                   "reports it\n(squeue / scontrol; without accounting Slurm forgets a finished job after MinJobAge, "
                   "then the\ntask's log tells), and failed tasks with the last lines of their logs.");
    std::vector<std::string> targets;
    bool json = false;
    int tailLines = 10;
    cl.positionals("shot", "a job id, or the shot's manifest NAME.farm.json", &targets)->type_name("JOB|MANIFEST");
    cl.flag("--json", "print the status as JSON", &json);
    cl.value("--lines", "N", "the last N lines of each failed task's log (default 10)",
             [&](const std::string& v) { tailLines = int(parseInt("--lines", v, 0, 10000)); });
    if (!cl.parse(args)) return 0;
    const std::string target = oneTarget(targets, "status");
    const Manifest m = findManifest(target);

    // Slurm's view, when it can be asked; the files' otherwise.
    bool slurm = false;
    try {
        checkSlurmReachable();
        slurm = true;
    } catch (const InputError&) {
    }
    std::map<long, std::pair<bool, std::vector<TaskState>>> jobs;
    if (slurm)
        for (const Submission& s : m.submissions) {
            bool known = false;
            std::vector<TaskState> t = jobTasks(s.job, &known);
            jobs[s.job] = {known, t};
        }

    std::vector<BlockStatus> blocks;
    int complete = 0, total = 0;
    std::vector<int> missingFrames;
    for (size_t k = 0; k < m.blocks.size(); ++k) {
        BlockStatus b;
        b.index = int(k);
        b.block = m.blocks[k];
        for (int f = b.block.first; f <= b.block.last; ++f) {
            ++total;
            if (isCompleteFrame(expandFramePattern(m.output, f), m.width, m.height, m.channels)) ++b.complete;
            else b.missing.push_back(f);
        }
        complete += b.complete;
        missingFrames.insert(missingFrames.end(), b.missing.begin(), b.missing.end());
        for (const Submission& s : m.submissions)
            if (std::find(s.tasks.begin(), s.tasks.end(), int(k)) != s.tasks.end()) b.job = s.job;
        if (b.job == 0) {
            b.state = "NOT_SUBMITTED";
            b.source = "none";
        } else {
            b.log = m.logPath(b.job, b.index);
            const auto it = jobs.find(b.job);
            bool found = false;
            if (it != jobs.end() && it->second.first)
                for (const TaskState& t : it->second.second)
                    if (t.task == b.index) {
                        b.state = t.state;
                        b.exitCode = t.exitCode;
                        b.nodes = t.nodes;
                        b.reason = t.reason;
                        b.restarts = t.restarts;
                        b.source = "slurm";
                        found = true;
                    }
            if (!found) {
                b.source = "log";
                bool exists = false;
                readTail(b.log, 1, &exists);
                const int code = loggedExitCode(b.log);
                if (!exists) b.state = "NOT_STARTED";
                else if (code == 0) b.state = "COMPLETED";
                else if (code != INT_MIN) b.state = "FAILED", b.exitCode = std::to_string(code);
                else b.state = "ENDED_UNFINISHED";
            }
        }
        b.failed = !b.missing.empty() && b.job != 0 && !activeState(b.state);
        blocks.push_back(b);
    }

    std::vector<const BlockStatus*> failed;
    for (const BlockStatus& b : blocks)
        if (b.failed) failed.push_back(&b);

    if (json) {
        Json j = Json::object();
        j["manifest"] = m.path;
        j["scene"] = m.scene;
        j["output"] = m.output;
        j["slurm_reachable"] = slurm;
        j["frames"] = {{"total", total},
                       {"complete", complete},
                       {"missing", total - complete},
                       {"missing_ranges", frameRanges(missingFrames)}};
        Json& jl = j["jobs"] = Json::array();
        for (const Submission& s : m.submissions)
            jl.push_back({{"job", s.job},
                          {"tasks", indexList(s.tasks)},
                          {"time", s.time},
                          {"known_to_slurm", jobs.count(s.job) && jobs[s.job].first}});
        Json& tl = j["tasks"] = Json::array();
        for (const BlockStatus& b : blocks) {
            Json o = {{"block", b.index},         {"frames", b.block.str()},  {"job", b.job},
                      {"task", b.index},          {"state", b.state},         {"state_from", b.source},
                      {"exit_code", b.exitCode},  {"restarts", b.restarts},   {"complete", b.complete},
                      {"missing", b.missing.size()}, {"failed", b.failed},    {"log", b.log}};
            if (b.failed) {
                bool exists = false;
                o["log_tail"] = readTail(b.log, tailLines, &exists);
            }
            tl.push_back(std::move(o));
        }
        j["failed_tasks"] = failed.size();
        std::printf("%s\n", dumpJson(j).c_str());
        return 0;
    }

    std::printf("shot %s\n  scene %s, frames %d-%d in %zu blocks of %d, %dx%d\n", m.path.c_str(), m.scene.c_str(),
                m.first, m.last, m.blocks.size(), m.block, m.width, m.height);
    std::printf("frames: %d of %d complete", complete, total);
    if (complete < total) std::printf(", %d missing: %s", total - complete, frameRanges(missingFrames).c_str());
    std::printf("\n");
    for (const Submission& s : m.submissions)
        std::printf("job %ld: task%s %s, submitted %s%s\n", s.job, s.tasks.size() == 1 ? "" : "s",
                    indexList(s.tasks).c_str(), s.time.c_str(),
                    !slurm ? "" : (jobs[s.job].first ? "" : " (Slurm no longer knows it: states from its logs)"));
    if (!slurm) std::printf("Slurm cannot be asked from here: task states come from their logs\n");
    std::printf("\n%-6s %-12s %-14s %-18s %s\n", "block", "frames", "job_task", "state", "frames complete");
    for (const BlockStatus& b : blocks) {
        const std::string id = b.job ? std::to_string(b.job) + "_" + std::to_string(b.index) : "-";
        std::string state = b.state;
        if (b.restarts > 0) state += " (requeued " + std::to_string(b.restarts) + "x)";
        std::printf("%-6d %-12s %-14s %-18s %d/%d\n", b.index, b.block.str().c_str(), id.c_str(), state.c_str(),
                    b.complete, b.block.length());
    }
    if (!failed.empty()) {
        std::printf("\nfailed tasks (%zu): they ended with frames missing; `streyes farm submit` with the same "
                    "arguments renders what is missing\n", failed.size());
        for (const BlockStatus* b : failed) {
            // streyes's exit code 2 is bad input (a scene, an option, the memory budget): the same
            // line fails the same way on any node.
            const bool badInput = b->exitCode == "2" || b->exitCode.rfind("2:", 0) == 0;
            std::printf("  %ld_%d, frames %s: %s%s%s%s; log %s", b->job, b->index, b->block.str().c_str(), b->state.c_str(),
                        b->exitCode.empty() ? "" : (", exit code " + b->exitCode).c_str(),
                        b->state == "ENDED_UNFINISHED" ? " (cancelled, killed, or its node failed)" : "",
                        badInput ? " (bad input: fix it, submitting again fails the same way)" : "", b->log.c_str());
            bool exists = false;
            const std::string tail = readTail(b->log, tailLines, &exists);
            if (!exists) {
                std::printf(" (none: the task never started)\n");
                continue;
            }
            std::printf(", last lines:\n");
            size_t at = 0;
            while (at < tail.size()) {
                size_t nl = tail.find('\n', at);
                std::printf("    | %s\n", tail.substr(at, nl - at).c_str());
                at = nl == std::string::npos ? tail.size() : nl + 1;
            }
        }
    }
    return 0;
}

namespace {

// ---- gather --------------------------------------------------------------------------------------

// Adds `v` into `sum`: numbers add (whole numbers stay whole), objects member by member, arrays
// item by item.
void addInto(Json& sum, const Json& v) {
    if (v.is_number()) {
        if (v.is_number_integer() && (sum.is_null() || sum.is_number_integer()))
            sum = (sum.is_null() ? 0 : sum.get<int64_t>()) + v.get<int64_t>();
        else
            sum = num(sum) + v.get<double>();
    } else if (v.is_object()) {
        if (!sum.is_object()) sum = Json::object();
        for (const auto& [k, x] : v.items()) addInto(sum[k], x);
    } else if (v.is_array()) {
        if (!sum.is_array()) sum = Json::array();
        for (size_t i = 0; i < v.size(); ++i) {
            if (i == sum.size()) sum.push_back(nullptr);
            addInto(sum[i], v[i]);
        }
    }
}

std::string bytesText(double b) {
    char buf[32];
    if (b >= double(1ull << 30)) std::snprintf(buf, sizeof buf, "%.2f GiB", b / double(1ull << 30));
    else std::snprintf(buf, sizeof buf, "%.0f MiB", b / double(1ull << 20));
    return buf;
}

}  // namespace

int farmGather(const std::vector<std::string>& args) {
    CommandLine cl("farm gather", "usage: streyes farm gather JOB|MANIFEST [--json] [-o FILE]",
                   "\nOne summary of a shot's tasks' --stats: CPU time, counters summed, peak memory per task.");
    std::vector<std::string> targets;
    std::string outPath;
    bool json = false;
    cl.positionals("shot", "a job id, or the shot's manifest NAME.farm.json", &targets)->type_name("JOB|MANIFEST");
    cl.flag("--json", "print the summary as JSON", &json);
    cl.value("-o,--output", "FILE", "where the summary goes (default NAME.farm/summary.json)", &outPath);
    if (!cl.parse(args)) return 0;
    const std::string target = oneTarget(targets, "gather");
    const Manifest m = findManifest(target);
    if (outPath.empty()) outPath = m.farmDir() + "/summary.json";

    struct TaskStats {
        long job;
        int task;
        Json stats;
    };
    std::vector<TaskStats> found;
    std::vector<std::string> missing;
    for (const Submission& s : m.submissions)
        for (int k : s.tasks) {
            const std::string p = m.statsPath(s.job, k);
            if (!fs::exists(p)) {
                missing.push_back(std::to_string(s.job) + "_" + std::to_string(k));
                continue;
            }
            try {
                found.push_back({s.job, k, loadJson(p)});
            } catch (const std::runtime_error& e) {
                throw InputError(e.what());
            }
        }

    Json counters = Json::object();
    double cpu = 0, wall = 0, peak = 0;
    int rendered = 0, skipped = 0;
    Json tasks = Json::array();
    for (const TaskStats& t : found) {
        const Json& s = t.stats;
        const Json& fr = member(s, "frames");
        const bool hasFrames = fr.is_array() && fr.size() == 2;
        const int n = hasFrames ? int(num(fr[1]) - num(fr[0])) + 1 : 0;
        const int sk = int(num(member(s, "frames_skipped")));
        rendered += n - sk;
        skipped += sk;
        const double c = num(member(s, "cpu_seconds")), w = num(member(member(s, "seconds"), "total"));
        const double pk = num(member(s, "peak_memory_bytes"));
        cpu += c;
        wall += w;
        peak = std::max(peak, pk);
        addInto(counters, member(s, "counters"));
        tasks.push_back({{"job", t.job},
                         {"task", t.task},
                         {"frames", hasFrames ? Block{int(num(fr[0])), int(num(fr[1]))}.str() : ""},
                         {"frames_rendered", n - sk},
                         {"frames_skipped", sk},
                         {"cpu_seconds", c},
                         {"wall_seconds", w},
                         {"peak_memory_bytes", pk},
                         {"threads", member(s, "threads")}});
    }
    // A ratio does not add up: computed again from the summed counts.
    const double tests = num(member(counters, "sample_tests"));
    if (counters.contains("hit_efficiency"))
        counters["hit_efficiency"] = tests > 0 ? num(member(counters, "sample_hits")) / tests : 0.0;

    Json summary = {{"manifest", m.path},
                    {"scene", m.scene},
                    {"frames", Block{m.first, m.last}.str()},
                    {"resolution", std::to_string(m.width) + "x" + std::to_string(m.height)},
                    {"tasks_with_stats", found.size()},
                    {"tasks_without_stats", missing},
                    {"frames_rendered", rendered},
                    {"frames_skipped", skipped},
                    {"cpu_seconds", cpu},
                    {"cpu_seconds_per_frame_rendered", rendered ? cpu / rendered : 0.0},
                    {"task_wall_seconds_sum", wall},
                    {"peak_memory_bytes_max", peak},
                    {"counters", counters},
                    {"tasks", tasks}};
    const std::string text = dumpJson(summary) + "\n";
    {
        const std::string tmp = outPath + ".tmp" + std::to_string(getpid());
        std::ofstream f(tmp, std::ios::binary);
        f << text;
        f.close();
        if (!f || std::rename(tmp.c_str(), outPath.c_str()) != 0) {
            std::remove(tmp.c_str());
            throw RenderError("cannot write '" + outPath + "'");
        }
    }
    if (json) {
        std::fputs(text.c_str(), stdout);
        return 0;
    }
    std::printf("shot %s: frames %d-%d, %dx%d\n", m.path.c_str(), m.first, m.last, m.width, m.height);
    std::printf("%zu task%s with stats", found.size(), found.size() == 1 ? "" : "s");
    if (!missing.empty()) {
        std::string list;
        for (const std::string& s : missing) list += (list.empty() ? "" : ", ") + s;
        std::printf("; %zu without (never finished): %s", missing.size(), list.c_str());
    }
    std::printf("\n\n%-14s %-12s %9s %8s %10s %10s %12s\n", "job_task", "frames", "rendered", "skipped", "CPU s",
                "wall s", "peak memory");
    for (const Json& t : tasks)
        std::printf("%-14s %-12s %9.0f %8.0f %10.1f %10.1f %12s\n",
                    (std::to_string(long(num(t["job"]))) + "_" + std::to_string(int(num(t["task"])))).c_str(),
                    str(t["frames"]).c_str(), num(t["frames_rendered"]), num(t["frames_skipped"]),
                    num(t["cpu_seconds"]), num(t["wall_seconds"]), bytesText(num(t["peak_memory_bytes"])).c_str());
    std::printf("\ntotal: %d frames rendered, %d skipped (already complete), %.1f CPU s (%.2f a frame rendered), "
                "peak memory %s (largest task)\n",
                rendered, skipped, cpu, rendered ? cpu / rendered : 0.0, bytesText(peak).c_str());
    const Json& splits = member(counters, "splits");
    std::printf("counters summed: %.0f splits, %.0f grids, %.0f micropolygons, %.0f sample tests, %.0f procedurals "
                "expanded, %.0f bodies culled by occlusion\n",
                splits.is_object() ? num(member(splits, "total")) : num(splits), num(member(counters, "grids_diced")),
                num(member(counters, "micropolygons")), num(member(counters, "sample_tests")),
                num(member(counters, "procedurals_expanded")), num(member(counters, "culled_occlusion")));
    std::printf("summary: %s\n", outPath.c_str());
    return 0;
}

}  // namespace streyes::cli
