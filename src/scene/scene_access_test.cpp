// checkSceneWrite: the one check every file a scene asks to write goes through (--safe).
#include <gtest/gtest.h>

#include <filesystem>

#include "streyes/scene_access.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;

// Sets an access for one test and puts back what was there.
struct ScopedAccess {
    SceneAccess before = sceneAccess();
    explicit ScopedAccess(const SceneAccess& a) { setSceneAccess(a); }
    ~ScopedAccess() { setSceneAccess(before); }
};

SourceLoc at(int line) { return SourceLoc{std::make_shared<const std::string>("scene.rib"), line, 0}; }

// The message of the InputError checkSceneWrite throws, "" when it allows the write.
std::string refusal(const std::string& name, const std::string& base = "") {
    try {
        checkSceneWrite("Display", name, at(7), base);
    } catch (const InputError& e) {
        EXPECT_EQ(e.loc.line, 7);
        return e.what();
    }
    return "";
}

TEST(SceneAccess, WithoutAWriteFolderEveryNameIsAllowed) {
    const ScopedAccess scoped(SceneAccess{});
    EXPECT_EQ(refusal("/etc/streyes-would-write-here"), "");
    EXPECT_EQ(refusal("../../up.exr"), "");
}

TEST(SceneAccess, SafeKeepsWritesInsideTheFolder) {
    const test::TempDir dir("scene-access");
    const std::string inside = dir.path() + "/out", outside = dir.path() + "/elsewhere";
    fs::create_directories(inside + "/sub");
    fs::create_directories(outside);
    fs::create_directory_symlink(outside, inside + "/link");  // inside, pointing out
    SceneAccess a;
    a.programs = false;
    a.safe = true;
    a.writeFolder = inside;
    const ScopedAccess scoped(a);

    // Relative names that stay inside: the folder's own files, its subfolders, names not there yet.
    EXPECT_EQ(refusal("frame.####.exr", inside), "");
    EXPECT_EQ(refusal("sub/frame.exr", inside), "");
    EXPECT_EQ(refusal("new/deeper/frame.exr", inside), "");
    EXPECT_EQ(refusal("./sub/./frame.exr", inside), "");

    const std::string absolute = refusal(outside + "/x.exr", inside);
    EXPECT_NE(absolute.find("scene.rib:7"), std::string::npos) << absolute;
    EXPECT_NE(absolute.find("Display \"" + outside + "/x.exr\": --safe refuses an absolute path"), std::string::npos)
        << absolute;
    EXPECT_NE(absolute.find("a scene may write only inside " + inside), std::string::npos) << absolute;
    EXPECT_NE(absolute.find("give a relative name, or render without --safe only if you trust the scene"),
              std::string::npos)
        << absolute;  // what to do
    // Even an absolute name inside the folder: a scene cannot know where it will be rendered.
    EXPECT_NE(refusal(inside + "/x.exr", inside).find("refuses an absolute path"), std::string::npos);

    EXPECT_NE(refusal("../x.exr", inside).find("refuses a path with \"..\""), std::string::npos);
    EXPECT_NE(refusal("sub/../../x.exr", inside).find("refuses a path with \"..\""), std::string::npos);
    // ".." that would stay inside is refused too: the rule is simple to state and to check.
    EXPECT_NE(refusal("sub/../x.exr", inside).find("refuses a path with \"..\""), std::string::npos);

    // A symbolic link inside that leads out.
    const std::string link = refusal("link/x.exr", inside);
    EXPECT_NE(link.find("would write '" + fs::canonical(outside).string() + "/x.exr'"), std::string::npos) << link;
    EXPECT_NE(link.find("--safe refuses it (a scene may write only inside " + inside +
                        "): give --safe-dir a folder that holds it"),
              std::string::npos)
        << link;
    // A relative name taken from a folder outside (MakeTexture's is its RIB file's).
    EXPECT_NE(refusal("x.tx", outside).find("would write '" + fs::canonical(outside).string() + "/x.tx'"),
              std::string::npos);
    // The folder itself is not a file inside it.
    EXPECT_NE(refusal(".", inside), "");
}

}  // namespace
}  // namespace streyes
