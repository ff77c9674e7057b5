// The options and attributes real RIB files set around their geometry: Sides, Orientation and
// ReverseOrientation, ShadingInterpolation, Exposure, Hider "hidden" (jitter, depthfilter) and
// Option "limits" (bucketsize, gridsize), against what each must do to the pixels.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>

#include "test_util.h"

namespace streyes {
namespace {

// Polygon [x0, x1] x [y0, y1] at depth z, its vertices clockwise on the screen (raster y is
// down, scene y up): in RenderMan's left-handed camera space its normal P1-P0 x P2-P1 points at
// the eye, so it is front-facing. `clockwise` false lists them the other way round.
std::string polygon(double x0, double x1, double y0, double y1, double z, bool clockwise) {
    auto p = [&](double x, double y) {
        return std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + " ";
    };
    const std::string cw = p(x0, y0) + p(x0, y1) + p(x1, y1) + p(x1, y0);
    const std::string ccw = p(x0, y0) + p(x1, y0) + p(x1, y1) + p(x0, y1);
    return "Polygon \"P\" [" + (clockwise ? cw : ccw) + "]\n";
}

// The covered pixels of [x0, x1) x [y0, y1) (raster) in frame 0.
double coverage(const test::RenderResult& r, int x0, int x1, int y0, int y1) {
    double sum = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += r.alpha(0, x, y);
    return sum;
}

// A clockwise (front-facing) square on the left, a counter-clockwise one on the right, with
// `attributes` before them.
std::string facingPair(const std::string& attributes) {
    return test::orthoHeader(64, 32) + attributes + polygon(0, 32, 0, 32, 10, true) +
           polygon(32, 64, 0, 32, 10, false) + "WorldEnd\n";
}

TEST(RenderAttributes, SidesOneDrawsOnlyTheOutside) {
    const test::RenderResult both = test::renderRib(facingPair(""));
    EXPECT_EQ(coverage(both, 0, 32, 0, 32), 1024.0);
    EXPECT_EQ(coverage(both, 32, 64, 0, 32), 1024.0);
    const test::RenderResult one = test::renderRib(facingPair("Sides 1\n"));
    EXPECT_EQ(coverage(one, 0, 32, 0, 32), 1024.0);  // facing the eye: drawn
    EXPECT_EQ(coverage(one, 32, 64, 0, 32), 0.0);    // facing away: not one sample
    // Orientation turns the outside: "inside", ReverseOrientation and the absolute "rh" draw the
    // other square; "lh" is the camera's own handedness, as "outside" is here.
    for (const char* turn : {"Orientation \"inside\"\n", "ReverseOrientation\n", "Orientation \"rh\"\n"}) {
        const test::RenderResult r = test::renderRib(facingPair(std::string("Sides 1\n") + turn));
        EXPECT_EQ(coverage(r, 0, 32, 0, 32), 0.0) << turn;
        EXPECT_EQ(coverage(r, 32, 64, 0, 32), 1024.0) << turn;
    }
    const test::RenderResult lh = test::renderRib(facingPair("Sides 1\nOrientation \"lh\"\n"));
    EXPECT_TRUE(test::identicalPixels(lh, one));
    // ReverseOrientation twice is the identity; Sides 2 again draws both.
    EXPECT_TRUE(test::identicalPixels(test::renderRib(facingPair("Sides 1\nReverseOrientation\nReverseOrientation\n")), one));
    EXPECT_TRUE(test::identicalPixels(test::renderRib(facingPair("Sides 1\nSides 2\n")), both));
}

TEST(RenderAttributes, TheRayTracerDrawsOneSidedSurfacesAsTheRasterizerDoes) {
    for (const char* attributes : {"Sides 1\n", "Sides 1\nReverseOrientation\n", ""}) {
        const test::RenderResult raster = test::renderRib(facingPair(attributes));
        const test::RenderResult traced = test::renderRib(facingPair(attributes), test::optionsFor(Algorithm::Raytrace));
        EXPECT_TRUE(test::identicalPixels(raster, traced)) << attributes;
        EXPECT_GT(test::alphaSum(traced), 1000.0) << attributes;
    }
}

TEST(RenderAttributes, AMirroringTransformTurnsTheOutsideUnlessOrientationIsAbsolute) {
    // Scale 1 1 -1 mirrors: the clockwise square's outside (its object-space normal, mirrored)
    // now faces away, so "outside" draws the other one; "lh" does not follow the mirror.
    const std::string mirror = "Translate 0 0 20\nScale 1 1 -1\n";
    const test::RenderResult r = test::renderRib(facingPair("Sides 1\n" + mirror));
    EXPECT_EQ(coverage(r, 0, 32, 0, 32), 0.0);
    EXPECT_EQ(coverage(r, 32, 64, 0, 32), 1024.0);
    const test::RenderResult lh = test::renderRib(facingPair("Sides 1\nOrientation \"lh\"\n" + mirror));
    EXPECT_EQ(coverage(lh, 0, 32, 0, 32), 1024.0);
    EXPECT_EQ(coverage(lh, 32, 64, 0, 32), 0.0);
}

// A sphere of radius 20 at depth 100 in a 64 x 64 orthographic view, with `attributes`.
std::string sphere(const std::string& options, const std::string& attributes) {
    return test::orthoHeader(64, 64, options) + attributes + "Translate 32 32 100\nSphere 20 -20 20 360\nWorldEnd\n";
}

TEST(RenderAttributes, ASphereIsSeenFromOutsideUnlessReversed) {
    // One-sided, a closed sphere shows its near half (Z = 80 at the centre); reversed, the inside
    // of its far half (Z = 120). Two-sided it is the near half either way.
    const float front = test::renderRib(sphere("", "Sides 1\n")).z(0, 32, 32);
    const float back = test::renderRib(sphere("", "Sides 1\nReverseOrientation\n")).z(0, 32, 32);
    const float twoSided = test::renderRib(sphere("", "ReverseOrientation\n")).z(0, 32, 32);
    EXPECT_NEAR(front, 80.0f, 0.05f);
    EXPECT_NEAR(back, 120.0f, 0.05f);
    EXPECT_NEAR(twoSided, 80.0f, 0.05f);
    EXPECT_EQ(test::alphaSum(test::renderRib(sphere("", "Sides 1\n"))),
              test::alphaSum(test::renderRib(sphere("", ""))));
}

TEST(RenderAttributes, ShadersSeeTheOutsideNormal) {
    // N . I < 0 where the normal faces the eye: white on the sphere's near half by default, black
    // when the orientation is reversed (shaders see the turned normal too).
    test::TempDir dir("sides-shaders");
    std::ofstream(dir.path() + "/facing.sl") << "surface facing() { Ci = N . I < 0 ? 1 : 0; Oi = 1; }\n";
    const std::string path = "Option \"searchpath\" \"shader\" \"" + dir.path() + ":@\"\n";
    const test::RenderResult out = test::renderRib(sphere(path, "Surface \"facing\"\n"));
    const test::RenderResult in = test::renderRib(sphere(path, "Surface \"facing\"\nReverseOrientation\n"));
    int lit = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const float dx = float(x) + 0.5f - 32, dy = float(y) + 0.5f - 32;
            if (dx * dx + dy * dy > 17.0f * 17.0f) continue;  // clear of the rim, whose micropolygons span both sides
            EXPECT_EQ(out.channel(0, x, y, 0), 1.0f) << x << "," << y;
            EXPECT_EQ(in.channel(0, x, y, 0), 0.0f) << x << "," << y;
            ++lit;
        }
    EXPECT_GT(lit, 850);
    // The polygons facing each way, in the rasterizer and the ray tracer (which shades its hits
    // with the same turned normal).
    const std::string pair = test::orthoHeader(64, 32, path) + "Surface \"facing\"\n";
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace})
        for (bool reversed : {false, true}) {
            const test::RenderResult r = test::renderRib(pair + (reversed ? "ReverseOrientation\n" : "") +
                                                             polygon(0, 32, 0, 32, 10, true) +
                                                             polygon(32, 64, 0, 32, 10, false) + "WorldEnd\n",
                                                         test::optionsFor(a));
            EXPECT_EQ(r.channel(0, 16, 16, 0), reversed ? 0.0f : 1.0f) << test::testName(a);
            EXPECT_EQ(r.channel(0, 48, 16, 0), reversed ? 1.0f : 0.0f) << test::testName(a);
        }
}

TEST(RenderAttributes, ConstantShadingInterpolationTakesEachMicropolygonsFirstVertex) {
    // A 64 x 64 square shaded red = s, at ShadingRate 16: 4 x 4-pixel micropolygons whose edges lie
    // on pixel edges (16 x 16 micropolygons a grid). "constant": pixel x shows s at its
    // micropolygon's first vertex, floor(x / 4) / 16, exactly; "smooth": s at the pixel's samples,
    // the pixel centre's on average.
    test::TempDir dir("interp-shaders");
    std::ofstream(dir.path() + "/sred.sl") << "surface sred() { Ci = color(s, 0, 0); Oi = 1; }\n";
    const std::string header = test::orthoHeader(64, 64, "Option \"searchpath\" \"shader\" \"" + dir.path() + ":@\"\n") +
                               "Surface \"sred\"\nShadingRate 16\n";
    const test::RenderResult flat =
        test::renderRib(header + "ShadingInterpolation \"constant\"\n" + test::square(0, 64, 0, 64, 10) + "WorldEnd\n");
    const test::RenderResult smooth =
        test::renderRib(header + "ShadingInterpolation \"smooth\"\n" + test::square(0, 64, 0, 64, 10) + "WorldEnd\n");
    float worstFlat = 0, worstSmooth = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            worstFlat = std::max(worstFlat, test::absDifference(flat.channel(0, x, y, 0), float(x / 4) / 16.0f));
            worstSmooth = std::max(worstSmooth, test::absDifference(smooth.channel(0, x, y, 0), (float(x) + 0.5f) / 64.0f));
        }
    EXPECT_LT(worstFlat, 1e-6f);
    EXPECT_LT(worstSmooth, 0.01f);  // the samples' mean position is within the pixel's strata
    EXPECT_GT(test::absDifference(flat.channel(0, 3, 10, 0), smooth.channel(0, 3, 10, 0)), 0.05f);
}

TEST(RenderAttributes, ExposureAppliesGainThenGamma) {
    const std::string scene = "Color 0.25 0.5 0.1\n" + test::square(0, 16, 0, 16, 10) + "WorldEnd\n";
    const test::RenderResult plain = test::renderRib(test::orthoHeader(16, 16) + scene);
    const test::RenderResult exposed = test::renderRib(test::orthoHeader(16, 16, "Exposure 2 2.2\n") + scene);
    const float want[3] = {std::pow(0.5f, 1 / 2.2f), std::pow(1.0f, 1 / 2.2f), std::pow(0.2f, 1 / 2.2f)};
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(plain.channel(0, 5, 5, c), c == 0 ? 0.25f : c == 1 ? 0.5f : 0.1f, 1e-6f);
        EXPECT_NEAR(exposed.channel(0, 5, 5, c), want[c], 1e-5f);
    }
    EXPECT_EQ(exposed.alpha(0, 5, 5), 1.0f);
    EXPECT_EQ(exposed.z(0, 5, 5), plain.z(0, 5, 5));
    EXPECT_TRUE(test::identicalPixels(test::renderRib(test::orthoHeader(16, 16, "Exposure 1 1\n") + scene), plain));
}

TEST(RenderAttributes, HiderWithoutJitterPutsSamplesAtStrataCentres) {
    const std::string rib = test::orthoHeader(8, 8, "PixelSamples 4 2\nShutter 0 1\nHider \"hidden\" \"jitter\" [0]\n") +
                            test::square(0, 8, 0, 8, 10) + "WorldEnd\n";
    const test::SampleRecord s = test::renderSamples(rib);
    ASSERT_EQ(s.samplesPerPixel, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            std::set<float> times;
            for (int j = 0; j < 8; ++j) {
                const SamplePosition& p = s.positions[size_t((y * 8 + x) * 8 + j)];
                EXPECT_EQ(p.x, float(x) + (float(j % 4) + 0.5f) / 4.0f);
                EXPECT_EQ(p.y, float(y) + (float(j / 4) + 0.5f) / 2.0f);
                times.insert(p.tf);
            }
            // Times: the centres of the 8 time strata, in some order.
            ASSERT_EQ(times.size(), 8u);
            int k = 0;
            for (float t : times) EXPECT_EQ(t, (float(k++) + 0.5f) / 8.0f);
        }
    // Jittered (the default), positions are off the centres.
    const test::SampleRecord j = test::renderSamples(test::orthoHeader(8, 8, "PixelSamples 4 2\n") +
                                                     test::square(0, 8, 0, 8, 10) + "WorldEnd\n");
    size_t centred = 0;
    for (size_t i = 0; i < j.positions.size(); ++i)
        centred += j.positions[i].x == s.positions[i].x && j.positions[i].y == s.positions[i].y;
    EXPECT_LT(centred, j.positions.size() / 10);
}

TEST(RenderAttributes, DepthFilterChoosesThePixelsDepth) {
    // Pixel column 10 is half covered by a square at z = 10 (x < 10.5) in front of one at z = 20:
    // without jitter, samples 0 and 1 of each row (x + 1/8, x + 3/8) see z = 10, samples 2 and 3
    // see z = 20.
    auto zAt = [](const std::string& filter) {
        const std::string hider = "PixelSamples 4 4\nHider \"hidden\" \"jitter\" [0]" +
                                  (filter.empty() ? std::string() : " \"depthfilter\" \"" + filter + "\"") + "\n";
        const std::string rib = test::orthoHeader(16, 4, hider) + test::square(0, 10.5, 0, 4, 10) +
                                test::square(0, 16, 0, 4, 20) + "WorldEnd\n";
        const test::RenderResult r = test::renderRib(rib);
        return std::make_pair(r.z(0, 10, 1), r.z(0, 12, 1));
    };
    EXPECT_EQ(zAt("").first, 10.0f);
    EXPECT_EQ(zAt("min").first, 10.0f);
    EXPECT_EQ(zAt("max").first, 20.0f);
    EXPECT_EQ(zAt("average").first, 15.0f);
    EXPECT_EQ(zAt("average").second, 20.0f);
    // An uncovered pixel keeps Z = +inf with any filter.
    const std::string miss = test::orthoHeader(16, 4, "Hider \"hidden\" \"depthfilter\" \"average\"\n") +
                             test::square(0, 4, 0, 4, 10) + "WorldEnd\n";
    EXPECT_EQ(test::renderRib(miss).z(0, 12, 1), std::numeric_limits<float>::infinity());
}

TEST(RenderAttributes, LimitsSetBucketAndGridSizeUnlessTheCommandLineDoes) {
    const std::string scene = test::square(0, 64, 0, 64, 10) + "WorldEnd\n";
    const test::RenderResult plain = test::renderRib(test::orthoHeader(64, 64) + scene);
    EXPECT_EQ(plain.stats.bucketSize, kDefaultBucketSize);
    const test::RenderResult limited =
        test::renderRib(test::orthoHeader(64, 64, "Option \"limits\" \"bucketsize\" [16 16] \"gridsize\" 16\n") + scene);
    EXPECT_EQ(limited.stats.bucketSize, 16);
    // 4,096 micropolygons at ShadingRate 1 in grids of at most 16: at least 256 grids (16 buckets
    // each dice their own part).
    EXPECT_GE(limited.stats.counters.gridsDiced, 256u);
    EXPECT_LT(plain.stats.counters.gridsDiced, 64u);
    EXPECT_TRUE(test::identicalPixels(limited, plain));  // a constant square: the same pixels
    RenderOptions o;
    o.bucketSize = 32;
    EXPECT_EQ(test::renderRib(test::orthoHeader(64, 64, "Option \"limits\" \"bucketsize\" [16 16]\n") + scene, o)
                  .stats.bucketSize,
              32);
}

TEST(RenderAttributes, BadValuesNameTheLine) {
    const std::string head = "Format 8 8 1\n";
    struct Case {
        std::string rib, message;
    };
    const Case cases[] = {
        {head + "WorldBegin\nSides 3\nWorldEnd\n", "bad.rib:3: Sides: must be 1 or 2, got 3"},
        {head + "WorldBegin\nOrientation \"sideways\"\nWorldEnd\n", "bad.rib:3: Orientation: unknown orientation \"sideways\""},
        {head + "WorldBegin\nShadingInterpolation \"phong\"\nWorldEnd\n", "bad.rib:3: ShadingInterpolation: unknown shading interpolation \"phong\""},
        {head + "Exposure 1 0\nWorldBegin\nWorldEnd\n", "bad.rib:2: Exposure: gamma must be positive, got 0"},
        {head + "Exposure -1 1\nWorldBegin\nWorldEnd\n", "bad.rib:2: Exposure: gain must be a finite number >= 0, got -1"},
        {head + "Hider \"hidden\" \"depthfilter\" \"median\"\nWorldBegin\nWorldEnd\n", "bad.rib:2: Hider \"hidden\": depthfilter"},
        {head + "Hider \"hidden\" \"jitter\" [2]\nWorldBegin\nWorldEnd\n", "bad.rib:2: Hider \"hidden\": jitter is 0 or 1"},
        {head + "Option \"limits\" \"bucketsize\" [0 0]\nWorldBegin\nWorldEnd\n", "bad.rib:2: Option \"limits\": bucketsize"},
        {head + "Option \"limits\" \"gridsize\" [0]\nWorldBegin\nWorldEnd\n", "bad.rib:2: Option \"limits\": gridsize"},
    };
    for (const Case& c : cases) {
        const std::string e = test::ribError(c.rib);
        EXPECT_NE(e.find(c.message), std::string::npos) << c.rib << "\n -> " << e;
    }
}

TEST(RenderAttributes, AnUnsupportedHiderWarnsAndAMidpointPictureRendersTheNearestDepth) {
    const std::string scene = test::square(0, 8, 0, 8, 10) + "WorldEnd\n";
    const test::RenderResult r =
        test::renderRib(test::orthoHeader(8, 8, "Hider \"raytrace\"\n") + scene);
    EXPECT_EQ(test::alphaSum(r), 64.0);
    bool warned = false;
    for (const std::string& w : r.warnings) warned = warned || w.find("Hider \"raytrace\" is not supported") != std::string::npos;
    EXPECT_TRUE(warned);
    // "midpoint" is a depth pass's (tests/core/depth_pass_test.cpp): a picture's Z is the nearest.
    const test::RenderResult m =
        test::renderRib(test::orthoHeader(8, 8, "Hider \"hidden\" \"depthfilter\" \"midpoint\"\n") + scene);
    EXPECT_EQ(m.warnings, std::vector<std::string>{});
    EXPECT_EQ(m.z(0, 4, 4), 10.0f);
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// calculatenormal(P) turns with N: under ReverseOrientation, Orientation "inside" or a mirroring
// transform, the normal a shader computes from P points the way the shading normal N does.
TEST(RenderAttributes, CalculatenormalFollowsOrientation) {
    test::TempDir dir("calcnormal");
    std::ofstream(dir.path() + "/agree.sl")
        << "surface agree() { Oi = 1; float d = normalize(N) . normalize(calculatenormal(P)); Ci = color(max(d, 0), max(-d, 0), 0); }\n";
    const std::string header = test::orthoHeader(32, 32, "Option \"searchpath\" \"shader\" \"" + dir.path() + ":@\"\n");
    for (const char* turn : {"", "ReverseOrientation\n", "Orientation \"inside\"\n", "Translate 0 0 20\nScale 1 1 -1\n"}) {
        const test::RenderResult r =
            test::renderRib(header + "Surface \"agree\"\n" + turn + polygon(0, 32, 0, 32, 10, true) + "WorldEnd\n");
        EXPECT_NEAR(r.channel(0, 16, 16, 0), 1.0f, 1e-4f) << turn;
        EXPECT_EQ(r.channel(0, 16, 16, 1), 0.0f) << turn;
    }
}

}  // namespace
}  // namespace streyes
