// Interrupted renders and --resume: a render killed mid-way leaves only complete frames under
// their final names; --resume skips the frames that are complete (read back and checked) and
// renders the rest, to the same pixels an uninterrupted render gives.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::listDir;
using test::runStreyes;
using test::writeFile;

// Ten frames of a moving, shaded square, slow enough per frame (256 samples per pixel) to be
// interrupted between frames.
const char* kAnimation = R"(Format 64 48 1
Projection "perspective" "fov" [40]
PixelSamples 16 16
Shutter 0 0.5
Option "streyes" "int frames" [1 10]
WorldBegin
LightSource "distantlight" 1 "from" [0 1 -1] "to" [0 0 0]
Surface "matte"
MotionBegin [1 10]
  Translate -1 0 6
  Translate 1 0.5 7
MotionEnd
Rotate 30 1 1 0
Patch "bilinear" "P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0] "Cs" [1 0 0  0 1 0  0 0 1  1 1 1]
WorldEnd
)";

// Frames under their final names, f.NNNN.exr.
std::vector<std::string> framesIn(const std::string& dir) {
    std::vector<std::string> r;
    for (const std::string& n : listDir(dir))
        if (n.size() == 10 && n.compare(0, 2, "f.") == 0 && n.compare(6, 4, ".exr") == 0 &&
            n.find_first_not_of("0123456789", 2) == 6)
            r.push_back(n);
    return r;
}

// Pixels of every frame, read back.
std::vector<std::vector<float>> pixelsOf(const std::string& dir, int frames) {
    std::vector<std::vector<float>> r;
    for (int f = 1; f <= frames; ++f) r.push_back(readImage(expandFramePattern(dir + "/f.####.exr", f)).pixels);
    return r;
}

struct FileId {
    ino_t inode;
    struct timespec mtime;
    bool operator==(const FileId& o) const {
        return inode == o.inode && mtime.tv_sec == o.mtime.tv_sec && mtime.tv_nsec == o.mtime.tv_nsec;
    }
};
FileId fileId(const std::string& path) {
    struct stat st {};
    stat(path.c_str(), &st);
    return {st.st_ino, st.st_mtim};
}

// Renders in the background and kills it (SIGKILL: no chance to clean up) once `atLeast` frames
// are on disk. Returns false if the render finished first.
bool renderAndKill(const std::vector<std::string>& args, const std::string& dir, size_t atLeast) {
    pid_t pid = fork();
    if (pid == 0) {
        std::vector<char*> argv{const_cast<char*>(STREYES_EXE)};
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        freopen("/dev/null", "w", stdout);
        freopen("/dev/null", "w", stderr);
        execv(STREYES_EXE, argv.data());
        _exit(127);
    }
    int status = 0;
    while (framesIn(dir).size() < atLeast) {
        if (waitpid(pid, &status, WNOHANG) == pid) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    return WIFSIGNALED(status);
}

TEST(Interrupt, KilledRenderLeavesCompleteFramesAndResumeFinishesIt) {
    const test::TempDir tempDir("killed"), refTempDir("uninterrupted");
    const std::string &dir = tempDir.path(), &ref = refTempDir.path();
    const std::string scene = writeFile(dir, "anim.rib", kAnimation);
    const std::vector<std::string> args = {"render", scene, "-o", dir + "/f.####.exr", "--frame-block", "1",
                                           "--threads", "1", "--quiet"};
    ASSERT_TRUE(renderAndKill(args, dir, 2)) << "the render ended before it could be killed";

    // Only complete frames under final names (a frame being written may have left a temporary).
    const std::vector<std::string> kept = framesIn(dir);
    ASSERT_GE(kept.size(), 2u);
    ASSERT_LT(kept.size(), 10u);
    for (const std::string& n : kept) EXPECT_TRUE(isCompleteFrame(dir + "/" + n, 64, 48, "rgbaz")) << n;
    std::vector<FileId> before;
    for (const std::string& n : kept) before.push_back(fileId(dir + "/" + n));

    CliRun resumed = runStreyes("render " + scene + " -o " + dir + "/f.####.exr --frame-block 1 --resume");
    EXPECT_EQ(resumed.exitCode, 0) << resumed.output;
    EXPECT_NE(resumed.output.find(std::to_string(kept.size()) + " frames already complete"), std::string::npos)
        << resumed.output;
    // The kept frames were not written again; everything else is there, and nothing more.
    for (size_t i = 0; i < kept.size(); ++i) EXPECT_TRUE(fileId(dir + "/" + kept[i]) == before[i]) << kept[i];
    std::vector<std::string> all = framesIn(dir);
    EXPECT_EQ(all.size(), 10u);
    all.push_back("anim.rib");
    std::sort(all.begin(), all.end());
    EXPECT_EQ(listDir(dir), all);  // no temporary left over

    // The same pixels as a render that was never interrupted.
    CliRun whole = runStreyes("render " + scene + " -o " + ref + "/f.####.exr --frame-block 1 --quiet");
    ASSERT_EQ(whole.exitCode, 0) << whole.output;
    EXPECT_EQ(pixelsOf(dir, 10), pixelsOf(ref, 10));
}

// A frame counts as done only when it is a complete image of the right size and channels.
TEST(Resume, RendersAgainWhatIsMissingTruncatedOrWrong) {
    const test::TempDir tempDir("resume"), refTempDir("resume-ref");
    const std::string &dir = tempDir.path(), &ref = refTempDir.path();
    std::string rib = kAnimation;
    rib.replace(rib.find("PixelSamples 16 16"), 18, "PixelSamples 2 2");
    rib.replace(rib.find("[1 10]"), 6, "[1 6]");
    const std::string scene = writeFile(dir, "anim.rib", rib);
    ASSERT_EQ(runStreyes("render " + scene + " -o " + ref + "/f.####.exr --quiet").exitCode, 0);
    ASSERT_EQ(runStreyes("render " + scene + " -o " + dir + "/f.####.exr --quiet").exitCode, 0);
    auto frame = [&](int f) { return expandFramePattern(dir + "/f.####.exr", f); };
    // 2: cut off half way; 3: another size; 4: no Z channel; 5: gone; 6: not an image at all.
    fs::resize_file(frame(2), fs::file_size(frame(2)) / 2);
    ASSERT_EQ(runStreyes("render " + scene + " --res 32x24 --frames 3 -o " + frame(3) + " --quiet").exitCode, 0);
    std::string rgba = rib;
    rgba.insert(rgba.find("WorldBegin"), "Display \"x.exr\" \"openexr\" \"rgba\"\n");
    const std::string rgbaScene = writeFile(ref, "rgba.rib", rgba);
    ASSERT_EQ(runStreyes("render " + rgbaScene + " --frames 4 -o " + frame(4) + " --quiet").exitCode, 0);
    fs::remove(frame(5));
    writeFile(dir, "f.0006.exr", "not an image\n");
    const FileId first = fileId(frame(1));
    EXPECT_TRUE(isCompleteFrame(frame(1), 64, 48, "rgbaz"));
    for (int f : {2, 3, 4, 5, 6}) EXPECT_FALSE(isCompleteFrame(frame(f), 64, 48, "rgbaz")) << f;

    // One frame block for all six frames: rendered whole, frame 1 not written again.
    CliRun r = runStreyes("render " + scene + " -o " + dir + "/f.####.exr --resume");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("1 frame already complete"), std::string::npos) << r.output;
    EXPECT_TRUE(fileId(frame(1)) == first);
    EXPECT_EQ(pixelsOf(dir, 6), pixelsOf(ref, 6));
    // Everything complete now: nothing is rendered.
    CliRun again = runStreyes("render " + scene + " -o " + dir + "/f.####.exr --resume --stats " + dir + "/s.json");
    EXPECT_EQ(again.exitCode, 0) << again.output;
    EXPECT_NE(again.output.find("6 frames already complete"), std::string::npos) << again.output;
    EXPECT_NE(again.output.find("(nothing written)"), std::string::npos) << again.output;
}

// Temporaries of writers that no longer run are removed before rendering the frames they were
// for; those of a running process, of other frames and of other names are left alone (on a render
// farm, other frames are other tasks', written from other machines).
TEST(Resume, StaleTemporariesOfDeadRendersAreRemoved) {
    const test::TempDir tempDir("stale");
    const std::string& dir = tempDir.path();
    std::string rib = kAnimation;
    rib.replace(rib.find("PixelSamples 16 16"), 18, "PixelSamples 1 1");
    const std::string scene = writeFile(dir, "anim.rib", rib);
    pid_t dead = fork();
    if (dead == 0) _exit(0);
    waitpid(dead, nullptr, 0);  // its id is now free
    const std::string deadTmp = temporaryFrameName(dir + "/f.0003.exr", dead);
    const std::string liveTmp = temporaryFrameName(dir + "/f.0004.exr", getpid());
    const std::string otherName = temporaryFrameName(dir + "/g.0003.exr", dead);
    const std::string otherFrame = temporaryFrameName(dir + "/f.0007.exr", dead);
    for (const std::string& p : {deadTmp, liveTmp, otherName, otherFrame}) std::ofstream(p) << "partial";
    CliRun r = runStreyes("render " + scene + " --frames 1-4 -o " + dir + "/f.####.exr");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("removed 1 temporary file left by an interrupted render"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(deadTmp));
    EXPECT_TRUE(fs::exists(liveTmp));
    EXPECT_TRUE(fs::exists(otherName));
    EXPECT_TRUE(fs::exists(otherFrame));  // frame 7 is not this render's
    // Rendering frame 7 removes it.
    r = runStreyes("render " + scene + " --frames 7 -o " + dir + "/f.####.exr");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_FALSE(fs::exists(otherFrame));
    EXPECT_TRUE(fs::exists(liveTmp));
}

}  // namespace
}  // namespace streyes
