// Depth passes (RenderOptions::depthPass): Hider "hidden" "depthfilter" "midpoint" keeps every
// surface a sample crosses and gives each pixel the mean of the two nearest.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "test_util.h"

namespace streyes {
namespace {

using test::orthoHeader;
using test::square;

constexpr float kInf = std::numeric_limits<float>::infinity();

// Three squares one behind the other, each a little smaller: pixels see three, two, one or no
// surfaces. The opaque fronts are at z = 2, 5 and 9.
std::string threeLayers(const std::string& filter, const std::string& extra = "") {
    return orthoHeader(40, 40, "Hider \"hidden\" \"depthfilter\" \"" + filter + "\"\nPixelSamples 3 3\n" + extra) +
           square(10, 30, 10, 30, 2) + square(5, 35, 5, 35, 5) + square(2, 38, 2, 38, 9) + "WorldEnd\n";
}

TEST(DepthPass, MidpointIsTheMeanOfTheTwoNearestSurfaces) {
    RenderOptions depth;
    depth.depthPass = true;
    const test::RenderResult r = test::renderRib(threeLayers("midpoint"), depth);
    // Well inside each region (the pixel filter is a box one pixel wide: a pixel's own samples).
    EXPECT_EQ(r.z(0, 20, 20), 0.5f * (2 + 5));  // three surfaces: the two nearest
    EXPECT_EQ(r.z(0, 7, 20), 0.5f * (5 + 9));   // two
    EXPECT_EQ(r.z(0, 3, 20), kInf);             // one: nothing behind it
    EXPECT_EQ(r.z(0, 0, 0), kInf);              // none
    // Every pixel: a pixel's depth is the nearest of its samples' midpoints, so a pixel on an edge
    // takes the nearer pair. Check against the regions' depths pixel by pixel.
    for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 40; ++x) {
            auto inside = [&](int lo, int hi) { return x >= lo && x < hi && y >= lo && y < hi; };
            const float want = inside(10, 30) ? 3.5f : inside(5, 35) ? 7.0f : kInf;
            EXPECT_EQ(r.z(0, x, y), want) << x << " " << y;
        }
    // The nearest ("min", the default) for comparison; a picture (no depth pass) with midpoint
    // keeps the nearest too, its colours its own.
    const test::RenderResult near = test::renderRib(threeLayers("min"));
    EXPECT_EQ(near.z(0, 20, 20), 2.0f);
    const test::RenderResult picture = test::renderRib(threeLayers("midpoint"));
    EXPECT_TRUE(test::identicalPixels(picture, near));
}

// A see-through surface is no surface of a depth map (RenderMan's zthreshold 1): the midpoint
// skips it.
TEST(DepthPass, MidpointSkipsSeeThroughSurfaces) {
    RenderOptions depth;
    depth.depthPass = true;
    const std::string rib = orthoHeader(40, 40, "Hider \"hidden\" \"depthfilter\" \"midpoint\"\n") +
                            "AttributeBegin\nOpacity [0.5 0.5 0.5]\n" + square(0, 40, 0, 40, 1) + "AttributeEnd\n" +
                            square(10, 30, 10, 30, 2) + square(5, 35, 5, 35, 5) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib, depth);
    EXPECT_EQ(r.z(0, 20, 20), 3.5f);
    EXPECT_EQ(r.z(0, 7, 20), kInf);
}

// A depth pass with motion: a square moving across a still one, shutter open: each frame's
// samples see it where they are, and the frames of a block are the frames alone.
TEST(DepthPass, MidpointOfAMovingSurfaceDoesNotDependOnTheBlock) {
    const std::string rib = orthoHeader(40, 40,
                                        "Hider \"hidden\" \"depthfilter\" \"midpoint\"\nShutter 0 0.5\n"
                                        "Option \"streyes\" \"int frames\" [1 4]\n") +
                            square(0, 40, 0, 40, 8) +
                            "MotionBegin [1 4]\nTranslate 0 0 0\nTranslate 20 0 0\nMotionEnd\n" +
                            square(0, 10, 10, 30, 3) + "WorldEnd\n";
    RenderOptions depth;
    depth.depthPass = true;
    const test::ShotAndFrame r = test::renderShotAndFrame(rib, depth, 1, 4, 3);
    EXPECT_TRUE(r.samePixels(3));
    EXPECT_EQ(r.shot.z(1, 5, 20), 0.5f * (3 + 8));  // frame 1: the square over x 0-10
    EXPECT_EQ(r.shot.z(1, 35, 20), kInf);
}

}  // namespace
}  // namespace streyes
