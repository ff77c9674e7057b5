// streyes farm without a cluster: frame blocks, the block-length choice, the manifest, the batch
// script (run by bash with a stand-in for streyes), and the parsing of Slurm's output.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "farm_json.h"
#include "farm_plan.h"
#include "farm_slurm.h"

namespace streyes::farm {
namespace {

namespace fs = std::filesystem;

// A temporary folder removed at the end of the test.
struct Folder {
    std::string path;
    Folder() {
        char tmpl[] = "/tmp/streyes-farm-plan-XXXXXX";
        path = mkdtemp(tmpl);
    }
    ~Folder() { fs::remove_all(path); }
};

std::string run(const std::string& cmd) {
    std::string out;
    FILE* p = popen(cmd.c_str(), "r");
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
    pclose(p);
    return out;
}

// CPU per frame = a + b / L, measured at the usual lengths.
BlockCurve modelCurve(double a, double b, std::vector<int> blocks = {1, 4, 16, 64}) {
    BlockCurve c;
    c.name = "model";
    c.blocks = blocks;
    for (int L : blocks) c.cpuPerFrame.push_back(a + b / L);
    return c;
}

// The rule chooseBlock states: within 5% of the shortest wall time, the least CPU; then the
// shortest wall time; then the shortest block.
void expectTheRule(const BlockChoice& ch) {
    double minWall = ch.options[0].wall;
    for (const BlockOption& o : ch.options) minWall = std::min(minWall, o.wall);
    EXPECT_LE(ch.chosen.wall, minWall * 1.05);
    for (const BlockOption& o : ch.options) {
        if (o.wall > minWall * 1.05) continue;
        EXPECT_GE(o.cpu, ch.chosen.cpu * 0.995) << o.block;
        if (o.cpu <= ch.chosen.cpu * 1.005) {
            EXPECT_GE(o.wall, ch.chosen.wall * 0.995) << o.block;
            if (o.wall <= ch.chosen.wall * 1.005) {
                EXPECT_GE(o.block, ch.chosen.block);
            }
        }
    }
}

TEST(FarmBlocks, CutInOrderWithAShorterLast) {
    auto b = cutBlocks(1, 16, 4);
    ASSERT_EQ(b.size(), 4u);
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(b[size_t(k)].first, 1 + 4 * k);
        EXPECT_EQ(b[size_t(k)].last, 4 + 4 * k);
    }
    b = cutBlocks(-2, 7, 4);
    ASSERT_EQ(b.size(), 3u);
    EXPECT_EQ(b[2].str(), "6-7");
    EXPECT_EQ(b[0].str(), "-2-1");
    EXPECT_EQ(cutBlocks(5, 5, 3)[0].str(), "5");
    // Every frame in exactly one block, whatever the length.
    for (int L = 1; L <= 12; ++L) {
        int next = 3;
        for (const Block& blk : cutBlocks(3, 40, L)) {
            EXPECT_EQ(blk.first, next);
            EXPECT_LE(blk.length(), L);
            next = blk.last + 1;
        }
        EXPECT_EQ(next, 41);
    }
}

TEST(FarmBlocks, IndexListsAndFrameRanges) {
    EXPECT_EQ(indexList({0, 1, 2, 3}), "0-3");
    EXPECT_EQ(indexList({3, 1, 5, 6, 7}), "1,3,5-7");
    EXPECT_EQ(frameRanges({5, 6, 7, 8, 12}), "5-8, 12");
    EXPECT_EQ(frameRanges({}), "");
    EXPECT_EQ(parseTaskIds("0-3"), (std::vector<int>{0, 1, 2, 3}));
    EXPECT_EQ(parseTaskIds("1,3,5-7%2"), (std::vector<int>{1, 3, 5, 6, 7}));
    EXPECT_EQ(parseTaskIds(indexList({2, 9, 10, 11})), (std::vector<int>{2, 9, 10, 11}));
}

TEST(FarmCurve, ExactForTheModelBetweenPointsAndHeldBeyond) {
    const BlockCurve c = modelCurve(1.5, 3.0);
    for (double L : {1.0, 2.0, 3.0, 4.0, 7.0, 16.0, 40.0, 64.0}) EXPECT_NEAR(c.at(L), 1.5 + 3.0 / L, 1e-12) << L;
    EXPECT_DOUBLE_EQ(c.at(1000), c.at(64));
    EXPECT_DOUBLE_EQ(c.at(0.5), c.at(1));
}

TEST(FarmCurve, ChoosesOneWaveWhenCoherenceKeepsPaying) {
    // 1,000 frames on 50 slots, per-block work large: blocks long enough for one wave of tasks.
    const BlockCurve c = modelCurve(1.0, 10.0);
    const BlockChoice ch = chooseBlock(1000, 50, c, 64, 1000);
    EXPECT_EQ(ch.chosen.waves, 1);
    EXPECT_LE(ch.chosen.tasks, 50);
    EXPECT_GE(ch.chosen.block, (1000 + 49) / 50);
    EXPECT_EQ(ch.options.size(), 1000u);
    expectTheRule(ch);
    // Block 64 would leave 34 of the 50 slots idle: far slower.
    EXPECT_GT(ch.options[63].wall, 2 * ch.chosen.wall);
}

TEST(FarmCurve, NoCoherenceMeansOneFrameATask) {
    // CPU per frame the same at every length: shorter blocks only spread the work.
    BlockCurve flat = modelCurve(2.0, 0.0);
    EXPECT_EQ(chooseBlock(16, 50, flat, 64, 16).chosen.block, 1);
    // With one slot, every length costs the same wall and CPU: the shortest wins.
    EXPECT_EQ(chooseBlock(16, 1, flat, 64, 16).chosen.block, 1);
    // With one slot and coherence, the whole shot in one block.
    EXPECT_EQ(chooseBlock(16, 1, modelCurve(1.0, 5.0), 64, 16).chosen.block, 16);
}

TEST(FarmCurve, NoLongerThanTheRendererKeepsTogether) {
    // The renderer keeps at most 6 frames together (4K): longer blocks save nothing, so with one
    // slot the choice is the shortest block that reaches the renderer's: 6 (60 frames: no
    // shorter last block to tip the balance).
    const BlockChoice ch = chooseBlock(60, 1, modelCurve(1.0, 5.0), 6, 60);
    EXPECT_EQ(ch.chosen.block, 6);
    EXPECT_NE(ch.why.find("at most 6 frames together"), std::string::npos) << ch.why;
    // A task longer than 6 frames is rendered 6 at a time, the rest after: 12 frames cost twice 6,
    // 10 cost 6 and then 4 (dearer a frame).
    const BlockCurve c = modelCurve(1.0, 5.0);
    const BlockChoice wide = chooseBlock(1000, 50, c, 6, 1000);
    EXPECT_DOUBLE_EQ(wide.options[11].cpu, 1000 / 12 * 12 * c.at(6) + 4 * c.at(4));  // 83 tasks of 12, one of 4
    EXPECT_DOUBLE_EQ(wide.options[9].wall, 2 * (6 * c.at(6) + 4 * c.at(4)));          // 100 tasks of 10: two waves
    // 1,000 frames on 50 slots: one wave of tasks a little over 18 frames beats waves of 6.
    expectTheRule(wide);
    EXPECT_GT(wide.chosen.block, 6);
    EXPECT_LT(wide.chosen.wall, wide.options[5].wall);
}

TEST(FarmCurve, BuiltInCurvesAreTheMeasuredOnes) {
    const std::vector<BlockCurve> curves = builtinCurves();
    std::set<std::string> names;
    for (const BlockCurve& c : curves) {
        names.insert(c.name);
        ASSERT_FALSE(c.blocks.empty()) << c.name;
        EXPECT_EQ(c.blocks.front(), 1) << c.name;
        for (double v : c.cpuPerFrame) EXPECT_GT(v, 0) << c.name;
    }
    for (const char* n : {"demo", "forest", "forest-flyover"}) EXPECT_TRUE(names.count(n)) << n;
    EXPECT_EQ(findCurve(kDefaultCurve).name, kDefaultCurve);
}

TEST(FarmCurve, CurvesFromFilesByName) {
    Folder dir;
    const std::string one = dir.path + "/one.json", two = dir.path + "/two.json";
    std::ofstream(one) << R"({"curves": {"mine": {"scene": "x.rib", "resolution": [64, 36],
        "points": [{"block": 4, "cpu_per_frame": 2}, {"block": 1, "cpu_per_frame": 5}]}}})";
    std::ofstream(two) << R"({"curves": {"a": {"points": [{"block": 1, "cpu_per_frame": 1}]},
                                         "b": {"points": [{"block": 2, "cpu_per_frame": 3}]}}})";
    const BlockCurve c = findCurve(one);
    EXPECT_EQ(c.name, "mine");
    EXPECT_EQ(c.blocks, (std::vector<int>{1, 4}));  // sorted
    EXPECT_DOUBLE_EQ(c.at(2), 5 + (2 - 5) * (1.0 / 2 - 1) / (1.0 / 4 - 1));
    EXPECT_EQ(findCurve(two + ":b").blocks, std::vector<int>{2});
    try {
        findCurve(two);
        FAIL() << "a file of two curves needs a name";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("a, b"), std::string::npos) << e.what();
    }
    try {
        findCurve("no-such-curve");
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("forest"), std::string::npos) << e.what();  // names the choices
    }
    std::ofstream(one) << R"({"curves": {"bad": {"points": [{"block": 0, "cpu_per_frame": 1}]}}})";
    EXPECT_THROW(findCurve(one), std::runtime_error);
}

// The farm's files through nlohmann-json: errors name the file and where the text goes wrong,
// and what older files lack reads as its fallback.
TEST(FarmJson, ErrorsNameTheFileAndAbsentMembersFallBack) {
    const std::string text = R"({"a": [1, 2.5, -3e2], "b": {"c": "x\"y\\z\n\u00e9"}, "d": true, "e": null})";
    const Json j = parseJson(text, "t");
    EXPECT_EQ(member(j, "a").size(), 3u);
    EXPECT_DOUBLE_EQ(num(member(j, "a")[2]), -300);
    EXPECT_EQ(str(member(member(j, "b"), "c")), "x\"y\\z\n\xc3\xa9");
    EXPECT_TRUE(member(member(j, "missing"), "deeper").is_null());
    EXPECT_EQ(num(member(j, "d"), 7), 7);  // not a number: the fallback
    EXPECT_EQ(str(member(j, "a")), "");
    EXPECT_EQ(parseJson(dumpJson(j), "dump"), j);
    EXPECT_EQ(num(parseJson(dumpJson(Json(uint64_t(1) << 60)), "n")), double(uint64_t(1) << 60));
    for (const char* bad : {"", "{", "[1,]x", "{\"a\" 1}", "\"open", "tru", "[1] 2"}) {
        try {
            parseJson(bad, "shot.farm.json");
            ADD_FAILURE() << bad;
        } catch (const std::runtime_error& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind("shot.farm.json: not valid JSON: ", 0), 0u) << what;
            EXPECT_NE(what.find("line 1, column "), std::string::npos) << what;
            EXPECT_EQ(what.find("[json.exception"), std::string::npos) << what;  // the library's tag, cut
        }
    }
    try {
        parseJson("{\n  \"a\": 1,\n  \"b\": ]\n}", "two.json");
        ADD_FAILURE();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("line 3, column 8"), std::string::npos) << e.what();
    }
    EXPECT_THROW(loadJson("/no/such/file.json"), std::runtime_error);
}

Manifest sampleManifest(const std::string& dir) {
    Manifest m;
    m.path = dir + "/shot.farm.json";
    m.scene = dir + "/it's a scene.rib";
    m.output = dir + "/shot.####.exr";
    m.executable = dir + "/fake-streyes";
    m.first = 1;
    m.last = 10;
    m.shotFirst = 1;  // the scene has 48 frames: streyes render --frames 1-10 decides motion over 1-48
    m.shotLast = 48;
    m.block = 4;
    m.blocks = cutBlocks(1, 10, 4);
    m.seed = 7;
    m.renderOptions = {"--res", "64x48", "--samples", "4"};
    m.width = 64;
    m.height = 48;
    m.partition = "render";
    m.blockChoice = {{"mode", "given"}};
    m.submissions.push_back({12, {0, 1, 2}, "2026-01-01 00:00:00", dir + "/shot.farm/submission-1.sh"});
    return m;
}

TEST(FarmManifest, NamesBesideTheFramesAndRoundTrips) {
    EXPECT_EQ(manifestPathFor("out/shot.####.exr"), "out/shot.farm.json");
    EXPECT_EQ(manifestPathFor("/a/b/f_####.exr"), "/a/b/f.farm.json");
    EXPECT_EQ(manifestPathFor("####.exr"), "frames.farm.json");
    Folder dir;
    const Manifest m = sampleManifest(dir.path);
    EXPECT_EQ(m.farmDir(), dir.path + "/shot.farm");
    EXPECT_EQ(m.logPath(12, 2), dir.path + "/shot.farm/logs/12_2.log");
    EXPECT_EQ(m.statsPath(12, 2), dir.path + "/shot.farm/stats/12_2.json");
    m.save();
    const Manifest r = Manifest::load(m.path);
    std::string why;
    EXPECT_TRUE(r.sameShot(m, &why)) << why;
    EXPECT_EQ(r.toJson(), m.toJson());
    // The file as tools read it: whole numbers stay whole, names as given.
    const Json file = loadJson(m.path);
    EXPECT_EQ(file["frames"], Json::array({1, 10}));
    EXPECT_EQ(file["shot"], Json::array({1, 48}));
    EXPECT_EQ(file["blocks"], Json::parse("[[1, 4], [5, 8], [9, 10]]"));
    EXPECT_EQ(file["scene"], dir.path + "/it's a scene.rib");
    EXPECT_EQ(file["submissions"][0]["job"], 12);
    ASSERT_EQ(r.submissions.size(), 1u);
    EXPECT_EQ(r.submissions[0].tasks, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(r.blocks.size(), 3u);
    EXPECT_EQ(r.blocks[2].str(), "9-10");

    Manifest other = m;
    other.renderOptions = {"--res", "64x36"};
    EXPECT_FALSE(m.sameShot(other, &why));
    EXPECT_NE(why.find("render options"), std::string::npos) << why;
    other = m;
    other.seed = 8;
    EXPECT_FALSE(m.sameShot(other, &why));
    EXPECT_NE(why.find("seed"), std::string::npos) << why;
    other = m;
    other.shotLast = 10;
    EXPECT_FALSE(m.sameShot(other, &why));
    EXPECT_NE(why.find("its shot is 1-48, not 1-10"), std::string::npos) << why;

    // A manifest written before the shot was kept: its tasks ran with the frames as the shot.
    Json old = m.toJson();
    Json without = old;
    without.erase("shot");
    const Manifest o = Manifest::fromJson(without, m.path);
    EXPECT_EQ(o.shotFirst, 1);
    EXPECT_EQ(o.shotLast, 10);
    // A shot that does not hold the frames is not a manifest streyes wrote.
    Json narrow = old;
    narrow["shot"] = {2, 10};
    EXPECT_THROW(Manifest::fromJson(narrow, m.path), std::runtime_error);

    std::ofstream(dir.path + "/not.json") << R"({"scene": "x"})";
    EXPECT_THROW(Manifest::load(dir.path + "/not.json"), std::runtime_error);
    // Members of the wrong type: refused naming the file, not a crash or a half-read manifest.
    const std::string bad = dir.path + "/bad.json";
    for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
             {"blocks", R"(["1-4", "5-8"])"},
             {"frames", R"("1-10")"},
             {"render_options", "[1, 2]"},
             {"submissions", R"([{"job": 12, "tasks": ["a"]}])"},
             {"submissions", "3"}}) {
        Json j = old;
        j[key] = Json::parse(value);
        std::ofstream(bad) << dumpJson(j);
        try {
            Manifest::load(bad);
            ADD_FAILURE() << key << " " << value;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find("bad.json' is not a streyes farm manifest"), std::string::npos) << e.what();
        }
    }
    // Cut short, as a full disk would leave it.
    const std::string whole = dumpJson(old);
    std::ofstream(bad, std::ios::trunc) << whole.substr(0, whole.size() / 2);
    try {
        Manifest::load(bad);
        ADD_FAILURE();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.json: not valid JSON: "), std::string::npos) << e.what();
    }
}

TEST(FarmManifest, TheTaskCommandIsTheContract) {
    Folder dir;
    Manifest m = sampleManifest(dir.path);
    std::vector<std::string> cmd = m.taskCommand(m.blocks[1], "s.json");
    const std::vector<std::string> want = {m.executable, "render", m.scene, "--frames", "5-8", "--shot", "1-48",
                                           "-o", m.output, "--resume", "--seed", "7", "--res", "64x48",
                                           "--samples", "4", "--stats", "s.json"};
    EXPECT_EQ(cmd, want);
    m.cpusPerTask = 3;  // a share of a node: as many threads as cores
    cmd = m.taskCommand(m.blocks[1], "s.json");
    EXPECT_EQ(std::vector<std::string>(cmd.end() - 4, cmd.end() - 2), (std::vector<std::string>{"--threads", "3"}));
}

// The batch script, run by bash as Slurm would for task 2 of job 12, with a stand-in for streyes
// that prints its arguments one a line.
TEST(FarmManifest, BatchScriptRunsTheBlocksRenderLine) {
    Folder dir;
    const Manifest m = sampleManifest(dir.path);
    const std::string script = dir.path + "/task.sh";
    std::ofstream(script) << m.batchScript(1);
    std::ofstream(m.executable) << "#!/bin/sh\nfor a in \"$@\"; do echo \"arg:$a\"; done\nexit 3\n";
    fs::permissions(m.executable, fs::perms::owner_all);
    const std::string out =
        run("SLURM_ARRAY_JOB_ID=12 SLURM_ARRAY_TASK_ID=2 bash " + script + " 2>&1; echo \"script exit $?\"");
    std::string args;
    std::istringstream ss(out);
    for (std::string line; std::getline(ss, line);)
        if (line.rfind("arg:", 0) == 0) args += line.substr(4) + "|";
    // The stand-in prints what follows its own name: every argument, quoting intact.
    const std::vector<std::string> cmd = m.taskCommand(m.blocks[2], m.statsPath(12, 2));
    std::string want;
    for (size_t i = 1; i < cmd.size(); ++i) want += cmd[i] + "|";
    EXPECT_EQ(args, want) << out;
    EXPECT_NE(out.find("streyes farm: job 12 task 2, frames 9-10"), std::string::npos) << out;
    EXPECT_NE(out.find("streyes farm: exit code 3"), std::string::npos) << out;
    EXPECT_NE(out.find("script exit 3"), std::string::npos) << out;
}

TEST(FarmManifest, ShellQuotingSurvivesTheShell) {
    for (const std::string s : {"plain", "with space", "it's", "$HOME", "a\"b", "x;rm -rf y", "####"}) {
        const std::string out = run("printf %s " + shellQuote(s));
        EXPECT_EQ(out, s);
    }
}

TEST(FarmSlurmParsing, ScontrolFieldsWithSpacesInValues) {
    const auto f = parseScontrolLine(
        "JobId=5 ArrayJobId=4 ArrayTaskId=1 JobState=CANCELLED Reason=None ExitCode=0:15 "
        "Comment=streyes-farm:/a b/shot.farm.json StdOut=/x/4_1.log Power=");
    auto get = [&](const std::string& k) {
        for (const auto& [key, v] : f)
            if (key == k) return v;
        return std::string("?");
    };
    EXPECT_EQ(get("JobState"), "CANCELLED");
    EXPECT_EQ(get("ExitCode"), "0:15");
    EXPECT_EQ(get("Comment"), "streyes-farm:/a b/shot.farm.json");
    EXPECT_EQ(get("StdOut"), "/x/4_1.log");
    EXPECT_EQ(get("Power"), "");
}

TEST(FarmSlurmParsing, ProgramsRunWithoutAShell) {
    const ProgramRun r = runProgram({"sh", "-c", "echo out; echo err >&2; exit 4"});
    EXPECT_TRUE(r.started);
    EXPECT_EQ(r.exitCode, 4);
    EXPECT_EQ(r.out, "out\n");
    EXPECT_EQ(r.err, "err\n");
    EXPECT_FALSE(runProgram({"no-such-program-streyes"}).started);
    const ProgramRun slow = runProgram({"sleep", "10"}, 1);
    EXPECT_TRUE(slow.timedOut);
}

}  // namespace
}  // namespace streyes::farm
