// Hard cases in time (scenes/hard/time_*.rib): an instant shutter, motion crossing the frame in
// one exposure, motion keys at sampled instants, a 10,000-frame animation. Each is checked sample
// by sample against where its squares are at the sample's own time (sample_oracle.h).
#include <gtest/gtest.h>

#include <cmath>

#include "sample_oracle.h"
#include "streyes/rib.h"

namespace streyes {
namespace {

using test::OracleReport;
using test::RenderResult;

using Checked = test::CheckedCase;

Checked checkScene(const std::string& name) { return test::checkHardCase(name); }

TEST(Time, ShutterOpenEqualsCloseSamplesOneInstant) {
    Checked c = checkScene("time_instant.rib");
    ASSERT_EQ(c.render.frames.size(), 4u);
    EXPECT_GT(c.oracle.pixelsCovered, 4 * 6);
    // No blur: pixels are covered all or nothing, except where the square's edges cut them.
    EXPECT_EQ(c.render.alpha(1, 4, 3), 1.0f);   // x in [2.75, 6.75] at t = 1.25
    EXPECT_EQ(c.render.alpha(4, 11, 3), 1.0f);  // x in [10.25, 14.25] at t = 4.25
    EXPECT_EQ(c.render.stats.counters.splitsT, 0u);
}

TEST(Time, BodyCrossingTheWholeFrameInOneExposure) {
    Checked c = checkScene("time_fast.rib");
    const RenderCounters& n = c.render.stats.counters;
    EXPECT_EQ(n.splitsT, 0u);  // diced once for its exposure; its micropolygons move across the frame
    EXPECT_EQ(n.culledSplitLimit, 0u);
    EXPECT_GT(c.oracle.samplesCovered, 500u);
    // A point is covered while 4 of the 80 pixels of travel pass over it: alpha ~ 0.05 (64 samples).
    for (int x = 2; x < 62; x += 6) EXPECT_NEAR(c.render.alpha(0, x, 4), 0.05, 0.04) << x;
}

TEST(Time, KeysAtSampledInstantsAndBodiesForPartOfTheAnimation) {
    Checked c = checkScene("time_keys.rib");
    ASSERT_EQ(c.render.frames.size(), 7u);
    // Each square is one body with several keys (KeyedPatchBody), cut at each frame's exposure
    // (an instant here: no blur) before the split loop, so no time split is needed.
    EXPECT_EQ(c.render.stats.counters.rootBodies, 2u);
    EXPECT_EQ(c.render.stats.counters.splitsT, 0u);
}

TEST(Time, KeysInsideExposures) {
    Checked c = checkScene("time_keys_blur.rib");
    ASSERT_EQ(c.render.frames.size(), 7u);
}

TEST(Time, TenThousandFrames) {
    Checked c = checkScene("time_10000.rib");
    ASSERT_EQ(c.render.frames.size(), 10001u);
    EXPECT_GT(c.oracle.pixelsCovered, 10000);
}


// A curved surface under a camera that moves, with a closed shutter, in the frame at the camera's
// last key: the root cut to that frame is one instant, a moving grid of no time, whose colours
// were 0 / 0 (NaN) before. Every pixel of the disk is its colour, in every algorithm.
TEST(Time, CurvedSurfaceAtTheLastKeyOfAMovingCamera) {
    const std::string rib = "Format 32 32 1\nProjection \"perspective\" \"fov\" 90\nPixelFilter \"box\" 1 1\n"
                            "Option \"streyes\" \"int frames\" [0 4]\n"
                            "MotionBegin [0 4]\nTranslate 0 0 2\nTranslate 0 0 3\nMotionEnd\n"
                            "WorldBegin\nSurface \"constant\"\nColor 0 1 0\nDisk 0 1 360\nWorldEnd\n";
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Frames}) {
        RenderOptions o;
        o.algorithm = a;
        const RenderResult r = test::renderRib(rib, o);
        ASSERT_EQ(r.frames.size(), 5u);
        for (int f = 0; f <= 4; ++f) {
            double green = 0;
            for (int y = 0; y < 32; ++y)
                for (int x = 0; x < 32; ++x) {
                    ASSERT_FALSE(std::isnan(r.channel(f, x, y, 1))) << algorithmName(a) << " frame " << f;
                    green += r.channel(f, x, y, 1);
                }
            // The disk of radius 1 at depth 2 + f / 4 spans 16 / depth pixels: pi (16 / depth)^2.
            const double depth = 2 + 0.25 * f, area = 3.14159265358979 * std::pow(16 / depth, 2);
            EXPECT_NEAR(green, area, 0.03 * area) << algorithmName(a) << " frame " << f;
        }
    }
}

}  // namespace
}  // namespace streyes
