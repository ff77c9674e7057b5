// CropWindow: only the crop's pixels are rendered and handed on, exactly the whole frame's pixels
// there (the same tiles and buckets: bit for bit, under every algorithm and with motion), with
// fewer buckets; RI Spec 3.2's rounding of the window to pixels; option("CropWindow") in shaders.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <string>

#include "streyes/renderer.h"
#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

// 64 x 48, the default 2 x 2 gaussian (its guard band reaches into the neighbouring tiles), 16-pixel
// buckets, three frames: a lit sphere, a square moving across it, a see-through square.
std::string scene(const std::string& crop) {
    return "Format 64 48 1\nProjection \"perspective\" \"fov\" 40\nPixelSamples 3 3\nShutter 0 0.5\n"
           "Option \"limits\" \"bucketsize\" [16 16]\nOption \"streyes\" \"int frames\" [0 2]\n" +
           crop +
           "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0.3 -0.4 1]\n"
           "Surface \"plastic\"\nAttributeBegin\nTranslate 0 0 6\nSphere 1.5 -1.5 1.5 360\nAttributeEnd\n"
           "AttributeBegin\nColor [1 0.3 0.1]\nMotionBegin [0 2]\nTranslate -2 0.3 4\nTranslate 1.5 0.3 4\nMotionEnd\n"
           "Polygon \"P\" [-0.4 -0.4 0  0.4 -0.4 0  0.4 0.4 0  -0.4 0.4 0]\nAttributeEnd\n"
           "AttributeBegin\nOpacity [0.4 0.4 0.4]\nColor [0.1 0.2 1]\nTranslate 0.5 -0.6 5\n"
           "Polygon \"P\" [-0.7 -0.5 0  0.7 -0.5 0  0.7 0.5 0  -0.7 0.5 0]\nAttributeEnd\nWorldEnd\n";
}

// The crop [x0, x0 + w) x [y0, y0 + h) of every frame of `full` against `crop`'s frames, bit for bit.
void expectSamePixels(const test::RenderResult& full, const test::RenderResult& crop, int x0, int y0, int w, int h,
                      const std::string& what) {
    ASSERT_EQ(crop.frames.size(), full.frames.size()) << what;
    for (size_t f = 0; f < full.frames.size(); ++f) {
        const FrameImage& a = full.frames[f];
        const FrameImage& b = crop.frames[f];
        ASSERT_EQ(b.width, w) << what;
        ASSERT_EQ(b.height, h) << what;
        EXPECT_EQ(b.frame, a.frame) << what;
        int differing = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(y + y0) * size_t(a.width) + size_t(x + x0), j = size_t(y) * size_t(w) + size_t(x);
                if (std::memcmp(&a.rgba[i * 4], &b.rgba[j * 4], 4 * sizeof(float)) != 0 ||
                    std::memcmp(&a.z[i], &b.z[j], sizeof(float)) != 0)
                    ++differing;
            }
        EXPECT_EQ(differing, 0) << what << ", frame " << a.frame;
    }
}

TEST(CropWindow, PixelsAreTheWholeFramesBitForBitWithFewerBuckets) {
    // RI Spec 3.2: columns ceil(64 * 0.3) = 20 to ceil(64 * 0.7 - 1) = 44, rows ceil(48 * 0.25) = 12
    // to ceil(48 * 0.6 - 1) = 28: 25 x 17 pixels, in tiles 1-2 across and 0-1 down: 4 of the 12.
    const std::string crop = "CropWindow 0.3 0.7 0.25 0.6\n";
    for (const Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Spacetime, Algorithm::Frames, Algorithm::Raytrace}) {
        const std::string name = algorithmName(a);
        const test::RenderResult full = test::renderRib(scene(""), test::optionsFor(a));
        const test::RenderResult part = test::renderRib(scene(crop), test::optionsFor(a));
        EXPECT_TRUE(part.warnings.empty()) << name << ": " << part.warnings.front();
        expectSamePixels(full, part, 20, 12, 25, 17, name);
        EXPECT_GT(full.stats.counters.buckets, 0u) << name;
        EXPECT_EQ(full.stats.counters.buckets, 3 * part.stats.counters.buckets) << name;
        // Something is in the crop: the sphere's lit middle.
        EXPECT_GT(part.frames[0].rgba[(size_t(10) * 25 + 12) * 4 + 3], 0.99f) << name;
    }
    // The whole frame given as a window is the whole frame.
    const test::RenderResult whole = test::renderRib(scene("CropWindow 0 1 0 1\n"));
    expectSamePixels(test::renderRib(scene("")), whole, 0, 0, 64, 48, "CropWindow 0 1 0 1");
}

// A window narrower than a pixel keeps the pixel RI Spec 3.2's rounding gives (a 1 x 1 crop at
// column ceil(64 * 0.5) = 32, row ceil(48 * 0.5) = 24).
TEST(CropWindow, ATinyWindowIsOnePixel) {
    const test::RenderResult full = test::renderRib(scene(""));
    const test::RenderResult part = test::renderRib(scene("CropWindow 0.5 0.501 0.5 0.501\n"));
    expectSamePixels(full, part, 32, 24, 1, 1, "one pixel");
    Log log;
    const ResolvedSettings s = resolveSettings(parseRibString(scene("CropWindow 0.5 0.501 0.5 0.501\n"), "crop.rib", log), {});
    EXPECT_EQ(s.cropX0, 32);
    EXPECT_EQ(s.cropX1, 33);
    EXPECT_TRUE(s.cropped());
}

// option("CropWindow") gives the window as the scene says it.
TEST(CropWindow, ShadersReadItWithOption) {
    const test::TempDir dir("crop-shaders");
    std::ofstream(dir.path() + "/probe.sl")
        << "surface probe() { float c[4] = {-1, -1, -1, -1}; option(\"CropWindow\", c); Ci = color(c[0], c[1], c[2] + c[3]); Oi = 1; }\n";
    const std::string rib = "Option \"searchpath\" \"shader\" \"" + dir.path() + ":@\"\n" +
                            "Format 8 8 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 8\nPixelFilter \"box\" 1 1\n"
                            "CropWindow 0.25 0.75 0.5 1\nWorldBegin\nSurface \"probe\"\n" + test::square(0, 8, 0, 8, 5) +
                            "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    ASSERT_EQ(r.frame(0).width, 4);
    ASSERT_EQ(r.frame(0).height, 4);
    EXPECT_EQ(r.channel(0, 1, 1, 0), 0.25f);
    EXPECT_EQ(r.channel(0, 1, 1, 1), 0.75f);
    EXPECT_EQ(r.channel(0, 1, 1, 2), 1.5f);
}

}  // namespace
}  // namespace streyes
