// The paper's leaf bending (LeafBend): leaves worked through by hand, and a whole tree whose leaves
// face further up and out with it while they stay where they grow.
#include <gtest/gtest.h>

#include <cmath>

#include "procedural/weber_penn.h"

namespace streyes {
namespace {

void expectNear(Vec3d a, Vec3d b) {
    EXPECT_NEAR(a.x, b.x, 1e-12);
    EXPECT_NEAR(a.y, b.y, 1e-12);
    EXPECT_NEAR(a.z, b.z, 1e-12);
}

// A leaf at azimuth 90 degrees about the trunk (position (0, 5, 2)), facing along +x (azimuth 0),
// its blade straight up.
WeberPennLeaf sideways() {
    WeberPennLeaf l;
    l.position = {0, 5, 2};
    l.normal = {1, 0, 0};
    l.direction = {0, 1, 0};
    return l;
}

TEST(WeberPennLeafBend, TurnsOutThenUpByHand) {
    // LeafBend 1: theta_bend = 90 - 0 degrees turns the face to (0, 0, 1), the blade stays up; the
    // leaf's x axis is then direction x normal = (1, 0, 0), phi_bend = 90 degrees, and turning about it
    // towards up brings the face to (0, 1, 0) and the blade to (0, 0, -1).
    WeberPennLeaf l = sideways();
    weberPennBendLeaf(1, &l);
    expectNear(l.normal, {0, 1, 0});
    expectNear(l.direction, {0, 0, -1});
    expectNear(l.position, {0, 5, 2});
    // LeafBend 0.5: 45 degrees about the vertical, face (h, 0, h), h = sqrt(1/2); x axis (h, 0, -h);
    // 45 degrees towards up: face (1/2, h, 1/2), blade (-1/2, h, -1/2).
    const double h = std::sqrt(0.5);
    l = sideways();
    weberPennBendLeaf(0.5, &l);
    expectNear(l.normal, {0.5, h, 0.5});
    expectNear(l.direction, {-0.5, h, -0.5});
    // Bending 0 leaves the leaf as it was.
    l = sideways();
    weberPennBendLeaf(0, &l);
    expectNear(l.normal, {1, 0, 0});
    expectNear(l.direction, {0, 1, 0});
}

TEST(WeberPennLeafBend, ATreesLeavesFaceUpAndOutWhereTheyGrew) {
    WeberPennParams p = *weberPennPreset("quaking_aspen");
    const WeberPennTree flat = growWeberPenn(p);
    p.leafBend = 1;
    const WeberPennTree bent = growWeberPenn(p);
    ASSERT_EQ(flat.leaves.size(), bent.leaves.size());
    ASSERT_GT(flat.leaves.size(), 100u);
    double upFlat = 0, upBent = 0;
    for (size_t i = 0; i < flat.leaves.size(); ++i) {
        const WeberPennLeaf &a = flat.leaves[i], &b = bent.leaves[i];
        EXPECT_EQ(a.position.x, b.position.x);  // the same place: bending draws nothing
        EXPECT_EQ(a.position.y, b.position.y);
        EXPECT_NEAR(length(b.normal), 1, 1e-12);
        EXPECT_NEAR(dot(b.normal, b.direction), 0, 1e-12);
        upFlat += std::fabs(a.normal.y);
        upBent += b.normal.y;
    }
    // Turning about the leaf's own x axis brings the face up only as far as that axis allows, leaf by
    // leaf; over the crown the bent leaves face up more than the unbent ones, either side up.
    EXPECT_GT(upBent, upFlat + 0.1 * double(bent.leaves.size()));
    EXPECT_EQ(parseWeberPennParams("model=weberpenn LeafBend=0.6", {}).leafBend, 0.6);
    EXPECT_THROW(parseWeberPennParams("model=weberpenn LeafBend=2", {}), InputError);
}

}  // namespace
}  // namespace streyes
