// Image comparison without files: resampling, pooling of frames, what counts as an error.
#include "streyes/compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "streyes/error.h"

namespace streyes {
namespace {

ImageData image(int w, int h, std::vector<std::string> channels, std::vector<float> pixels) {
    ImageData im;
    im.width = w;
    im.height = h;
    im.channels = std::move(channels);
    im.pixels = std::move(pixels);
    return im;
}

TEST(CompareImages, BilinearResampleMapsPixelCentres) {
    // Two pixels 0 and 1 become four: centres at source x = -0.25 (held), 0.25, 0.75, 1.25 (held).
    const float inf = std::numeric_limits<float>::infinity();
    ImageData src = image(2, 1, {"R", "Z"}, {0.0f, 1.0f, 1.0f, inf});
    ImageData dst = resampleImage(src, 4, 1);
    ASSERT_EQ(dst.pixels.size(), 8u);
    EXPECT_FLOAT_EQ(dst.at(0, 0, 0), 0.0f);
    EXPECT_FLOAT_EQ(dst.at(1, 0, 0), 0.25f);
    EXPECT_FLOAT_EQ(dst.at(2, 0, 0), 0.75f);
    EXPECT_FLOAT_EQ(dst.at(3, 0, 0), 1.0f);
    // Z takes the nearest sample: +inf stays +inf, no NaN from blending it.
    EXPECT_EQ(dst.at(1, 0, 1), 1.0f);
    EXPECT_EQ(dst.at(2, 0, 1), inf);
}

TEST(CompareImages, FramesPoolIntoTheWholeAnimation) {
    // Two frames with different errors: the pooled RMSE is that of all pixels together.
    ImageData a = image(2, 1, {"R", "G", "B"}, {0, 0, 0, 0, 0, 0});
    ImageData b1 = image(2, 1, {"R", "G", "B"}, {0.3f, 0, 0, 0, 0, 0});
    ImageData b2 = image(2, 1, {"B", "G", "R"}, {0, 0, 0, 0, 0.6f, 0});  // channel order differs: matched by name
    ImageErrors e1 = compareImages(a, b1, {}), e2 = compareImages(a, b2, {});
    EXPECT_NEAR(e2.rmseRGB(), std::sqrt(0.36 / 6), 1e-7);
    ImageErrors all = e1;
    all += e2;
    EXPECT_NEAR(all.rmseRGB(), std::sqrt((0.09 + 0.36) / 12), 1e-7);
    EXPECT_NEAR(all.maxAbsRGB, 0.6, 1e-7);
    EXPECT_EQ(all.pixels, 4u);
    EXPECT_EQ(all.pixelsDiffering, 2u);
    EXPECT_FALSE(all.hasAlpha);
    EXPECT_FALSE(all.zCompared);
}

TEST(CompareImages, MismatchesThrowInsteadOfMeasuring) {
    ImageData a = image(1, 1, {"R", "G", "B"}, {0, 0, 0});
    EXPECT_THROW(compareImages(a, image(1, 1, {"R", "G", "B", "A"}, {0, 0, 0, 0}), {}), InputError);
    EXPECT_THROW(compareImages(a, image(1, 2, {"R", "G", "B"}, {0, 0, 0, 0, 0, 0}), {}), InputError);
    EXPECT_THROW(compareImages(image(1, 1, {"Y"}, {0}), image(1, 1, {"Y"}, {0}), {}), InputError);  // no RGB
    CompareOptions resize;
    resize.resize = true;
    EXPECT_NO_THROW(compareImages(a, image(1, 2, {"R", "G", "B"}, {0, 0, 0, 0, 0, 0}), resize));
}

}  // namespace
}  // namespace streyes
