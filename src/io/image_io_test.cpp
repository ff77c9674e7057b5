// Frame patterns on disk.
#include "streyes/image_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

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

std::string fileBytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// A frame whose pixels equal the last frame written reuses that encoding: the file must be the one
// encoding it would have given, and a frame that differs in one bit must not reuse it.
TEST(FrameFiles, IdenticalFramesReuseTheirEncodingBitForBit) {
    const test::TempDir tempDir("reuse");
    const std::string& dir = tempDir.path();
    FrameImage a, b;
    a.resize(8, 4);
    for (size_t i = 0; i < a.rgba.size(); ++i) a.rgba[i] = float(i % 7) * 0.125f;
    for (size_t i = 0; i < a.z.size(); ++i) a.z[i] = 1.0f + float(i);
    b = a;
    b.z[5] = std::nextafter(b.z[5], 100.0f);  // one bit apart
    writeFrame(dir + "/a1.exr", a, "rgbaz");   // encoded
    writeFrame(dir + "/b.exr", b, "rgbaz");    // encoded: differs
    writeFrame(dir + "/a2.exr", a, "rgbaz");   // encoded again (the last was b)
    writeFrame(dir + "/a3.exr", a, "rgbaz");   // reused
    writeFrame(dir + "/a4.exr", a, "rgba");    // another mode: encoded
    const std::string a1 = fileBytes(dir + "/a1.exr");
    ASSERT_FALSE(a1.empty());
    EXPECT_EQ(fileBytes(dir + "/a2.exr"), a1);
    EXPECT_EQ(fileBytes(dir + "/a3.exr"), a1);
    EXPECT_NE(fileBytes(dir + "/b.exr"), a1);
    EXPECT_NE(fileBytes(dir + "/a4.exr"), a1);
    const ImageData rb = readImage(dir + "/b.exr"), ra = readImage(dir + "/a3.exr"), r4 = readImage(dir + "/a4.exr");
    ASSERT_EQ(rb.channels.size(), 5u);
    EXPECT_EQ(rb.at(5, 0, 4), b.z[5]);
    EXPECT_EQ(ra.at(5, 0, 4), a.z[5]);
    EXPECT_EQ(r4.channels.size(), 4u);
}

}  // namespace
}  // namespace streyes
