// Frame patterns on disk.
#include "streyes/image_io.h"

#include <gtest/gtest.h>

#include <fstream>

#include "streyes/error.h"
#include "test_util.h"

namespace streyes {
namespace {

TEST(FramePatterns, FindFramesListsExactlyTheFilesThePatternNames) {
    const test::TempDir tempDir("find-frames");
    const std::string& dir = tempDir.path();
    for (const char* name : {"a.0001.exr", "a.0002.exr", "a.12345.exr", "a.-003.exr",  // frames 1, 2, 12345, -3
                             "a.7.exr", "a.0004.exr.tmp", "b.0005.exr", "a.00x6.exr", "a.0007.EXR"})
        std::ofstream(dir + "/" + name) << "x";
    EXPECT_EQ(findFrames(dir + "/a.####.exr"), (std::vector<int>{-3, 1, 2, 12345}));
    EXPECT_EQ(findFrames(dir + "/a.#.exr"), (std::vector<int>{7, 12345}));  // "0001" is not "1"
    EXPECT_TRUE(findFrames(dir + "/c.####.exr").empty());
    EXPECT_TRUE(findFrames(dir + "/missing/a.####.exr").empty());
    EXPECT_THROW(findFrames(dir + "/f##/a.####.exr"), InputError);
}

}  // namespace
}  // namespace streyes
