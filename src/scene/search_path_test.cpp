// Option "searchpath" (search_path.h): '&' and '@', lookup with suffixes, and archives found
// along the archive path by ReadArchive and DelayedReadArchive.
#include "scene/search_path.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

TEST(SearchPath, AmpersandIsThePathBeforeAndAtIsTheFilesFolder) {
    EXPECT_EQ(expandSearchPath("/a:&", "@"), "/a:@");
    EXPECT_EQ(expandSearchPath("&:/b", "/a:@"), "/a:@:/b");
    EXPECT_EQ(expandSearchPath("/c", "/a:@"), "/c");
    EXPECT_EQ(searchPathFolders("/a:@::/b", "/scenes"), (std::vector<std::string>{"/a", "/scenes", "/b"}));
    EXPECT_EQ(searchPathFolders("@", ""), (std::vector<std::string>{"."}));
}

// STREYES_SHADERPATH and the like: folders separated by ':', nothing special in them.
TEST(SearchPath, TheEnvironmentsFoldersInOrder) {
    const char* name = "STREYES_SEARCH_PATH_TEST";
    unsetenv(name);
    EXPECT_TRUE(environmentSearchPath(name).empty());
    setenv(name, "/a::/b c:@:&:", 1);
    EXPECT_EQ(environmentSearchPath(name), (std::vector<std::string>{"/a", "/b c", "@", "&"}));
    setenv(name, "", 1);
    EXPECT_TRUE(environmentSearchPath(name).empty());
    unsetenv(name);
}

TEST(SearchPath, FindsTheFirstFolderHoldingTheNameOrTheNameWithASuffix) {
    test::TempDir a("searchpath-a"), b("searchpath-b");
    std::ofstream(b.path() + "/tree.rib") << "\n";
    std::ofstream(a.path() + "/tree") << "\n";
    const std::string path = a.path() + ":" + b.path();
    EXPECT_EQ(findOnSearchPath("tree", path, "", {".rib"}), a.path() + "/tree");
    EXPECT_EQ(findOnSearchPath("tree.rib", path, "", {".rib"}), b.path() + "/tree.rib");
    EXPECT_EQ(findOnSearchPath("tree", b.path(), "", {".rib"}), b.path() + "/tree.rib");
    EXPECT_EQ(findOnSearchPath("bush", path, "", {".rib"}), "");
    EXPECT_EQ(findOnSearchPath("tree", "@", b.path(), {".rib"}), b.path() + "/tree.rib");
}

TEST(SearchPath, ArchivesAreFoundAlongTheArchivePath) {
    test::TempDir lib("searchpath-lib");
    std::ofstream(lib.path() + "/square.rib") << "Patch \"bilinear\" \"P\" [0 0 5 4 0 5 0 4 5 4 4 5]\n";
    const std::string option = "Option \"searchpath\" \"archive\" [\"/nonexistent:" + lib.path() + "\"]\n";
    // ReadArchive, with and without ".rib".
    for (const char* name : {"square.rib", "square"}) {
        const test::RenderResult r =
            test::renderRib(test::orthoHeader(8, 8, option) + "ReadArchive \"" + name + "\"\nWorldEnd\n");
        EXPECT_EQ(r.alpha(0, 1, 6), 1.0f) << name;
    }
    // DelayedReadArchive.
    const test::RenderResult r = test::renderRib(test::orthoHeader(8, 8, option) +
                                                 "Procedural \"DelayedReadArchive\" [\"square\"] [0 4 0 4 5 5]\n"
                                                 "WorldEnd\n");
    EXPECT_EQ(r.alpha(0, 1, 6), 1.0f);
    // Without the path: not found, and the message says where to look.
    const std::string e = test::ribError(test::orthoHeader(8, 8) + "ReadArchive \"square\"\nWorldEnd\n");
    EXPECT_NE(e.find("cannot open 'square'"), std::string::npos) << e;
}

TEST(SearchPath, OptionNeedsAValueAndWarnsOnPathsItDoesNotUse) {
    EXPECT_NE(test::ribError("Option \"searchpath\" \"procedural\"\nWorldBegin\nWorldEnd\n").find("needs a value"),
              std::string::npos);
    Log log;
    log.setQuiet(true);
    parseRibString("Option \"searchpath\" \"display\" [\"/x\"]\nWorldBegin\nWorldEnd\n", "s.rib", log);
    ASSERT_EQ(log.warnings().size(), 1u);
    EXPECT_NE(log.warnings()[0].find("\"display\" is not used"), std::string::npos) << log.warnings()[0];
}

// The texture path is resolved where it is given: '@' the giving file's folder, '&' the path before.
TEST(SearchPath, TexturePathResolvesAtAndAmpersandWhereGiven) {
    Log log;
    Scene scene = parseRibString("Option \"searchpath\" \"texture\" [\"/a:&\"]\n"
                                 "Option \"searchpath\" \"texture\" [\"/b:&\"]\nWorldBegin\nWorldEnd\n",
                                 "/scenes/s.rib", log);
    EXPECT_EQ(scene.settings.textureSearchPath, (std::vector<std::string>{"/b", "/a", "/scenes"}));
    EXPECT_TRUE(log.warnings().empty());
    EXPECT_TRUE(parseRibString("WorldBegin\nWorldEnd\n", "s.rib", log).settings.textureSearchPath.empty());
}

TEST(SearchPath, ShaderPathKeepsWhatCameBeforeForAmpersand) {
    Log log;
    Scene scene = parseRibString("Option \"searchpath\" \"shader\" [\"/a:&\"]\n"
                                 "Option \"searchpath\" \"shader\" [\"/b:&\"]\nWorldBegin\nWorldEnd\n",
                                 "s.rib", log);
    EXPECT_EQ(scene.settings.shaderSearchPath, "/b:/a:@");  // '@': the shipped shaders
    EXPECT_TRUE(log.warnings().empty());
}

}  // namespace
}  // namespace streyes
