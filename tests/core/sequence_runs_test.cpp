// Still runs over the whole input (streyes/sequence.h, RunTable): a block's runs live over their
// frames in the input within their epoch, so a frame renders the same alone and in every block,
// swaying procedurals included.
#include <gtest/gtest.h>

#include <fstream>

#include "streyes/passes.h"
#include "streyes/sequence.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::renderScene;
using test::RenderResult;

RenderResult oneFrame(const RenderResult& r, int f) {
    RenderResult one;
    one.frames.push_back(r.frame(f));
    return one;
}

// A file of FrameBegin blocks, one per frame number, each from `frame`.
std::string writeFrames(const test::TempDir& dir, int first, int last, const std::function<std::string(int)>& frame) {
    const std::string path = dir.path() + "/shot.rib";
    std::ofstream out(path);
    for (int f = first; f <= last; ++f) out << frame(f);
    return path;
}

Sequence readFrames(const std::string& path, int first, int last) {
    Log log;
    return readScene(path, FrameRequest{true, first, last}, log);
}

// A forest and grass whose children sway between motion keys 16 frames apart, the same procedural
// calls every frame: each call is one still run.
std::string swayingFrame(int f) {
    return "FrameBegin " + std::to_string(f) +
           "\nFormat 64 40 1\nPixelSamples 2 2\nShutter 0 0.5\nProjection \"perspective\" \"fov\" [50]\n"
           "Rotate 12 1 0 0\nTranslate 0 -5 14\nWorldBegin\n"
           "LightSource \"distantlight\" 1 \"from\" [-5 10 -5] \"to\" [0 0 0] \"intensity\" [1.2]\n"
           "LightSource \"ambientlight\" 2 \"intensity\" [0.2]\n"
           "AttributeBegin\nSurface \"matte\"\n"
           "Procedural \"DynamicLoad\" [\"forest\" \"count=2 seed=5 area=6,6 wind=3 period=40 keystep=16\"] "
           "[-12 12 -1 30 -12 12]\nAttributeEnd\n"
           "AttributeBegin\nSurface \"matte\"\nColor [0.2 0.5 0.1]\n"
           "Procedural \"DynamicLoad\" [\"grass\" \"seed=7 rect=-4,-4,4,2 density=20 height=1,2.5 width=0.06 "
           "wind=2 period=40 keystep=16\"] [-5 5 -0.5 2 -5 3]\nAttributeEnd\n"
           "WorldEnd\nFrameEnd\n";
}

// The children's motion over a frame was interpolated between corners at the block's ends (frame
// 1 alone: 1 and 1.5; in a block of 2: 1 and 2.5) and their pieces cut there: last-bit depths on
// the leaves, which a block of frames changed. Now they live over the run in the input.
TEST(SequenceRuns, SwayingProceduralFrameIsTheSameAloneAndInEveryBlock) {
    test::TempDir dir("seqruns");
    const std::string path = writeFrames(dir, 1, 3, swayingFrame);
    const Sequence three = readFrames(path, 1, 3);
    EXPECT_EQ(three.stats.stillRuns, 2u);  // each procedural one run over the three frames
    for (Algorithm a : {Algorithm::Spacetime, Algorithm::SpacetimeOcclusion}) {
        const RenderOptions o = test::optionsFor(a);
        const RenderResult r13 = renderScene(three.scene, o), r12 = renderScene(readFrames(path, 1, 2).scene, o);
        const RenderResult r23 = renderScene(readFrames(path, 2, 3).scene, o);
        const RenderResult r1 = renderScene(readFrames(path, 1, 1).scene, o);
        const RenderResult r2 = renderScene(readFrames(path, 2, 2).scene, o);
        ASSERT_GT(test::alphaSum(r1, 1), 40.0);  // the trees fill a share of the frame
        EXPECT_GT(test::meanAbsDifference(oneFrame(r13, 1), oneFrame(r13, 3)), 0.0f);  // they sway
        EXPECT_TRUE(test::identicalPixels(r1, oneFrame(r12, 1))) << "algorithm " << int(a);
        EXPECT_TRUE(test::identicalPixels(r1, oneFrame(r13, 1))) << "algorithm " << int(a);
        EXPECT_TRUE(test::identicalPixels(r2, oneFrame(r12, 2))) << "algorithm " << int(a);
        EXPECT_TRUE(test::identicalPixels(r2, oneFrame(r13, 2))) << "algorithm " << int(a);
        EXPECT_TRUE(test::identicalPixels(r2, oneFrame(r23, 2))) << "algorithm " << int(a);
        EXPECT_TRUE(test::identicalPixels(oneFrame(r13, 3), oneFrame(r23, 3))) << "algorithm " << int(a);
    }
}

// Across an epoch's end (frame 64 | 65) runs are cut whatever the block: frames 64 and 65 are the
// same alone and in a block over both epochs.
TEST(SequenceRuns, AFrameAtAnEpochsEdgeIsTheSameAloneAndInABlockAcrossIt) {
    test::TempDir dir("seqruns");
    const std::string path = writeFrames(dir, 62, 67, swayingFrame);
    const Sequence across = readFrames(path, 63, 66);
    EXPECT_EQ(across.stats.stillRuns, 4u);  // two procedurals, each a run a side of the cut
    EXPECT_EQ(across.scene.settings.shotFirst, 62);
    EXPECT_EQ(across.scene.settings.shotLast, 67);
    const RenderOptions o = test::optionsFor(Algorithm::SpacetimeOcclusion);
    const RenderResult block = renderScene(across.scene, o);
    for (int f : {63, 64, 65, 66}) {
        const RenderResult alone = renderScene(readFrames(path, f, f).scene, o);
        ASSERT_GT(test::alphaSum(alone, f), 40.0);
        EXPECT_TRUE(test::identicalPixels(alone, oneFrame(block, f))) << "frame " << f;
    }
}

// A run lives over its frames in the input, not the block's: a ball still over frames 1-3 that
// moves at frame 4 lives over 1-3 read with frame 2 alone, and is two runs read over 1-5.
TEST(SequenceRuns, ARunLivesOverItsFramesInTheInput) {
    auto frame = [](int f) {
        const double x = f <= 3 ? 0.0 : double(f);
        return "FrameBegin " + std::to_string(f) +
               "\nFormat 32 32 1\nShutter 0 0.5\nProjection \"perspective\" \"fov\" [40]\nTranslate 0 0 10\n"
               "WorldBegin\nAttributeBegin\nAttribute \"identifier\" \"name\" [\"ball\"]\nTranslate " +
               std::to_string(x) + " 0 0\nSphere 1 -1 1 360\nAttributeEnd\nWorldEnd\nFrameEnd\n";
    };
    test::TempDir dir("seqruns");
    const std::string path = writeFrames(dir, 1, 5, frame);
    const Sequence two = readFrames(path, 2, 2);
    ASSERT_EQ(two.scene.quadrics.size(), 1u);
    EXPECT_EQ(two.scene.quadrics[0].life.t0, 1.0);
    EXPECT_EQ(two.scene.quadrics[0].life.t1, 3.5);
    EXPECT_TRUE(two.scene.settings.hasShot);
    EXPECT_EQ(two.scene.settings.shotFirst, 1);
    EXPECT_EQ(two.scene.settings.shotLast, 3);
    const Sequence five = readFrames(path, 1, 5);
    ASSERT_EQ(five.scene.quadrics.size(), 3u);  // 1-3 still, then frames 4 and 5 each its own
    EXPECT_EQ(five.scene.quadrics[0].life.t1, 3.5);
    EXPECT_EQ(five.scene.quadrics[1].life.t0, 4.0);
    EXPECT_EQ(five.scene.quadrics[1].life.t1, 4.5);
    // Frame 4 read alone: a run of its own frame.
    const Sequence four = readFrames(path, 4, 4);
    ASSERT_EQ(four.scene.quadrics.size(), 1u);
    EXPECT_EQ(four.scene.quadrics[0].life.t0, 4.0);
    EXPECT_EQ(four.scene.quadrics[0].life.t1, 4.5);
}

}  // namespace
}  // namespace streyes
