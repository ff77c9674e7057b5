// streyes farm end to end on a real one-node Slurm cluster (tools/slurm-local.sh, started by the
// ctest fixture; SLURM_CONF points at it). A shot in four blocks gives the frames a single machine
// gives; a task cancelled midway and the shot submitted again renders only what is missing;
// status tells both states; bad input is refused before anything is submitted.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "cli/cli_run.h"
#include "farm_json.h"
#include "farm_plan.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;
using farm::Json;
using test::readFile;
using test::writeFile;

struct Shell {
    int code = -1;
    std::string out;
};

// A shell command, stdout and stderr together (unless `cmd` sends stderr elsewhere itself).
Shell sh(const std::string& cmd, bool withStderr = true) {
    Shell r;
    FILE* p = popen((withStderr ? cmd + " 2>&1" : cmd).c_str(), "r");
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
    const int status = pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

// `streyes ARGS` with stdout and stderr apart: stdout is where submit prints the job id.
struct Ran {
    int code = -1;
    std::string out, err;
};
Ran streyes(const std::string& args, const std::string& prefix = "") {
    char errPath[] = "/tmp/streyes-farm-stderr-XXXXXX";
    const int fd = mkstemp(errPath);
    close(fd);
    Shell s = sh(prefix + STREYES_EXE + " " + args + " 2>" + errPath, false);
    Ran r{s.code, s.out, readFile(errPath)};
    std::remove(errPath);
    return r;
}

std::string queue() { return sh("squeue -h -o '%i %T'").out; }

// Waits until Slurm has no task of `job` pending or running.
bool waitForJob(long job, int seconds = 600) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    while (std::chrono::steady_clock::now() < end) {
        if (sh("squeue -h -j " + std::to_string(job) + " -o %i").out.empty()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    return false;
}

long jobId(const Ran& submit) {
    const std::string s = submit.out.substr(0, submit.out.find('\n'));
    return s.find_first_not_of("0123456789") == std::string::npos && !s.empty() ? std::atol(s.c_str()) : 0;
}

Json statusOf(const std::string& what, const std::string& prefix = "") {
    Ran r = streyes("farm status " + what + " --json", prefix);
    EXPECT_EQ(r.code, 0) << r.err;
    return farm::parseJson(r.out, "farm status --json");
}

const Json* taskIn(const Json& status, int block) {
    for (const Json& t : status.at("tasks"))
        if (int(t.at("block").get<double>()) == block) return &t;
    return nullptr;
}

// Frames identical pixel for pixel: the same channels and size, every value the same bits, NaN
// matching NaN. Returns how many values differ (and says where the first does).
size_t differingValues(const std::string& a, const std::string& b, std::string* where) {
    const ImageData x = readImage(a), y = readImage(b);
    if (x.width != y.width || x.height != y.height || x.channels != y.channels) {
        *where = "size or channels differ";
        return size_t(-1);
    }
    size_t n = 0;
    for (size_t i = 0; i < x.pixels.size(); ++i) {
        const float p = x.pixels[i], q = y.pixels[i];
        const bool same = (std::isnan(p) && std::isnan(q)) || std::memcmp(&p, &q, sizeof p) == 0;
        if (!same && n++ == 0)
            *where = "value " + std::to_string(i) + ": " + std::to_string(p) + " against " + std::to_string(q);
    }
    return n;
}

struct FileId {
    ino_t inode = 0;
    struct timespec mtime {};
    bool operator==(const FileId& o) const {
        return inode == o.inode && mtime.tv_sec == o.mtime.tv_sec && mtime.tv_nsec == o.mtime.tv_nsec;
    }
};
FileId fileId(const std::string& path) {
    struct stat st {};
    stat(path.c_str(), &st);
    return {st.st_ino, st.st_mtim};
}

std::string frame(const std::string& dir, int f) { return expandFramePattern(dir + "/f.####.exr", f); }

// 16 frames of a square moving and turning, lit and shaded: what moves is cut where frame blocks
// meet. `samples` per pixel side, `res` as WxH.
std::string movingScene(int samples, const std::string& res) {
    const std::string w = res.substr(0, res.find('x')), h = res.substr(res.find('x') + 1);
    return "Format " + w + " " + h + " 1\n" + "PixelSamples " + std::to_string(samples) + " " + std::to_string(samples) +
           "\n" + R"(Projection "perspective" "fov" [40]
Shutter 0 0.5
Option "streyes" "int frames" [1 16]
WorldBegin
LightSource "distantlight" 1 "from" [0 1 -1] "to" [0 0 0]
Surface "matte"
AttributeBegin
Color [0.6 0.6 0.6]
Patch "bilinear" "P" [-4 -3 9  4 -3 9  -4 3 9  4 3 9]
AttributeEnd
MotionBegin [1 16]
  Translate -1 0 6
  Translate 1 0.5 7
MotionEnd
MotionBegin [1 16]
  Rotate 0 1 1 0
  Rotate 90 1 1 0
MotionEnd
Patch "bilinear" "P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0] "Cs" [1 0 0  0 1 0  0 0 1  1 1 1]
WorldEnd
)";
}

// The same without motion: the square still, in front of the still wall.
std::string stillScene() {
    std::string s = movingScene(4, "64x48");
    const std::pair<const char*, const char*> still[] = {
        {"MotionBegin [1 16]\n  Translate -1 0 6\n  Translate 1 0.5 7\nMotionEnd\n", "Translate -1 0 6\n"},
        {"MotionBegin [1 16]\n  Rotate 0 1 1 0\n  Rotate 90 1 1 0\nMotionEnd\n", "Rotate 30 1 1 0\n"}};
    for (const auto& [motion, fixed] : still) {
        const size_t at = s.find(motion);
        EXPECT_NE(at, std::string::npos) << motion;
        if (at != std::string::npos) s.replace(at, std::string(motion).size(), fixed);
    }
    return s;
}

class Farm : public ::testing::Test {
  protected:
    void SetUp() override {
        ASSERT_NE(std::getenv("SLURM_CONF"), nullptr) << "run through ctest: the fixture starts the cluster";
        ASSERT_EQ(sh("scontrol ping").code, 0) << "no controller: " << sh("scontrol ping").out;
        ASSERT_EQ(queue(), "") << "jobs left in the queue by an earlier test";
    }
    // A test that failed half way may leave jobs: cancelled, so that the next test starts clean.
    void TearDown() override {
        if (queue().empty()) return;
        sh("scancel --user=$(id -un)");
        for (int i = 0; i < 300 && !queue().empty(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
};

// Submits frames 1-16 of `scene` in 4 blocks and renders the same frames on this machine with the
// same seed and render `options`; every frame must be identical. Then status and gather on the
// finished shot.
void expectFarmMatchesOneMachine(const test::TempDir& dir, const std::string& scene, const std::string& options = "") {
    const std::string ref = dir.path() + "/ref", out = dir.path() + "/farm";
    fs::create_directories(ref);
    fs::create_directories(out);
    const Ran single =
        streyes("render " + scene + " --frames 1-16 --seed 7 " + options + " -o " + ref + "/f.####.exr --quiet");
    ASSERT_EQ(single.code, 0) << single.err;

    const Ran submit = streyes("farm submit " + scene + " -o " + out + "/f.####.exr --frames 1-16 --block 4 --seed 7 "
                               "--cpus-per-task 1 " + options);
    ASSERT_EQ(submit.code, 0) << submit.err;
    const long job = jobId(submit);
    ASSERT_GT(job, 0) << submit.out << submit.err;
    ASSERT_TRUE(waitForJob(job)) << "job " << job << " did not finish: " << queue();

    const farm::Manifest m = farm::Manifest::load(out + "/f.farm.json");
    ASSERT_EQ(m.blocks.size(), 4u);
    ASSERT_EQ(m.submissions.size(), 1u);
    EXPECT_EQ(m.submissions[0].job, job);
    EXPECT_EQ(m.submissions[0].tasks, (std::vector<int>{0, 1, 2, 3}));
    for (int k = 0; k < 4; ++k) {
        // Each task rendered its own block, and only it.
        const Json st = farm::loadJson(m.statsPath(job, k));
        EXPECT_EQ(st.at("frames"), Json::array({1 + 4 * k, 4 + 4 * k}));
        EXPECT_EQ(st.at("frames_skipped").get<double>(), 0);
    }

    int covered = 0;
    for (int f = 1; f <= 16; ++f) {
        ASSERT_TRUE(fs::exists(frame(out, f))) << f << "\n" << readFile(m.logPath(job, (f - 1) / 4));
        std::string where;
        EXPECT_EQ(differingValues(frame(ref, f), frame(out, f), &where), 0u) << "frame " << f << ": " << where;
        const ImageData img = readImage(frame(out, f));
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) covered += img.at(x, y, 3) > 0;
    }
    EXPECT_GT(covered, 16 * 64) << "the frames are nearly empty: the comparison would prove little";

    const Json status = statusOf(out + "/f.farm.json");
    EXPECT_EQ(status.at("frames").at("complete").get<double>(), 16);
    EXPECT_EQ(status.at("frames").at("missing").get<double>(), 0);
    EXPECT_EQ(status.at("failed_tasks").get<double>(), 0);
    for (int k = 0; k < 4; ++k) {
        ASSERT_NE(taskIn(status, k), nullptr);
        EXPECT_EQ((*taskIn(status, k)).at("state").get<std::string>(), "COMPLETED") << k;
        EXPECT_EQ((*taskIn(status, k)).at("state_from").get<std::string>(), "slurm") << k;
    }
    // By job id, through the job's comment: the same answer.
    EXPECT_EQ(statusOf(std::to_string(job)).at("frames").at("complete").get<double>(), 16);

    // gather: sums of the tasks' own stats.
    const Ran gather = streyes("farm gather " + std::to_string(job) + " --json");
    ASSERT_EQ(gather.code, 0) << gather.err;
    const Json g = farm::parseJson(gather.out, "gather");
    double cpu = 0, peak = 0, micropolygons = 0, sampleTests = 0;
    for (int k = 0; k < 4; ++k) {
        const Json st = farm::loadJson(m.statsPath(job, k));
        ASSERT_GT(st.at("cpu_seconds").get<double>(), 0);
        cpu += st.at("cpu_seconds").get<double>();
        peak = std::max(peak, st.at("peak_memory_bytes").get<double>());
        micropolygons += st.at("counters").at("micropolygons").get<double>();
        sampleTests += st.at("counters").at("sample_tests").get<double>();
    }
    EXPECT_EQ(g.at("tasks_with_stats").get<double>(), 4);
    EXPECT_EQ(g.at("frames_rendered").get<double>(), 16);
    EXPECT_EQ(g.at("frames_skipped").get<double>(), 0);
    EXPECT_NEAR(g.at("cpu_seconds").get<double>(), cpu, 1e-6);
    EXPECT_EQ(g.at("peak_memory_bytes_max").get<double>(), peak);
    EXPECT_EQ(g.at("counters").at("micropolygons").get<double>(), micropolygons);
    EXPECT_EQ(g.at("counters").at("sample_tests").get<double>(), sampleTests);
    EXPECT_TRUE(fs::exists(m.farmDir() + "/summary.json"));
}

void expectFarmMatchesOneMachine(const std::string& rib) {
    const test::TempDir dir("farm-identity");
    expectFarmMatchesOneMachine(dir, writeFile(dir.path(), "shot.rib", rib));
}

TEST_F(Farm, StillShotInFourBlocksIsIdenticalToOneMachine) { expectFarmMatchesOneMachine(stillScene()); }

// A frame's pixels never depend on the frames rendered with it (DESIGN.md): moving bodies are cut
// at each frame's exposure, and every task passes the shot (--shot) so that motion segments (this
// square turns: its motion is not linear) are made over the same frames as on one machine.
TEST_F(Farm, MovingShotInFourBlocksIsIdenticalToOneMachine) { expectFarmMatchesOneMachine(movingScene(4, "64x48")); }

// A scene of more frames than are submitted (the demo's 48; frames 1-16 in 4 blocks): one machine
// rendering --frames 1-16 decides motion over the scene's frames joined with those (1-48), and so
// must every task, whose own frames are 4.
TEST_F(Farm, PartOfALongerSceneInFourBlocksIsIdenticalToOneMachine) {
    const test::TempDir dir("farm-demo");
    expectFarmMatchesOneMachine(dir, std::string(STREYES_SOURCE_DIR) + "/scenes/demo.rib", "--res 160x90");
    const farm::Manifest m = farm::Manifest::load(dir.path() + "/farm/f.farm.json");
    EXPECT_EQ(m.shotFirst, 1);
    EXPECT_EQ(m.shotLast, 48);
}

// One task cancelled while it renders (its frames written one at a time, so some are on disk),
// then the shot submitted again: only the missing frames are rendered, complete ones untouched.
TEST_F(Farm, CancelledTaskThenResubmittedRendersOnlyTheMissingFrames) {
    const test::TempDir dir("farm-cancel");
    const std::string scene = writeFile(dir.path(), "shot.rib", movingScene(16, "256x192"));
    const std::string out = dir.path() + "/farm";
    fs::create_directories(out);
    const std::string submitArgs =
        "farm submit " + scene + " -o " + out + "/f.####.exr --block 4 --cpus-per-task 1 --frame-block 1";
    const Ran submit = streyes(submitArgs);
    ASSERT_EQ(submit.code, 0) << submit.err;
    const long job = jobId(submit);
    ASSERT_GT(job, 0);

    // Task 1 renders frames 5-8: cancel it once one or two of them are written.
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(300);
    int onDisk = 0;
    while (std::chrono::steady_clock::now() < end) {
        onDisk = 0;
        for (int f = 5; f <= 8; ++f) onDisk += fs::exists(frame(out, f));
        if (onDisk >= 1) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ASSERT_GE(onDisk, 1) << "task 1 wrote nothing in 5 minutes: " << queue();
    ASSERT_LT(onDisk, 4) << "task 1 finished before it could be cancelled: make its frames slower";
    ASSERT_EQ(sh("scancel " + std::to_string(job) + "_1").code, 0);
    ASSERT_TRUE(waitForJob(job)) << queue();

    std::vector<int> complete;
    for (int f = 1; f <= 16; ++f)
        if (isCompleteFrame(frame(out, f), 256, 192, "rgbaz")) complete.push_back(f);
    int kept = 0;  // frames of block 1 the cancelled task finished
    for (int f : complete) kept += f >= 5 && f <= 8;
    ASSERT_GE(kept, 1);
    ASSERT_LT(kept, 4);
    ASSERT_EQ(complete.size(), size_t(12 + kept)) << "the other blocks' tasks finished";

    // Status, from Slurm: the frames on disk and the cancelled task with its log.
    const Json s1 = statusOf(out + "/f.farm.json");
    EXPECT_EQ(s1.at("frames").at("complete").get<double>(), 12 + kept);
    EXPECT_EQ(s1.at("frames").at("missing").get<double>(), 4 - kept);
    EXPECT_EQ(s1.at("failed_tasks").get<double>(), 1);
    const Json* t1 = taskIn(s1, 1);
    ASSERT_NE(t1, nullptr);
    EXPECT_EQ((*t1).at("state").get<std::string>(), "CANCELLED");
    EXPECT_EQ((*t1).at("state_from").get<std::string>(), "slurm");
    EXPECT_TRUE((*t1).at("failed").get<bool>());
    EXPECT_EQ((*t1).at("missing").get<double>(), 4 - kept);
    const std::string tail = t1->at("log_tail").get<std::string>();
    EXPECT_NE(tail.find("streyes farm: job " + std::to_string(job) + " task 1"), std::string::npos) << tail;
    for (int k : {0, 2, 3}) {
        EXPECT_EQ((*taskIn(s1, k)).at("state").get<std::string>(), "COMPLETED") << k;
        EXPECT_FALSE((*taskIn(s1, k)).at("failed").get<bool>()) << k;
    }
    // The text report names the cancelled task and quotes its log.
    const Ran text = streyes("farm status " + out + "/f.farm.json");
    EXPECT_NE(text.out.find("frames: " + std::to_string(12 + kept) + " of 16 complete"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find(std::to_string(job) + "_1, frames 5-8: CANCELLED"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("    | streyes farm: job"), std::string::npos) << text.out;
    // Without Slurm's commands (a machine that only sees the files): the same, from the logs.
    const Json s2 = statusOf(out + "/f.farm.json", "env PATH=/nonexistent ");
    EXPECT_FALSE(s2.at("slurm_reachable").get<bool>());
    EXPECT_EQ(s2.at("frames").at("complete").get<double>(), 12 + kept);
    EXPECT_EQ((*taskIn(s2, 1)).at("state").get<std::string>(), "ENDED_UNFINISHED");
    EXPECT_EQ((*taskIn(s2, 0)).at("state").get<std::string>(), "COMPLETED");

    std::vector<FileId> before;
    for (int f : complete) before.push_back(fileId(frame(out, f)));

    // Submitted again with the same arguments: one task, for block 1 only.
    const Ran again = streyes(submitArgs);
    ASSERT_EQ(again.code, 0) << again.err;
    const long job2 = jobId(again);
    ASSERT_GT(job2, job);
    ASSERT_TRUE(waitForJob(job2)) << queue();
    const farm::Manifest m = farm::Manifest::load(out + "/f.farm.json");
    ASSERT_EQ(m.submissions.size(), 2u);
    EXPECT_EQ(m.submissions[1].tasks, std::vector<int>{1});

    for (int f = 1; f <= 16; ++f) EXPECT_TRUE(isCompleteFrame(frame(out, f), 256, 192, "rgbaz")) << f;
    for (size_t i = 0; i < complete.size(); ++i)
        EXPECT_TRUE(fileId(frame(out, complete[i])) == before[i]) << "frame " << complete[i] << " was written again";
    // The second run's own account: it skipped the frames the cancelled task had finished.
    const Json st = farm::loadJson(m.statsPath(job2, 1));
    EXPECT_EQ(st.at("frames"), Json::array({5, 8}));
    EXPECT_EQ(st.at("frames_skipped").get<double>(), kept);
    const std::string log = readFile(m.logPath(job2, 1));
    EXPECT_NE(log.find(std::to_string(kept) + " frame" + (kept == 1 ? "" : "s") + " already complete"), std::string::npos)
        << log;
    EXPECT_NE(log.find("streyes farm: exit code 0"), std::string::npos) << log;

    const Json s3 = statusOf(out + "/f.farm.json");
    EXPECT_EQ(s3.at("frames").at("complete").get<double>(), 16);
    EXPECT_EQ(s3.at("frames").at("missing").get<double>(), 0);
    EXPECT_EQ(s3.at("failed_tasks").get<double>(), 0);
    EXPECT_EQ((*taskIn(s3, 1)).at("job").get<double>(), job2);
    EXPECT_EQ((*taskIn(s3, 1)).at("state").get<std::string>(), "COMPLETED");

    // gather: the cancelled task left no stats; the rest add up to the shot.
    const Json g = farm::parseJson(streyes("farm gather " + out + "/f.farm.json --json").out, "gather");
    EXPECT_EQ(g.at("tasks_with_stats").get<double>(), 4);
    ASSERT_EQ(g.at("tasks_without_stats").size(), 1u);
    EXPECT_EQ(g.at("tasks_without_stats")[0].get<std::string>(), std::to_string(job) + "_1");
    EXPECT_EQ(g.at("frames_rendered").get<double>(), 16 - kept);
    EXPECT_EQ(g.at("frames_skipped").get<double>(), kept);

    // Nothing left to do: a third submit submits nothing.
    const Ran third = streyes(submitArgs);
    EXPECT_EQ(third.code, 0) << third.err;
    EXPECT_EQ(third.out, "");
    EXPECT_NE(third.err.find("all 16 frames are complete: nothing to submit"), std::string::npos) << third.err;
    EXPECT_EQ(farm::Manifest::load(out + "/f.farm.json").submissions.size(), 2u);
}

// ---- Bad input: exit 2, a message saying what to do, and nothing submitted -----------------------

class FarmBadInput : public Farm {
  protected:
    void SetUp() override {
        Farm::SetUp();
        scene_ = writeFile(dir_.path(), "shot.rib", movingScene(2, "32x24"));
        out_ = dir_.path() + "/out";
        fs::create_directories(out_);
    }
    // Runs `streyes farm submit ARGS` and checks it was refused before anything was submitted.
    void expectRefused(const std::string& args, const std::string& message, const std::string& prefix = "") {
        const Ran r = streyes("farm submit " + args, prefix);
        EXPECT_EQ(r.code, 2) << r.out << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
        EXPECT_EQ(r.out, "") << "no job id";
        EXPECT_EQ(queue(), "") << "something was submitted";
        EXPECT_FALSE(fs::exists(out_ + "/f.farm.json"));
        EXPECT_FALSE(fs::exists(out_ + "/f.farm"));
    }
    test::TempDir dir_{"farm-bad"};
    std::string scene_, out_;
};

TEST_F(FarmBadInput, NoSlurmInstalled) {
    expectRefused(scene_ + " -o " + out_ + "/f.####.exr --block 4", "Slurm is not installed here: no 'sbatch' on PATH",
                  "env PATH=/nonexistent ");
}

TEST_F(FarmBadInput, NoControllerReachable) {
    // The same cluster's configuration with the controller's port moved to one nobody listens on.
    std::string conf = readFile(std::getenv("SLURM_CONF"));
    const size_t at = conf.find("SlurmctldPort=");
    ASSERT_NE(at, std::string::npos);
    conf.replace(at, conf.find('\n', at) - at, "SlurmctldPort=1");
    const std::string dead = writeFile(dir_.path(), "dead.conf", conf);
    expectRefused(scene_ + " -o " + out_ + "/f.####.exr --block 4", "no Slurm controller answers",
                  "env SLURM_CONF=" + dead + " ");
}

TEST_F(FarmBadInput, OutputFolderMissingOrNotAFolder) {
    expectRefused(scene_ + " -o " + out_ + "/missing/f.####.exr --block 4", "does not exist");
    writeFile(out_, "file", "x");
    expectRefused(scene_ + " -o " + out_ + "/file/f.####.exr --block 4", "is not a folder");
}

TEST_F(FarmBadInput, OutputFolderReadOnly) {
    // Root ignores permission bits: the command runs as 'nobody' then, for whom the folder is read-only.
    const std::string ro = dir_.path() + "/ro";
    fs::create_directories(ro);
    fs::permissions(dir_.path(), fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                     fs::perms::others_read | fs::perms::others_exec);
    fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                            fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
    fs::permissions(scene_, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
    // Nobody may not read the cluster's slurm.conf where the build keeps it (a clone in root's home
    // folder, mode 700, is closed to others): the command reads a copy beside the scene.
    const std::string conf = writeFile(dir_.path(), "slurm.conf", readFile(std::getenv("SLURM_CONF")));
    fs::permissions(conf, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
    const std::string asNobody =
        geteuid() == 0 ? "env SLURM_CONF=" + conf + " setpriv --reuid=65534 --regid=65534 --clear-groups " : "";
    expectRefused(scene_ + " -o " + ro + "/f.####.exr --block 4", "cannot write '" + ro + "/f.0001.exr'", asNobody);
    EXPECT_TRUE(fs::is_empty(ro));
}

TEST_F(FarmBadInput, BlockLongerThanTheShot) {
    expectRefused(scene_ + " -o " + out_ + "/f.####.exr --frames 1-16 --block 32",
                  "--block 32 is longer than the shot: frames 1-16 are 16 frames; give --block 16 or less");
}

TEST_F(FarmBadInput, SceneThatDoesNotParse) {
    const std::string bad = writeFile(dir_.path(), "bad.rib", "WorldBegin\nPatch \"bilinear\" \"P\" [0 0 0 1\nWorldEnd\n");
    expectRefused(bad + " -o " + out_ + "/f.####.exr --block 4", "bad.rib:");
}

TEST_F(FarmBadInput, UnknownPartitionAndBadRenderOption) {
    expectRefused(scene_ + " -o " + out_ + "/f.####.exr --block 4 --partition nosuch", "no partition 'nosuch'");
    expectRefused(scene_ + " -o " + out_ + "/f.####.exr --block 4 --samples many", "--samples expects");
    expectRefused(scene_ + " -o " + out_ + "/f.exr --block 4", "has no #### frame field");
}

TEST_F(FarmBadInput, AnotherShotInTheSameOutput) {
    farm::Manifest m;
    m.path = out_ + "/f.farm.json";
    m.scene = scene_;
    m.output = out_ + "/f.####.exr";
    m.first = m.shotFirst = 1;
    m.last = m.shotLast = 16;
    m.block = 4;
    m.blocks = farm::cutBlocks(1, 16, 4);
    m.seed = 3;  // not the seed given below
    m.width = 32;
    m.height = 24;
    m.save();
    const Ran r = streyes("farm submit " + scene_ + " -o " + out_ + "/f.####.exr --block 4");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("holds another shot (its seed is 3, not 0 as given now)"), std::string::npos) << r.err;
    EXPECT_EQ(queue(), "");
    EXPECT_EQ(farm::Manifest::load(m.path).submissions.size(), 0u);
}

}  // namespace
}  // namespace streyes
