#include "raster/micropolygon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>

namespace streyes::micropolygon {
namespace {

uint32_t bitsOf(float v) {
    uint32_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

// The edge function in its canonical form times the quad's direction, as Edge::eval was written
// until 2026-11-28: sign * (cdx (y - py) - cdy (x - px)), cd the canonical direction.
float canonicalTimesSign(float ax, float ay, float bx, float by, float x, float y) {
    const bool canonical = ax < bx || (ax == bx && ay < by);
    const float px = canonical ? ax : bx, py = canonical ? ay : by;
    const float dx = canonical ? bx - ax : ax - bx, dy = canonical ? by - ay : ay - by;
    return (canonical ? 1.0f : -1.0f) * (dx * (y - py) - dy * (x - px));
}

// A shared edge's two sides must see exactly opposite values (no sample is lost or hit twice
// between two micropolygons), and the values are the canonical function's times the sign, bit for
// bit but for the sign of a zero: the kernels evaluate the edge without the multiplication.
TEST(Micropolygon, AnEdgesTwoDirectionsGiveExactlyOppositeValues) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(-40.0f, 40.0f);
    std::uniform_int_distribution<int> lattice(-4, 4);
    int zeros = 0, nonzeros = 0;
    for (int n = 0; n < 20000; ++n) {
        // Half the edges on a quarter-pixel lattice, with samples on it: many lie exactly on the edge.
        const bool onLattice = n % 2 == 0;
        auto pick = [&] { return onLattice ? 0.25f * float(lattice(rng)) : coord(rng); };
        const float ax = pick(), ay = pick(), bx = pick(), by = pick(), x = pick(), y = pick();
        const float ab = makeEdge(ax, ay, bx, by).eval(x, y), ba = makeEdge(bx, by, ax, ay).eval(x, y);
        ASSERT_FALSE(std::isnan(ab));
        const float reference = canonicalTimesSign(ax, ay, bx, by, x, y);
        if (ab == 0) {  // on the edge from both sides (zeros of either sign: they compare equal)
            ASSERT_EQ(ba, 0.0f);
            ASSERT_EQ(reference, 0.0f);
            ++zeros;
        } else {
            ASSERT_EQ(bitsOf(ab), bitsOf(-ba))
                << "a (" << ax << ", " << ay << ") b (" << bx << ", " << by << ") sample (" << x << ", " << y << ")";
            ASSERT_EQ(bitsOf(ab), bitsOf(reference));
            ++nonzeros;
        }
    }
    EXPECT_GT(zeros, 500);  // the lattice put hundreds of samples exactly on edges
    EXPECT_GT(nonzeros, 10000);
}

// The edge keeps the canonical flag and start point, whichever way the quad runs it.
TEST(Micropolygon, AnEdgeStartsAtItsCanonicalEndEitherWay) {
    const Edge e = makeEdge(3, 1, 2, 5), f = makeEdge(2, 5, 3, 1);
    EXPECT_FALSE(e.canonical);
    EXPECT_TRUE(f.canonical);
    EXPECT_EQ(e.px, 2.0f);
    EXPECT_EQ(e.py, 5.0f);
    EXPECT_EQ(f.px, 2.0f);
    EXPECT_EQ(f.py, 5.0f);
    EXPECT_EQ(e.dx, -1.0f);
    EXPECT_EQ(e.dy, 4.0f);
    EXPECT_EQ(f.dx, 1.0f);
    EXPECT_EQ(f.dy, -4.0f);
    // Equal x: the smaller y starts.
    EXPECT_TRUE(makeEdge(1, 2, 1, 3).canonical);
    EXPECT_FALSE(makeEdge(1, 3, 1, 2).canonical);
}

}  // namespace
}  // namespace streyes::micropolygon
