#include "render/dof_preview.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

TEST(DepthOfFieldPreview, LayersAreEvenInInverseDepth) {
    const std::vector<double> z = dofLayerDepths(1, 10, 3);
    ASSERT_EQ(z.size(), 4u);
    EXPECT_EQ(z.front(), 1.0);
    EXPECT_EQ(z.back(), 10.0);
    for (size_t i = 1; i < z.size(); ++i) EXPECT_NEAR(1 / z[i - 1] - 1 / z[i], 0.3, 1e-12);
}

// One lit pixel in the middle spreads evenly over the disc: the variance along x of a uniform disc
// of radius r (r^2 / 4, and the pixel's own 1/12), the total kept, nothing beyond the radius.
TEST(DepthOfFieldPreview, BlurSpreadsAPixelOverTheDisc) {
    FrameImage in;
    in.resize(41, 41);
    in.rgba[(20 * 41 + 20) * 4 + 0] = 1;
    in.rgba[(20 * 41 + 20) * 4 + 3] = 1;
    FrameImage out;
    const float r = 8;
    blurDisc(in, r, r, out);
    double sum = 0, alpha = 0, squares = 0;
    for (int y = 0; y < 41; ++y)
        for (int x = 0; x < 41; ++x) {
            const float v = out.rgba[(size_t(y) * 41 + size_t(x)) * 4];
            sum += v;
            alpha += out.rgba[(size_t(y) * 41 + size_t(x)) * 4 + 3];
            squares += double(v) * (x - 20) * (x - 20);
            if (std::hypot(x - 20, y - 20) > r + 1) {
                EXPECT_EQ(v, 0.0f) << x << " " << y;
            }
        }
    EXPECT_NEAR(sum, 1.0, 1e-5);
    EXPECT_NEAR(alpha, 1.0, 1e-5);
    EXPECT_NEAR(squares / sum, r * r / 4 + 1.0 / 12, 0.02 * r * r / 4);
}

TEST(DepthOfFieldPreview, CompositeIsPremultipliedOver) {
    FrameImage front, back;
    front.resize(1, 1);
    back.resize(1, 1);
    front.rgba = {0.25f, 0, 0, 0.5f};
    front.z = {2};
    back.rgba = {0, 1, 0, 1};
    back.z = {5};
    compositeOver(front, back);
    EXPECT_FLOAT_EQ(back.rgba[0], 0.25f);
    EXPECT_FLOAT_EQ(back.rgba[1], 0.5f);
    EXPECT_FLOAT_EQ(back.rgba[3], 1.0f);
    EXPECT_EQ(back.z[0], 2.0f);
}

// Without DepthOfField the preview is the ordinary render, bit for bit.
TEST(DepthOfFieldPreview, WithoutALensItIsTheRender) {
    const std::string rib = "Format 24 16 1\nProjection \"perspective\" \"fov\" [40]\nClipping 0.1 100\nWorldBegin\n"
                            "Surface \"constant\"\n" + test::square(-1, 0.5, -0.5, 1, 5) + "WorldEnd\n";
    Log log;
    const Scene scene = parseRibString(rib, "test.rib", log);
    const test::RenderResult plain = test::renderScene(scene);
    test::RenderResult preview;
    renderDofPreview(scene, RenderOptions{}, 8, log, [&](const FrameImage& f) { preview.frames.push_back(f); });
    EXPECT_TRUE(test::identicalPixels(plain, preview));
}

// The layers' depth range comes from the whole shot's bodies: frame 13 of a leaf keyed every
// other frame of a 65-frame shot, receding from depth 3 to 40, is the same alone as in the shot.
TEST(DepthOfFieldPreview, AFramesLayersDoNotDependOnTheFramesRendered) {
    std::string rib = "Option \"streyes\" \"int frames\" [0 64]\nFormat 24 16 1\nProjection \"perspective\" \"fov\" [40]\n"
                      "Clipping 0.1 100\nDepthOfField 2.8 0.5 6\nPixelSamples 2 2\nShutter 0 0.5\nWorldBegin\n"
                      "Surface \"constant\"\nAttributeBegin\nMotionBegin [";
    for (int k = 0; k <= 32; ++k) rib += std::to_string(2 * k) + (k < 32 ? " " : "]\n");
    for (int k = 0; k <= 32; ++k) rib += "Translate 0 0 " + std::to_string(3 + 37.0 * k / 32) + "\n";
    rib += "MotionEnd\nPatch \"bilinear\" \"P\" [-0.6 -0.4 0  0.6 -0.4 0  -0.6 0.4 0  0.6 0.4 0]\nAttributeEnd\n" +
           test::square(-3, 3, -2, 2, 30) + "WorldEnd\n";
    Log log;
    const Scene scene = parseRibString(rib, "test.rib", log);
    auto preview = [&](int first, int last) {
        RenderOptions o;
        o.hasFrames = true, o.firstFrame = first, o.lastFrame = last;
        test::RenderResult r;
        renderDofPreview(scene, o, 4, log, [&](const FrameImage& f) { r.frames.push_back(f); });
        return r;
    };
    const test::RenderResult shot = preview(0, 64), alone = preview(13, 13);
    ASSERT_EQ(shot.frames.size(), 65u);
    test::RenderResult thirteen;
    thirteen.frames = {shot.frame(13)};
    EXPECT_TRUE(test::identicalPixels(thirteen, alone));
    EXPECT_GT(test::alphaSum(alone, 13), 10.0);  // the wall is there (4.4 x 2.9 pixels), the leaf before it
}

}  // namespace
}  // namespace streyes
