// `streyes farm submit | status | gather`: a shot on a Slurm cluster, one job array a submission,
// one task a frame block (docs/FARM.md).
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
#include "farm_report.h"
#include "farm_slurm.h"
#include "procedural/procedural.h"
#include "render_request.h"
#include "streyes/image_io.h"
#include "streyes/passes.h"
#include "streyes/rib.h"

namespace streyes::cli {

using namespace streyes::farm;
namespace fs = std::filesystem;

namespace {

const char* kFarmSynopsis =
    "usage: streyes farm submit SCENE -o PATTERN [--frames A-B] [options] [render options] [-- sbatch options]\n"
    "       streyes farm status JOB|MANIFEST [--json] [--lines N]\n"
    "       streyes farm gather JOB|MANIFEST [--json] [-o FILE]";

const char* kFarmDescription = R"(
Renders a shot on a Slurm cluster: the frames are cut into blocks, and one job array runs one
task per block, each `streyes render SCENE --frames BLOCK -o PATTERN --resume --seed S ...`.
Frames, logs and stats go beside PATTERN, on a filesystem every node sees: the manifest
NAME.farm.json and the folder NAME.farm/ (scripts, logs/JOB_TASK.log, stats/JOB_TASK.json).

  submit    submits a shot (streyes farm submit --help)
  status    frames complete and missing (each frame read back), each block's task as Slurm
            reports it (squeue / scontrol; without accounting Slurm forgets a finished job after
            MinJobAge, then the task's log tells), and failed tasks with the last lines of their
            logs (streyes farm status --help)
  gather    one summary of the tasks' --stats: CPU time, counters summed, peak memory per task;
            written to NAME.farm/summary.json (or -o FILE) (streyes farm gather --help))";

const char* kFarmExitCodes = R"(exit codes: 0 done, 1 the command failed (sbatch refused the job), 2 bad input: no Slurm, no
            controller answering, an unwritable output folder, a block longer than the shot, a
            scene that does not parse (all found before anything is submitted))";

}  // namespace

namespace {

std::string nowString() {
    std::time_t t = std::time(nullptr);
    char buf[64];
    std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S", std::localtime(&t));
    return buf;
}

std::string selfExecutable() {
    std::error_code ec;
    fs::path p = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("streyes") : p.string();
}

// ---- submit --------------------------------------------------------------------------------------

int farmSubmit(const std::vector<std::string>& given) {
    // Anything after -- goes to sbatch.
    const auto dashes = std::find(given.begin(), given.end(), "--");
    const std::vector<std::string> args(given.begin(), dashes);
    const std::vector<std::string> sbatchOptions(dashes == given.end() ? dashes : dashes + 1, given.end());

    CommandLine cl("farm submit",
                   "usage: streyes farm submit SCENE -o PATTERN [--frames A-B] [options] [render options] "
                   "[-- sbatch options]",
                   "\nSubmits a shot to Slurm: one job array, one task a block of frames, each task `streyes render "
                   "SCENE\n--frames BLOCK -o PATTERN --resume --seed S --shot A-B ...` (docs/FARM.md).");
    std::string outPattern, blockArg = "auto", curveArg, partition, framesArg;
    int cpusPerTask = 0, slotsGiven = 0;
    uint64_t seed = 0;
    bool allBlocks = false, dryRun = false;
    std::vector<std::string> scenes;
    cl.positionals("scene", "the shot's scene: a RIB file, or a #### pattern of frame files", &scenes)
        ->type_name("SCENE");
    cl.value("-o,--output", "PATTERN", "output frames, with a #### frame field (required)", &outPattern);
    cl.value("--frames", "A-B", "the shot's frames (default: the scene's)", &framesArg);
    cl.value("--block", "N|auto",
             "frames per task (default auto: from the shot's length, the cluster's\n"
             "size and the measured block-length curve)",
             &blockArg);
    cl.value("--curve", "NAME|FILE",
             "the curve --block auto uses: a built-in one, measured by\n"
             "tools/block-curve (docs/results/block-curve.md: demo, forest,\n"
             "forest-flyover ...; default forest), or a file it wrote (FILE or\n"
             "FILE:NAME)",
             &curveArg);
    cl.value("--slots", "N",
             "plan --block auto for N tasks at once instead of the partition's\n"
             "(with --dry-run: plan a shot for a cluster you are not on)",
             [&](const std::string& v) { slotsGiven = int(parseInt("--slots", v, 1, 10000000)); });
    cl.value("-p,--partition", "P", "the Slurm partition (default: the cluster's default)", &partition);
    cl.value("--cpus-per-task", "N", "N cores a task, rendering with N threads (default: a whole node a task)",
             [&](const std::string& v) { cpusPerTask = int(parseInt("--cpus-per-task", v, 1, 4096)); });
    cl.value("--seed", "N", "the shot's sample seed, the same in every task (default 0)",
             [&](const std::string& v) { seed = uint64_t(parseInt("--seed", v, 0, 0x7fffffffL)); });
    cl.flag("--all-blocks",
            "submit every block (by default, blocks whose frames are all complete\n"
            "are left out; every task skips complete frames anyway)",
            &allBlocks);
    cl.flag("--dry-run", "print the plan, the batch script and the sbatch line; submit nothing", &dryRun);
    // render's options the farm sets for each task: refused, saying what to give instead.
    for (const char* name : {"--stats", "--resume", "--threads", "--shot"}) {
        const std::string n = name;
        const std::string why =
            n == "--threads" ? " (use --cpus-per-task N)"
            : n == "--shot"  ? " (the shot streyes render --frames A-B would use: the scene's frames joined with A-B)"
                             : "";
        auto refuse = [n, why](const std::string&) -> void { throw UsageError(n + " is set by the farm for each task" + why); };
        CLI::Option* o = n == "--resume" ? cl.app().add_flag_callback(n, [refuse] { refuse(""); })
                                         : cl.value(n, "", "", refuse);
        o->group("");  // not in the help
    }
    // The rest of render's options, passed to every task as given; checked here by the code the
    // tasks run (parseRenderArgs).
    RenderRequest given_;
    addRenderOptions(cl, given_, {"--frames", "--shot", "-o", "--stats", "--threads", "--seed", "--resume"},
                     "render options (as for streyes render, passed to every task; with --safe the scene is "
                     "checked here first)");
    cl.app().footer("-- OPTIONS: anything after -- goes to sbatch (e.g. -- --time=2:00:00 --mem=8G).\n\n"
                    "Submitting the same shot again (same scene, frames, blocks, seed and options) adds a job to\n"
                    "its manifest and renders only the frames still missing.\n\n" +
                    std::string(kFarmExitCodes));
    if (!cl.parse(args)) return 0;
    // The render options in the order given, as the tasks will get them (--safe-dir made absolute:
    // the tasks run elsewhere, and name the folder as this machine does).
    std::vector<std::string> renderOptions;
    std::map<const CLI::Option*, size_t> seen;
    for (const CLI::Option* o : cl.app().parse_order()) {
        if (o->get_group().rfind("render options", 0) != 0) continue;
        const std::string name = o->get_name(false, true).substr(0, o->get_name(false, true).find(','));
        renderOptions.push_back(name);
        if (o->get_expected_max() == 0) continue;  // a flag
        const size_t k = seen[o]++;
        const std::string v = k < o->results().size() ? o->results()[k] : o->results().back();
        renderOptions.push_back(name == "--safe-dir" ? fs::absolute(v).lexically_normal().string() : v);
    }
    if (scenes.size() > 1) throw UsageError("more than one scene given ('" + scenes[0] + "' and '" + scenes[1] + "')");
    const std::string scenePath = scenes.empty() ? std::string() : scenes[0];
    if (scenePath.empty()) throw UsageError("no scene given");
    if (outPattern.empty())
        throw UsageError("farm submit needs -o PATTERN (with a #### frame field), in a folder every node of the cluster "
                         "sees: the tasks write the frames there");
    if (!hasFrameField(outPattern))
        throw UsageError("-o " + outPattern + " has no #### frame field: every frame needs a file of its own");
    int blockFixed = 0;
    if (blockArg != "auto") blockFixed = int(parseInt("--block", blockArg, 1, 1000000));
    int first = 0, last = 0;
    if (!framesArg.empty()) parseFrameRange("--frames", framesArg, &first, &last);

    // The render options, checked by the code every task runs.
    std::vector<std::string> check = renderOptions;
    check.push_back(scenePath);
    if (!framesArg.empty()) {
        check.push_back("--frames");
        check.push_back(framesArg);
    }
    RenderRequest req;
    parseRenderArgs(check, &req);
    // --safe: the scene is read here as the tasks will read it, its refusals found before anything
    // is submitted (the tasks' write folder is -o's, as given here, unless --safe-dir says).
    req.outPattern = fs::absolute(outPattern).lexically_normal().string();
    setSceneAccess(sceneAccessFor(req));

    // Before anything is submitted: Slurm, the scene, the output folder, the blocks, the partition.
    if (!dryRun) checkSlurmReachable();
    const std::string scene = fs::absolute(scenePath).lexically_normal().string();
    const std::string output = fs::absolute(outPattern).lexically_normal().string();
    if (!isFramePattern(scene) && !fs::exists(scene)) throw InputError("no scene '" + scenePath + "'");
    Log log;
    log.setEcho(true);
    log.setStrict(req.strict);  // with --strict, refused here rather than by every task
    // A scene, or a frame sequence (a pattern of frame files, FrameBegin blocks), read as the tasks
    // will read it: InputError naming file and line when it does not parse. The shot is its
    // pictures' frames (streyes/passes.h: each task renders the depth frames its pictures read).
    FrameRequest wanted;
    wanted.given = !framesArg.empty();
    wanted.first = first, wanted.last = last;
    PassRequest passes;
    passes.frames = wanted;
    passes.blockFrames = std::numeric_limits<int>::max() / 4;
    checkRibDefaults(req.ribOptions);
    passes.defaults = req.ribOptions;
    Sequence sequence;
    bool havePicture = false, haveAny = false;
    int firstPicture = std::numeric_limits<int>::max(), lastPicture = std::numeric_limits<int>::min();
    readPasses(scene, passes, log, [&](PassJob&& job) {
        if (job.kind != PassJob::Kind::Render || (havePicture && job.depth) || job.frames.empty()) return;
        if (!job.depth) {
            firstPicture = std::min(firstPicture, job.frames.begin()->first);
            lastPicture = std::max(lastPicture, job.frames.rbegin()->first);
        }
        if (!haveAny || (!havePicture && !job.depth)) sequence = std::move(job.sequence);
        haveAny = true;
        havePicture = havePicture || !job.depth;
    });
    if (!haveAny) throw InputError("'" + scenePath + "' renders no frame");
    Scene& parsed = sequence.scene;
    if (req.safe)  // a program or plug-in the scene names is refused now, not in every task
        for (const ProceduralDesc& p : parsed.procedurals) makeProceduralGenerator(p);
    applyPreview(req, parsed);
    RenderOptions shot = req.opts;
    if (havePicture && sequence.isSequence) {
        shot.hasFrames = true;
        shot.firstFrame = firstPicture;
        shot.lastFrame = lastPicture;
    }
    const ResolvedSettings rs = resolveSettings(parsed, shot);
    first = rs.firstFrame;
    last = rs.lastFrame;
    const int frames = last - first + 1;
    const std::vector<Output> outs = chooseOutputs(parsed, output, scene, frames, log);
    try {
        checkWritableFolder(expandFramePattern(output, first), "-o");
    } catch (const RenderError& e) {
        throw InputError(e.what());
    }

    ClusterSize cluster;
    if (!dryRun) {
        cluster = clusterSize(partition);
        const int widest = *std::max_element(cluster.cpusPerNode.begin(), cluster.cpusPerNode.end());
        if (cpusPerTask > widest)
            throw InputError("--cpus-per-task " + std::to_string(cpusPerTask) + ": the largest node of partition '" +
                             cluster.partition + "' has " + std::to_string(widest) + " CPUs");
    } else {
        // --dry-run asks Slurm when it answers, and plans for one task at a time when it does not.
        try {
            checkSlurmReachable();
            cluster = clusterSize(partition);
        } catch (const InputError&) {
            cluster.nodes = 1;
            cluster.cpusPerNode = {std::max(1, cpusPerTask)};
        }
    }
    int block = blockFixed;
    Json choiceJson = Json::object();
    // Submitting a shot again: --block auto keeps the blocks it has (the cluster may have changed
    // since, but the shot's blocks may not).
    const std::string manifestPath = fs::absolute(manifestPathFor(output)).lexically_normal().string();
    std::unique_ptr<Manifest> old;
    if (fs::exists(manifestPath)) {
        try {
            old = std::make_unique<Manifest>(Manifest::load(manifestPath));
        } catch (const std::runtime_error& e) {
            throw InputError(std::string(e.what()) + ": remove it, or give another -o");
        }
        if (block == 0) {
            block = old->block;
            choiceJson = old->blockChoice;
        }
    }
    if (blockFixed > frames)
        throw InputError("--block " + std::to_string(block) + " is longer than the shot: frames " + std::to_string(first) +
                         "-" + std::to_string(last) + " are " + std::to_string(frames) + " frame" +
                         (frames == 1 ? "" : "s") + "; give --block " + std::to_string(frames) + " or less");
    if (old && blockFixed == 0) {
        // kept from the manifest
    } else if (block > 0) {
        choiceJson["mode"] = "given";
    } else {
        BlockCurve curve;
        try {
            curve = findCurve(curveArg.empty() ? kDefaultCurve : curveArg);
        } catch (const std::runtime_error& e) {
            throw InputError(std::string("--curve: ") + e.what());
        }
        const int renderBlock = frameBlockLimit(parsed, req.opts);
        const int slots = slotsGiven > 0 ? slotsGiven : cluster.slots(cpusPerTask);
        const BlockChoice c = chooseBlock(frames, slots, curve, renderBlock, frames);
        block = c.chosen.block;
        choiceJson["mode"] = "auto";
        choiceJson["curve"] = curve.name;
        choiceJson["slots"] = slots;
        choiceJson["render_frame_block"] = renderBlock;
        choiceJson["why"] = c.why;
    }
    const std::vector<Block> blocks = cutBlocks(first, last, block);
    const int arrayLimit = dryRun ? INT_MAX : maxArraySize();
    if (int(blocks.size()) > arrayLimit)
        throw InputError(std::to_string(blocks.size()) + " blocks of " + std::to_string(block) +
                         " frames are more tasks than the cluster's MaxArraySize (" + std::to_string(arrayLimit) +
                         ") allows in one job array: give --block " +
                         std::to_string((frames + arrayLimit - 1) / arrayLimit) + " or more");

    Manifest m;
    m.path = manifestPath;
    m.scene = scene;
    m.output = output;
    m.executable = selfExecutable();
    m.first = first;
    m.last = last;
    m.shotFirst = rs.shotFirst;  // streyes render --frames first-last's shot
    m.shotLast = rs.shotLast;
    m.block = block;
    m.blocks = blocks;
    m.seed = seed;
    m.renderOptions = renderOptions;
    m.width = rs.width;
    m.height = rs.height;
    m.channels = outs.back().mode;
    m.partition = partition.empty() ? cluster.partition : partition;
    m.cpusPerTask = cpusPerTask;
    m.sbatchOptions = sbatchOptions;
    m.blockChoice = choiceJson;
    if (old) {
        std::string difference;
        if (!old->sameShot(m, &difference))
            throw InputError("'" + m.path + "' holds another shot (" + difference + " as given now): its frames " +
                             "would mix with these. Give another -o, or remove it and the folder " + old->farmDir() +
                             " to start again");
        if (!dryRun)
            for (const Submission& s : old->submissions)
                if (jobActive(s.job))
                    throw InputError("job " + std::to_string(s.job) + " of this shot is still pending or running: wait " +
                                     "for it (streyes farm status " + m.path + ") or cancel it (scancel " +
                                     std::to_string(s.job) + ") before submitting again");
        m.submissions = old->submissions;
        m.blockChoice = old->blockChoice;
    }

    // The blocks to render: those with a frame missing, unless --all-blocks.
    std::vector<int> tasks;
    for (size_t k = 0; k < blocks.size(); ++k) {
        bool complete = !allBlocks;
        for (int f = blocks[k].first; complete && f <= blocks[k].last; ++f)
            complete = isCompleteFrame(expandFramePattern(output, f), m.width, m.height, m.channels);
        if (!complete) tasks.push_back(int(k));
    }
    std::fprintf(stderr, "streyes farm: %s, frames %d-%d (%d), %dx%d, in %zu block%s of %d%s\n", scene.c_str(), first,
                 last, frames, m.width, m.height, blocks.size(), blocks.size() == 1 ? "" : "s", block,
                 member(m.blockChoice, "why").is_string() ? (" (" + str(member(m.blockChoice, "why")) + ")").c_str() : "");
    if (tasks.empty()) {
        std::fprintf(stderr, "streyes farm: all %d frames are complete: nothing to submit (--all-blocks submits every "
                             "block anyway)\n", frames);
        return 0;
    }

    const int number = int(m.submissions.size()) + 1;
    const std::string script = m.farmDir() + "/submission-" + std::to_string(number) + ".sh";
    std::string stem = fs::path(m.farmDir()).filename().string();
    stem = stem.substr(0, stem.size() - 5);  // without ".farm"
    std::vector<std::string> sbatch = {"--array=" + indexList(tasks), "--job-name=streyes:" + stem,
                                       "--output=" + m.farmDir() + "/logs/%A_%a.log", "--open-mode=append",
                                       "--requeue", "--comment=streyes-farm:" + m.path, "--nodes=1"};
    if (!m.partition.empty()) sbatch.push_back("--partition=" + m.partition);
    if (cpusPerTask > 0) sbatch.push_back("--cpus-per-task=" + std::to_string(cpusPerTask));
    else sbatch.push_back("--exclusive");
    sbatch.insert(sbatch.end(), sbatchOptions.begin(), sbatchOptions.end());

    if (dryRun) {
        std::string line = "sbatch --parsable";
        for (const std::string& a : sbatch) line += " " + shellQuote(a);
        std::printf("%s\n# %s\n%s %s\n", m.batchScript(number).c_str(), script.c_str(), line.c_str(), script.c_str());
        return 0;
    }

    std::error_code ec;
    fs::create_directories(m.farmDir() + "/logs", ec);
    fs::create_directories(m.farmDir() + "/stats", ec);
    if (ec) throw RenderError("cannot create '" + m.farmDir() + "': " + ec.message());
    {
        std::ofstream f(script, std::ios::binary);
        f << m.batchScript(number);
        f.close();
        if (!f) throw RenderError("cannot write '" + script + "'");
        chmod(script.c_str(), 0755);
    }
    const long job = submitBatch(sbatch, script);
    m.submissions.push_back({job, tasks, nowString(), script});
    m.save();
    std::fprintf(stderr,
                 "streyes farm: submitted job %ld: %zu task%s (array %s), frames %s\n"
                 "  manifest %s\n  logs     %s/logs/%ld_*.log\n  status   streyes farm status %ld\n",
                 job, tasks.size(), tasks.size() == 1 ? "" : "s", indexList(tasks).c_str(),
                 [&] {
                     std::vector<int> fr;
                     for (int k : tasks)
                         for (int f = blocks[size_t(k)].first; f <= blocks[size_t(k)].last; ++f) fr.push_back(f);
                     return frameRanges(fr);
                 }().c_str(),
                 m.path.c_str(), m.farmDir().c_str(), job, job);
    std::printf("%ld\n", job);
    return 0;
}

}  // namespace

int farmCommand(const std::vector<std::string>& args) {
    CommandLine cl("farm", kFarmSynopsis, kFarmDescription);
    cl.app().footer(kFarmExitCodes);
    if (args.empty()) throw UsageError("farm needs a subcommand: submit, status or gather");
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (args[0] == "submit") return farmSubmit(rest);
    if (args[0] == "status") return farmStatus(rest);
    if (args[0] == "gather") return farmGather(rest);
    if (args[0].size() > 1 && args[0][0] == '-') {  // farm's own: --help
        if (!cl.parse(args)) return 0;
        throw UsageError("farm needs a subcommand: submit, status or gather");
    }
    throw UsageError("unknown farm subcommand '" + args[0] + "' (submit, status or gather)");
}

}  // namespace streyes::cli