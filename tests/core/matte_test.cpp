// Matte 1 (a holdout, RI Spec 3.2 section 4.1.4): the surface hides what is behind it and adds
// neither colour nor alpha. Pixel values against the closed forms under every algorithm, behind a
// see-through surface, occlusion culling at ε = 0 unchanged (a matte still occludes), and the
// Shading Language's attribute("Matte").
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "test_util.h"

namespace streyes {
namespace {

const Algorithm kAll[] = {Algorithm::Frames, Algorithm::FramesOcclusion, Algorithm::Spacetime,
                          Algorithm::SpacetimeOcclusion, Algorithm::Raytrace, Algorithm::RaytraceFrames};

// A square [x0, x1] x [y0, y1] at depth z, Surface "constant" of that colour and opacity.
std::string layer(double x0, double x1, double y0, double y1, double z, const std::string& color,
                  const std::string& opacity = "1 1 1", bool matte = false) {
    return "AttributeBegin\nColor [" + color + "]\nOpacity [" + opacity + "]\n" + (matte ? "Matte 1\n" : "Matte 0\n") +
           test::square(x0, x1, y0, y1, z) + "AttributeEnd\n";
}

void expectPixel(const test::RenderResult& r, int x, int y, std::array<float, 4> want, const std::string& what) {
    const std::array<float, 4> got = {r.channel(0, x, y, 0), r.channel(0, x, y, 1), r.channel(0, x, y, 2), r.alpha(0, x, y)};
    for (int c = 0; c < 4; ++c)
        EXPECT_LE(test::absDifference(got[size_t(c)], want[size_t(c)]), 1e-5f)
            << what << " pixel (" << x << ", " << y << ") channel " << c << ": " << got[size_t(c)] << " want "
            << want[size_t(c)];
}

// A red matte square (pixels 8..24, z = 5) in front of a green one covering the frame (z = 10):
// the matte's 16 x 16 pixels are colour 0, alpha 0; every other pixel green, alpha 1. The sums
// over the frame are the closed forms: alpha 32² − 16², green the same, red and blue 0.
TEST(Matte, HolesOfExactlyItsArea) {
    const std::string rib = test::orthoHeader(32, 32, "PixelSamples 3 3\n") + layer(0, 32, 0, 32, 10, "0 1 0") +
                            layer(8, 24, 8, 24, 5, "1 0 0", "1 1 1", true) + "WorldEnd\n";
    for (const Algorithm a : kAll) {
        const test::RenderResult r = test::renderRib(rib, test::optionsFor(a));
        const std::string name = algorithmName(a);
        EXPECT_TRUE(r.warnings.empty()) << name << ": " << r.warnings.front();
        double alpha = 0, red = 0, green = 0, blue = 0;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                alpha += r.alpha(0, x, y), red += r.channel(0, x, y, 0);
                green += r.channel(0, x, y, 1), blue += r.channel(0, x, y, 2);
            }
        EXPECT_EQ(alpha, 32 * 32 - 16 * 16) << name;
        EXPECT_EQ(green, 32 * 32 - 16 * 16) << name;
        EXPECT_EQ(red, 0) << name;
        EXPECT_EQ(blue, 0) << name;
        expectPixel(r, 16, 16, {0, 0, 0, 0}, name + " inside the matte");
        expectPixel(r, 8, 8, {0, 0, 0, 0}, name + " the matte's corner pixel");
        expectPixel(r, 7, 16, {0, 1, 0, 1}, name + " beside the matte");
        // The matte is a surface: Z is its depth where it hides the green square.
        EXPECT_EQ(r.z(0, 16, 16), 5.0f) << name;
    }
}

// Behind a 50% red square (left half, z = 3), a matte (x 8..24, z = 5) cuts the green wall (z = 10):
// red over the matte is (0.5, 0, 0) alpha 0.5, red over green (0.5, 0.5, 0) alpha 1, the matte
// alone 0; a matte in front of the see-through square hides it.
TEST(Matte, CutsWhatLiesBehindASeeThroughSurface) {
    const std::string rib = test::orthoHeader(32, 32) + layer(0, 32, 0, 32, 10, "0 1 0") +
                            layer(0, 16, 0, 32, 3, "1 0 0", "0.5 0.5 0.5") +
                            layer(8, 24, 0, 16, 5, "0 0 1", "1 1 1", true) +  // behind the red one
                            layer(0, 4, 16, 32, 1, "0 0 1", "0.25 0.25 0.25", true) +  // in front: opaque all the same
                            "WorldEnd\n";
    for (const Algorithm a : kAll) {
        const test::RenderResult r = test::renderRib(rib, test::optionsFor(a));
        const std::string name = algorithmName(a);
        // Raster y is down: scene y 0..16 is rows 16..31.
        expectPixel(r, 12, 24, {0.5f, 0, 0, 0.5f}, name + " red over the matte");
        expectPixel(r, 4, 24, {0.5f, 0.5f, 0, 1}, name + " red over green");
        expectPixel(r, 20, 24, {0, 0, 0, 0}, name + " the matte alone");
        expectPixel(r, 20, 4, {0, 1, 0, 1}, name + " green alone");
        expectPixel(r, 2, 4, {0, 0, 0, 0}, name + " a matte in front of the see-through square");
    }
}

// A matte wall hides a field of squares: at ε = 0 occlusion culling changes no pixel and still
// culls (the matte counts as cover), and nothing of the field shows through.
TEST(Matte, OcclusionCullingStaysExactAndAMatteOccludes) {
    std::string rib = test::orthoHeader(64, 64, "PixelSamples 3 3\n");
    rib += layer(0, 40, 0, 64, 2, "1 0 0", "0.4 0.4 0.4");
    rib += layer(0, 64, 0, 48, 20, "0.2 0.2 0.9", "1 1 1", true);  // the matte wall
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) rib += layer(i * 8 + 1, i * 8 + 7, j * 8 + 1, j * 8 + 7, 30 + i + j, "1 1 0");
    rib += "WorldEnd\n";
    const test::RenderResult plain = test::renderRib(rib, test::optionsFor(Algorithm::Spacetime));
    RenderOptions culled = test::optionsFor(Algorithm::SpacetimeOcclusion);
    culled.tolerance = 0;
    const test::RenderResult occl = test::renderRib(rib, culled);
    EXPECT_TRUE(test::identicalPixels(plain, occl));
    EXPECT_GT(occl.stats.counters.culledOcclusion + occl.stats.counters.culledHidden, 0u);
    expectPixel(occl, 44, 36, {0, 0, 0, 0}, "the matte over a yellow square");
    expectPixel(occl, 20, 36, {0.4f, 0, 0, 0.4f}, "red over the matte");
    expectPixel(occl, 44, 4, {1, 1, 0, 1}, "a yellow square above the wall");
    EXPECT_TRUE(test::identicalPixels(plain, test::renderRib(rib, test::optionsFor(Algorithm::Frames))));
    EXPECT_LE(test::maxAbsDifference(plain, test::renderRib(rib, test::optionsFor(Algorithm::Raytrace))), 1e-5f);
}

// attribute("Matte") reports the primitive's Matte: written to an output variable (resolved over
// the opaque hits, a matte's included), 1 under the matte square and 0 under the other.
TEST(Matte, ShadersReadItWithAttribute) {
    const test::TempDir dir("matte-shaders");
    std::ofstream(dir.path() + "/probe.sl")
        << "surface probe(output varying float m = -1) { float v = -2; attribute(\"Matte\", v); m = v; Ci = 1; Oi = 1; }\n";
    const std::string rib = "Option \"searchpath\" \"shader\" \"" + dir.path() + ":@\"\n" +
                            "Format 8 4 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 4\nPixelFilter \"box\" 1 1\n"
                            "Display \"out.exr\" \"openexr\" \"rgba\"\nDisplay \"+m.exr\" \"openexr\" \"float m\"\n"
                            "WorldBegin\nSurface \"probe\"\n" +
                            layer(0, 4, 0, 4, 5, "1 1 1", "1 1 1", true) + layer(4, 8, 0, 4, 5, "1 1 1") + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    const FrameImage& f = r.frame(0);
    ASSERT_EQ(f.aovNames, std::vector<std::string>{"m"});
    for (int x = 0; x < 8; ++x) {
        SCOPED_TRACE(x);
        EXPECT_EQ(f.aov[size_t(2 * 8 + x)], x < 4 ? 1.0f : 0.0f);
        EXPECT_EQ(r.alpha(0, x, 2), x < 4 ? 0.0f : 1.0f);
    }
}

}  // namespace
}  // namespace streyes
