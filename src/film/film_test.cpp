#include "film/film.h"

#include <gtest/gtest.h>

#include <cmath>

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

// The RenderMan Interface's filters against their formulas (tables of 256 bins a radius: within
// the change of the function over half a bin).
TEST(PixelFilter, EveryFilterFollowsItsFormula) {
    const double pi = 3.14159265358979323846;
    PixelFilter tri({"triangle", 2, 4}), sinc({"sinc", 4, 4}), mitchell({"mitchell", 4, 4}), disk({"disk", 2, 3});
    for (float x : {0.0f, 0.3f, -0.7f, 0.95f}) EXPECT_NEAR(tri.weight(x, 0.5f), (1 - std::fabs(x)) * 0.75f, 5e-3f) << x;
    EXPECT_EQ(tri.weight(1.0f, 0), 0.0f);
    for (float x : {0.5f, 1.0f, 1.5f, -1.9f}) {  // RiSincFilter: sin(pi x) / (pi x), windowed by cos(pi x / (2 width))
        const double px = pi * x, want = std::cos(0.5 * px / 4.0) * std::sin(px) / px;
        EXPECT_NEAR(sinc.weight(x, 0), want, 1e-2) << x;
    }
    EXPECT_NEAR(sinc.weight(0, 0), 1.0f, 1e-3f);
    EXPECT_LT(sinc.weight(1.5f, 0), 0.0f);  // a negative lobe
    // Mitchell-Netravali with B = C = 1/3 over [-2, 2] at radius 2: its values at 0, 1 and 2.
    EXPECT_NEAR(mitchell.weightX(0), 16.0f / 18.0f, 1e-2f);
    EXPECT_NEAR(mitchell.weightX(1.0f), 1.0f / 18.0f, 1e-2f);
    EXPECT_NEAR(mitchell.weight(1.0f, 0), mitchell.weightX(1.0f) * mitchell.weightY(0), 1e-6f);  // separable
    EXPECT_EQ(mitchell.weight(2.0f, 0), 0.0f);
    // The disk: 1 inside the ellipse of radii 1 and 1.5, 0 outside, not a product of two axes.
    EXPECT_EQ(disk.weight(0.69f, 1.05f), 1.0f);  // (0.69)^2 + (0.7)^2 < 1
    EXPECT_EQ(disk.weight(0.72f, 1.08f), 0.0f);  // (0.72)^2 + (0.72)^2 > 1
    EXPECT_EQ(disk.weight(0.99f, 0), 1.0f);
    EXPECT_EQ(disk.weight(0, 1.49f), 1.0f);
    EXPECT_EQ(disk.guardX(), 1);
    EXPECT_EQ(disk.guardY(), 1);
}

// Blackman-Harris (Blender's and Cycles' default filter) over the whole width: 1 at the centre,
// a0 - a2 = 0.21747 halfway out, a0 - a1 + a2 - a3 = 6e-5 at the edge, separable; the Cycles
// film's "filter width" w is this filter's radius (Cycles doubles it), so Blender's 1.5 px is
// PixelFilter "blackman-harris" 3 3, which reaches one pixel on each side.
TEST(PixelFilter, BlackmanHarrisFollowsItsFormula) {
    const double pi = 3.14159265358979323846;
    const auto bh = [&](double x, double r) {
        const double a = pi * (x / r + 1);
        return 0.35875 - 0.48829 * std::cos(a) + 0.14128 * std::cos(2 * a) - 0.01168 * std::cos(3 * a);
    };
    const PixelFilter f({"blackman-harris", 3, 4});  // radii 1.5 and 2
    EXPECT_NEAR(f.weight(0, 0), 1.0f, 1e-3f);
    EXPECT_NEAR(f.weightX(0.75f), 0.21747f, 5e-3f);
    EXPECT_NEAR(f.weightY(-1.0f), 0.21747f, 5e-3f);
    EXPECT_NEAR(f.weightX(1.499f), 6e-5f, 1e-3f);
    for (float x : {0.1f, -0.4f, 0.6f, 1.2f, -1.45f}) EXPECT_NEAR(f.weightX(x), bh(x, 1.5), 5e-3) << x;
    for (float y : {0.3f, -1.1f, 1.8f}) EXPECT_NEAR(f.weightY(y), bh(y, 2.0), 5e-3) << y;
    EXPECT_NEAR(f.weight(0.6f, -1.1f), f.weightX(0.6f) * f.weightY(-1.1f), 1e-6f);  // separable
    EXPECT_EQ(f.weight(1.5f, 0), 0.0f);
    EXPECT_EQ(f.weight(0, 2.0f), 0.0f);
    EXPECT_GT(f.weight(-1.49f, 0), 0.0f);
    EXPECT_EQ(f.guardX(), 1);
    EXPECT_EQ(f.guardY(), 2);
    // Decreasing from the centre: a window, with no negative lobe.
    float last = 2;
    for (int i = 0; i <= 30; ++i) {
        const float w = f.weightX(1.5f * float(i) / 31);
        EXPECT_LE(w, last) << i;
        EXPECT_GE(w, 0.0f) << i;
        last = w;
    }
}

// Resolves `tile` of every frame of the block into images of width x height (zero outside it).
void resolveInto(const ImageBlock& block, const PixelRect& tile, const FilterWeights& weights, FrameImage* images,
                 int width, int height) {
    TiledFrames frames;
    frames.reset(width, height, {tile}, block.firstFrame(), block.frameCount(), {});
    ResolveScratch scratch;
    resolveTile(block, weights, frames, 0, scratch);
    for (int fi = 0; fi < block.frameCount(); ++fi) {
        FrameImage& img = images[fi];
        img.resize(width, height);
        const float* p = frames.tile(0).pixels(fi);
        ASSERT_NE(p, nullptr);
        for (int y = tile.y0; y <= tile.y1; ++y)
            for (int x = tile.x0; x <= tile.x1; ++x, p += 5) {
                const size_t i = size_t(y) * size_t(width) + size_t(x);
                std::copy(p, p + 4, &img.rgba[i * 4]);
                img.z[i] = p[4];
            }
    }
}

// A sample exactly on a pixel's top-left corner belongs to that pixel: with a box filter of
// one pixel, no pixel is left without samples (it would resolve to black).
TEST(Resolve, SamplesOnPixelCornersBelongToTheirPixel) {
    const PatternTable patterns(SamplePattern{1, 1, 0}, {{0.0f}}, {0.0f, 0.0f});
    ImageBlock block;
    block.reset({0, 0, 7, 7}, 0, 1, patterns, false);
    for (size_t i = 0; i < 64; ++i) block.still(i)[0] = {2.0f, {0.5f, 0.5f, 0.5f}, 1};
    const PixelFilter box({"box", 1, 1});
    const FilterWeights weights(box, patterns);
    FrameImage img;
    resolveInto(block, {0, 0, 7, 7}, weights, &img, 8, 8);
    for (int p = 0; p < 64; ++p) {
        EXPECT_EQ(img.rgba[size_t(p) * 4 + 3], 1.0f) << p;
        EXPECT_EQ(img.rgba[size_t(p) * 4], 0.5f) << p;
    }
}

// Uniform samples resolve to their value whatever the filter, from the still layer as from a
// dense block's records; Z is the pixel's nearest sample.
TEST(Resolve, UniformSamplesGiveTheirValueAndZIsTheNearest) {
    const PatternTable patterns(SamplePattern{3, 3, 5});
    for (bool dense : {false, true}) {
        ImageBlock block;
        block.reset({0, 0, 9, 9}, 0, 1, patterns, dense);
        for (size_t i = 0; i < 100; ++i) {
            SampleHit* h = dense ? block.record(0, i) : block.still(i);
            for (int k = 0; k < 9; ++k) h[k] = {3.0f + float(k), {0.25f, 0.5f, 0.75f}, 1};
        }
        for (const char* type : {"box", "triangle", "gaussian", "catmull-rom", "sinc", "mitchell", "blackman-harris", "disk"}) {
            const PixelFilter filter({type, 3, 3});
            const FilterWeights weights(filter, patterns);
            FrameImage img;
            resolveInto(block, {2, 2, 7, 7}, weights, &img, 10, 10);
            float* p = &img.rgba[(5 * 10 + 5) * 4];
            EXPECT_NEAR(p[0], 0.25f, 1e-5f) << type;
            EXPECT_NEAR(p[1], 0.5f, 1e-5f) << type;
            EXPECT_NEAR(p[3], 1.0f, 1e-5f) << type;
            EXPECT_EQ(img.z[5 * 10 + 5], 3.0f);
            EXPECT_EQ(img.rgba[0], 0.0f);  // outside the tile: untouched
        }
    }
}

// A frame's record changes the pixels whose filter reaches it, in that frame only; the others
// show the still layer, bit for bit as the record-free frames do.
TEST(Resolve, AFramesRecordChangesOnlyThePixelsItsFilterReaches) {
    const PatternTable patterns(SamplePattern{2, 2, 1});
    ImageBlock block;
    block.reset({0, 0, 9, 9}, 0, 2, patterns, false);
    for (size_t i = 0; i < 100; ++i)
        for (int k = 0; k < 4; ++k) block.still(i)[k] = {5.0f, {0.2f, 0.4f, 0.6f}, 1};
    SampleHit* r = block.makeRecord(1, block.pixelIndex(5, 5));
    for (int k = 0; k < 4; ++k) r[k] = {2.0f, {1, 0, 0}, 2};
    const PixelFilter gauss({"gaussian", 2, 2});  // reaches one pixel on each side
    const FilterWeights weights(gauss, patterns);
    FrameImage img[2];
    resolveInto(block, {1, 1, 8, 8}, weights, img, 10, 10);
    for (int y = 1; y <= 8; ++y)
        for (int x = 1; x <= 8; ++x) {
            const size_t p = size_t(y * 10 + x) * 4;
            const bool reached = std::abs(x - 5) <= 1 && std::abs(y - 5) <= 1;
            EXPECT_EQ(img[1].rgba[p] != img[0].rgba[p], reached) << x << "," << y;
        }
    EXPECT_EQ(img[1].z[55], 2.0f);
    EXPECT_EQ(img[0].z[55], 5.0f);
    EXPECT_NEAR(img[0].rgba[(3 * 10 + 3) * 4 + 1], 0.4f, 1e-6f);
}

}  // namespace
}  // namespace streyes
