// Occlusion culling end to end: with tolerance 0 the image never changes by a bit; the hidden
// geometry of scenes/occluded.rib is culled.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::RenderResult;

RenderOptions with(Algorithm a, int layers = 0, double tolerance = 0) {
    RenderOptions o = test::optionsFor(a);
    o.layers = layers;
    o.tolerance = tolerance;
    o.bucketSize = 16;
    return o;
}

// A floor slanting through every depth layer, an occluder, objects moving in depth behind it and
// one passing in front of it, and two coplanar patches (exact depth ties).
const char* kLayered = R"(Format 64 48 1
Projection "perspective" "fov" [60]
PixelSamples 3 3
Shutter 0 0.6
Option "streyes" "int frames" [0 7]
WorldBegin
LightSource "distantlight" 1 "from" [1 2 -1] "to" [0 0 0]
LightSource "ambientlight" 2 "intensity" [0.2]
Surface "matte"
AttributeBegin
  Color [0.6 0.6 0.5]
  Patch "bilinear" "P" [-10 -2 2  10 -2 2  -10 -2 40  10 -2 40]
AttributeEnd
AttributeBegin
  Color [0.3 0.4 0.8]
  Patch "bilinear" "P" [-3 -2 8  3 -2 8  -3 3 8  3 3 8]
AttributeEnd
AttributeBegin
  Color [0.9 0.2 0.2]
  MotionBegin [0 7]
    Translate 0 0 0
    Translate 0.5 0 12
  MotionEnd
  Patch "bilinear" "P" [-1 -1 10  1 -1 10  -1 1 10  1 1 10]
AttributeEnd
AttributeBegin
  Color [0.2 0.9 0.2]
  MotionBegin [0 7]
    Translate -4 0.5 0
    Translate 4 0.5 0
  MotionEnd
  Patch "bilinear" "P" [-0.7 -0.7 6  0.7 -0.7 6  -0.7 0.7 6.5  0.7 0.7 6.5]
AttributeEnd
AttributeBegin
  Color [0.9 0.9 0.1]
  MotionBegin [0 3 7]
    Translate -1 1 0
    Translate 1 1.2 -5
    Translate -1 1 0
  MotionEnd
  Patch "bilinear" "P" [-0.5 -0.5 14  0.5 -0.5 14  -0.5 0.5 16  0.5 0.5 16]
AttributeEnd
AttributeBegin
  Color [1 0 1]
  Patch "bilinear" "P" [1 -1 20  4 -1 20  1 1 20  4 1 20]
AttributeEnd
AttributeBegin
  Color [0 1 1]
  Patch "bilinear" "P" [2 -2 20  5 -2 20  2 0.5 20  5 0.5 20]
AttributeEnd
WorldEnd
)";

// The hard case for layers: one small grid (a strip seen at a grazing angle) spans depths 5 to
// 100 and is drawn first; a card at depth 6..6.5, nearer than the strip's far part, floats in
// front of it where the strip is 8 to 11 deep. Coverage must count only hits nearer than the
// card, or the card is culled although it is seen. A wall hides a second card completely.
const char* kGrazing = R"(Format 64 48 1
Projection "perspective" "fov" [60]
PixelSamples 3 3
Shutter 0 1
Option "streyes" "int frames" [0 3]
WorldBegin
Surface "constant"
AttributeBegin
  Color [0.5 0.5 0.5]
  Patch "bilinear" "P" [-0.5 -0.5 5  0.5 -0.5 5  -10 -0.5 100  10 -0.5 100]
AttributeEnd
AttributeBegin
  Color [1 0.2 0.2]
  MotionBegin [0 4]
    Translate 0 0 0
    Translate 0 0 0.5
  MotionEnd
  Patch "bilinear" "P" [-0.18 -0.36 6  0.18 -0.36 6  -0.18 -0.27 6  0.18 -0.27 6]
AttributeEnd
AttributeBegin
  Color [0.2 0.2 1]
  Patch "bilinear" "P" [2 0.5 7  6 0.5 7  2 3 7  6 3 7]
AttributeEnd
AttributeBegin
  Color [0.2 1 0.2]
  Patch "bilinear" "P" [2.5 1 9  4 1 9  2.5 2 9  4 2 9]
AttributeEnd
WorldEnd
)";

TEST(OcclusionRender, ToleranceZeroIsBitIdenticalOnLayeredScenes) {
    for (const char* rib : {kLayered, kGrazing}) {
        RenderResult st = test::renderRib(rib, with(Algorithm::Spacetime));
        RenderResult fr = test::renderRib(rib, with(Algorithm::Frames));
        for (int layers : {0, 1, 2, 5, 16}) {
            RenderResult sto = test::renderRib(rib, with(Algorithm::SpacetimeOcclusion, layers));
            RenderResult fro = test::renderRib(rib, with(Algorithm::FramesOcclusion, layers));
            EXPECT_TRUE(test::identicalPixels(st, sto)) << "layers " << layers;
            EXPECT_TRUE(test::identicalPixels(fr, fro)) << "layers " << layers;
            if (layers == 1) {  // one layer: no table is ever built
                EXPECT_EQ(sto.stats.counters.occlusionTables, 0u);
            }
            if (layers == 0 || layers == 16) {  // culling did happen
                EXPECT_GT(sto.stats.counters.culledOcclusion, 0u) << "layers " << layers;
                EXPECT_GT(fro.stats.counters.culledOcclusion, 0u) << "layers " << layers;
                // Grids no bucket sees are never diced, and the rest are diced in fewer buckets
                // (counted with each bucket dicing its own: sharing grids hides the second).
                RenderOptions own = with(Algorithm::Spacetime), ownOcclusion = with(Algorithm::SpacetimeOcclusion, layers);
                own.gridCacheBytes = ownOcclusion.gridCacheBytes = 0;
                EXPECT_LE(sto.stats.counters.gridsDiced, st.stats.counters.gridsDiced);
                EXPECT_LT(test::renderRib(rib, ownOcclusion).stats.counters.gridsDiced,
                          test::renderRib(rib, own).stats.counters.gridsDiced);
            }
        }
    }
}

// Every scene in scenes/, one test each (so that ctest runs them side by side); files of several
// worlds render as passes, in tests/cli/multipass_scenes_test.cpp.
std::vector<std::string> sceneFiles() {
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(test::sourcePath("scenes")))
        if (entry.path().extension() == ".rib" && !test::multiPassScene(entry.path().string()))
            files.push_back(entry.path().filename().string());
    std::sort(files.begin(), files.end());
    return files;
}

class EveryScene : public testing::TestWithParam<std::string> {};

TEST_P(EveryScene, ToleranceZeroIsBitIdentical) {
    if (test::slowUnderSanitizers(GetParam())) GTEST_SKIP() << "minutes under the sanitizers: the release suite runs it";
    Log log;
    Scene scene = parseRibFile(test::sourcePath("scenes/" + GetParam()), log);
    // Small and short: the first two frames at 64 pixels wide (with motion blur across them).
    RenderOptions o = with(Algorithm::Spacetime);
    o.xres = 64;
    o.yres = std::max(1, scene.camera.yres * 64 / scene.camera.xres);
    o.hasFrames = true;
    o.firstFrame = scene.settings.hasFrames ? scene.settings.firstFrame : 0;
    o.lastFrame = o.firstFrame + 1;
    o.samples = 4;
    RenderResult base = test::renderScene(scene, o);
    o.algorithm = Algorithm::SpacetimeOcclusion;
    EXPECT_TRUE(test::identicalPixels(base, test::renderScene(scene, o)));
    o.algorithm = Algorithm::Frames;
    RenderResult frames = test::renderScene(scene, o);
    o.algorithm = Algorithm::FramesOcclusion;
    EXPECT_TRUE(test::identicalPixels(frames, test::renderScene(scene, o)));
}

INSTANTIATE_TEST_SUITE_P(Scenes, EveryScene, testing::ValuesIn(sceneFiles()),
                         [](const testing::TestParamInfo<std::string>& info) {
                             std::string name = info.param.substr(0, info.param.size() - 4);
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

TEST(OcclusionRender, ThereAreScenesToCheck) { EXPECT_GE(sceneFiles().size(), 3u); }

// Micropolygons of the occluded scene, with only the primitives whose identifier does not start
// with `drop` (empty: all).
uint64_t micropolygons(const Scene& full, const std::string& drop, Algorithm a) {
    Scene s = full;
    if (!drop.empty()) {
        s.patches.clear();
        for (const BilinearPatchDesc& p : full.patches) {
            const Param* name = p.attributes->user.find("identifier:name");
            if (!(name && name->strings.size() == 1 && name->strings[0].rfind(drop, 0) == 0)) s.patches.push_back(p);
        }
    }
    RenderOptions o = with(a);
    o.xres = 320;
    o.yres = 180;
    o.hasFrames = true;
    o.firstFrame = 1;
    o.lastFrame = 12;
    return test::renderScene(s, o).stats.counters.micropolygons;
}

TEST(OcclusionRender, CullsAtLeastNinetyPercentOfTheHiddenGeometry) {
    Log log;
    Scene scene = parseRibFile(test::sourcePath("scenes/occluded.rib"), log);
    const uint64_t all = micropolygons(scene, "", Algorithm::Spacetime);
    const uint64_t visibleOnly = micropolygons(scene, "hidden", Algorithm::Spacetime);
    const uint64_t culled = micropolygons(scene, "", Algorithm::SpacetimeOcclusion);
    const uint64_t culledVisibleOnly = micropolygons(scene, "hidden", Algorithm::SpacetimeOcclusion);
    ASSERT_GT(all, visibleOnly);
    // Micropolygons of hidden cubes that survived culling, against those drawn without it.
    const double survived = double(culled - culledVisibleOnly) / double(all - visibleOnly);
    EXPECT_LT(survived, 0.10) << "hidden micropolygons: " << all - visibleOnly << " without culling, "
                              << culled - culledVisibleOnly << " with";
}

// A wall tilted in depth (10 at the bottom of the view, 40 at the top) covers every pixel; small
// patches tiling the whole view hide behind it at depths 45 to 60. Once the wall has hit every
// sample no first hits come any more, yet the table must keep up as depth passes the wall's far
// rows: every hidden patch is culled, none is diced. (Adaptive layers once stalled here.)
TEST(OcclusionRender, EverythingBehindATiltedWallIsCulled) {
    std::string wall = R"(Format 64 48 1
Projection "perspective" "fov" [60]
PixelSamples 2 2
WorldBegin
Surface "constant"
Patch "bilinear" "P" [-60 -30 10  60 -30 10  -60 40 40  60 40 40]
)";
    std::string hidden;
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 10; ++i) {
            // A 10 x 8 tiling of the view (x/z in [-0.77, 0.77], y/z in [-0.58, 0.58]) at depth z.
            const double z = 45 + 15.0 * ((i + j) % 5) / 4;
            const double x0 = (-0.8 + 0.16 * i) * z, x1 = x0 + 0.17 * z, y0 = (-0.6 + 0.15 * j) * z, y1 = y0 + 0.16 * z;
            auto v = [](double a) { return std::to_string(a); };
            hidden += "Patch \"bilinear\" \"P\" [" + v(x0) + " " + v(y0) + " " + v(z) + "  " + v(x1) + " " + v(y0) + " " +
                      v(z) + "  " + v(x0) + " " + v(y1) + " " + v(z) + "  " + v(x1) + " " + v(y1) + " " + v(z) + "]\n";
        }
    RenderOptions o = with(Algorithm::SpacetimeOcclusion);
    RenderResult wallOnly = test::renderRib(wall + "WorldEnd\n", o);
    RenderResult both = test::renderRib(wall + hidden + "WorldEnd\n", o);
    EXPECT_EQ(both.stats.counters.gridsDiced, wallOnly.stats.counters.gridsDiced);
    EXPECT_GE(both.stats.counters.culledOcclusion, 80u);
    EXPECT_TRUE(test::identicalPixels(both, test::renderRib(wall + hidden + "WorldEnd\n", with(Algorithm::Spacetime))));
}

// `rib` without the AttributeBegin ... AttributeEnd block that holds `marker`.
std::string withoutBlock(const std::string& rib, const std::string& marker) {
    const size_t at = rib.find(marker), begin = rib.rfind("AttributeBegin", at), end = rib.find("AttributeEnd", at);
    if (at == std::string::npos || begin == std::string::npos || end == std::string::npos)
        throw std::runtime_error("no block holds " + marker);
    return rib.substr(0, begin) + rib.substr(end + std::string("AttributeEnd").size());
}

// A tolerance loses what a body shows through the uncovered eps of its block: the rims of
// partly hidden bodies peeking past their occluders, never a whole object. So the measure is
// per frame, pixels whose colour or alpha moves by more than 0.1 (a mean over 8 frames of
// 64 x 48 pixels would pass a lost object of 100 pixels: about 0.01), and the bound is 1% of the
// frame, 30 pixels. Measured on kLayered: at most 5 pixels a frame at eps 0.2, 10 at 0.5; without
// the green card (100 to 130 pixels a frame) every frame has more than 100.
constexpr float kVisibleChange = 0.1f;
constexpr size_t kMaxChangedPixels = 64 * 48 / 100;

TEST(OcclusionRender, HigherToleranceCullsMoreAndChangesLittle) {
    RenderResult exact = test::renderRib(kLayered, with(Algorithm::SpacetimeOcclusion));
    ASSERT_EQ(exact.frames.size(), 8u);
    uint64_t last = exact.stats.counters.culledOcclusion;
    for (double eps : {0.05, 0.2, 0.5}) {
        RenderResult r = test::renderRib(kLayered, with(Algorithm::SpacetimeOcclusion, 0, eps));
        EXPECT_GE(r.stats.counters.culledOcclusion, last) << eps;
        last = r.stats.counters.culledOcclusion;
        for (size_t f = 0; f < exact.frames.size(); ++f)
            EXPECT_LE(test::differingPixels(exact.frames[f], r.frames[f], kVisibleChange), kMaxChangedPixels)
                << "eps " << eps << ", frame " << exact.frames[f].frame;
    }
    EXPECT_GT(last, exact.stats.counters.culledOcclusion);
}

// The bound above fails on a lost object: the green card (0.2 0.9 0.2) dropped from kLayered.
TEST(OcclusionRender, ToleranceBoundFailsWhenAnObjectIsLost) {
    RenderResult exact = test::renderRib(kLayered, with(Algorithm::SpacetimeOcclusion));
    RenderResult lost =
        test::renderRib(withoutBlock(kLayered, "Color [0.2 0.9 0.2]"), with(Algorithm::SpacetimeOcclusion));
    ASSERT_EQ(lost.frames.size(), exact.frames.size());
    for (size_t f = 0; f < exact.frames.size(); ++f)
        EXPECT_GT(test::differingPixels(exact.frames[f], lost.frames[f], kVisibleChange), kMaxChangedPixels)
            << "frame " << exact.frames[f].frame;
    EXPECT_LT(test::meanAbsDifference(exact, lost), 0.05f);  // which the old bound let through
}

}  // namespace
}  // namespace streyes
