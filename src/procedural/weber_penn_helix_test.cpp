// Helical stems (the paper's nCurveV < 0): each segment of the stem is one turn of a helix whose
// tangent leans |nCurveV| from the segment, so its radius is tan|nCurveV| segment / (2 pi). The
// trunk's patch mesh is a cubic B-spline along its control rings; its curve through the rings'
// centres, at each ring, must lie on that helix.
#include <gtest/gtest.h>

#include <cmath>

#include "procedural/weber_penn.h"

namespace streyes {
namespace {

ProceduralOutput expandTrunk(const std::string& datablock) {
    ProceduralOutput out;
    ExpandContext ctx;
    ctx.detail = 1e12;
    makeWeberPennGenerator(datablock, {})->expand(ctx, out);
    return out;
}

std::vector<Vec3d> ringCentres(const PatchMeshDesc& m) {
    std::vector<Vec3d> c(size_t(m.nv), Vec3d{0, 0, 0});
    for (int v = 0; v < m.nv; ++v) {
        for (int u = 0; u < m.nu; ++u) c[size_t(v)] = c[size_t(v)] + m.P[0][size_t(v * m.nu + u)];
        c[size_t(v)] = c[size_t(v)] * (1.0 / m.nu);
    }
    return c;
}

const char* kTrunk = "model=weberpenn Levels=1 Leaves=0 Scale=10 ScaleV=0 0Length=1 0LengthV=0 0CurveRes=4 0Curve=0 "
                     "Flare=0 Lobes=0 Ratio=0.02 ";

TEST(WeberPennHelix, EachSegmentIsOneTurnOfTheHelixOfItsAngle) {
    for (double angle : {20.0, 45.0}) {
        SCOPED_TRACE("nCurveV -" + std::to_string(angle));
        const ProceduralOutput out = expandTrunk(std::string(kTrunk) + "0CurveV=-" + std::to_string(angle));
        ASSERT_EQ(out.scene.patchMeshes.size(), 1u);
        const std::vector<Vec3d> c = ringCentres(out.scene.patchMeshes[0]);
        // A straight trunk up y: 10 long, 4 segments of 2.5; the helix turns about a line parallel
        // to the trunk, at its radius from it.
        const double L = 2.5, R = std::tan(angle * M_PI / 180) * L / (2 * M_PI);
        // The rings: the first twice (the spline's end), the 4 * 10 + 1 points and rings of the
        // helix, the last twice.
        ASSERT_EQ(c.size(), size_t(4 * 10 + 1 + 2));
        // The helix's axis: the trunk's, moved by -R along its first ring's x (the helix starts on
        // the trunk's axis: offset (cos 0 - 1, sin 0) R).
        const Vec3d foot = c[1];
        EXPECT_NEAR(foot.x, 0, 1e-12);
        EXPECT_NEAR(foot.z, 0, 1e-12);
        // The spline passes inside its control points' circle, as a ring's does; the control points
        // sit on a circle of R 6 / (4 + 2 cos 36 deg) about the helix's axis, so that the spline's
        // own circle has radius R.
        const double controlR = R * 6 / (4 + 2 * std::cos(2 * M_PI / 10));
        for (int segment = 0; segment < 4; ++segment) {
            auto splineAt = [&](int j) {  // ring j of the helix's, j = 0 .. 40 (c[j + 1])
                const size_t k = size_t(j + 1);
                return (c[k - 1] + c[k] * 4 + c[k + 1]) * (1.0 / 6);
            };
            // Half a turn in: the far side, across the axis from where the turn starts (on the
            // trunk's axis): controlR + R from the trunk's axis.
            const Vec3d half = splineAt(segment * 10 + 5);
            const double across = std::hypot(half.x, half.z);
            EXPECT_NEAR(across, controlR + R, 1e-9);
            const Vec3d axis{half.x * controlR / across, 0, half.z * controlR / across};
            for (int j = segment * 10 + 1; j < segment * 10 + 10; ++j) {
                const Vec3d q = splineAt(j);
                EXPECT_NEAR(q.y, L * j / 10, 1e-9) << "ring " << j;  // climbing evenly
                EXPECT_NEAR(std::hypot(q.x - axis.x, q.z - axis.z), R, 1e-9) << "ring " << j;
            }
        }
    }
}

TEST(WeberPennHelix, ANegativeCurveVDrawsNoRandomBend) {
    // nCurveV > 0 bends each segment by a random +-nCurveV / nCurveRes; negative, the axis stays
    // straight (the helix is drawn about it).
    WeberPennParams p = parseWeberPennParams(std::string(kTrunk) + "0CurveV=-30", {});
    const WeberPennStem trunk = weberPennTrunk(p, nullptr);
    for (const Vec3d& q : trunk.paths[0].points) {
        EXPECT_NEAR(q.x, 0, 1e-12);
        EXPECT_NEAR(q.z, 0, 1e-12);
    }
    p = parseWeberPennParams(std::string(kTrunk) + "0CurveV=30", {});
    double off = 0;
    const WeberPennStem bent = weberPennTrunk(p, nullptr);  // named: a loop over a temporary's member would dangle
    for (const Vec3d& q : bent.paths[0].points) off = std::max(off, std::hypot(q.x, q.z));
    EXPECT_GT(off, 0.01) << "the positive nCurveV must bend the trunk (the test's own check)";
}

}  // namespace
}  // namespace streyes
