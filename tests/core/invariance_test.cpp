// A frame's pixels never depend on the block of frames it is rendered in: render farms cut shots
// into blocks, and the memory budget shrinks blocks on smaller machines. Every scene in scenes/
// and scenes/hard/, three frames rendered as one block, as blocks of one frame, and the middle
// frame on its own: bit-identical, with the rasterizer and with the ray tracer. (Files of several
// worlds, depth frames and pictures, render as passes: tests/cli/multipass_scenes_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

std::vector<std::string> everyScene() { return test::sceneFiles(false); }

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

class FrameBlockInvariance : public testing::TestWithParam<std::string> {};

TEST_P(FrameBlockInvariance, AFramesPixelsDoNotDependOnItsBlock) {
    if (test::slowUnderSanitizers(GetParam())) GTEST_SKIP() << "minutes under the sanitizers: the release suite runs it";
    Log log;
    Scene scene = parseRibFile(test::sourcePath(GetParam()), log);
    RenderOptions o;
    o.xres = 64;
    o.yres = std::max(1, scene.camera.yres * 64 / scene.camera.xres);
    o.samples = 4;
    const int first = scene.settings.hasFrames ? scene.settings.firstFrame : 0;
    o.hasShot = true;  // the shot is fixed; which of its frames are rendered together varies
    o.shotFirst = first;
    o.shotLast = first + 2;
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Frames, Algorithm::Raytrace}) {
        if (a == Algorithm::Raytrace && test::tooLargeToRayTrace(GetParam())) continue;
        SCOPED_TRACE(algorithmName(a));
        o.algorithm = a;
        o.hasFrames = true;
        o.firstFrame = first;
        o.lastFrame = first + 2;
        o.maxFrameBlock = 3;
        const test::RenderResult together = test::renderScene(scene, o);
        o.maxFrameBlock = 1;
        const test::RenderResult apart = test::renderScene(scene, o);
        o.firstFrame = o.lastFrame = first + 1;
        o.maxFrameBlock = 64;
        const test::RenderResult alone = test::renderScene(scene, o);
        ASSERT_EQ(together.frames.size(), 3u);
        // The one exception: geometry that exhausts its split budget (a warning says pieces were
        // dropped). With occlusion culling, which pieces reach the budget depends on when depth
        // layers close, and layers close on the coverage of every frame of the bucket.
        const bool dropped = std::any_of(together.warnings.begin(), together.warnings.end(), [](const std::string& w) {
            return w.find("splits in one bucket") != std::string::npos;
        });
        if (dropped && usesOcclusion(a)) continue;
        EXPECT_TRUE(test::identicalPixels(together, apart)) << "blocks of three frames and of one frame differ: max "
                                                            << test::maxAbsDifference(together, apart) << " mean "
                                                            << test::meanAbsDifference(together, apart);
        const FrameImage* middle = findFrame(together, first + 1);
        ASSERT_NE(middle, nullptr);
        EXPECT_TRUE(sameFrame(*middle, alone.frames.at(0))) << "the middle frame rendered alone differs";
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, FrameBlockInvariance, testing::ValuesIn(everyScene()),
                         [](const testing::TestParamInfo<std::string>& info) {
                             std::string name = info.param.substr(0, info.param.size() - 4);
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

// The review's case: a still matte wall under a point light that moves away. The wall's shading
// changes every frame although the wall does not move; inside a block it was shaded once (frame 4
// had mean RGB 0.62 inside frames 0-4 and 0.002 alone). Rendered alone or in a block, frame 4 is
// the same, and agrees with the ray tracer, which shades every sample at its own time.
TEST(FrameBlockInvariance, StillWallUnderAMovingLightIsShadedPerFrame) {
    const std::string rib = R"(Format 32 32 1
Projection "orthographic"
ScreenWindow -1 1 -1 1
PixelSamples 2 2
Option "streyes" "int frames" [0 4]
WorldBegin
MotionBegin [0 4]
  Translate 0 0 0
  Translate 0 0 -40
MotionEnd
LightSource "pointlight" 1 "from" [0 0 -1] "intensity" [2]
Identity
Surface "matte"
Patch "bilinear" "P" [-1 -1 1  1 -1 1  -1 1 1  1 1 1]
WorldEnd
)";
    auto meanRed = [](const test::RenderResult& r, int frame) {
        const FrameImage* f = findFrame(r, frame);
        double sum = 0;
        for (size_t i = 0; i < f->rgba.size(); i += 4) sum += f->rgba[i];
        return sum / double(f->rgba.size() / 4);
    };
    RenderOptions o;
    const test::RenderResult block = test::renderRib(rib, o);
    o.hasFrames = true;
    o.firstFrame = o.lastFrame = 4;
    const test::RenderResult alone = test::renderRib(rib, o);
    o.algorithm = Algorithm::Raytrace;
    const test::RenderResult traced = test::renderRib(rib, o);
    EXPECT_TRUE(sameFrame(*findFrame(block, 4), alone.frames.at(0)));
    // At frame 4 the light is 42 units from the wall: about 2 / 42^2 = 0.0011 at its centre.
    EXPECT_LT(meanRed(alone, 4), 0.002);
    EXPECT_NEAR(meanRed(alone, 4), meanRed(traced, 4), 1e-4);
    // At frame 0 it is 2 units away: 0.5 at the centre, falling off towards the corners.
    EXPECT_GT(meanRed(block, 0), 0.2);
}


// Leaves keyed every other frame of a 65-frame shot, turning under a moving camera and casting
// shadows on a wall: one frame rendered alone keeps only the keys the chunks of its frames reach
// (BodyFactory::addPatch, KeyedPatchBody::keysOver), and gives the pixels the whole shot gives
// it, rasterized frame by frame or in spacetime (shadow rays trace the leaves) and ray traced.
TEST(FrameBlockInvariance, OneFrameOfALongKeyedShotKeepsOnlyItsOwnKeys) {
    std::string rib = "Option \"streyes\" \"int frames\" [0 64]\nFormat 48 32 1\nProjection \"perspective\" \"fov\" 40\n"
                      "PixelSamples 2 2\nShutter 0 0.5\nMotionBegin [0 64]\nTranslate 0 0 8\nTranslate -1 0 8\nMotionEnd\n"
                      "WorldBegin\nAttribute \"light\" \"shadows\" \"on\"\n"
                      "LightSource \"distantlight\" 1 \"from\" [-1 1 -2] \"to\" [0 0 0]\nSurface \"matte\"\n"
                      "Patch \"bilinear\" \"P\" [-6 -4 1.5  6 -4 1.5  -6 4 1.5  6 4 1.5]\n";
    std::string times;
    for (int k = 0; k <= 32; ++k) times += std::to_string(2 * k) + (k < 32 ? " " : "");
    for (int leaf = 0; leaf < 6; ++leaf) {
        rib += "AttributeBegin\nColor [" + std::to_string(0.2 + 0.15 * leaf) + " 0.6 0.3]\nTranslate " +
               std::to_string(-2.5 + leaf) + " " + std::to_string(0.4 * (leaf % 3) - 0.4) + " 0\nMotionBegin [" + times + "]\n";
        for (int k = 0; k <= 32; ++k) rib += "Rotate " + std::to_string(25 * std::sin(0.7 * k + leaf)) + " 0 0 1\n";
        rib += "MotionEnd\nPatch \"bilinear\" \"P\" [-0.4 -0.3 0  0.4 -0.3 0  -0.4 0.3 0  0.4 0.3 0]\nAttributeEnd\n";
    }
    rib += "WorldEnd\n";
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Frames, Algorithm::Raytrace}) {
        SCOPED_TRACE(algorithmName(a));
        const test::ShotAndFrame r = test::renderShotAndFrame(rib, test::optionsFor(a), 0, 64, 13);
        EXPECT_TRUE(r.samePixels(13));
        EXPECT_GT(test::alphaSum(r.alone, 13), 1000.0);  // the wall fills the frame (48 x 32)
        // Each leaf holds 33 keys for the shot; frame 13 alone, those of a chunk of frames either side.
        EXPECT_LT(r.alone.stats.memoryBodiesBytes * 2, r.shot.stats.memoryBodiesBytes);
        EXPECT_GT(r.alone.stats.counters.shadowRays, 0u);
    }
}

// --layers N spaces its layers over the depth of the whole shot's bodies: a deforming mesh keyed
// every frame of a 16-frame shot, receding from depth 4 to 40, gives frame 5 rendered alone the
// layers the shot gives it, although frame 5's render scene holds only its own segments.
TEST(FrameBlockInvariance, LayerDepthsComeFromTheWholeShot) {
    const std::string rib = "Option \"streyes\" \"int frames\" [0 15]\nFormat 32 24 1\nProjection \"perspective\" \"fov\" 40\n"
                            "Clipping 0.5 100\nPixelSamples 2 2\nShutter 0 0.5\nWorldBegin\nSurface \"constant\"\n" +
                            test::keyedSheet(16, [](int k, int i, int j) {
                                return std::array<double, 3>{-1.0 + i, -1.0 + j, 4 + 36.0 * k / 16};
                            }) +
                            "Patch \"bilinear\" \"P\" [-30 -20 60  30 -20 60  -30 20 60  30 20 60]\nWorldEnd\n";
    RenderOptions o;
    o.layers = 4;
    o.tolerance = 0.05;
    const test::ShotAndFrame r = test::renderShotAndFrame(rib, o, 0, 15, 5);
    ASSERT_EQ(r.shot.stats.layerDepths.size(), 3u);
    EXPECT_EQ(r.alone.stats.layerDepths, r.shot.stats.layerDepths);
    // Geometric from the mesh's nearest depth (about 4) to the wall (60).
    EXPECT_LT(r.shot.stats.layerDepths.front(), 10.0f);
    EXPECT_GT(r.shot.stats.layerDepths.back(), 20.0f);
    EXPECT_TRUE(r.samePixels(5));
}

}  // namespace
}  // namespace streyes
