// Every command's options through CLI11: --help generated per command and listing every option
// name, usage errors (an unknown option, a value missing, a bad value) named and exit 2, values
// that look like options, an option given twice; and a corrupt farm manifest refused naming it.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::CliRun;
using test::runStreyes;
using test::writeFile;

struct CommandOptions {
    std::string command;                // "render", "farm submit" ...
    std::vector<std::string> options;   // every option it takes, as its help names it
};

// The options each command has always taken (the hand-written parsers' names and short forms).
const std::vector<CommandOptions> kCommands = {
    {"render",
     {"--frames A-B", "--shot A-B", "--res WxH", "--samples N", "--algorithm NAME", "--tolerance EPS",
      "--layers N|adaptive", "--preview", "--dof-preview N", "-o,--output PATTERN", "--stats FILE", "--threads N",
      "--seed N", "--bucket N", "--simd NAME", "--frame-block N", "--max-memory SIZE", "--grid-cache SIZE",
      "--resume", "--option 'REQUEST'", "--safe", "--safe-dir DIR", "-q,--quiet", "--strict"}},
    {"farm submit",
     {"-o,--output PATTERN", "--frames A-B", "--block N|auto", "--curve NAME|FILE", "--slots N", "-p,--partition P",
      "--cpus-per-task N", "--seed N", "--all-blocks", "--dry-run", "--res WxH", "--samples N", "--safe",
      "--safe-dir DIR", "--option 'REQUEST'", "-q,--quiet", "--strict", "--preview"}},
    {"farm status", {"--json", "--lines N"}},
    {"farm gather", {"--json", "-o,--output FILE"}},
    {"compare", {"--frames A-B", "--threshold X", "--z-tolerance X", "--resize", "--fail X", "--json"}},
    {"sheet", {"-o,--output FILE", "--frames A-B", "--every N", "--columns N", "--cell-width W", "--gap N",
               "--no-labels"}},
    {"shader", {"-I DIR"}},
    {"catrib", {"--ascii", "--binary", "--float32", "--gzip", "-o,--output FILE"}},
};

TEST(Usage, EveryCommandHasItsOwnGeneratedHelp) {
    for (const CommandOptions& c : kCommands)
        for (const char* help : {" --help", " -h"}) {
            const CliRun r = runStreyes(c.command + help);
            EXPECT_EQ(r.exitCode, 0) << c.command << help << "\n" << r.output;
            // Its own synopsis first (farm's subcommands too), then its options, each described.
            EXPECT_EQ(r.output.rfind("usage: streyes " + c.command + " ", 0), 0u) << c.command << "\n" << r.output;
            EXPECT_NE(r.output.find("\noptions:\n"), std::string::npos) << c.command << "\n" << r.output;
            EXPECT_NE(r.output.find("  -h,--help "), std::string::npos) << c.command;
            for (const std::string& o : c.options)
                EXPECT_NE(r.output.find("\n  " + o + " "), std::string::npos) << c.command << ": " << o << "\n"
                                                                              << r.output;
        }
    // farm submit's render options, in a group of their own; those the farm sets are not offered.
    const CliRun submit = runStreyes("farm submit --help");
    const size_t group = submit.output.find("\nrender options (as for streyes render");
    ASSERT_NE(group, std::string::npos) << submit.output;
    EXPECT_GT(submit.output.find("\n  --res WxH"), group);
    for (const char* set : {"--stats", "--resume", "--threads", "--shot"})
        EXPECT_EQ(submit.output.find("\n  " + std::string(set)), std::string::npos) << set;
    // The overview names every command, and farm's help its subcommands.
    const CliRun all = runStreyes("--help");
    EXPECT_EQ(all.exitCode, 0);
    for (const char* command : {"render", "compare", "sheet", "shader", "catrib", "farm"})
        EXPECT_NE(all.output.find("streyes " + std::string(command) + " "), std::string::npos) << command;
    const CliRun farm = runStreyes("farm --help");
    EXPECT_EQ(farm.exitCode, 0);
    for (const char* sub : {"submit", "status", "gather"})
        EXPECT_NE(farm.output.find("\n  " + std::string(sub) + " "), std::string::npos) << sub << farm.output;
}

// A usage error: exit 2, the message on the first line, then the command's synopsis and where its
// options are listed (not the whole help).
void expectUsageError(const std::string& command, const std::string& args, const std::string& message) {
    const CliRun r = runStreyes(command + " " + args);
    EXPECT_EQ(r.exitCode, 2) << command << " " << args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("streyes: " + message + "\n", 0), 0u) << command << " " << args << "\n" << r.output;
    EXPECT_NE(r.output.find("\nusage: streyes " + command + " "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\nstreyes " + command + " --help lists the options.\n"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("\noptions:\n"), std::string::npos) << r.output;
}

TEST(Usage, UnknownOptionsMissingAndBadValuesNameTheOption) {
    // An unknown option, in every command.
    for (const CommandOptions& c : kCommands)
        expectUsageError(c.command, "x --bogus", "unknown option '--bogus'");
    expectUsageError("render", "x.rib --bogus=3", "unknown option '--bogus'");
    // A value missing: the option and what it takes.
    expectUsageError("render", "x.rib --frames", "--frames needs a value (--frames A-B)");
    expectUsageError("render", "x.rib -o", "-o needs a value (-o PATTERN)");
    expectUsageError("render", "x.rib --option", "--option needs a value (--option 'REQUEST')");
    expectUsageError("farm submit", "x.rib --block", "--block needs a value (--block N|auto)");
    expectUsageError("farm status", "x --lines", "--lines needs a value (--lines N)");
    expectUsageError("compare", "a b --threshold", "--threshold needs a value (--threshold X)");
    expectUsageError("sheet", "x.####.exr --every", "--every needs a value (--every N)");
    expectUsageError("shader", "-I", "-I needs a value (-I DIR)");
    expectUsageError("catrib", "x.rib -o", "-o needs a value (-o FILE)");
    // A bad value: the option, what it expects and what it got.
    expectUsageError("render", "x.rib --samples many", "--samples expects a whole number from 1 to 4096, not 'many'");
    expectUsageError("render", "x.rib --res 64", "--res expects WIDTHxHEIGHT, e.g. 640x360, not '64'");
    expectUsageError("render", "x.rib --frames 5-2", "--frames 5-2: the last frame comes before the first");
    expectUsageError("render", "x.rib --tolerance 2", "--tolerance expects a number from 0.000000 to 1.000000, not '2'");
    expectUsageError("render", "x.rib --algorithm fast",
                     "--algorithm expects spacetime-occlusion, spacetime, frames-occlusion, frames, raytrace or "
                     "raytrace-frames, not 'fast'");
    expectUsageError("farm submit", "x.rib -o f.####.exr --cpus-per-task 0",
                     "--cpus-per-task expects a whole number from 1 to 4096, not '0'");
    expectUsageError("farm submit", "x.rib -o f.####.exr --samples many",
                     "--samples expects a whole number from 1 to 4096, not 'many'");
    expectUsageError("farm status", "x --lines -1", "--lines expects a whole number from 0 to 10000, not '-1'");
    expectUsageError("compare", "a b --fail x", "--fail expects a number from 0.000000 to 1000000000000000019884624838656.000000, not 'x'");
    expectUsageError("sheet", "x.####.exr -o s.png --gap -1", "--gap expects a whole number from 0 to 1000, not '-1'");
    // What the farm sets for each task, and one word too many.
    expectUsageError("farm submit", "x.rib -o f.####.exr --threads 4",
                     "--threads is set by the farm for each task (use --cpus-per-task N)");
    expectUsageError("farm submit", "x.rib -o f.####.exr --resume", "--resume is set by the farm for each task");
    expectUsageError("render", "a.rib b.rib", "more than one scene given ('a.rib' and 'b.rib')");
    expectUsageError("farm status", "1 2", "give one job or manifest, not '1' and '2'");
    expectUsageError("catrib", "--ascii --binary x.rib", "--ascii and --binary: give one encoding");
    // No command, or one that does not exist: the overview's synopsis.
    CliRun r = runStreyes("");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.output.rfind("streyes: no command given\n", 0), 0u) << r.output;
    r = runStreyes("paint x.rib");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.output.rfind("streyes: unknown command 'paint'", 0), 0u) << r.output;
    r = runStreyes("farm resubmit x");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(r.output.rfind("streyes: unknown farm subcommand 'resubmit' (submit, status or gather)\n", 0), 0u)
        << r.output;
}

// A value may start with '-' (a negative frame, a RIB request), and an option given twice is
// the last one; --option and -I are taken every time, in order.
TEST(Usage, ValuesLikeOptionsAndOptionsGivenTwice) {
    const test::TempDir dir("usage");
    // Frames -3 to 5: the first missing frame named is -3 (the range was read as a value).
    writeFile(dir.path(), "f.0001.exr", "");
    CliRun r = runStreyes("sheet " + dir.path() + "/f.####.exr -o " + dir.path() + "/s.png --frames -3-5");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("frame -3: '" + dir.path() + "/f.-003.exr' does not exist"), std::string::npos)
        << r.output;
    const std::string scene = writeFile(dir.path(), "s.rib", R"(Format 16 8 1
PixelSamples 1 1
Display "s.####.exr" "file" "rgba"
WorldBegin
Surface "constant"
Patch "bilinear" "P" [-0.5 -0.5 1  0.5 -0.5 1  -0.5 0.5 1  0.5 0.5 1]
WorldEnd
)");
    r = runStreyes("render " + scene + " --res 4x2 --res 12x6 -q --quiet -o " + dir.path() + "/f.####.exr --stats " +
                   dir.path() + "/stats.json --option 'Option \"limits\" \"bucketsize\" [8 8]' --option " +
                   "'PixelSamples 2 2'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    std::ifstream f(dir.path() + "/stats.json");
    const nlohmann::json stats = nlohmann::json::parse(f);
    EXPECT_EQ(stats["resolution"], nlohmann::json::array({12, 6}));  // the last --res
    EXPECT_EQ(stats["samples_per_pixel"], 1);  // the scene's PixelSamples overrides --option's
    // An --option a scene may not give before the world: named by its place, so both were taken.
    r = runStreyes("render " + scene + " -q --option 'Option \"limits\" \"bucketsize\" [8 8]' --option WorldBegin");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--option 2 ('WorldBegin')"), std::string::npos) << r.output;
}

// A manifest that is not JSON, or not the shape streyes writes: status, gather and a submission to
// the same output refuse it naming the file (exit 2), never a crash.
TEST(Usage, CorruptFarmManifestIsNamedAndRefused) {
    const test::TempDir dir("usage-manifest");
    const std::string cut = writeFile(dir.path(), "cut.farm.json", "{\n  \"streyes_farm_manifest\": 1,\n  \"scene\": \"");
    for (const char* command : {"status", "gather"}) {
        const CliRun r = runStreyes("farm " + std::string(command) + " " + cut);
        EXPECT_EQ(r.exitCode, 2) << command << "\n" << r.output;
        EXPECT_NE(r.output.find(cut + ": not valid JSON: parse error at line 3, column "), std::string::npos)
            << command << "\n" << r.output;
        EXPECT_EQ(r.output.find("render failed"), std::string::npos) << r.output;
    }
    const std::string shape = writeFile(dir.path(), "shape.farm.json",
                                        R"({"streyes_farm_manifest": 1, "scene": "/s.rib", "output": "/f.####.exr",
                                            "frames": [1, 8], "blocks": "1-8"})");
    CliRun r = runStreyes("farm status " + shape);
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("'" + shape + "' is not a streyes farm manifest: no blocks"), std::string::npos)
        << r.output;
    // Submitting to an output whose manifest is corrupt: refused before anything is submitted.
    const std::string scene = writeFile(dir.path(), "s.rib", R"(Format 16 8 1
Option "streyes" "int frames" [1 4]
WorldBegin
Surface "constant"
Patch "bilinear" "P" [-0.5 -0.5 1  0.5 -0.5 1  -0.5 0.5 1  0.5 0.5 1]
WorldEnd
)");
    writeFile(dir.path(), "f.farm.json", "[1, 2");
    r = runStreyes("farm submit " + scene + " -o " + dir.path() + "/f.####.exr --block 2 --dry-run");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find(dir.path() + "/f.farm.json: not valid JSON: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("remove it, or give another -o"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace streyes
