// Output variables in files: the channels a mode names, written from the frame and read back.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "streyes/error.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

std::string bytesOf(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

FrameImage frameWithNormals() {
    FrameImage f;
    f.aovNames = {"N.X", "N.Y", "N.Z", "motion.X", "motion.Y"};
    f.resize(6, 4);
    for (size_t i = 0; i < f.rgba.size(); ++i) f.rgba[i] = float(i % 5) * 0.25f;
    for (size_t i = 0; i < f.z.size(); ++i) f.z[i] = 2.0f + float(i) / 3.0f;
    for (size_t i = 0; i < f.aov.size(); ++i) f.aov[i] = float(i) * 0.1f - 1.0f / 7.0f;  // not a half
    return f;
}

TEST(AovFiles, ModesWriteTheirChannelsAsFloat) {
    const test::TempDir dir("aov-files");
    const FrameImage f = frameWithNormals();
    writeFrame(dir.path() + "/all.exr", f, "rgba,N,z,motion");
    writeFrame(dir.path() + "/n.exr", f, "N");
    const ImageData all = readImage(dir.path() + "/all.exr"), n = readImage(dir.path() + "/n.exr");
    // readExr orders R G B A, then the others by name.
    EXPECT_EQ(all.channels, (std::vector<std::string>{"R", "G", "B", "A", "N.X", "N.Y", "N.Z", "Z", "motion.X", "motion.Y"}));
    EXPECT_EQ(n.channels, (std::vector<std::string>{"N.X", "N.Y", "N.Z"}));
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 6; ++x) {
            const size_t p = size_t(y) * 6 + size_t(x);
            for (int c = 0; c < 3; ++c) {
                EXPECT_EQ(n.at(x, y, c), f.aov[p * 5 + size_t(c)]);  // float: exact
                EXPECT_EQ(all.at(x, y, all.channelIndex(n.channels[size_t(c)])), f.aov[p * 5 + size_t(c)]);
            }
            EXPECT_EQ(all.at(x, y, all.channelIndex("motion.Y")), f.aov[p * 5 + 4]);
            EXPECT_EQ(all.at(x, y, all.channelIndex("Z")), f.z[p]);  // z is the frame's Z
            EXPECT_EQ(all.at(x, y, 1), f.rgba[p * 4 + 1]);             // quarters: exact in half
        }
    EXPECT_EQ(all.formats[4], "float");
    EXPECT_EQ(all.formats[0], "half");
    EXPECT_TRUE(isCompleteFrame(dir.path() + "/all.exr", 6, 4, "rgba,N,z,motion"));
    EXPECT_TRUE(isCompleteFrame(dir.path() + "/n.exr", 6, 4, "N"));
    EXPECT_FALSE(isCompleteFrame(dir.path() + "/n.exr", 6, 4, "N,P"));
}

TEST(AovFiles, ColourModesAreTheSameBytesWhateverTheFrameCarries) {
    const test::TempDir dir("aov-colour");
    FrameImage plain = frameWithNormals();
    plain.aovNames.clear();
    plain.aov.clear();
    writeFrame(dir.path() + "/plain.exr", plain, "rgbaz");
    writeFrame(dir.path() + "/other.exr", frameWithNormals(), "N");  // another encoding between
    writeFrame(dir.path() + "/with.exr", frameWithNormals(), "rgbaz");
    EXPECT_EQ(bytesOf(dir.path() + "/plain.exr"), bytesOf(dir.path() + "/with.exr"));
}

TEST(AovFiles, ShaderOutputsAreTheFramesChannelsOfTheirName) {
    const test::TempDir dir("aov-shader-files");
    FrameImage f;
    f.aovNames = {"N.X", "N.Y", "N.Z", "halfCs.R", "halfCs.G", "halfCs.B", "height"};
    f.resize(3, 2);
    for (size_t i = 0; i < f.aov.size(); ++i) f.aov[i] = float(i);
    writeFrame(dir.path() + "/s.exr", f, "rgba,halfCs,height");
    const ImageData s = readImage(dir.path() + "/s.exr");
    EXPECT_EQ(s.channels, (std::vector<std::string>{"R", "G", "B", "A", "halfCs.B", "halfCs.G", "halfCs.R", "height"}));
    EXPECT_EQ(s.at(2, 1, s.channelIndex("halfCs.G")), f.aov[5 * 7 + 4]);
    EXPECT_EQ(s.at(2, 1, s.channelIndex("height")), f.aov[5 * 7 + 6]);
    EXPECT_TRUE(isCompleteFrame(dir.path() + "/s.exr", 3, 2, "rgba,halfCs,height"));
    EXPECT_FALSE(isCompleteFrame(dir.path() + "/s.exr", 3, 2, "rgba,halfCs"));
    EXPECT_THROW(writeFrame(dir.path() + "/t.exr", f, "rgba,other"), RenderError);
}

TEST(AovFiles, AModeNamingAVariableTheFrameLacksFails) {
    const test::TempDir dir("aov-missing");
    EXPECT_THROW(writeFrame(dir.path() + "/p.exr", frameWithNormals(), "P"), RenderError);
    EXPECT_FALSE(validChannelMode("rgba,1x"));
    EXPECT_FALSE(validChannelMode("rgba,,N"));
    EXPECT_TRUE(validChannelMode("rgba, N ,P"));
}

}  // namespace
}  // namespace streyes
