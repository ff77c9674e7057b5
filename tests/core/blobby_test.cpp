// Blobby: the level-27/64 surface of the (1 - r^2)^3 field, cut into triangles (scene/blobby_field.h),
// against the analytic silhouettes of blobs seen from the front.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Where a lone blob's field (1 - r^2)^3 is the level 27/64, in its own space: half its reach.
const double kLevelRadius = 0.5;

std::string n(double v) { return std::to_string(v); }

// The matrix of a sphere blob of radius R (its field's reach) centred at (x, y, z).
std::string sphereMatrix(double R, double x, double y, double z) {
    return n(R) + " 0 0 0  0 " + n(R) + " 0 0  0 0 " + n(R) + " 0  " + n(x) + " " + n(y) + " " + n(z) + " 1";
}

// Blobby of the given code over the concatenated float lists.
std::string blobby(int nleaf, const std::string& code, const std::string& floats, const std::string& extra = "") {
    return "Blobby " + std::to_string(nleaf) + " [" + code + "] [" + floats + "] [\"\"]" + extra + "\n";
}

TEST(Blobby, OneBlobIsADiscOfTheLevelRadius) {
    const double R = 60;
    const std::string rib =
        test::orthoHeader(64, 64) + blobby(1, "1001 0", sphereMatrix(R, 32, 32, 100)) + "WorldEnd\n";
    const double r = R * kLevelRadius;  // 27.25 pixels
    EXPECT_NEAR(test::alphaSum(test::renderRib(rib)), kPi * r * r, 0.01 * kPi * r * r);
}

TEST(Blobby, SidesOneDrawsTheWholeBlobWithNoCracks) {
    // Triangles face out of the blob and share their vertices: with only the outside drawn, every
    // pixel well inside the silhouette is covered exactly (a box filter one pixel wide).
    const double R = 60, r = R * kLevelRadius;
    for (const char* sides : {"Sides 2\n", "Sides 1\n", "ReverseOrientation\nSides 1\n"}) {
        const bool reversed = std::string(sides).find("Reverse") != std::string::npos;
        const std::string rib =
            test::orthoHeader(64, 64) + sides + blobby(1, "1001 0", sphereMatrix(R, 32, 32, 100)) + "WorldEnd\n";
        const test::RenderResult result = test::renderRib(rib);
        int inside = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                if (std::hypot(x + 0.5 - 32, y + 0.5 - 32) > r - 1.5) continue;
                ++inside;
                ASSERT_EQ(result.alpha(0, x, y), 1.0f) << sides << " pixel " << x << "," << y;
            }
        EXPECT_GT(inside, 2000);
        // The near side is the one drawn; ReverseOrientation makes the inside the outside, and
        // Sides 1 then shows the far side.
        const FrameImage& image = result.frame(0);
        EXPECT_NEAR(image.z[size_t(32 * 64 + 32)], reversed ? 100 + r : 100 - r, 0.5) << sides;
    }
}

TEST(Blobby, TwoBlobsMergeWithABridge) {
    // Apart, the discs (radius 10, centres 22 apart) do not touch; their fields do (reach 20,
    // (1 - 0.55^2)^3 = 0.339 each at the midpoint, together over 27/64), so the surface bridges
    // them: more than the two discs, and the midpoint between them is covered. Seen along z, a
    // point (x, y) is covered where the sum of the fields passes the level at z = 0 (both fall off
    // with |z|): the silhouette's area, integrated here on a fine grid.
    const double R = 20, r = R * kLevelRadius;
    const std::string floats = sphereMatrix(R, 21, 32, 100) + "  " + sphereMatrix(R, 43, 32, 100);
    const test::RenderResult merged =
        test::renderRib(test::orthoHeader(64, 64) + blobby(2, "1001 0 1001 16 0 2 0 1", floats) + "WorldEnd\n");
    auto field = [&](double dx, double dy) {
        const double s = 1 - (dx * dx + dy * dy) / (R * R);
        return s > 0 ? s * s * s : 0.0;
    };
    double bridged = 0;
    const double step = 1.0 / 32;
    for (double y = 0.5 * step; y < 64; y += step)
        for (double x = 0.5 * step; x < 64; x += step)
            if (field(x - 21, y - 32) + field(x - 43, y - 32) > 27.0 / 64.0) bridged += step * step;
    EXPECT_GT(bridged, 2 * kPi * r * r * 1.05);  // the bridge adds area
    EXPECT_NEAR(test::alphaSum(merged), bridged, 0.01 * bridged);
    EXPECT_EQ(merged.alpha(0, 31, 31), 1.0f);
    EXPECT_EQ(merged.alpha(0, 32, 32), 1.0f);
    // The maximum of the two fields does not merge: two discs, apart.
    const test::RenderResult apart =
        test::renderRib(test::orthoHeader(64, 64) + blobby(2, "1001 0 1001 16 2 2 0 1", floats) + "WorldEnd\n");
    EXPECT_NEAR(test::alphaSum(apart), 2 * kPi * r * r, 0.02 * 2 * kPi * r * r);
    EXPECT_EQ(apart.alpha(0, 32, 32), 0.0f);
}

TEST(Blobby, SubtractCarvesAndMinimumIntersects) {
    // A blob minus a larger one at the same centre: its field is below the other's everywhere,
    // so nothing is left.
    const std::string contained = sphereMatrix(10, 32, 32, 100) + "  " + sphereMatrix(20, 32, 32, 100);
    EXPECT_EQ(test::alphaSum(test::renderRib(test::orthoHeader(64, 64) +
                                             blobby(2, "1001 0 1001 16 4 0 1", contained) + "WorldEnd\n")),
              0.0);
    // A big blob (reach 60) minus an ellipsoid through it along the view (reach 20 across, 60
    // deep): a ring. A line of sight at distance rho from the axis is covered where the largest
    // f60 - fB along it passes 27/64 (found here numerically); outside, the big blob's level radius.
    const double RA = 60, RB = 20;
    auto f = [](double r2) {
        const double s = 1 - r2;
        return s > 0 ? s * s * s : 0;
    };
    auto covered = [&](double rho) {
        double best = -1;
        for (double z = -RA; z <= RA; z += 0.01)
            best = std::max(best, f((rho * rho + z * z) / (RA * RA)) - f(rho * rho / (RB * RB) + z * z / (RA * RA)));
        return best > 27.0 / 64.0;
    };
    double lo = 0, hi = RB;
    for (int i = 0; i < 30; ++i) {
        const double m = (lo + hi) / 2;
        (covered(m) ? hi : lo) = m;
    }
    const double inner = lo, outer = RA * kLevelRadius;
    const std::string ring = sphereMatrix(RA, 32, 32, 100) + "  " + n(RB) + " 0 0 0  0 " + n(RB) + " 0 0  0 0 " +
                             n(RA) + " 0  32 32 100 1";
    const test::RenderResult carved =
        test::renderRib(test::orthoHeader(64, 64) + blobby(2, "1001 0 1001 16 4 0 1", ring) + "WorldEnd\n");
    const double area = kPi * (outer * outer - inner * inner);
    EXPECT_NEAR(test::alphaSum(carved), area, 0.01 * area) << "hole radius " << inner;
    EXPECT_EQ(carved.alpha(0, 31, 31), 0.0f);
    EXPECT_EQ(carved.alpha(0, int(32 + (inner + outer) / 2), 32), 1.0f);
    // The minimum of two overlapping blobs is their lens, smaller than either disc.
    const double R = 40, r = R * kLevelRadius;
    const std::string two = sphereMatrix(R, 26, 32, 100) + "  " + sphereMatrix(R, 38, 32, 100);
    const double lens = test::alphaSum(
        test::renderRib(test::orthoHeader(64, 64) + blobby(2, "1001 0 1001 16 3 2 0 1", two) + "WorldEnd\n"));
    // Two discs of radius r, 12 apart: their intersection.
    const double d = 12, lensArea = 2 * r * r * std::acos(d / (2 * r)) - d / 2 * std::sqrt(4 * r * r - d * d);
    EXPECT_NEAR(lens, lensArea, 0.015 * lensArea);
}

TEST(Blobby, DivideIsTheDivisorsReachWhereTheQuotientPassesTheLevel) {
    // Aqsis's sub.rib, top left (its "5 0 1" is a division, as the RI Spec and Aqsis both read
    // it), scaled by 40: blob A of reach 40, B of reach 20 centred 16 above A's centre. Inside B's
    // reach A / B is at least 0.442 (its least, where B's field is largest against A's), over
    // 27/64; outside it B's field is 0 and the quotient is 0 (a division by 0 gives 0). So the
    // surface is B's reach, the sphere of radius 20, where the field jumps from 0.442 or more to 0:
    // seen along z, the disc of radius 20 about B's centre, whole (no pits on the jump).
    auto f = [](double r2) { return r2 < 1 ? std::pow(1 - r2, 3) : 0.0; };
    double least = 1e9;  // A / B over B's reach, on a grid of its (x, y) half plane (symmetric about the axis)
    for (double x = 0; x <= 20; x += 0.25)
        for (double y = -20; y <= 20; y += 0.25)
            if (x * x + y * y < 20 * 20) least = std::min(least, f((x * x + (y + 16) * (y + 16)) / 1600) / f((x * x + y * y) / 400));
    EXPECT_GT(least, 0.44);
    const std::string floats = sphereMatrix(40, 32, 16, 100) + "  " + sphereMatrix(20, 32, 32, 100);
    const test::RenderResult quotient =
        test::renderRib(test::orthoHeader(64, 64) + blobby(2, "1001 0 1001 16 5 0 1", floats) + "WorldEnd\n");
    const double disc = kPi * 20 * 20;
    EXPECT_NEAR(test::alphaSum(quotient), disc, 0.01 * disc);
    for (int y = 14; y < 50; ++y)  // every pixel within 18 of B's centre is covered, none beyond 22
        for (int x = 14; x < 50; ++x) {
            const double d = std::hypot(x + 0.5 - 32, y + 0.5 - 32);
            if (d < 18) {
                EXPECT_EQ(quotient.alpha(0, x, y), 1.0f) << x << " " << y;
            }
        }
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            if (std::hypot(x + 0.5 - 32, y + 0.5 - 32) > 22) {
                EXPECT_EQ(quotient.alpha(0, x, y), 0.0f) << x << " " << y;
            }
}

TEST(Blobby, SegmentBlobIsACapsule) {
    // A segment blob of radius 20 from x = 20 to x = 44: a stadium of half-width 20 * 0.5.
    const double rad = 20, r = rad * kLevelRadius, len = 24;
    const std::string floats = "20 32 100  44 32 100  " + n(rad) + "  1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1";
    const double area = kPi * r * r + 2 * r * len;
    EXPECT_NEAR(test::alphaSum(test::renderRib(test::orthoHeader(64, 64) + blobby(1, "1002 0", floats) + "WorldEnd\n")),
                area, 0.01 * area);
}

TEST(Blobby, MotionBlockDrawsTheFirstKey) {
    const std::string one = blobby(1, "1001 0", sphereMatrix(40, 32, 32, 100));
    const std::string other = blobby(1, "1001 0", sphereMatrix(40, 20, 32, 100));
    const test::RenderResult still = test::renderRib(test::orthoHeader(64, 64) + one + "WorldEnd\n");
    const test::RenderResult moving = test::renderRib(test::orthoHeader(64, 64, "Shutter 0 1\n") +
                                                      "MotionBegin [0 1]\n" + one + other + "MotionEnd\nWorldEnd\n");
    EXPECT_TRUE(test::identicalPixels(still, moving));
    bool warned = false;
    for (const std::string& w : moving.warnings) warned = warned || w.find("the first key is drawn") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(Blobby, CellsFollowTheScreenSizeUnlessGiven) {
    // Without "blobbyresolution", a cell is about 2 pixels of the bound's extent on screen: twice
    // the image, twice the cells along each side, about four times the triangles.
    auto triangles = [](int size, const std::string& attribute) {
        Log log;
        const std::string rib = "Format " + std::to_string(size) + " " + std::to_string(size) +
                                " 1\nProjection \"orthographic\"\nScreenWindow 0 64 0 64\nWorldBegin\n" + attribute +
                                blobby(1, "1001 0", sphereMatrix(30, 32, 32, 100)) + "WorldEnd\n";
        const Scene scene = parseRibString(rib, "blob.rib", log);
        EXPECT_EQ(scene.polygonMeshes.size(), 1u);
        return scene.polygonMeshes.empty() ? size_t(0) : scene.polygonMeshes[0].polygons.size();
    };
    const double small = double(triangles(64, "")), large = double(triangles(128, ""));
    EXPECT_NEAR(large / small, 4, 0.4);
    const std::string fixed = "Attribute \"streyes\" \"float blobbyresolution\" [20]\n";
    EXPECT_EQ(triangles(64, fixed), triangles(128, fixed));
}

// The triangles of the one Blobby of a RIB file read with `detail`.
size_t trianglesRead(const std::string& path, const std::string& rib, const ReadDetail& detail) {
    std::ofstream(path) << rib;
    Log log;
    size_t count = 0;
    parseRibFrames(
        path, log, [&](Scene&& s) { count = s.polygonMeshes.empty() ? 0 : s.polygonMeshes[0].polygons.size(); },
        detail);
    return count;
}

TEST(Blobby, CellsFollowTheSizeRendered) {
    // --res and --preview render at another size than the Format's: a Blobby is cut for the size
    // rendered, so a Format of 64 rendered at 128 is cut as a Format of 128 is, and a Format of 128
    // rendered at half (a preview) as one of 64.
    test::TempDir dir("blobby-res");
    auto triangles = [&](int format, const ReadDetail& detail) {
        const std::string rib = "Format " + std::to_string(format) + " " + std::to_string(format) +
                                " 1\nProjection \"orthographic\"\nScreenWindow 0 64 0 64\nWorldBegin\n" +
                                blobby(1, "1001 0", sphereMatrix(30, 32, 32, 100)) + "WorldEnd\n";
        return trianglesRead(dir.path() + "/blob.rib", rib, detail);
    };
    ReadDetail format, at128, half;
    at128.xres = at128.yres = 128;
    half.formatScale = 0.5;
    const size_t small = triangles(64, format), large = triangles(128, format);
    EXPECT_GT(large, 3 * small);  // the size matters
    EXPECT_EQ(triangles(64, at128), large);
    EXPECT_EQ(triangles(128, half), small);
}

TEST(Blobby, ProceduralOutputIsCutForItsSizeOnScreen) {
    // A procedural's output has no camera of its own: a Blobby in it is cut for the procedural's
    // pixels per world unit. One pixel a unit cuts it as the same Blobby seen by a camera at one
    // pixel a unit.
    test::TempDir dir("blobby-procedural");
    const std::string blob = blobby(1, "1001 0", sphereMatrix(30, 32, 32, 100));
    const size_t seen = trianglesRead(dir.path() + "/seen.rib",
                                      "Format 64 64 1\nProjection \"orthographic\"\nScreenWindow 0 64 0 64\n"
                                      "WorldBegin\n" + blob + "WorldEnd\n",
                                      {});
    Log log;
    ReadDetail onePixel;
    onePixel.pixelsPerUnit = 1;
    const Scene fragment = parseRibFragment(blob, "fragment", MotionTransform(), nullptr, log, onePixel);
    ASSERT_EQ(fragment.polygonMeshes.size(), 1u);
    EXPECT_EQ(fragment.polygonMeshes[0].polygons.size(), seen);
    onePixel.pixelsPerUnit = 2;
    EXPECT_GT(parseRibFragment(blob, "fragment", MotionTransform(), nullptr, log, onePixel).polygonMeshes[0].polygons.size(),
              3 * seen);

    // Rendered: the same blob read by a DelayedReadArchive, whose bound spans 60 of the 64
    // pixels, is cut about as finely as inline (before, it was cut for a default camera at the
    // origin), and covers the disc it should.
    const std::string archive = dir.path() + "/blob.rib";
    std::ofstream(archive) << blob;
    const std::string head = test::orthoHeader(64, 64);
    const test::RenderResult inline_ = test::renderRib(head + blob + "WorldEnd\n");
    const test::RenderResult read = test::renderRib(head + "Procedural \"DelayedReadArchive\" [\"" + archive +
                                                    "\"] [2 62 2 62 70 130]\nWorldEnd\n");
    const double ratio = double(read.stats.counters.micropolygons) / double(inline_.stats.counters.micropolygons);
    EXPECT_GT(ratio, 0.8);
    EXPECT_LT(ratio, 1.6);  // sqrt(detail) rounds the bound's area up to a power of two
    const double r = 30 * kLevelRadius;
    EXPECT_NEAR(test::alphaSum(read), kPi * r * r, 0.01 * kPi * r * r);
}

TEST(Blobby, AnObjectsBlobbyIsCutAsIfInstancedWhereDefined) {
    // An object's definition has no camera of its own: its blobby is sized by the scene's camera
    // with ObjectBegin's transform. Instanced there, it is the same as inline, pixel for pixel
    // (before, a default camera at the origin cut it at 256 cells).
    const std::string head = test::orthoHeader(64, 64) + "Translate 32 32 0\nScale 0.5 0.5 1\n";
    const std::string blob = blobby(1, "1001 0", sphereMatrix(50, 0, 0, 100));
    const test::RenderResult inline_ = test::renderRib(head + blob + "WorldEnd\n");
    const test::RenderResult instanced = test::renderRib(head + "ObjectBegin \"blob\"\n" + blob +
                                                         "ObjectEnd\nObjectInstance \"blob\"\nWorldEnd\n");
    EXPECT_EQ(instanced.stats.counters.micropolygons, inline_.stats.counters.micropolygons);
    EXPECT_TRUE(test::identicalPixels(instanced, inline_));
    const double r = 25 * kLevelRadius;
    EXPECT_NEAR(test::alphaSum(instanced), kPi * r * r, 0.01 * kPi * r * r);
}

TEST(Blobby, BadInputNamesFileAndLine) {
    // A coarse polygonization on one line (the blobby stays on line 2): without a camera the
    // blob around the eye would take the finest, seconds a case under the sanitizers.
    const std::string head = "WorldBegin Attribute \"streyes\" \"float blobbyresolution\" [8]\n";
    const std::string m = sphereMatrix(1, 0, 0, 0);
    struct Case {
        std::string rib, message;
    };
    const Case cases[] = {
        {blobby(1, "1001 0", "1 0 0"), "needs 16 floats"},
        {blobby(1, "1001 0 0 1 1", m), "not an earlier one"},
        {blobby(2, "1001 0", m), "nleaf is 2 but the code has 1 leaf"},
        {blobby(1, "1001 0 0 2 0", m), "the code ends inside instruction 1"},
        {blobby(1, "1001 0", "0 0 0 0  0 0 0 0  0 0 0 0  0 0 0 1"), "singular matrix"},
        {blobby(1, "1002 0", "0 0 0 1 0 0 -1 " + m), "radius -1"},
        {blobby(1, "1001 0", "nan 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1"), "NaN and infinity are not allowed"},
    };
    for (const Case& c : cases) {
        const std::string error = test::ribError(head + c.rib + "WorldEnd\n");
        EXPECT_NE(error.find("bad.rib:2"), std::string::npos) << error;
        EXPECT_NE(error.find(c.message), std::string::npos) << error;
    }
    // An unknown opcode: the peers warn and skip the blobby (its operands cannot be counted); an
    // error under --strict (an error until issue 46).
    const std::string unknown = head + blobby(1, "1001 0 9", m) + "WorldEnd\n";
    EXPECT_EQ(test::ribError(unknown), "");
    const std::string strict = test::ribError(unknown, true);
    EXPECT_NE(strict.find("bad.rib:2"), std::string::npos) << strict;
    EXPECT_NE(strict.find("unknown opcode 9"), std::string::npos) << strict;
    Log log;
    const Scene skipped = parseRibString(unknown, "w.rib", log);
    EXPECT_TRUE(skipped.polygonMeshes.empty());
    ASSERT_EQ(log.warnings().size(), 1u);
    EXPECT_NE(log.warnings()[0].find("the blobby is skipped"), std::string::npos) << log.warnings()[0];
    // Aqsis's field plug-in (9000 n, n operands) that is not found: a leaf whose field is 0, with a
    // warning; counted in nleaf or not, as writers do (blobby_plugin_test.cpp loads real ones).
    for (int nleaf : {1, 2}) {
        Log plugin;
        const Scene s = parseRibString(head + blobby(nleaf, "1001 0 9000 2 0 0 0 2 0 1", m) + "WorldEnd\n", "p.rib", plugin);
        EXPECT_EQ(s.polygonMeshes.size(), 1u) << nleaf;
        ASSERT_EQ(plugin.warnings().size(), 1u) << nleaf;
        EXPECT_NE(plugin.warnings()[0].find("p.rib:2"), std::string::npos) << plugin.warnings()[0];
        EXPECT_NE(plugin.warnings()[0].find("no field plug-in ''"), std::string::npos) << plugin.warnings()[0];
        EXPECT_NE(plugin.warnings()[0].find("its field is taken as 0"), std::string::npos);
    }
}

}  // namespace
}  // namespace streyes
