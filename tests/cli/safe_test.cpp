// streyes render --safe, for scenes from others: no program is run, no plug-in is loaded (the
// built-in generators stay), and every file the scene asks to write lies inside one folder; each
// refusal exits 2 naming file:line, before anything is written. Without --safe a scene may do all
// of it, which the same scenes show.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::runStreyesWith;
using test::writeFile;

// An 8 x 8 orthographic view of a square covering it; `options` before WorldBegin (line 5 on),
// `world` inside it.
std::string scene(const std::string& options, const std::string& world = "") {
    return "Format 8 8 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 8\nPixelFilter \"box\" 1 1\n" + options +
           "WorldBegin\nSurface \"constant\"\n" + world + "Patch \"bilinear\" \"P\" [0 0 5  8 0 5  0 8 5  8 8 5]\n" +
           "WorldEnd\n";
}

CliRun renderIn(const std::string& dir, const std::string& args) {
    return runStreyesWith("cd '" + dir + "' && ", "render " + args + " --quiet");
}

double alphaSum(const std::string& exr) {
    const ImageData img = readImage(exr);
    double sum = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) sum += img.at(x, y, img.channelIndex("A"));
    return sum;
}

TEST(Safe, RunProgramIsRefusedAndNeverRuns) {
    const test::TempDir dir("safe");
    const std::string marker = dir.path() + "/ran";
    const std::string rib = writeFile(dir.path(), "scene.rib",
                                      scene("", "Procedural \"RunProgram\" [\"/usr/bin/touch " + marker +
                                                    "\" \"\"] [0 8 0 8 1 2]\n"));
    const CliRun safe = renderIn(dir.path(), rib + " --safe -o out.exr");
    EXPECT_EQ(safe.exitCode, 2) << safe.output;
    EXPECT_NE(safe.output.find("scene.rib:7: error: Procedural \"RunProgram\" is refused by --safe: it would run a "
                               "program"),
              std::string::npos)
        << safe.output;
    EXPECT_FALSE(fs::exists(marker)) << "the program ran";
    EXPECT_FALSE(fs::exists(dir.path() + "/out.exr"));
    // Without --safe the scene runs it (touch writes no RIB: the procedural then fails).
    renderIn(dir.path(), rib + " -o out.exr");
    EXPECT_TRUE(fs::exists(marker));
}

TEST(Safe, APlugInIsRefusedTheBuiltInGeneratorsStay) {
    const test::TempDir dir("safe");
    const std::string plugin = writeFile(
        dir.path(), "plugin.rib",
        scene("", "Procedural \"DynamicLoad\" [\"" STREYES_PLUGIN_DIR "/menger.so\" \"level=1 x=2 y=2 z=1 size=3\"] [2 5 2 5 1 4]\n"));
    const CliRun refused = renderIn(dir.path(), plugin + " --safe -o out.exr");
    EXPECT_EQ(refused.exitCode, 2) << refused.output;
    EXPECT_NE(refused.output.find("plugin.rib:7: error: Procedural \"DynamicLoad\" \"" STREYES_PLUGIN_DIR
                                  "/menger.so\" is refused by --safe: it would load a plug-in"),
              std::string::npos)
        << refused.output;
    EXPECT_FALSE(fs::exists(dir.path() + "/out.exr"));
    ASSERT_EQ(renderIn(dir.path(), plugin + " -o out.exr").exitCode, 0) << "without --safe it loads";

    // The built-in tree renders the same with --safe as without.
    const std::string tree = writeFile(
        dir.path(), "tree.rib",
        "Format 32 32 1\nProjection \"perspective\" \"fov\" [40]\nTranslate 0 -5 30\nWorldBegin\n"
        "Procedural \"DynamicLoad\" [\"tree\" \"kind=broadleaf height=10 seed=3\"] [-10 10 0 20 -10 10]\nWorldEnd\n");
    const CliRun a = renderIn(dir.path(), tree + " --safe -o safe.exr");
    ASSERT_EQ(a.exitCode, 0) << a.output;
    ASSERT_EQ(renderIn(dir.path(), tree + " -o trusted.exr").exitCode, 0);
    EXPECT_GT(alphaSum(dir.path() + "/safe.exr"), 20.0) << "the tree covers some pixels";
    EXPECT_EQ(readImage(dir.path() + "/safe.exr").pixels, readImage(dir.path() + "/trusted.exr").pixels);
}

// Display names are taken from the current folder; with --safe and no -o that folder is the one
// the scene may write in.
TEST(Safe, DisplaysOutsideTheFolderAreRefusedAtTheirLine) {
    const test::TempDir dir("safe");
    const std::string work = dir.path() + "/work", outside = dir.path() + "/outside";
    fs::create_directories(work + "/sub");
    fs::create_directories(outside);
    fs::create_directory_symlink(outside, work + "/link");
    struct Case {
        std::string display, mentions, wouldWrite;
    };
    const Case cases[] = {
        {outside + "/abs.exr", "refuses an absolute path", outside + "/abs.exr"},
        {"../up.exr", "refuses a path with \"..\"", dir.path() + "/up.exr"},
        {"link/linked.exr", "would write '" + fs::canonical(outside).string() + "/linked.exr'",
         outside + "/linked.exr"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.display);
        const std::string rib =
            writeFile(work, "scene.rib", scene("Display \"" + c.display + "\" \"openexr\" \"rgba\"\n"));
        const CliRun r = renderIn(work, "scene.rib --safe");
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("scene.rib:5: error: Display \"" + c.display + "\""), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(c.mentions), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("a scene may write only inside " + work), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(c.wouldWrite));
        // Trusted, the scene writes there.
        const CliRun trusted = renderIn(work, "scene.rib");
        EXPECT_EQ(trusted.exitCode, 0) << trusted.output;
        EXPECT_TRUE(fs::exists(c.wouldWrite));
    }
    // Inside the folder: written.
    writeFile(work, "scene.rib", scene("Display \"sub/ok.exr\" \"openexr\" \"rgba\"\n"));
    const CliRun ok = renderIn(work, "scene.rib --safe");
    EXPECT_EQ(ok.exitCode, 0) << ok.output;
    EXPECT_DOUBLE_EQ(alphaSum(work + "/sub/ok.exr"), 64.0);
}

// With -o the scene's primary display is not written (no check); a display of an output variable
// still is, under the name the scene gives, and its folder is -o's unless --safe-dir says.
TEST(Safe, WithMinusOOnlyTheDisplaysWrittenAreChecked) {
    const test::TempDir dir("safe");
    const std::string out = dir.path() + "/out";
    fs::create_directories(out);
    // A display outside every folder --safe allows (beside the test's own folder).
    const std::string outside =
        (fs::path(dir.path()).parent_path() / ("streyes-safe-outside-" + std::to_string(getpid()) + ".exr")).string();
    const std::string primary = writeFile(dir.path(), "primary.rib",
                                          scene("Display \"" + outside + "\" \"openexr\" \"rgba\"\n"));
    CliRun r = renderIn(dir.path(), "primary.rib --safe -o out/f.exr");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_DOUBLE_EQ(alphaSum(out + "/f.exr"), 64.0);
    EXPECT_FALSE(fs::exists(outside));

    const std::string aov = writeFile(dir.path(), "aov.rib",
                                      scene("Display \"primary.exr\" \"openexr\" \"rgba\"\n"
                                            "Display \"+normals.exr\" \"openexr\" \"N\"\n"));
    r = renderIn(dir.path(), "aov.rib --safe -o out/f.exr");  // normals.exr: in the current folder, not out/
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("aov.rib:6: error: Display \"normals.exr\" would write '" + fs::canonical(dir.path()).string() +
                            "/normals.exr': --safe refuses it (a scene may write only inside " + out + ")"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(dir.path() + "/normals.exr"));
    r = renderIn(dir.path(), "aov.rib --safe-dir . -o out/f.exr");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir.path() + "/normals.exr"));

    r = renderIn(dir.path(), "aov.rib --safe-dir nosuch -o out/f.exr");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--safe-dir nosuch: no such folder"), std::string::npos) << r.output;
}

// MakeTexture and MakeLatLongEnvironment write beside their RIB file (here in s/).
TEST(Safe, TexturesAreMadeOnlyInsideTheFolder) {
    const test::TempDir dir("safe");
    const std::string d = dir.path(), s = d + "/s";
    fs::create_directories(d + "/out");
    fs::create_directories(s);
    // A picture to make textures of: a frame of the square.
    writeFile(s, "square.rib", scene(""));
    ASSERT_EQ(renderIn(s, "square.rib -o picture.exr").exitCode, 0);
    struct Case {
        std::string request, mentions, made;
    };
    const Case cases[] = {
        {"MakeTexture \"picture.exr\" \"" + d + "/abs.tx\" \"clamp\" \"clamp\" \"box\" 1 1",
         "MakeTexture \"" + d + "/abs.tx\": --safe refuses an absolute path", d + "/abs.tx"},
        {"MakeLatLongEnvironment \"picture.exr\" \"../up.tx\" \"box\" 1 1",
         "MakeLatLongEnvironment \"../up.tx\": --safe refuses a path with \"..\"", d + "/up.tx"},
        // Beside the RIB file, which is not in out/ (-o's folder).
        {"MakeTexture \"picture.exr\" \"beside.tx\" \"clamp\" \"clamp\" \"box\" 1 1",
         "MakeTexture \"beside.tx\" would write '" + fs::canonical(s).string() + "/beside.tx'", s + "/beside.tx"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.request);
        writeFile(s, "scene.rib", c.request + "\n" + scene(""));
        const CliRun r = renderIn(d, "s/scene.rib --safe -o out/f.exr");
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("scene.rib:1: error: " + c.mentions), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(c.made));
        EXPECT_FALSE(fs::exists(d + "/out/f.exr"));
    }
    // With the RIB file's folder as the one the scene may write in, it is made.
    const CliRun r = renderIn(d, "s/scene.rib --safe-dir s -o out/f.exr");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(fs::exists(s + "/beside.tx"));
}

// Each frame of a sequence names its own displays: each is checked.
TEST(Safe, AFrameOfASequenceWritingOutsideIsRefused) {
    const test::TempDir dir("safe");
    for (int f = 1; f <= 3; ++f)
        writeFile(dir.path(), "shot.000" + std::to_string(f) + ".rib",
                  scene(f == 3 ? "Display \"/tmp/streyes-safe-frame3.exr\" \"openexr\" \"rgba\"\n"
                               : "Display \"shot.####.exr\" \"openexr\" \"rgba\"\n"));
    const CliRun r = renderIn(dir.path(), "'shot.####.rib' --safe");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("shot.0003.rib:5: error: Display \"/tmp/streyes-safe-frame3.exr\": --safe refuses an "
                            "absolute path"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists("/tmp/streyes-safe-frame3.exr"));
}

// streyes farm submit passes --safe to every task, and checks the scene with it before submitting.
TEST(Safe, TheFarmPassesItToItsTasksAndChecksFirst) {
    const test::TempDir dir("safe");
    const std::string ok = writeFile(dir.path(), "ok.rib", scene("Option \"streyes\" \"int frames\" [1 4]\n"));
    CliRun r = runStreyesWith("", "farm submit " + ok + " -o " + dir.path() + "/f.####.exr --block 2 --safe --dry-run");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(" --safe --stats "), std::string::npos) << r.output;
    const std::string program = writeFile(
        dir.path(), "program.rib",
        scene("Option \"streyes\" \"int frames\" [1 4]\n", "Procedural \"RunProgram\" [\"/bin/true\" \"\"] [0 8 0 8 1 2]\n"));
    r = runStreyesWith("", "farm submit " + program + " -o " + dir.path() + "/f.####.exr --block 2 --safe --dry-run");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("program.rib:8: error: Procedural \"RunProgram\" is refused by --safe"), std::string::npos)
        << r.output;
    r = runStreyesWith("", "farm submit " + program + " -o " + dir.path() + "/f.####.exr --block 2 --dry-run");
    EXPECT_EQ(r.exitCode, 0) << r.output;
}

}  // namespace
}  // namespace streyes
