// DepthOfField: the request read, the lens samples, and the blur rendered against the thin-lens
// circle of confusion computed here from the request's numbers (not from the camera's helpers).
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "raster/sample_pattern.h"
#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::RenderResult;

Scene parse(const std::string& text, Log& log) { return parseRibString(text, "test.rib", log); }

TEST(DepthOfField, RequestLandsInTheCamera) {
    Log log;
    Scene s = parse("Projection \"perspective\"\nDepthOfField 2.8 0.05 3.5\nWorldBegin\nWorldEnd\n", log);
    EXPECT_TRUE(s.camera.depthOfField());
    EXPECT_DOUBLE_EQ(s.camera.fstop, 2.8);
    EXPECT_DOUBLE_EQ(s.camera.focalLength, 0.05);
    EXPECT_DOUBLE_EQ(s.camera.focalDistance, 3.5);
    EXPECT_TRUE(log.warnings().empty());
    // No arguments, or RI_INFINITY as RIB writers give it: a pinhole again.
    s = parse("Projection \"perspective\"\nDepthOfField 2 1 3\nDepthOfField\nWorldBegin\nWorldEnd\n", log);
    EXPECT_FALSE(s.camera.depthOfField());
    s = parse("Projection \"perspective\"\nDepthOfField 1e38 1 3\nWorldBegin\nWorldEnd\n", log);
    EXPECT_FALSE(s.camera.depthOfField());
    EXPECT_FALSE(parse("WorldBegin\nWorldEnd\n", log).camera.depthOfField());  // the default
}

TEST(DepthOfField, BadValuesNameFileAndLine) {
    for (const char* bad : {"DepthOfField 0 1 3", "DepthOfField -2 1 3", "DepthOfField 2 0 3", "DepthOfField 2 1 -1",
                            "DepthOfField 2 1", "DepthOfField 2 1 3 4", "DepthOfField 2 \"a\" 3"}) {
        const std::string rib = std::string("Projection \"perspective\"\n\n") + bad + "\nWorldBegin\nWorldEnd\n";
        const std::string e = test::ribError(rib);
        EXPECT_NE(e.find("bad.rib:3"), std::string::npos) << bad << ": " << e;
    }
    // An option: not inside the world (skipped there with a warning, as the peers do; an error
    // under --strict).
    EXPECT_NE(test::ribError("WorldBegin\nDepthOfField 2 1 3\nWorldEnd\n", true), "");
}

TEST(DepthOfField, OrthographicWarnsAndIgnoresIt) {
    Log log;
    Scene s = parse("DepthOfField 2 1 3\nWorldBegin\nWorldEnd\n", log);
    EXPECT_FALSE(s.camera.depthOfField());
    ASSERT_EQ(log.warnings().size(), 1u);
    EXPECT_NE(log.warnings()[0].find("orthographic"), std::string::npos);
    EXPECT_NE(log.warnings()[0].find("test.rib:1"), std::string::npos);
}

// Lens positions lie in the unit disc, one in each of S strata of it (the concentric map keeps
// areas: as many in each half and quadrant as the stratification gives), and are not the
// positions' strata: the lens stratum of sample j is not its (x, y) stratum throughout.
TEST(DepthOfField, LensSamplesAreStratifiedOnTheDisc) {
    SamplePattern sp;
    sp.sx = sp.sy = 8;
    const PatternTable t(sp);
    for (int p = 0; p < t.patternCount(); ++p) {
        const float* l = t.lens(p);
        const float* o = t.offsets(p);
        int right = 0, top = 0, quadrants[4] = {0, 0, 0, 0};
        double correlation = 0;
        for (int j = 0; j < t.samples(); ++j) {
            const float u = l[2 * j], v = l[2 * j + 1];
            ASSERT_LE(u * u + v * v, 1.0f + 1e-6f);
            right += u > 0;
            top += v > 0;
            ++quadrants[(u > 0) + 2 * (v > 0)];
            correlation += double(u) * (double(o[2 * j]) - 0.5);
        }
        EXPECT_EQ(right, 32);
        EXPECT_EQ(top, 32);
        for (int q : quadrants) EXPECT_EQ(q, 16);
        EXPECT_LT(std::fabs(correlation / 64), 0.1) << "lens u follows the sample's x in pattern " << p;
    }
}

// A strip `widthPx` pixels wide at depth z, taller than the image: its image along a row is the
// strip's box convolved with the circle of confusion's line spread (a disc of radius r projected
// on x, variance r^2 / 4) and the pixel's box (variance 1/12). The row's alpha variance about
// its centroid, less the strip's w^2 / 12 and the pixel's 1/12, is r^2 / 4.
RenderResult renderStrip(double fstop, double focalLength, double focalDistance, double z, double widthPx,
                         Algorithm algorithm = Algorithm::Spacetime) {
    const int W = 64;
    const double ax = (1 / std::tan(20 * M_PI / 180)) * W / 2;  // fov 40 across 64 square pixels
    const double half = 0.5 * widthPx * z / ax, tall = 2 * z;
    std::ostringstream rib;
    rib << "Format " << W << " " << W << " 1\nProjection \"perspective\" \"fov\" [40]\nClipping 0.1 100\n"
        << "DepthOfField " << fstop << " " << focalLength << " " << focalDistance << "\n"
        << "PixelSamples 8 8\nPixelFilter \"box\" 1 1\nWorldBegin\nSurface \"constant\"\n"
        << test::square(-half, half, -tall, tall, z) << "WorldEnd\n";
    return test::renderRib(rib.str(), test::optionsFor(algorithm));
}

double measuredCocRadius(double fstop, double focalLength, double focalDistance, double z, double widthPx,
                         Algorithm algorithm = Algorithm::Spacetime) {
    const int W = 64;
    const RenderResult r = renderStrip(fstop, focalLength, focalDistance, z, widthPx, algorithm);
    double variance = 0;
    int rows = 0;
    for (int y = 16; y < 48; ++y) {
        double sum = 0, first = 0, second = 0;
        for (int x = 0; x < W; ++x) {
            const double a = r.alpha(0, x, y), c = x + 0.5;
            sum += a, first += a * c, second += a * c * c;
        }
        EXPECT_NEAR(sum, widthPx, 0.05 * widthPx) << "row " << y << ": coverage is conserved";
        const double mean = first / sum;
        EXPECT_NEAR(mean, W / 2.0, 0.25);
        variance += second / sum - mean * mean;
        ++rows;
    }
    variance /= rows;
    const double r2 = 4 * (variance - widthPx * widthPx / 12 - 1.0 / 12);
    return r2 > 0 ? std::sqrt(r2) : -std::sqrt(-r2);
}

// The thin lens from the request's numbers: lens radius f / (2 N); a point at depth z seen through
// the lens edge meets the focal plane R (1 - d / z) off axis, at screen offset R |1/d - 1/z|.
double thinLensCoc(double fstop, double focalLength, double focalDistance, double z) {
    const double R = focalLength / (2 * fstop);
    const double ax = (1 / std::tan(20 * M_PI / 180)) * 64 / 2;
    return R * std::fabs(1 / focalDistance - 1 / z) * ax;
}

TEST(DepthOfField, BlurBehindTheFocusIsTheThinLensCircle) {
    const double expected = thinLensCoc(1, 0.5, 2, 10);  // 8.8 pixels
    ASSERT_GT(expected, 8);
    EXPECT_NEAR(measuredCocRadius(1, 0.5, 2, 10, 6), expected, 0.04 * expected);
}

TEST(DepthOfField, BlurInFrontOfTheFocusIsTheThinLensCircle) {
    const double expected = thinLensCoc(1, 0.5, 2, 1.2);  // 7.3 pixels
    EXPECT_NEAR(measuredCocRadius(1, 0.5, 2, 1.2, 6), expected, 0.04 * expected);
    // The same with occlusion culling and frame by frame.
    EXPECT_NEAR(measuredCocRadius(1, 0.5, 2, 1.2, 6, Algorithm::SpacetimeOcclusion), expected, 0.04 * expected);
    EXPECT_NEAR(measuredCocRadius(1, 0.5, 2, 1.2, 6, Algorithm::Frames), expected, 0.04 * expected);
    // The ray tracer's eye rays from the lens points.
    EXPECT_NEAR(measuredCocRadius(1, 0.5, 2, 1.2, 6, Algorithm::Raytrace), expected, 0.04 * expected);
    EXPECT_NEAR(measuredCocRadius(1, 0.5, 2, 10, 6, Algorithm::Raytrace), thinLensCoc(1, 0.5, 2, 10),
                0.04 * thinLensCoc(1, 0.5, 2, 10));
}

// A strip on the focal plane with its edges on pixel borders: every pixel wholly in or out.
TEST(DepthOfField, TheFocalPlaneStaysSharp) {
    const RenderResult r = renderStrip(1, 0.5, 4, 4, 6);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            EXPECT_NEAR(r.alpha(0, x, y), x >= 29 && x < 35 ? 1.0f : 0.0f, 1e-6f) << x << " " << y;
}

// fstop RI_INFINITY is the pinhole: the same pixels as no request at all.
TEST(DepthOfField, InfiniteFstopIsThePinholeBitForBit) {
    const std::string head = "Format 32 24 1\nProjection \"perspective\" \"fov\" [40]\nClipping 0.1 100\n";
    const std::string world = "WorldBegin\nSurface \"constant\"\n" + test::square(-1, 0.5, -0.5, 1, 5) +
                              "Color [1 0 0]\n" + test::square(-0.2, 2, -1, 0.2, 3) + "WorldEnd\n";
    const RenderResult pinhole = test::renderRib(head + world);
    EXPECT_TRUE(test::identicalPixels(pinhole, test::renderRib(head + "DepthOfField 1e38 1 3\n" + world)));
    EXPECT_FALSE(test::identicalPixels(pinhole, test::renderRib(head + "DepthOfField 2 1 3\n" + world)));
}

// scenes/dof.rib larger than the scene lists render it (EveryScene, FrameBlockInvariance): at
// tolerance 0 occlusion culling drops bodies whose grown bounds are covered, and not one pixel
// changes; the blur reaches across bucket borders, which the grown view bounds keep.
TEST(DepthOfField, OcclusionCullingAtToleranceZeroIsBitIdentical) {
    Log log;
    const Scene scene = parseRibFile(test::sourcePath("scenes/dof.rib"), log);
    RenderOptions o;
    o.xres = 120;
    o.yres = 80;
    o.bucketSize = 16;
    o.hasFrames = true;
    o.firstFrame = 0;
    o.lastFrame = 2;
    o.algorithm = Algorithm::Spacetime;
    const RenderResult plain = test::renderScene(scene, o);
    o.algorithm = Algorithm::SpacetimeOcclusion;
    const RenderResult culled = test::renderScene(scene, o);
    EXPECT_TRUE(test::identicalPixels(plain, culled)) << "max " << test::maxAbsDifference(plain, culled);
    EXPECT_GT(culled.stats.counters.culledOcclusion + culled.stats.counters.culledHidden, 0u);  // not vacuous
    o.algorithm = Algorithm::Frames;
    const RenderResult frames = test::renderScene(scene, o);
    o.algorithm = Algorithm::FramesOcclusion;
    EXPECT_TRUE(test::identicalPixels(frames, test::renderScene(scene, o)));
}

// The blur of a moving body reaches pixels a circle of confusion beyond its own bound, in the
// bucket beside it too: the moving sampler skipped a group of slices whose unblurred bound missed
// the bucket, so scenes/dof.rib's frame 19 differed between 32 and 64-pixel buckets in four
// pixels on a bucket border (x = 159, the moving sphere's blur; 0.009 at most).
TEST(DepthOfField, MovingBlurIsTheSameWhateverTheBucketSize) {
    Log log;
    const Scene scene = parseRibFile(test::sourcePath("scenes/dof.rib"), log);
    RenderOptions o;
    o.hasFrames = true;
    o.firstFrame = 18;
    o.lastFrame = 19;
    o.samples = 4;
    o.algorithm = Algorithm::Frames;
    std::vector<RenderResult> byBucket;
    for (int bucket : {64, 32, 16}) {
        o.bucketSize = bucket;
        byBucket.push_back(test::renderScene(scene, o));
    }
    for (size_t i = 1; i < byBucket.size(); ++i)
        EXPECT_TRUE(test::identicalPixels(byBucket[0], byBucket[i]))
            << "bucket " << (i == 1 ? 32 : 16) << ": max " << test::maxAbsDifference(byBucket[0], byBucket[i]);
}

}  // namespace
}  // namespace streyes
