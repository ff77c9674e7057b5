// keysOf: the key times a transform's motion needs, less keys on a straight line.
#include "bodies/motion_segments.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace streyes {
namespace {

MotionTransform keyed(int keys, Matrix4 (*at)(int)) {
    std::vector<double> ts;
    std::vector<Matrix4> ms;
    for (int k = 0; k < keys; ++k) {
        ts.push_back(double(k));
        ms.push_back(at(k));
    }
    return MotionTransform(ts, ms);
}

TEST(MotionSegments, KeysOnAStraightLineAreOneSegment) {
    // A pan and dolly keyed every frame: 0.4 - 0.05 f is not exact in binary, so the keys are on
    // the line to rounding only.
    const MotionTransform pan = keyed(17, [](int f) { return Matrix4::translate({0.4 - 0.05 * f, 0, 0.03125 * f}); });
    EXPECT_EQ(keysOf(pan), (std::vector<double>{0, 16}));
    EXPECT_TRUE(keysOf(MotionTransform(Matrix4::translate({1, 2, 3}))).empty());
}

TEST(MotionSegments, AKeyOffTheLineIsKept) {
    // Straight to frame 8, then another direction: the bend stays a key.
    const MotionTransform bend = keyed(17, [](int f) { return Matrix4::translate({double(std::min(f, 8)), 0, double(std::max(f - 8, 0))}); });
    EXPECT_EQ(keysOf(bend), (std::vector<double>{0, 8, 16}));
    // A turn keyed every frame: no three keys on a line (matrices interpolate linearly).
    const MotionTransform turn = keyed(9, [](int f) { return Matrix4::rotate(10.0 * f, {0, 1, 0}); });
    EXPECT_EQ(keysOf(turn).size(), 9u);
    // A drift too small for neighbours to show but not for the chord: each key is checked against
    // the chord from the last key kept, not against its neighbours.
    const MotionTransform drift = keyed(41, [](int f) { return Matrix4::translate({double(f), 1e-12 * f * f, 0}); });
    const std::vector<double> k = keysOf(drift);
    ASSERT_GT(k.size(), 2u);
    EXPECT_LT(k.size(), 41u);
    for (size_t i = 1; i + 1 < k.size(); ++i) {
        // Every key dropped lies on the chord of the keys kept around it.
        const Matrix4 a = drift.at(k[i - 1]), b = drift.at(k[i]);
        for (double t = k[i - 1] + 1; t < k[i]; t += 1) {
            const Matrix4 l = lerp(a, b, (t - k[i - 1]) / (k[i] - k[i - 1]));
            EXPECT_NEAR(l(3, 1), drift.at(t)(3, 1), 2e-10) << t;
        }
    }
}

}  // namespace
}  // namespace streyes
