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

}  // namespace
}  // namespace streyes
