// Weber–Penn trees rendered (Procedural "DynamicLoad" ["tree" "model=weberpenn ..."]): a frame
// alone is the frame in a block, the tree stands where its bound says with bark and leaves, the
// level of detail thins a distant tree without losing it, and a bad parameter is an error at the
// Procedural's line.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "procedural/weber_penn.h"
#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

int lineOf(const std::string& text, const std::string& needle) {
    const size_t at = text.find(needle);
    return 1 + int(std::count(text.begin(), text.begin() + long(at), '\n'));
}

// One quaking aspen (about 13 m) seen from `distance` m, 6 m up; its bound from weberPennBound.
std::string aspen(double distance, const std::string& extra = "", const std::string& camera = "") {
    WeberPennParams p = *weberPennPreset("quaking_aspen");
    p.seed = 2;
    if (extra.find("Wind") != std::string::npos)  // the wind widens the bound
        p = parseWeberPennParams("model=weberpenn preset=quaking_aspen seed=2 " + extra, {});
    const Bounds3d b = weberPennBound(p);
    std::ostringstream rib;
    rib << "Format 96 96 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 2 2\nShutter 0 0.5\n"
        << (camera.empty() ? "Translate 0 -7 " + std::to_string(distance) + "\n" : camera) << "WorldBegin\n"
        << "LightSource \"distantlight\" 1 \"from\" [-1 2 -1] \"to\" [0 0 0]\nLightSource \"ambientlight\" 2 \"intensity\" [0.3]\n"
        << "Surface \"matte\"\nProcedural \"DynamicLoad\" [\"tree\" \"model=weberpenn preset=quaking_aspen seed=2 " << extra
        << "\"] [" << b.lo.x << " " << b.hi.x << " " << b.lo.y << " " << b.hi.y << " " << b.lo.z << " " << b.hi.z
        << "]\nWorldEnd\n";
    return rib.str();
}

// Pixels of leaf green (green well above red and blue) and of bark (red at least green), at
// least half covered (colours are premultiplied: their ratios hold).
void countColours(const FrameImage& f, int* leaf, int* bark) {
    *leaf = *bark = 0;
    for (size_t i = 0; i < f.rgba.size(); i += 4) {
        const float r = f.rgba[i], g = f.rgba[i + 1], b = f.rgba[i + 2], a = f.rgba[i + 3];
        if (a < 0.5f) continue;
        if (g > 1.3f * r && g > 1.3f * b) ++*leaf;
        else if (r >= g && r > b) ++*bark;
    }
}

TEST(WeberPennRender, AFrameAloneIsTheFrameInABlock) {
    RenderOptions o;
    o.hasShot = true;
    o.shotFirst = 1;
    o.shotLast = 3;
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Frames}) {
        SCOPED_TRACE(algorithmName(a));
        o.algorithm = a;
        const test::ShotAndFrame r = test::renderShotAndFrame(aspen(35), o, 1, 3, 2);
        ASSERT_EQ(r.shot.frames.size(), 3u);
        EXPECT_TRUE(r.samePixels(2));
        EXPECT_TRUE(r.shot.warnings.empty()) << r.shot.warnings.front();  // nothing outgrew its bound
        int leaf = 0, bark = 0;
        countColours(r.alone.frames.at(0), &leaf, &bark);
        EXPECT_GT(leaf, 300) << "the crown's leaves";
        EXPECT_GT(bark, 5) << "the trunk";
        // The crown covers part of the frame, not all of it.
        const double alpha = test::alphaSum(r.alone, 2);
        EXPECT_GT(alpha, 600);
        EXPECT_LT(alpha, 0.6 * 96 * 96);
    }
}

// The paper's wind sway keys every branch over the shot: a frame alone is still the frame in a
// block (keys at multiples of keystep, whatever the block), nothing outgrows its bound, and the
// tree moves: the windy frames differ from each other and from the still tree.
TEST(WeberPennRender, AWindyTreesFrameAloneIsTheFrameInABlock) {
    const std::string windy = aspen(35, "WindSpeed=4 WindGust=2 keystep=1 windtime=200");
    RenderOptions o;
    o.hasShot = true;
    o.shotFirst = 1;
    o.shotLast = 3;
    o.algorithm = Algorithm::SpacetimeOcclusion;
    const test::ShotAndFrame r = test::renderShotAndFrame(windy, o, 1, 3, 2);
    ASSERT_EQ(r.shot.frames.size(), 3u);
    EXPECT_TRUE(r.samePixels(2));
    EXPECT_TRUE(r.shot.warnings.empty()) << r.shot.warnings.front();
    o.hasFrames = true;
    o.firstFrame = o.lastFrame = 1;
    const test::RenderResult still = test::renderRib(aspen(35), o);
    EXPECT_GT(test::differingPixels(r.shot.frames[0], still.frames.at(0), 0.05f), 50u) << "the wind moves the tree";
    EXPECT_GT(test::differingPixels(r.shot.frames[0], r.shot.frames[2], 0.05f), 50u) << "and it keeps moving";
}

// A camera dollying in from 60 m to 30 m changes the tree's level of detail (log2 of its raster
// area: about 3.4x larger from frame 1 to 3) within the block: each frame gets the
// children of its own level only, cut the same in any block (the runs of frames at one level do
// not end where the block does). Frame 2 of a 3-frame block differed from frame 2 alone (0.24% of
// pixels) before.
TEST(WeberPennRender, ALevelChangingUnderAMovingCameraKeepsAFrameAloneTheFrameInABlock) {
    const std::string rib = aspen(0, "", "MotionBegin [1 3]\nTranslate 0.5 -7 60\nTranslate -0.5 -7 30\nMotionEnd\n");
    RenderOptions o;
    o.hasShot = true;
    o.shotFirst = 1;
    o.shotLast = 3;
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Spacetime}) {
        SCOPED_TRACE(algorithmName(a));
        o.algorithm = a;
        const test::ShotAndFrame r = test::renderShotAndFrame(rib, o, 1, 3, 2);
        ASSERT_EQ(r.shot.frames.size(), 3u);
        EXPECT_TRUE(r.samePixels(2));
        EXPECT_GT(test::alphaSum(r.alone, 2), 300) << "the tree is there (about 500 pixels of crown)";
    }
}

// The paper's reduction for distant trees: fewer, larger leaves and no twigs under a quarter of
// a pixel; the distant tree still covers about what the same tree at full detail does.
TEST(WeberPennRender, ADistantTreeIsThinnedNotLost) {
    RenderOptions o;
    o.algorithm = Algorithm::Spacetime;
    const test::RenderResult far = test::renderRib(aspen(250), o);
    const test::RenderResult full = test::renderRib(aspen(250, "detail=1e6"), o);
    const test::RenderResult near = test::renderRib(aspen(35), o);
    EXPECT_LT(far.stats.bodiesGenerated * 5, full.stats.bodiesGenerated);
    EXPECT_LT(far.stats.bodiesGenerated, near.stats.bodiesGenerated);
    const double a = test::alphaSum(far), b = test::alphaSum(full);
    EXPECT_GT(b, 5);
    EXPECT_NEAR(a, b, 0.35 * b) << "the thinned crown covers about what the full one does";
}

// The cap on detail per pixel is decided over the shot, as the level is: a near windy aspen whose
// leaves are a sixth of a pixel long (0.006 m at about 29 pixels a metre), its branches 200-300
// pixels across, keeps 5% of them, grown; a frame alone is still the frame in a block.
TEST(WeberPennRender, ThePixelCapKeepsAFrameAloneTheFrameInABlock) {
    std::string rib = aspen(12, "LeafScale=0.006 WindSpeed=4 WindGust=2 keystep=1 windtime=200");
    rib.replace(rib.find("Format 96 96 1"), 14, "Format 256 256 1");
    RenderOptions o;
    o.hasShot = true;
    o.shotFirst = 1;
    o.shotLast = 3;
    o.algorithm = Algorithm::SpacetimeOcclusion;
    const test::ShotAndFrame r = test::renderShotAndFrame(rib, o, 1, 3, 2);
    ASSERT_EQ(r.shot.frames.size(), 3u);
    EXPECT_TRUE(r.samePixels(2));
    EXPECT_TRUE(r.shot.warnings.empty()) << r.shot.warnings.front();
    int leaf = 0, bark = 0;  // (the leaves' area is a few pixels' worth: what counts is the stems)
    countColours(r.alone.frames.at(0), &leaf, &bark);
    EXPECT_GT(bark, 300) << "the trunk and branches";
}

TEST(WeberPennRender, ABadParameterIsAnErrorAtTheProceduralsLine) {
    for (const char* bad : {"1Branchs=3", "preset=maple", "Levels=9", "model=oak"}) {
        const std::string rib = aspen(35, bad);
        // The generator is made when bodies are, before anything renders.
        try {
            test::renderRib(rib, {});
            ADD_FAILURE() << bad << " must be an error";
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find("test.rib:" + std::to_string(lineOf(rib, "Procedural"))), std::string::npos) << msg;
            EXPECT_NE(msg.find("tree"), std::string::npos) << msg;
        }
    }
}

}  // namespace
}  // namespace streyes
