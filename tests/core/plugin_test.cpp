// Procedural plug-ins end to end (Procedural "DynamicLoad" with a shared object, calling back the
// RI C API): the Menger sponge plug-in (examples/plugins/menger.c) renders exactly as the same
// sponge written as plain RIB, covers the area the Sierpinski carpet has, is found along
// Option "searchpath" "procedural"; missing and broken plug-ins are errors naming the procedural.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::RenderResult;

const std::string kPluginDir = STREYES_PLUGIN_DIR;
const std::string kMenger = kPluginDir + "/menger.so";

std::string num(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", double(v));
    return buf;
}

// The cube [x, x+s]^3 as the plug-in writes it (the same vertex order and float sums).
std::string cubeRib(float x, float y, float z, float s) {
    std::string p;
    for (int i = 0; i < 8; ++i)
        p += " " + num((i & 1) ? x + s : x) + " " + num((i & 2) ? y + s : y) + " " + num((i & 4) ? z + s : z);
    return "PointsPolygons [4 4 4 4 4 4] [0 2 3 1 4 5 7 6 0 1 5 4 2 6 7 3 0 4 6 2 1 3 7 5] \"P\" [" + p + "]\n";
}

// The sponge's cubes, computed as the plug-in computes them, as plain RIB.
void spongeRib(int level, float x, float y, float z, float size, std::string& rib) {
    if (level <= 0) {
        rib += cubeRib(x, y, z, size);
        return;
    }
    const float t = size / 3.0f;
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i)
                if ((i == 1) + (j == 1) + (k == 1) < 2)
                    spongeRib(level - 1, x + float(i) * t, y + float(j) * t, z + float(k) * t, t, rib);
}

std::string mengerRequest(const std::string& plugin, int level, float x, float y, float z, float size,
                          const std::string& extra = "") {
    return "Procedural \"DynamicLoad\" [\"" + plugin + "\" \"level=" + std::to_string(level) + " x=" + num(x) +
           " y=" + num(y) + " z=" + num(z) + " size=" + num(size) + " plugin=" + plugin + extra + "\"] [" + num(x) +
           " " + num(x + size) + " " + num(y) + " " + num(y + size) + " " + num(z) + " " + num(z + size) + "]\n";
}

// A perspective view of a sponge from above a corner: every kind of face shows.
std::string perspectiveHeader() {
    return "Format 96 72 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 3 3\n"
           "Translate 0 0 4.5\nRotate 30 1 0 0\nRotate 35 0 1 0\n"
           "WorldBegin\nSurface \"constant\"\nColor [0.8 0.6 0.3]\n";
}

using test::alphaSum;

TEST(PluginProcedural, MengerSpongeEqualsTheSameSpongeWrittenAsRib) {
    std::string reference = perspectiveHeader();
    spongeRib(2, -1, -1, -1, 2, reference);
    reference += "WorldEnd\n";
    const RenderResult plain = test::renderRib(reference);
    ASSERT_GT(alphaSum(plain), 500.0);  // the sponge is in view

    // Sub-cubes as procedurals through the plug-in again (RiProcDynamicLoad), or through the
    // plug-in's own subdivide function (RiProcedural with a function pointer).
    for (const char* recurse : {"dso", "function"}) {
        SCOPED_TRACE(recurse);
        const RenderResult viaPlugin = test::renderRib(perspectiveHeader() +
                                                       mengerRequest(kMenger, 2, -1, -1, -1, 2,
                                                                     std::string(" recurse=") + recurse) +
                                                       "WorldEnd\n");
        EXPECT_TRUE(test::identicalPixels(plain, viaPlugin));
        // The sponge, its 20 sub-sponges and (of the 400 cubes) at least those in front expanded.
        EXPECT_GT(viaPlugin.stats.counters.proceduralsExpanded, 21u);
        EXPECT_LE(viaPlugin.stats.counters.proceduralsExpanded, 421u);
    }
}

TEST(PluginProcedural, MengerSpongeFaceOnCoversTheSierpinskiCarpet) {
    // Face on, orthographic, one unit a pixel: a sponge of edge 81 at level L covers (8/9)^L of
    // its 81 x 81 square, with every hole on whole pixels.
    for (int level : {1, 2}) {
        const RenderResult r = test::renderRib(test::orthoHeader(97, 97, "PixelSamples 2 2\n") +
                                               mengerRequest(kMenger, level, 8, 8, 5, 81) + "WorldEnd\n");
        const double expected = 81.0 * 81.0 * std::pow(8.0 / 9.0, level);
        EXPECT_NEAR(alphaSum(r), expected, 1e-3) << "level " << level;
        // The centre hole (27 pixels wide) is empty; a pixel of the top-left sub-square is covered.
        EXPECT_EQ(r.alpha(0, 48, 48), 0.0f);
        EXPECT_EQ(r.alpha(0, 10, 10), 1.0f);
    }
}

TEST(PluginProcedural, SubdivideGetsTheDetailOfItsBound) {
    // mindetail=2000: the sponge of edge 81 (6561 pixels, detail 8192) subdivides; its sub-cubes
    // (729 pixels, detail 1024) are drawn whole. Level 3 asked, level 1 drawn: 8/9 of the face.
    const RenderResult r = test::renderRib(test::orthoHeader(97, 97, "PixelSamples 2 2\n") +
                                           mengerRequest(kMenger, 3, 8, 8, 5, 81, " mindetail=2000") +
                                           "WorldEnd\n");
    EXPECT_NEAR(alphaSum(r), 81.0 * 81.0 * 8.0 / 9.0, 1e-3);
    // The sponge and at most its 20 sub-cubes (those hidden may be culled unexpanded); none deeper.
    EXPECT_GE(r.stats.counters.proceduralsExpanded, 9u);
    EXPECT_LE(r.stats.counters.proceduralsExpanded, 21u);
}

TEST(PluginProcedural, SameImageWhateverTheThreadCount) {
    const std::string rib = perspectiveHeader() + mengerRequest(kMenger, 2, -1, -1, -1, 2) + "WorldEnd\n";
    RenderOptions one;
    one.threads = 1;
    RenderOptions two;
    two.threads = 2;
    EXPECT_TRUE(test::identicalPixels(test::renderRib(rib, one), test::renderRib(rib, two)));
}

TEST(PluginProcedural, FoundAlongTheProceduralSearchPath) {
    std::string reference = test::orthoHeader(40, 40) ;
    spongeRib(1, 2, 2, 5, 27, reference);
    const RenderResult plain = test::renderRib(reference + "WorldEnd\n");
    // A bare name, without ".so", along the path; '&' keeps what was there before.
    const std::string viaPath =
        test::orthoHeader(40, 40, "Option \"searchpath\" \"procedural\" [\"/nonexistent\"]\n"
                                  "Option \"searchpath\" \"procedural\" [\"" + kPluginDir + ":&\"]\n") +
        mengerRequest("menger", 1, 2, 2, 5, 27, " recurse=dso") + "WorldEnd\n";
    EXPECT_TRUE(test::identicalPixels(plain, test::renderRib(viaPath)));

    // By default ('@'), beside the RIB file.
    test::TempDir dir("plugin-beside");
    std::filesystem::copy_file(kMenger, dir.path() + "/menger.so");
    const std::string scene = dir.path() + "/sponge.rib";
    std::ofstream(scene) << test::orthoHeader(40, 40) + mengerRequest("menger", 1, 2, 2, 5, 27, " recurse=dso") +
                                "WorldEnd\n";
    EXPECT_TRUE(test::identicalPixels(plain, test::renderFile(scene)));
}

// The error rendering `rib` (read as "test.rib") makes, or "" when it renders.
std::string renderError(const std::string& rib) {
    try {
        test::renderRib(rib);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(PluginProcedural, MissingPluginIsAnErrorNamingTheProcedural) {
    const std::string rib = test::orthoHeader(8, 8) + "Procedural \"DynamicLoad\" [\"no-such-plugin\" \"\"] [0 1 0 1 0 1]\n"
                                                      "WorldEnd\n";
    const std::string e = renderError(rib);
    EXPECT_NE(e.find("test.rib:7"), std::string::npos) << e;
    EXPECT_NE(e.find("no plug-in 'no-such-plugin'"), std::string::npos) << e;
    EXPECT_NE(e.find("searchpath"), std::string::npos) << e;  // what to do

    const std::string path = renderError(test::orthoHeader(8, 8) +
                                         "Procedural \"DynamicLoad\" [\"/nonexistent/sponge.so\" \"\"] [0 1 0 1 0 1]\n"
                                         "WorldEnd\n");
    EXPECT_NE(path.find("no plug-in '/nonexistent/sponge.so'"), std::string::npos) << path;
}

TEST(PluginProcedural, SharedObjectWithoutTheProceduralFunctionsIsAnError) {
    const std::string e = renderError(test::orthoHeader(8, 8) + "Procedural \"DynamicLoad\" [\"" + kPluginDir +
                                      "/test_plugin_no_symbols.so\" \"\"] [0 1 0 1 0 1]\nWorldEnd\n");
    EXPECT_NE(e.find("test.rib:7"), std::string::npos) << e;
    EXPECT_NE(e.find("does not export Subdivide Free"), std::string::npos) << e;

    // A call streyes does not have: the symbol dlopen misses is named.
    const std::string unknown = renderError(test::orthoHeader(8, 8) + "Procedural \"DynamicLoad\" [\"" + kPluginDir +
                                            "/test_plugin_unknown_call.so\" \"\"] [0 1 0 1 0 1]\nWorldEnd\n");
    EXPECT_NE(unknown.find("test.rib:7"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("undefined symbol: RiBlobby"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("only the Ri functions of include/ri.h"), std::string::npos) << unknown;

    // Not a shared object at all: dlopen's complaint, with the file named.
    test::TempDir dir("plugin-bad");
    std::ofstream(dir.path() + "/junk.so") << "not an ELF file\n";
    const std::string junk = renderError(test::orthoHeader(8, 8) + "Procedural \"DynamicLoad\" [\"" + dir.path() +
                                         "/junk.so\" \"\"] [0 1 0 1 0 1]\nWorldEnd\n");
    EXPECT_NE(junk.find("test.rib:7"), std::string::npos) << junk;
    EXPECT_NE(junk.find("cannot load the plug-in"), std::string::npos) << junk;
}

TEST(PluginProcedural, BadCallInSubdivideNamesTheProceduralAndTheCall) {
    // The plug-in's third call is RiSphere with a NaN radius.
    const std::string e = renderError(test::orthoHeader(8, 8) + "Procedural \"DynamicLoad\" [\"" + kPluginDir +
                                      "/test_plugin_bad_call.so\" \"\"] [0 8 0 8 0 8]\nWorldEnd\n");
    EXPECT_NE(e.find("test.rib:7"), std::string::npos) << e;
    EXPECT_NE(e.find("call 3 (RiSphere)"), std::string::npos) << e;
    EXPECT_NE(e.find("not a finite number"), std::string::npos) << e;
}

}  // namespace
}  // namespace streyes
