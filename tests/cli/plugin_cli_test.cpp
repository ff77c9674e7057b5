// Procedural plug-ins through the streyes command: the command exports the Ri functions the
// Menger plug-in calls, and a missing or broken plug-in is bad input (exit 2) naming file:line.
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::CliRun;
using test::runStreyes;
using test::writeFile;

const std::string kPluginDir = STREYES_PLUGIN_DIR;

std::string scene(const std::string& procedural) {
    return "Format 32 32 1\nProjection \"orthographic\"\nScreenWindow 0 32 0 32\nPixelFilter \"box\" 1 1\n"
           "Option \"searchpath\" \"procedural\" [\"" + kPluginDir + ":&\"]\n"
           "WorldBegin\nSurface \"constant\"\n" + procedural + "WorldEnd\n";
}

TEST(PluginCli, MengerPluginRendersThroughTheCommand) {
    test::TempDir dir("plugin-cli");
    // A level-1 sponge of edge 27 face on: 8/9 of 27 x 27 pixels, sub-sponges loaded by name again.
    const std::string rib =
        writeFile(dir.path(), "sponge.rib",
                  scene("Procedural \"DynamicLoad\" [\"menger\" \"level=1 x=2 y=2 z=1 size=27 recurse=dso\"] "
                        "[2 29 2 29 1 28]\n"));
    const std::string out = dir.path() + "/sponge.exr";
    const CliRun r = runStreyes("render " + rib + " -o " + out + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const ImageData image = readImage(out);
    double sum = 0;
    const int a = image.channelIndex("A");
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) sum += image.at(x, y, a);
    EXPECT_NEAR(sum, 27.0 * 27.0 * 8.0 / 9.0, 1e-2);
}

TEST(PluginCli, MissingOrBrokenPluginExits2NamingTheLine) {
    test::TempDir dir("plugin-cli");
    struct Case {
        const char* plugin;
        const char* mentions;
    };
    for (const Case& c : {Case{"no-such-plugin", "no plug-in 'no-such-plugin'"},
                          Case{"test_plugin_no_symbols", "does not export Subdivide Free"},
                          Case{"test_plugin_bad_call", "call 3 (RiSphere): a value is not a finite number"}}) {
        SCOPED_TRACE(c.plugin);
        const std::string rib = writeFile(dir.path(), "bad.rib",
                                          scene(std::string("Procedural \"DynamicLoad\" [\"") + c.plugin +
                                                "\" \"\"] [0 8 0 8 1 8]\n"));
        const CliRun r = runStreyes("render " + rib + " -o " + dir.path() + "/bad.exr --quiet");
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("bad.rib:8: error: "), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(c.mentions), std::string::npos) << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir.path() + "/bad.exr"));
    }
}

}  // namespace
}  // namespace streyes
