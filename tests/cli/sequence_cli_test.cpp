// Frame sequences through the streyes command: patterns and --frames, per-frame Display names,
// and bad sequences (exit 2, the message naming the file and line).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;
using test::listDir;
using test::readFile;
using test::runStreyesWith;
using test::writeFile;

std::string shotFile(int f) {
    char name[64];
    std::snprintf(name, sizeof name, "shot.%04d.rib", f);
    return name;
}

// Frames 1..n of the generated shot copied into `dir`.
void copyShot(const std::string& dir, int n) {
    for (int f = 1; f <= n; ++f)
        fs::copy_file(test::sourcePath("scenes/sequence/" + shotFile(f)), dir + "/" + shotFile(f));
}

test::CliRun renderIn(const std::string& dir, const std::string& args) {
    return runStreyesWith("cd " + dir + " && ", "render " + args + " -q");
}

TEST(SequenceCli, PatternWritesEachFrameUnderItsOwnDisplayName) {
    test::TempDir tmp("seqcli");
    const test::CliRun r = renderIn(tmp.path(), "'" + test::sourcePath("scenes/sequence/shot.####.rib") + "' --frames 3-5");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(listDir(tmp.path()), (std::vector<std::string>{"shot.0003.exr", "shot.0004.exr", "shot.0005.exr"}));
    const ImageData img = readImage(tmp.path() + "/shot.0004.exr");
    EXPECT_EQ(img.width, 160);
    EXPECT_EQ(img.channels.size(), 4u);  // Display "rgba"
}

// Frames first..last of dir/A.####.exr and dir/B.####.exr hold the same pixels.
void expectSameFrames(const std::string& dir, const std::string& a, const std::string& b, int first, int last) {
    for (int f = first; f <= last; ++f) {
        char n[16];
        std::snprintf(n, sizeof n, ".%04d.exr", f);
        EXPECT_EQ(readImage(dir + "/" + a + n).pixels, readImage(dir + "/" + b + n).pixels) << f;
    }
}

TEST(SequenceCli, FramesOfAPatternEqualTheSameFramesOfOneFile) {
    test::TempDir tmp("seqcli");
    ASSERT_EQ(renderIn(tmp.path(), "'" + test::sourcePath("scenes/sequence/shot.####.rib") + "' -o 'p.####.exr'").exitCode, 0);
    const test::CliRun r = renderIn(tmp.path(), test::sourcePath("scenes/sequence/shot.rib") + " --frames 6-8 -o 'b.####.exr'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectSameFrames(tmp.path(), "p", "b", 6, 8);
    EXPECT_FALSE(fs::exists(tmp.path() + "/b.0005.exr"));
}

// --frame-block 3: the sequence is read and rendered three frames at a time; every frame the same.
TEST(SequenceCli, ABlockOfFramesAtATimeGivesTheSameFrames) {
    test::TempDir tmp("seqcli");
    const std::string shot = test::sourcePath("scenes/sequence/shot.rib");
    ASSERT_EQ(renderIn(tmp.path(), shot + " -o 'a.####.exr'").exitCode, 0);
    const test::CliRun r = renderIn(tmp.path(), shot + " --frame-block 3 -o 'b.####.exr' --stats s.json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectSameFrames(tmp.path(), "a", "b", 1, 8);
    const std::string stats = readFile(tmp.path() + "/s.json");
    EXPECT_EQ(nlohmann::json::parse(stats)["frames"], nlohmann::json::array({1, 8})) << stats;
}

// A render farm takes a sequence as it takes a scene: the plan's tasks render frame blocks of the
// pattern (each block renders its frames as the whole sequence does: the lines it runs are checked
// above); frames that disagree are refused before anything is submitted.
TEST(SequenceCli, FarmPlansASequence) {
    test::TempDir tmp("seqcli");
    const std::string pattern = "'" + test::sourcePath("scenes/sequence/shot.####.rib") + "'";
    test::CliRun r = runStreyesWith("", "farm submit " + pattern + " -o " + tmp.path() + "/f.####.exr --block 4 --dry-run");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("frames 1-8 (8), 160x90, in 2 blocks of 4"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("BLOCKS=(1-4 5-8)"), std::string::npos) << r.output;
    // A frame with another shutter is another pass: planned with the others, not refused.
    copyShot(tmp.path(), 2);
    std::string text = readFile(tmp.path() + "/" + shotFile(2));
    text.replace(text.find("Shutter 0 0.5"), 13, "Shutter 0 1");
    writeFile(tmp.path(), shotFile(2), text);
    r = runStreyesWith("cd " + tmp.path() + " && ", "farm submit 'shot.####.rib' -o " + tmp.path() + "/g.####.exr --dry-run");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("frames 1-2 (2)"), std::string::npos) << r.output;
}

TEST(SequenceCli, AMissingFrameFileIsAnErrorNamingIt) {
    test::TempDir tmp("seqcli");
    copyShot(tmp.path(), 4);
    fs::remove(tmp.path() + "/shot.0003.rib");
    test::CliRun r = renderIn(tmp.path(), "'shot.####.rib'");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("missing frame file 'shot.0003.rib' (frame 3)"), std::string::npos) << r.output;
    r = renderIn(tmp.path(), "'shot.####.rib' --frames 1-2");  // the frames there are render
    EXPECT_EQ(r.exitCode, 0) << r.output;
    r = renderIn(tmp.path(), "'shot.####.rib' --frames 4-5");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("missing frame file 'shot.0005.rib' (frame 5): --frames 4-5 asks for it"), std::string::npos)
        << r.output;
    r = renderIn(tmp.path(), "'nothing.####.rib'");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("no frame file matches the pattern 'nothing.####.rib'"), std::string::npos) << r.output;
    r = renderIn(tmp.path(), test::sourcePath("scenes/sequence/shot.rib") + " --frames 8-9");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("has no FrameBegin 9"), std::string::npos) << r.output;
}

// Frames of another resolution or shutter are passes of their own (streyes/passes.h): nothing is
// refused, and each frame is what it is alone.
TEST(SequenceCli, FramesOfOtherResolutionOrShutterRenderAsPassesOfTheirOwn) {
    test::TempDir tmp("seqcli");
    copyShot(tmp.path(), 3);
    std::string text = readFile(tmp.path() + "/" + shotFile(2));
    text.replace(text.find("Format 160 90"), 13, "Format 320 90");
    writeFile(tmp.path(), shotFile(2), text);
    text = readFile(tmp.path() + "/" + shotFile(3));
    text.replace(text.find("Shutter 0 0.5"), 13, "Shutter 0 0.4");
    writeFile(tmp.path(), shotFile(3), text);
    test::CliRun r = renderIn(tmp.path(), "'shot.####.rib' --algorithm frames");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(readImage(tmp.path() + "/shot.0002.exr").width, 320);
    EXPECT_EQ(readImage(tmp.path() + "/shot.0001.exr").width, 160);
    for (int f = 1; f <= 3; ++f) {
        const std::string name = "shot.000" + std::to_string(f) + ".exr";
        fs::rename(tmp.path() + "/" + name, tmp.path() + "/all-" + name);
        r = renderIn(tmp.path(), "'shot.####.rib' --algorithm frames --frames " + std::to_string(f));
        ASSERT_EQ(r.exitCode, 0) << r.output;
        const ImageData a = readImage(tmp.path() + "/all-" + name), b = readImage(tmp.path() + "/" + name);
        EXPECT_EQ(a.pixels, b.pixels) << name;
    }
}

TEST(SequenceCli, AnIdentifierGivenTwiceInAFrameWarnsNamingFileAndLine) {
    test::TempDir tmp("seqcli");
    std::string text = readFile(test::sourcePath("scenes/sequence/shot.0001.rib"));
    const std::string wall = "Attribute \"identifier\" \"name\" [\"wall\"]";
    text.replace(text.find("Attribute \"identifier\" \"name\" [\"pillar\"]"), wall.size() + 2, wall);
    writeFile(tmp.path(), "twice.rib", text);
    int line = 1;
    for (size_t i = 0; i < text.rfind(wall); ++i) line += text[i] == '\n';
    const test::CliRun r = runStreyesWith("cd " + tmp.path() + " && ", "render twice.rib");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("twice.rib:" + std::to_string(line) + ": warning: identifier \"wall\" is given again in frame 1"),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(fs::exists(tmp.path() + "/shot.0001.exr"));  // its Display, frame 1 of its FrameBegin
}

}  // namespace
}  // namespace streyes
