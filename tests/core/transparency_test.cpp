// Transparency: Oi < 1 (from Opacity or a shader) composited per sample in depth order, against the
// closed forms of "over"; alpha the composited coverage; the occlusion tables counting opaque
// coverage only (the ε = 0 identity with see-through surfaces in front); the ray tracer agreeing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "test_util.h"

namespace streyes {
namespace {

const Algorithm kAll[] = {Algorithm::Frames, Algorithm::FramesOcclusion, Algorithm::Spacetime,
                          Algorithm::SpacetimeOcclusion, Algorithm::Raytrace, Algorithm::RaytraceFrames};

// A square [x0, x1] x [y0, y1] at depth z with colour and opacity (Surface "constant": Ci = Os Cs).
std::string layer(double x0, double x1, double y0, double y1, double z, const std::string& color,
                  const std::string& opacity) {
    return "AttributeBegin\nColor [" + color + "]\nOpacity [" + opacity + "]\n" + test::square(x0, x1, y0, y1, z) +
           "AttributeEnd\n";
}

// The rgba of pixel (x, y) of frame 0.
std::array<float, 4> rgba(const test::RenderResult& r, int x, int y, int frame = 0) {
    return {r.channel(frame, x, y, 0), r.channel(frame, x, y, 1), r.channel(frame, x, y, 2), r.alpha(frame, x, y)};
}

void expectPixel(const test::RenderResult& r, int x, int y, std::array<float, 4> want, const std::string& what) {
    const std::array<float, 4> got = rgba(r, x, y);
    for (int c = 0; c < 4; ++c)
        EXPECT_LE(test::absDifference(got[size_t(c)], want[size_t(c)]), 1e-5f)
            << what << " pixel (" << x << ", " << y << ") channel " << c << ": " << got[size_t(c)] << " want "
            << want[size_t(c)];
}

// A 50% opaque red square (left half of the image, z = 5) over an opaque blue one (bottom half,
// z = 10): red over blue is (0.5, 0, 0.5) alpha 1, red over nothing (0.5, 0, 0) alpha 0.5, blue
// alone (0, 0, 1) alpha 1. The same in whichever order the RIB lists them, under every algorithm.
TEST(Transparency, HalfOpaqueRedOverBlueComposites) {
    const std::string red = layer(0, 16, 0, 32, 5, "1 0 0", "0.5 0.5 0.5");
    const std::string blue = layer(0, 32, 0, 16, 10, "0 0 1", "1 1 1");
    for (const Algorithm a : kAll) {
        const test::RenderResult front = test::renderRib(test::orthoHeader(32, 32) + red + blue + "WorldEnd\n", test::optionsFor(a));
        const test::RenderResult back = test::renderRib(test::orthoHeader(32, 32) + blue + red + "WorldEnd\n", test::optionsFor(a));
        const std::string name = algorithmName(a);
        // Raster y is down: the blue square (scene y 0..16) is the bottom half, rows 16..31.
        expectPixel(front, 4, 24, {0.5f, 0, 0.5f, 1}, name + " red over blue");
        expectPixel(front, 4, 4, {0.5f, 0, 0, 0.5f}, name + " red over nothing");
        expectPixel(front, 24, 24, {0, 0, 1, 1}, name + " blue alone");
        expectPixel(front, 24, 4, {0, 0, 0, 0}, name + " nothing");
        EXPECT_TRUE(test::identicalPixels(front, back)) << name;
        // Z is the opaque surface's; where only the see-through square is, nothing opaque: +inf.
        EXPECT_EQ(front.z(0, 4, 24), 10.0f) << name;
        EXPECT_TRUE(std::isinf(front.z(0, 4, 4))) << name;
        if (!raytraces(a)) {
            EXPECT_GT(front.stats.counters.sampleFragments, 0u) << name;
        }
    }
}

// Three layers, coloured opacity: C = C1 + (1 - O1) (C2 + (1 - O2) C3) per channel; alpha the mean
// of the composited opacity.
TEST(Transparency, LayersCompositeInDepthOrderWithColouredOpacity) {
    const std::string a = layer(0, 16, 0, 16, 3, "1 1 1", "0.5 0.25 0");    // Ci = (0.5, 0.25, 0)
    const std::string b = layer(0, 16, 0, 16, 6, "0 1 0", "0.5 0.5 0.5");   // Ci = (0, 0.5, 0)
    const std::string c = layer(0, 16, 0, 16, 9, "0.2 0.4 0.8", "1 1 1");  // opaque
    const Color o1{0.5f, 0.25f, 0}, c1{0.5f, 0.25f, 0}, o2{0.5f, 0.5f, 0.5f}, c2{0, 0.5f, 0}, c3{0.2f, 0.4f, 0.8f};
    auto over = [](float cf, float of, float cb) { return cf + (1 - of) * cb; };
    const std::array<float, 4> want = {over(c1.x, o1.x, over(c2.x, o2.x, c3.x)), over(c1.y, o1.y, over(c2.y, o2.y, c3.y)),
                                       over(c1.z, o1.z, over(c2.z, o2.z, c3.z)), 1.0f};
    // The two see-through layers alone over nothing: alpha = mean over channels of 1 - (1-O1)(1-O2).
    const float alpha = ((1 - (1 - o1.x) * (1 - o2.x)) + (1 - (1 - o1.y) * (1 - o2.y)) + (1 - (1 - o1.z) * (1 - o2.z))) / 3;
    for (const std::string& order : {a + b + c, c + b + a, b + c + a}) {
        for (const Algorithm alg : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
            const test::RenderResult r = test::renderRib(test::orthoHeader(16, 16) + order + "WorldEnd\n", test::optionsFor(alg));
            expectPixel(r, 8, 8, want, std::string(algorithmName(alg)) + " three layers");
        }
    }
    const test::RenderResult two = test::renderRib(test::orthoHeader(16, 16) + a + b + "WorldEnd\n");
    expectPixel(two, 8, 8, {over(c1.x, o1.x, c2.x), over(c1.y, o1.y, c2.y), over(c1.z, o1.z, c2.z), alpha}, "two layers");
}

// A scene where see-through squares lie in front of an opaque wall that hides a field of small
// squares: at ε = 0 occlusion culling changes no pixel, and it still culls (the see-through
// squares do not count as cover, the wall does).
std::string wallScene() {
    std::string rib = test::orthoHeader(64, 64, "PixelSamples 3 3\n");
    rib += layer(0, 40, 0, 64, 2, "1 0 0", "0.4 0.4 0.4");
    rib += layer(20, 64, 10, 50, 3, "0 1 0", "0.3 0.6 0.3");
    rib += layer(0, 64, 0, 64, 20, "0.2 0.2 0.9", "1 1 1");  // the wall
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j)
            rib += layer(i * 8 + 1, i * 8 + 7, j * 8 + 1, j * 8 + 7, 30 + i + j, "1 1 0", "1 1 1");
    // And a field of small squares between the see-through ones and the wall: seen through them.
    for (int i = 0; i < 4; ++i) rib += layer(i * 16 + 2, i * 16 + 10, 20, 30, 10, "0 1 1", "1 1 1");
    return rib + "WorldEnd\n";
}

TEST(Transparency, OcclusionCullingCountsOpaqueCoverageOnly) {
    const test::RenderResult plain = test::renderRib(wallScene(), test::optionsFor(Algorithm::Spacetime));
    RenderOptions culled = test::optionsFor(Algorithm::SpacetimeOcclusion);
    culled.tolerance = 0;
    const test::RenderResult occl = test::renderRib(wallScene(), culled);
    EXPECT_TRUE(test::identicalPixels(plain, occl));
    EXPECT_GT(occl.stats.counters.culledOcclusion + occl.stats.counters.culledHidden, 0u);
    // What lies between the see-through squares and the wall is seen through them: cyan square at
    // (4..10, raster rows 34..44) under the red layer: 0.4 red + 0.6 cyan.
    expectPixel(occl, 6, 38, {0.4f, 0.6f, 0.6f, 1}, "cyan through red");
    // The frames baseline and the ray tracer agree.
    EXPECT_TRUE(test::identicalPixels(plain, test::renderRib(wallScene(), test::optionsFor(Algorithm::Frames))));
    const test::RenderResult traced = test::renderRib(wallScene(), test::optionsFor(Algorithm::Raytrace));
    EXPECT_LE(test::maxAbsDifference(plain, traced), 1e-5f);
}

// A see-through square moving over a still one: a frame alone and inside a block of frames are
// the same picture, and spacetime equals frame-by-frame rendering.
TEST(Transparency, MovingSeeThroughSquareIsTheSameWhateverTheBlock) {
    const std::string rib = test::orthoHeader(48, 32, "PixelSamples 3 3\nShutter 0 0.5\nOption \"streyes\" \"int frames\" [0 3]\n") +
                            layer(8, 40, 4, 28, 10, "0.1 0.8 0.2", "1 1 1") +
                            "AttributeBegin\nColor [1 0 0]\nOpacity [0.5 0.5 0.5]\nMotionBegin [0 3]\nTranslate 0 0 0\n"
                            "Translate 24 0 0\nMotionEnd\n" +
                            test::square(0, 16, 8, 24, 5) + "AttributeEnd\nWorldEnd\n";
    RenderOptions block;
    block.firstFrame = 0;
    block.lastFrame = 3;
    const test::RenderResult all = test::renderRib(rib, block);
    RenderOptions alone = block;
    alone.firstFrame = alone.lastFrame = 2;
    const test::RenderResult two = test::renderRib(rib, alone);
    ASSERT_EQ(all.frames.size(), 4u);
    EXPECT_EQ(all.frame(2).rgba, two.frame(2).rgba);
    RenderOptions frames = block;
    frames.algorithm = Algorithm::Frames;
    EXPECT_TRUE(test::identicalPixels(all, test::renderRib(rib, frames)));
    // Frame 0: the red square over the green one at x 8..16 (mid-exposure it has moved 2 px).
    expectPixel(all, 12, 16, {0.5f + 0.5f * 0.1f, 0.5f * 0.8f, 0.5f * 0.2f, 1}, "red over green");
}

// A shader that cuts a surface with an opacity mask (a leaf): Oi = 0 and Ci = 0 where s < 0.5.
// The cut half covers nothing and what is behind shows through it exactly.
TEST(Transparency, AShaderOpacityMaskCutsTheSurface) {
    test::TempDir dir("mask");
    std::ofstream(dir.path() + "/mask.sl") << "surface mask() { float m = s < 0.5 ? 0 : 1; Oi = m; Ci = m * Cs; }\n";
    const std::string rib =
        test::orthoHeader(32, 32, "PixelSamples 4 4\nOption \"searchpath\" \"shader\" \"" + dir.path() + ":@\"\n") +
        "AttributeBegin\nSurface \"mask\"\nColor [1 1 1]\n" + test::square(0, 32, 0, 32, 5) + "AttributeEnd\n" +
        layer(0, 32, 0, 8, 10, "0 0 1", "1 1 1") + "WorldEnd\n";
    for (const Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        const test::RenderResult r = test::renderRib(rib, test::optionsFor(a));
        const std::string name = algorithmName(a);
        expectPixel(r, 4, 4, {0, 0, 0, 0}, name + " cut away");
        expectPixel(r, 4, 28, {0, 0, 1, 1}, name + " blue through the cut");
        expectPixel(r, 28, 4, {1, 1, 1, 1}, name + " the kept half");
        expectPixel(r, 28, 28, {1, 1, 1, 1}, name + " the kept half over blue");
    }
}

// Opacity does not darken an opaque picture's alpha any more: Opacity 0.5 over nothing gives alpha
// 0.5 and half the colour (premultiplied), and Opacity 1 is bit-identical to no Opacity at all.
TEST(Transparency, OpacityOneIsTheOpaquePath) {
    const std::string square = test::square(4, 28, 4, 28, 5);
    const test::RenderResult none = test::renderRib(test::orthoHeader(32, 32) + "Color [0.3 0.6 0.9]\n" + square + "WorldEnd\n");
    const test::RenderResult one =
        test::renderRib(test::orthoHeader(32, 32) + "Color [0.3 0.6 0.9]\nOpacity [1 1 1]\n" + square + "WorldEnd\n");
    EXPECT_TRUE(test::identicalPixels(none, one));
    EXPECT_EQ(one.stats.counters.sampleFragments, 0u);
    const test::RenderResult half =
        test::renderRib(test::orthoHeader(32, 32) + "Color [0.3 0.6 0.9]\nOpacity [0.5 0.5 0.5]\n" + square + "WorldEnd\n");
    expectPixel(half, 16, 16, {0.15f, 0.3f, 0.45f, 0.5f}, "half opaque");
    EXPECT_NEAR(test::alphaSum(half), 0.5 * 24 * 24, 1e-3);
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// scenes/transparency.rib (see-through panes, one moving, cut-out leaves, a light casting shadows,
// so that fragments take shadow rays): the rasterizer and the ray tracer agree to shading's
// interpolation (vertices against hit points), and the rasterizer made fragments.
TEST(Transparency, TheSceneAgreesWithTheRayTracer) {
    RenderOptions o;
    o.xres = 160;
    o.yres = 90;
    o.samples = 4;
    o.hasFrames = true;
    o.firstFrame = 4;
    o.lastFrame = 4;
    o.shadowsPerSample = true;  // as the ray tracer tests them: the comparison is of transparency
    const test::RenderResult raster = test::renderFile(test::sourcePath("scenes/transparency.rib"), o);
    o.algorithm = Algorithm::Raytrace;
    const test::RenderResult traced = test::renderFile(test::sourcePath("scenes/transparency.rib"), o);
    EXPECT_GT(raster.stats.counters.sampleFragments, 5000u);
    EXPECT_GT(raster.stats.counters.shadowRays, 0u);
    EXPECT_LT(test::meanAbsDifference(raster, traced), 2e-3f);
    // Off by more than 0.1 only on the leaves' cut edges (a few pixels): the rasterizer interpolates
    // the leaf shader's opacity between vertices, the ray tracer shades the hit point itself.
    const FrameImage &a = raster.frame(4), &b = traced.frame(4);
    int differing = 0, offLeaves = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            float worst = 0;
            for (int c = 0; c < 4; ++c)
                worst = std::max(worst, test::absDifference(a.rgba[(size_t(y) * size_t(a.width) + size_t(x)) * 4 + size_t(c)],
                                                            b.rgba[(size_t(y) * size_t(b.width) + size_t(x)) * 4 + size_t(c)]));
            if (!(worst <= 0.1f)) {
                ++differing;
                offLeaves += !(x >= 76 && x <= 106 && y >= 18 && y <= 38);
            }
        }
    EXPECT_LE(differing, 40);
    EXPECT_EQ(offLeaves, 0);
}

}  // namespace
}  // namespace streyes
