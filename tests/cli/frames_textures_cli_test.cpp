// --frames and texture-making requests: a wanted frame that maps a texture a MakeTexture of the same
// file makes from another frame's picture gets that frame rendered first (said in a line), and
// equals the frame rendered with the whole file, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;

test::CliRun renderIn(const std::string& dir, const std::string& args) {
    return test::runStreyesWith("cd " + dir + " && ", "render " + args);
}

bool samePixels(const std::string& a, const std::string& b) {
    const ImageData x = readImage(a), y = readImage(b);
    return x.width == y.width && x.height == y.height && x.channels == y.channels && !x.pixels.empty() &&
           x.pixels == y.pixels;
}

// Frame 1 renders a picture of four coloured corners (pic.tif), MakeTexture makes it pic.tex,
// frame 2 maps pic.tex on a square, frame 3 is a sphere that reads nothing.
const char* kShot = R"(Format 48 32 1
PixelSamples 2 2
Projection "perspective" "fov" [40]
FrameBegin 1
Display "pic.tif" "tiff" "rgba"
WorldBegin
Translate 0 0 3
Surface "constant"
Patch "bilinear" "P" [-2 -2 0  2 -2 0  -2 2 0  2 2 0] "Cs" [1 0 0  0 1 0  0 0 1  1 1 0]
WorldEnd
FrameEnd
MakeTexture "pic.tif" "pic.tex" "clamp" "clamp" "box" 1 1
FrameBegin 2
Display "two.exr" "openexr" "rgba"
WorldBegin
Translate 0 0 3
Rotate 30 0 0 1
Surface "paintedplastic" "texturename" ["pic.tex"] "Ks" [0]
LightSource "ambientlight" 1 "intensity" [1]
Patch "bilinear" "P" [-1 -1 0  1 -1 0  -1 1 0  1 1 0]
WorldEnd
FrameEnd
FrameBegin 3
Display "three.exr" "openexr" "rgba"
WorldBegin
Translate 0 0 3
Sphere 1 -1 1 360
WorldEnd
FrameEnd
)";

TEST(FramesTexturesCli, AFrameMappingATextureMadeFromAnotherFramesPictureRendersThatFrameFirst) {
    test::TempDir whole("frames-tex-whole"), one("frames-tex-one"), named("frames-tex-o");
    for (const auto* d : {&whole, &one, &named}) test::writeFile(d->path(), "shot.rib", kShot);
    const test::CliRun all = renderIn(whole.path(), "shot.rib");
    ASSERT_EQ(all.exitCode, 0) << all.output;
    EXPECT_EQ(all.output.find("warning"), std::string::npos) << all.output;

    const test::CliRun r = renderIn(one.path(), "shot.rib --frames 2");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;  // pic.tex is there when read
    EXPECT_NE(r.output.find("frame 1 rendered for frame 2: the texture it reads is made from its picture (shot.rib:12)"),
              std::string::npos)
        << r.output;
    // Frame 1's picture (the texture's input) and the texture are made; frame 3 is not rendered.
    EXPECT_EQ(test::listDir(one.path()), (std::vector<std::string>{"pic.tex", "pic.tif", "shot.rib", "two.exr"}));
    EXPECT_TRUE(samePixels(one.path() + "/two.exr", whole.path() + "/two.exr"));
    EXPECT_TRUE(samePixels(one.path() + "/pic.tif", whole.path() + "/pic.tif"));
    // The texture shows (the comparison can fail): frame 3's sphere is not frame 2's picture.
    EXPECT_FALSE(samePixels(one.path() + "/two.exr", whole.path() + "/three.exr"));

    // -o names the wanted frame's picture only: frame 1 still writes the picture the texture reads.
    const test::CliRun o = renderIn(named.path(), "shot.rib --frames 2 -o out.####.exr");
    ASSERT_EQ(o.exitCode, 0) << o.output;
    EXPECT_EQ(test::listDir(named.path()), (std::vector<std::string>{"out.0002.exr", "pic.tex", "pic.tif", "shot.rib"}));
    // (-o writes float RGBA and Z, the Display half RGBA: the same RGBA to half's precision.)
    const ImageData got = readImage(named.path() + "/out.0002.exr"), want = readImage(whole.path() + "/two.exr");
    ASSERT_EQ(got.width, want.width);
    ASSERT_EQ(got.height, want.height);
    ASSERT_GE(got.channels.size(), 4u);
    for (int y = 0; y < want.height; ++y)
        for (int x = 0; x < want.width; ++x)
            for (int c = 0; c < 4; ++c)
                ASSERT_NEAR(got.at(x, y, c), want.at(x, y, c), 1e-3 * std::max(1.0f, std::fabs(want.at(x, y, c))))
                    << x << " " << y << " " << c;

    // Frame 3 alone reads no texture: nothing else is rendered or made.
    test::TempDir three("frames-tex-three");
    test::writeFile(three.path(), "shot.rib", kShot);
    const test::CliRun t = renderIn(three.path(), "shot.rib --frames 3");
    ASSERT_EQ(t.exitCode, 0) << t.output;
    EXPECT_EQ(t.output.find("rendered for frame"), std::string::npos) << t.output;
    EXPECT_EQ(test::listDir(three.path()), (std::vector<std::string>{"shot.rib", "three.exr"}));
    EXPECT_TRUE(samePixels(three.path() + "/three.exr", whole.path() + "/three.exr"));
}

}  // namespace
}  // namespace streyes
