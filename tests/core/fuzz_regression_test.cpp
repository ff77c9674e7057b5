// Replays, through the fuzzer's own code (fuzz/fuzz_rib.h), every input in fuzz/regressions (what
// the fuzzer once crashed on, each fixed) and the seeds in fuzz/seeds. A file named *.bad.rib must
// be refused as bad input; any other must render. Under the asan preset this runs sanitized.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../../fuzz/fuzz_rib.h"
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

TEST(FuzzRegression, SeedsRender) { EXPECT_GE(replay("fuzz/seeds"), 1); }

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
    // Outside the fuzzer, scenes may again.
    EXPECT_TRUE(sceneAccess().programs);
    EXPECT_TRUE(sceneAccess().files);
}

}  // namespace
}  // namespace streyes
