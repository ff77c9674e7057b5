// A moving camera over a still world (issue 48): bodies still in world space are split and diced
// once for a chunk of up to 16 frames (render/bucket_world.cpp) and shaded once for it only where
// their shading cannot change with the view. A frame's pixels still never depend on its block,
// occlusion culling at tolerance 0 still changes nothing, and the micropolygons of a pan come
// near those of a still camera.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "test_util.h"

namespace streyes {
namespace {

const FrameImage* findFrame(const test::RenderResult& r, int frame) {
    for (const FrameImage& f : r.frames)
        if (f.frame == frame) return &f;
    return nullptr;
}

bool sameFrame(const FrameImage& a, const FrameImage& b) {
    test::RenderResult ra, rb;
    ra.frames = {a};
    rb.frames = {b};
    return test::identicalPixels(ra, rb);
}

// A still world (a matte floor, a constant card, a plastic sphere and a matte subdivision cube)
// under a camera that pans and dollies over 16 frames. `camera` replaces the camera block.
std::string panScene(const std::string& camera, const std::string& sphereSurface = "plastic") {
    return R"(Format 192 128 1
Projection "perspective" "fov" [45]
PixelSamples 2 2
Shutter 0 0.5
Option "streyes" "int frames" [0 15]
)" + camera + R"(
WorldBegin
LightSource "ambientlight" 1 "intensity" [0.2]
LightSource "distantlight" 2 "from" [-1 2 -1] "to" [0 0 0] "intensity" [1]
AttributeBegin
  Surface "matte"
  Color [0.6 0.6 0.5]
  Patch "bilinear" "P" [-6 -1 -2  6 -1 -2  -6 -1 12  6 -1 12]
AttributeEnd
AttributeBegin
  Surface "constant"
  Color [0.9 0.2 0.1]
  Patch "bilinear" "P" [-3 0.5 6  -1.5 0.5 6  -3 2 6  -1.5 2 6]
AttributeEnd
AttributeBegin
  Surface ")" + sphereSurface + R"(" "roughness" [0.05] "Ks" [1]
  Color [0.2 0.3 0.8]
  Translate 0.5 0 5
  Sphere 1 -1 1 360
AttributeEnd
AttributeBegin
  Surface "matte"
  Color [0.3 0.8 0.3]
  Translate 2.5 -0.4 7
  Rotate 30 0 1 0
  Scale 0.6 0.6 0.6
  SubdivisionMesh "catmull-clark" [4 4 4 4 4 4] [0 1 3 2 2 3 5 4 4 5 7 6 6 7 1 0 1 7 5 3 6 0 2 4]
    ["interpolateboundary"] [0 0] [] []
    "P" [-1 -1 1  1 -1 1  -1 1 1  1 1 1  -1 1 -1  1 1 -1  -1 -1 -1  1 -1 -1]
AttributeEnd
WorldEnd
)";
}

// Issue 48's slow pan and dolly (its creases.rib shot): keyed from Translate 0.4 0 0 at frame 0 to
// Translate -0.4 0 0.5 at frame 16.
const char* kPan = R"(MotionBegin [0 16]
  Translate 0.4 0 0
  Translate -0.4 0 0.5
MotionEnd)";
const char* kStill = "Translate 0.4 0 0";

// The same pan keyed every frame, as a baked camera curve is: 17 keys on the line
// kPan interpolates. Its keys add nothing to the motion (bodies/motion_segments.h, keysOf).
std::string panKeyedEveryFrame() {
    std::string s = "MotionBegin [";
    for (int f = 0; f <= 16; ++f) s += std::to_string(f) + (f < 16 ? " " : "]\n");
    for (int f = 0; f <= 16; ++f) {
        char buf[128];
        std::snprintf(buf, sizeof buf, "  Translate %.17g 0 %.17g\n", 0.4 - 0.05 * f, 0.03125 * f);
        s += buf;
    }
    return s + "MotionEnd";
}

// A camera keyed every frame that turns on an arc (its keys are not on one line): still a root
// per frame, and still each frame's pixels alone.
std::string arcKeyedEveryFrame() {
    std::string s = "MotionBegin [";
    for (int f = 0; f <= 16; ++f) s += std::to_string(f) + (f < 16 ? " " : "]\n");
    for (int f = 0; f <= 16; ++f) {
        const double a = 0.03 * (f - 8);
        char buf[320];
        std::snprintf(buf, sizeof buf, "  ConcatTransform [%.17g 0 %.17g 0  0 1 0 0  %.17g 0 %.17g 0  %.17g 0 %.17g 1]\n",
                      std::cos(a), -std::sin(a), std::sin(a), std::cos(a), 0.4 * std::sin(a * 4), 0.3 * (1 - std::cos(a * 4)));
        s += buf;
    }
    return s + "MotionEnd";
}

RenderOptions shotOptions(Algorithm a, int first, int last, int block) {
    RenderOptions o;
    o.algorithm = a;
    o.hasShot = true;
    o.shotFirst = 0;
    o.shotLast = 15;
    o.hasFrames = true;
    o.firstFrame = first;
    o.lastFrame = last;
    o.maxFrameBlock = block;
    return o;
}

// Frames of a camera pan over still geometry: the 16 frames as one block, as blocks of 4 and of 1,
// and frames 5 and 12 alone, bit for bit; with and without occlusion culling (tolerance 0), which
// give each other's pixels too.
// The pan given as one motion segment, keyed every frame, and an arc keyed every frame.
TEST(CameraWorld, APanOverStillGeometryGivesEachFrameItsPixelsAlone) {
  for (const std::string& camera : {std::string(kPan), panKeyedEveryFrame(), arcKeyedEveryFrame()}) {
    SCOPED_TRACE(camera.substr(0, 60));
    const std::string rib = panScene(camera);
    // The arc changes nothing on the still-in-world path (a root per frame): one algorithm.
    const bool arc = camera.find("ConcatTransform") != std::string::npos;
    // Its 192 x 128 pixels, halved under the sanitizers: the frames agree bit for bit at any size.
    auto panOptions = [](Algorithm a, int first, int last, int block) {
        RenderOptions o = shotOptions(a, first, last, block);
        test::halfResolutionUnderSanitizers(o, 192, 128);
        return o;
    };
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Spacetime, Algorithm::FramesOcclusion}) {
        if (arc && a != Algorithm::SpacetimeOcclusion) continue;
        SCOPED_TRACE(algorithmName(a));
        const test::RenderResult whole = test::renderRib(rib, panOptions(a, 0, 15, 16));
        ASSERT_EQ(whole.frames.size(), 16u);
        const test::RenderResult fours = test::renderRib(rib, panOptions(a, 0, 15, 4));
        EXPECT_TRUE(test::identicalPixels(whole, fours)) << "max " << test::maxAbsDifference(whole, fours);
        for (int f : {5, 12}) {
            const test::RenderResult alone = test::renderRib(rib, panOptions(a, f, f, 16));
            ASSERT_EQ(alone.frames.size(), 1u);
            EXPECT_TRUE(sameFrame(*findFrame(whole, f), alone.frames[0])) << "frame " << f << " alone differs";
        }
        if (a == Algorithm::SpacetimeOcclusion) {
            // The still-in-world path ran: fewer grids than the frames' own (one block of 16).
            const test::RenderResult ones = test::renderRib(rib, panOptions(a, 0, 15, 1));
            EXPECT_TRUE(test::identicalPixels(whole, ones));
            const test::RenderResult plain = test::renderRib(rib, panOptions(Algorithm::Spacetime, 0, 15, 16));
            EXPECT_TRUE(test::identicalPixels(whole, plain)) << "occlusion culling at tolerance 0 changed pixels";
        }
    }
  }
}

// A plastic sphere's highlight slides across it as the camera passes: shading that reads the view
// is not shared between frames. Each frame in the block is the frame alone, and is within rounding
// of the frame rendered as a shot of its own (one exposure: diced and shaded for that frame only,
// as before). Shared over the 16 frames, the highlight would cross-fade between the chunk's ends.
TEST(CameraWorld, ASlidingHighlightIsShadedPerFrame) {
  for (const std::string& camera : {std::string(kPan), panKeyedEveryFrame()}) {
    SCOPED_TRACE(camera.substr(0, 60));
    const std::string rib = panScene(camera);
    const test::RenderResult whole = test::renderRib(rib, shotOptions(Algorithm::SpacetimeOcclusion, 0, 15, 16));
    for (int f : {2, 8, 13}) {
        SCOPED_TRACE(f);
        const test::RenderResult alone = test::renderRib(rib, shotOptions(Algorithm::SpacetimeOcclusion, f, f, 16));
        EXPECT_TRUE(sameFrame(*findFrame(whole, f), alone.frames[0]));
        RenderOptions own = shotOptions(Algorithm::SpacetimeOcclusion, f, f, 16);
        own.shotFirst = own.shotLast = f;  // a shot of one frame: every piece spans one exposure
        const test::RenderResult single = test::renderRib(rib, own);
        test::RenderResult inBlock;
        inBlock.frames = {*findFrame(whole, f)};
        // The grids differ by rounding (interpolated from the chunk's ends or diced at the
        // exposure's), so a few samples on edges flip; the highlight itself agrees.
        EXPECT_LT(test::meanAbsDifference(inBlock, single), 2e-3f);
    }
    // The highlight moves: its brightest pixel on the sphere is not where it was.
    auto brightest = [](const FrameImage& im) {
        size_t best = 0;
        float v = -1;
        for (size_t i = 0; i < im.rgba.size() / 4; ++i) {
            const float g = im.rgba[i * 4 + 1];  // the sphere is blue: green is mostly highlight
            if (g > v) v = g, best = i;
        }
        return std::pair<int, float>(int(best % size_t(im.width)), v);
    };
    const auto b0 = brightest(*findFrame(whole, 0)), b15 = brightest(*findFrame(whole, 15));
    EXPECT_GT(b0.second, 0.5f);
    EXPECT_NE(b0.first, b15.first);
  }
}

// Micropolygons of a still world under a camera move over a 16-frame block: at most 1.5 times
// those of the same block with the camera still (issue 48's acceptance). Before, every frame diced
// its own (about 16 times). The sphere is matte here: plastic's highlight is shaded per frame, but
// its grids are diced once all the same.
TEST(CameraWorld, APanDicesAboutAsManyMicropolygonsAsAStillCamera) {
    RenderOptions o = shotOptions(Algorithm::SpacetimeOcclusion, 0, 15, 16);
    o.threads = 1;
    for (const std::string surface : {"matte", "plastic"}) {
        SCOPED_TRACE(surface);
        const test::RenderResult still = test::renderRib(panScene(kStill, surface), o);
        const double fixed = double(still.stats.counters.micropolygons);
        ASSERT_GT(fixed, 1000.0);
        // The pan as one motion segment and keyed every frame (before, a root per frame: 16 times).
        for (const std::string& camera : {std::string(kPan), panKeyedEveryFrame()}) {
            const test::RenderResult pan = test::renderRib(panScene(camera, surface), o);
            const double moving = double(pan.stats.counters.micropolygons);
            EXPECT_LE(moving, 1.5 * fixed) << moving << " micropolygons under " << camera.substr(0, 40) << ", " << fixed
                                           << " still";
        }
    }
}

// Plastic's highlight is shaded per frame, and its pieces, swept over the chunk, reach several
// buckets: each bucket shades (built-in surfaces) only the vertices of the quads its samples can
// reach in the frame (bucket_world.cpp, markSeenHere). The pan with every surface plastic renders
// the same frames bit for bit with 16-pixel and 64-pixel buckets (a vertex left unshaded where it
// is sampled would show at the small buckets' borders), and the small buckets shade under twice
// the points of the large ones (1.78 times; before, when each bucket shaded every frame's whole
// grid, 2.48 times).
TEST(CameraWorld, EachBucketShadesOnlyWhatItSamplesOfAFramesGrid) {
    std::string rib = panScene(kPan);
    for (size_t at; (at = rib.find("\"matte\"")) != std::string::npos;) rib.replace(at, 7, "\"plastic\"");
    RenderOptions o = shotOptions(Algorithm::SpacetimeOcclusion, 0, 15, 16);
    o.threads = 1;
    o.bucketSize = 64;
    const test::RenderResult large = test::renderRib(rib, o);
    o.bucketSize = 16;
    const test::RenderResult small = test::renderRib(rib, o);
    ASSERT_EQ(large.frames.size(), 16u);
    EXPECT_TRUE(test::identicalPixels(large, small)) << "max " << test::maxAbsDifference(large, small);
    const double pointsLarge = double(large.stats.counters.pointsShadedBuiltin);
    const double pointsSmall = double(small.stats.counters.pointsShadedBuiltin);
    ASSERT_GT(pointsLarge, 0.0);
    EXPECT_LT(pointsSmall, 2.0 * pointsLarge) << pointsSmall << " points in 16-pixel buckets, " << pointsLarge << " in 64";
}

}  // namespace
}  // namespace streyes
