// `streyes farm`: the plan of a shot on a render farm, apart from any scheduler. Frame blocks, the
// block length chosen from a measured curve, the shot manifest, and the per-task command line,
// which is the whole contract between streyes and a farm (docs/FARM.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "farm_json.h"

namespace streyes::farm {

// Frames first..last of the shot, rendered by one task.
struct Block {
    int first = 0, last = 0;
    int length() const { return last - first + 1; }
    std::string str() const;  // "5-8", or "5" for one frame
};

// Cuts frames first..last into blocks of `length` frames, in order; the last may be shorter.
std::vector<Block> cutBlocks(int first, int last, int length);

// Task indices as Slurm's --array wants them: "0-3", "1,3,5-7".
std::string indexList(const std::vector<int>& indices);
// The frames as ranges: "1-4, 9, 12-16" ("" when none).
std::string frameRanges(const std::vector<int>& frames);

// CPU time per frame against block length, measured by tools/block-curve: a block of L frames is
// one `streyes render --frames` process, and its CPU time over L is the point at L.
struct BlockCurve {
    std::string name;  // "forest"
    std::string scene;  // the scene it was measured on
    int width = 0, height = 0;
    std::vector<int> blocks;  // ascending
    std::vector<double> cpuPerFrame;
    // CPU seconds per frame at block length `length`: linear in 1/L between measured points (exact
    // for the model a + b/L: per-frame work a, per-block work b shared by L frames), held beyond.
    double at(double length) const;
};

// The curves of a tools/block-curve JSON document; `what` names it in errors (runtime_error).
std::vector<BlockCurve> readCurves(const Json& doc, const std::string& what);
// The curves measured in the source tree (docs/results/block-curve.json), built into streyes.
std::vector<BlockCurve> builtinCurves();
// The built-in curve --block auto uses unless --curve names another.
constexpr const char* kDefaultCurve = "forest";
// The curve `spec` names: a built-in one by name, or a tools/block-curve file (FILE, or FILE:NAME
// for one of several; a file with one curve needs no name). Throws runtime_error naming the choices.
BlockCurve findCurve(const std::string& spec);

// One candidate block length and what the model says of it.
struct BlockOption {
    int block = 0, tasks = 0, waves = 0;
    double wall = 0;  // modelled wall time: the sum over waves of their longest task (CPU s of one slot)
    double cpu = 0;   // modelled CPU time of the shot: sum over blocks of length x CPU per frame
};
struct BlockChoice {
    BlockOption chosen;
    std::vector<BlockOption> options;  // every length considered, ascending
    std::string why;                   // one sentence, for the user and the manifest
};
// Chooses the block length of a shot of `frames` frames on `slots` tasks that can run at once:
// every length from 1 to min(frames, maxBlock) is modelled (tasks = ceil(frames / L) in waves of
// `slots`; a task renders its frames in the renderer's blocks of `renderBlock`, the last shorter,
// each m frames long costing m x the curve at m); the choice is the
// least CPU among the lengths within 5% of the shortest wall time; of those equally cheap (within
// 0.5%), the shortest wall time; of those equally quick (within 0.5%), the shortest block (finer
// load balance, less lost to a failed task).
BlockChoice chooseBlock(int frames, int slots, const BlockCurve& curve, int renderBlock, int maxBlock);

// One `streyes farm submit` of the shot: a Slurm job array, one task per block listed.
struct Submission {
    long job = 0;
    std::vector<int> tasks;  // block indices = array task ids
    std::string time;        // local time of submission
    std::string script;      // the batch script
};

// The shot manifest, out/NAME.farm.json beside the frames (NAME from the output pattern): what
// status and gather read.
struct Manifest {
    std::string path;        // the manifest itself (absolute)
    std::string scene;       // absolute
    std::string output;      // absolute #### pattern
    std::string executable;  // the streyes the tasks run (absolute)
    int first = 0, last = 0, block = 0;
    // The whole animation the frames belong to, as `streyes render --frames first-last` decides it
    // (the scene's frames joined with those rendered): every task passes it as --shot, so that
    // motion segments and procedural detail are decided over the frames one machine would use.
    int shotFirst = 0, shotLast = 0;
    std::vector<Block> blocks;
    uint64_t seed = 0;
    std::vector<std::string> renderOptions;  // the shot's render options, as given (--res, --samples ...)
    int width = 0, height = 0;               // of the frames, for the completeness check
    std::string channels = "rgbaz";
    std::string partition;                   // "" for the cluster's default
    int cpusPerTask = 0;                     // 0: a whole node per task
    std::vector<std::string> sbatchOptions;  // given after --
    Json blockChoice;                        // how the block length was chosen
    std::vector<Submission> submissions;

    std::string farmDir() const;  // out/NAME.farm/: scripts, logs/, stats/
    std::string logPath(long job, int task) const;    // farmDir/logs/JOB_TASK.log
    std::string statsPath(long job, int task) const;  // farmDir/stats/JOB_TASK.json

    // The render command one task runs for block `b`: the whole contract (docs/FARM.md).
    // `statsPath` is where its --stats go.
    std::vector<std::string> taskCommand(const Block& b, const std::string& statsPath) const;
    // The batch script of a submission: BLOCKS indexed by SLURM_ARRAY_TASK_ID, the render line,
    // its exit code logged.
    std::string batchScript(int submissionNumber) const;

    // The same shot (scene, frames, shot, blocks, seed, options, output): a resubmission may add to it.
    bool sameShot(const Manifest& o, std::string* difference) const;

    Json toJson() const;
    static Manifest fromJson(const Json& j, const std::string& path);  // runtime_error when malformed
    static Manifest load(const std::string& path);
    void save() const;  // written whole: to a temporary file, then renamed
};

// The manifest's path for an output pattern: "out/shot.####.exr" -> "out/shot.farm.json".
std::string manifestPathFor(const std::string& outputPattern);

// A word for a POSIX shell, single-quoted when it needs to be: it's -> 'it'\''s'.
std::string shellQuote(const std::string& s);

}  // namespace streyes::farm
