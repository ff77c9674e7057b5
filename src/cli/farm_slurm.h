// `streyes farm`: talking to Slurm through its own commands (sbatch, sinfo, squeue, scontrol,
// scancel), as a user would. They find the cluster as they always do (SLURM_CONF, else
// /etc/slurm/slurm.conf). Works without accounting (no slurmdbd): sacct is not used; a job's tasks
// come from squeue and `scontrol show job`, which keeps finished jobs for MinJobAge seconds.
#pragma once

#include <string>
#include <vector>

namespace streyes::farm {

struct ProgramRun {
    bool started = false;  // false: not found on PATH, or could not be run
    bool timedOut = false;
    int exitCode = -1;     // -1 when it did not exit normally
    std::string out, err;
};

// Runs argv[0] (looked up on PATH) with the arguments, no shell, capturing stdout and stderr;
// killed after `timeoutSeconds`.
ProgramRun runProgram(const std::vector<std::string>& argv, int timeoutSeconds = 60);
// The program's path on PATH, or "" when it is not there.
std::string findOnPath(const std::string& program);

// Before anything is submitted: Slurm's commands are installed and the controller answers.
// Throws InputError (exit 2) saying what is missing and what to do.
void checkSlurmReachable();

// The nodes of a partition ("" for the default partition) that can take work.
struct ClusterSize {
    std::string partition;       // as found ("render")
    int nodes = 0;               // nodes up (not down, drained or failing)
    std::vector<int> cpusPerNode;
    int slots(int cpusPerTask) const;  // tasks that can run at once: nodes, or sum of cpus / cpusPerTask
};
// Throws InputError when the partition does not exist or has no node up.
ClusterSize clusterSize(const std::string& partition);

// The cluster's MaxArraySize (array task ids must be below it); 1001 when it cannot be read.
int maxArraySize();

// `sbatch --parsable ARGS SCRIPT`: the job id. Throws RenderError with sbatch's message.
long submitBatch(const std::vector<std::string>& sbatchArgs, const std::string& script);

// One array task as Slurm sees it.
struct TaskState {
    int task = -1;
    std::string state;     // PENDING, RUNNING, COMPLETED, CANCELLED, FAILED, NODE_FAIL, TIMEOUT, ...
    std::string reason;    // why pending, or why it ended
    std::string exitCode;  // "0:0", "1:0", "0:15" (code:signal)
    std::string nodes;
    int restarts = 0;      // requeues
};
// What Slurm knows of job `job`'s tasks (`scontrol -o show job`): `known` false when it has
// forgotten the job (finished more than MinJobAge ago) or never had it.
std::vector<TaskState> jobTasks(long job, bool* known);
// A job's Comment (the farm writes "streyes-farm:MANIFEST" there); "" when unknown.
std::string jobComment(long job);
// Jobs with tasks still pending or running (squeue).
bool jobActive(long job);

// Parsing, exposed for tests: task ids of an ArrayTaskId field ("0-3,5%2" -> 0 1 2 3 5), and the
// fields of one `scontrol -o show job` line.
std::vector<int> parseTaskIds(const std::string& field);
std::vector<std::pair<std::string, std::string>> parseScontrolLine(const std::string& line);

}  // namespace streyes::farm
