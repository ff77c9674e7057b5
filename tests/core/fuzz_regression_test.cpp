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

}  // namespace
}  // namespace streyes
