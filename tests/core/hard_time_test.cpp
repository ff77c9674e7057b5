// Hard cases in time (scenes/hard/time_*.rib): an instant shutter, motion crossing the frame in
// one exposure, motion keys at sampled instants, a 10,000-frame animation. Each is checked sample
// by sample against where its squares are at the sample's own time (sample_oracle.h).
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace streyes
