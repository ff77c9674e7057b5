#include "film/film.h"

#include <gtest/gtest.h>

namespace streyes {
namespace {

TEST(PixelFilter, ShapesAndSupport) {
    PixelFilter box({"box", 1, 1}), gauss({"gaussian", 2, 2}), cr({"catmull-rom", 4, 4});
    EXPECT_EQ(box.weight(0.49f, -0.49f), 1.0f);
    EXPECT_EQ(box.weight(0.51f, 0), 0.0f);
    EXPECT_EQ(box.guardX(), 0);
    EXPECT_NEAR(gauss.weight(0, 0), 1.0f, 1e-3f);
    EXPECT_NEAR(gauss.weight(0.5f, 0), std::exp(-2.0f * 0.25f), 1e-2f);
    EXPECT_EQ(gauss.weight(1.01f, 0), 0.0f);
    EXPECT_EQ(gauss.guardX(), 1);
    EXPECT_EQ(cr.guardX(), 2);
    EXPECT_LT(cr.weight(1.5f, 0), 0.0f);  // the negative lobe
    // The support is half-open, like a pixel: -r is inside, +r outside.
    EXPECT_EQ(box.weight(-0.5f, -0.5f), 1.0f);
    EXPECT_EQ(box.weight(0.5f, 0), 0.0f);
    EXPECT_GT(gauss.weight(-1.0f, 0), 0.1f);
    EXPECT_EQ(gauss.weight(1.0f, 0), 0.0f);
}

// A sample exactly on a pixel's top-left corner belongs to that pixel: with a box filter of
// one pixel, no pixel is left without samples (it would resolve to black).
TEST(Resolve, SamplesOnPixelCornersBelongToTheirPixel) {
    ImageBlock block;
    block.reset({0, 0, 7, 7}, 0, 1, SamplePattern{1, 1, 0});
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const size_t i = block.sliceIndex(0, 0, x, y);
            block.positions()[i].x = float(x);
            block.positions()[i].y = float(y);
            block.hits()[i] = {2.0f, {0.5f, 0.5f, 0.5f}, 1.0f, 1};
        }
    PixelFilter box({"box", 1, 1});
    FrameImage img;
    img.resize(8, 8);
    std::vector<float> scratch;
    resolveTile(block, {0, 0, 7, 7}, box, &img, scratch);
    for (int p = 0; p < 64; ++p) {
        EXPECT_EQ(img.rgba[size_t(p) * 4 + 3], 1.0f) << p;
        EXPECT_EQ(img.rgba[size_t(p) * 4], 0.5f) << p;
    }
}

TEST(Resolve, UniformSamplesGiveTheirValueAndZIsTheNearest) {
    ImageBlock block;
    block.reset({0, 0, 9, 9}, 0, 1, SamplePattern{3, 3, 5});
    for (int k = 0; k < 9; ++k)
        for (int y = 0; y < 10; ++y)
            for (int x = 0; x < 10; ++x) {
                SampleHit& s = block.hits()[block.sliceIndex(0, k, x, y)];
                s.c = {0.25f, 0.5f, 0.75f};
                s.a = 1;
                s.z = 3.0f + float(k);
            }
    for (const char* type : {"box", "gaussian", "catmull-rom"}) {
        PixelFilter filter({type, 3, 3});
        FrameImage img;
        img.resize(10, 10);
        std::vector<float> scratch;
        resolveTile(block, {2, 2, 7, 7}, filter, &img, scratch);
        float* p = &img.rgba[(5 * 10 + 5) * 4];
        EXPECT_NEAR(p[0], 0.25f, 1e-5f) << type;
        EXPECT_NEAR(p[1], 0.5f, 1e-5f) << type;
        EXPECT_NEAR(p[3], 1.0f, 1e-5f) << type;
        EXPECT_EQ(img.z[5 * 10 + 5], 3.0f);
        EXPECT_EQ(img.rgba[0], 0.0f);  // outside the tile: untouched
    }
}

}  // namespace
}  // namespace streyes
