// Replays, through the fuzzers' own code (fuzz/fuzz_rib.h, fuzz_sl.h, fuzz_sequence.h), every input
// in their regression folders (what a fuzzer once crashed on, each fixed) and their seeds. A file
// named *.bad.EXT must be refused as bad input; any other must render (or compile, or run). Under the
// asan preset this runs sanitized.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../../fuzz/fuzz_rib.h"
#include "../../fuzz/fuzz_sequence.h"
#include "../../fuzz/fuzz_sl.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;

int replay(const std::string& folder) {
    int n = 0;
    for (const auto& entry : fs::directory_iterator(test::sourcePath(folder))) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() != ".rib") continue;
        std::ifstream in(entry.path(), std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        const bool bad = name.size() > 8 && name.compare(name.size() - 8, 8, ".bad.rib") == 0;
        EXPECT_EQ(fuzz::parseAndRender(text.str()), bad ? fuzz::Outcome::BadInput : fuzz::Outcome::Rendered) << name;
        ++n;
    }
    return n;
}

// The inputs of `folder` with extension `ext` (".sl"), each with whether it is named NAME.bad.EXT.
struct Input {
    std::string name, text;
    bool bad = false;
};
std::vector<Input> inputs(const std::string& folder, const std::string& ext) {
    std::vector<Input> out;
    std::error_code ec;
    if (!fs::is_directory(test::sourcePath(folder), ec)) return out;  // none found yet
    for (const auto& entry : fs::directory_iterator(test::sourcePath(folder))) {
        if (entry.path().extension() != ext) continue;
        std::ifstream in(entry.path(), std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        const std::string name = entry.path().filename().string(), bad = ".bad" + ext;
        out.push_back({name, text.str(), name.size() > bad.size() && name.compare(name.size() - bad.size(), bad.size(), bad) == 0});
    }
    return out;
}

TEST(FuzzRegression, SeedsRender) { EXPECT_GE(replay("fuzz/seeds"), 1); }

// The Shading Language fuzzers' seeds: the shipped shaders and fuzz/seeds-sl compile and run on the
// fuzzers' grid, lit, within the instruction budget.
TEST(FuzzRegression, ShaderSeedsCompileAndRun) {
    int n = 0;
    for (const char* folder : {"shaders", "fuzz/seeds-sl"})
        for (const Input& i : inputs(folder, ".sl")) {
            EXPECT_EQ(fuzz::compileFuzzedShader(i.text), fuzz::ShaderOutcome::Compiled) << i.name;
            EXPECT_EQ(fuzz::runFuzzedShader(i.text), fuzz::ShaderOutcome::Ran) << i.name;
            ++n;
        }
    EXPECT_GE(n, 20);
}

TEST(FuzzRegression, WhatTheShadingLanguageFuzzersFoundStaysFixed) {
    for (const Input& i : inputs("fuzz/regressions-sl", ".sl"))
        EXPECT_EQ(fuzz::compileFuzzedShader(i.text), i.bad ? fuzz::ShaderOutcome::BadInput : fuzz::ShaderOutcome::Compiled)
            << i.name;
    for (const Input& i : inputs("fuzz/regressions-vm", ".sl"))
        EXPECT_EQ(fuzz::runFuzzedShader(i.text), i.bad ? fuzz::ShaderOutcome::BadInput : fuzz::ShaderOutcome::Ran)
            << i.name;
}

// A shader may loop forever, as in any renderer; the fuzzers' interpreter stops it at its budget.
TEST(FuzzRegression, AShaderThatNeverEndsRunsOutOfTheFuzzersBudget) {
    const std::string forever = "surface forever() { float x = 0; while (x < 1) { x = x * 2; } Ci = x; }";
    EXPECT_EQ(fuzz::compileFuzzedShader(forever), fuzz::ShaderOutcome::Compiled);
    EXPECT_EQ(fuzz::runFuzzedShader(forever), fuzz::ShaderOutcome::BadInput);
    sl::ShadingVM vm;
    vm.setInstructionBudget(1000);
    const fuzz::FuzzGrid g;
    const sl::ShaderInstance shader(sl::compileShader(forever, "forever.sl"));
    try {
        vm.run(shader, g.grid);
        ADD_FAILURE() << "the loop ended";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("shader \"forever\" (forever.sl) ran more than 1000 instructions"),
                  std::string::npos)
            << e.what();
    }
}

// The frame-sequence fuzzer's seeds (FrameBegin blocks, and frame files apart) and what it found.
TEST(FuzzRegression, SequenceSeedsRenderAndWhatTheFuzzerFoundStaysFixed) {
    int n = 0;
    for (const char* folder : {"fuzz/seeds-sequence", "fuzz/regressions-sequence"})
        for (const Input& i : inputs(folder, ".rib")) {
            EXPECT_EQ(fuzz::readFuzzedSequence(i.text), i.bad ? fuzz::Outcome::BadInput : fuzz::Outcome::Rendered)
                << folder << "/" << i.name;
            ++n;
        }
    EXPECT_GE(n, 2);
    // Frames of other sizes are passes of their own (streyes/passes.h), rendered; a frame that
    // opens a block it never closes is bad input.
    EXPECT_EQ(fuzz::readFuzzedSequence("Format 8 8 1\nWorldBegin\nWorldEnd\n\fFormat 9 8 1\nWorldBegin\nWorldEnd\n"),
              fuzz::Outcome::Rendered);
    EXPECT_EQ(fuzz::readFuzzedSequence("Format 8 8 1\nWorldBegin\nWorldEnd\n\fFormat 9 8 1\nWorldBegin\nAttributeBegin\n"),
              fuzz::Outcome::BadInput);
}

TEST(FuzzRegression, WhatTheFuzzerFoundStaysFixed) { EXPECT_GE(replay("fuzz/regressions"), 1); }

// Fuzzed scenes may name any program or file: the fuzzer runs no program and reads no other file.
TEST(FuzzRegression, FuzzedScenesRunNoProgramAndReadNoFile) {
    const std::string world = "WorldBegin\n", end = "\nWorldEnd\n";
    const test::TempDir tempDir("fuzz-access");
    const std::string marker = tempDir.path() + "/ran";
    for (const std::string& request :
         {"Procedural \"RunProgram\" [\"/usr/bin/touch " + marker + "\" \"\"] [-1 1 -1 1 1 2]",
          "ReadArchive \"" + test::sourcePath("scenes/ramp.rib") + "\"",
          "Procedural \"DelayedReadArchive\" [\"" + test::sourcePath("scenes/ramp.rib") + "\"] [-1 1 -1 1 1 2]"})
        EXPECT_EQ(fuzz::parseAndRender(world + request + end), fuzz::Outcome::BadInput) << request;
    EXPECT_FALSE(fs::exists(marker));
    // Outside the fuzzers, scenes may again.
    EXPECT_EQ(fuzz::readFuzzedSequence(world + "ReadArchive \"" + test::sourcePath("scenes/ramp.rib") + "\"" + end),
              fuzz::Outcome::BadInput);
    EXPECT_TRUE(sceneAccess().programs);
    EXPECT_TRUE(sceneAccess().files);
}

}  // namespace
}  // namespace streyes
