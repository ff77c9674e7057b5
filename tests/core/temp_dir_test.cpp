// test::TempDir: the tests' temporary folders go when the test ends, whatever the test left in
// them (files, subfolders, permissions taken away).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;

TEST(TempDir, IsRemovedWithEverythingInIt) {
    std::string path;
    {
        const test::TempDir dir("temp-dir");
        path = dir.path();
        EXPECT_TRUE(fs::is_directory(path));
        EXPECT_TRUE(fs::is_empty(path));
        EXPECT_NE(fs::path(path).filename().string().find("streyes-temp-dir-"), std::string::npos) << path;
        fs::create_directories(path + "/a/b");
        std::ofstream(path + "/a/b/file") << "x";
        std::ofstream(path + "/.hidden") << "x";
        // A folder no one may write to or enter, as the bad-input tests leave them.
        fs::permissions(path + "/a", fs::perms::owner_read);
    }
    EXPECT_FALSE(fs::exists(path)) << path;
}

TEST(TempDir, MovedOnceRemovedOnce) {
    std::string path;
    {
        test::TempDir first("temp-dir-move");
        path = first.path();
        test::TempDir second(std::move(first));
        EXPECT_EQ(second.path(), path);
        EXPECT_TRUE(first.path().empty());  // a moved-from TempDir holds no folder
        EXPECT_TRUE(fs::is_directory(path));
    }
    EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace streyes
