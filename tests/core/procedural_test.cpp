// Procedurals end to end: lazy expansion (never for what is culled), RunProgram, archives,
// depth limits, bounds that are too small, and the forest's determinism.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::RenderResult;

std::string writeArchive(const std::string& dir, const std::string& name, const std::string& text) {
    std::string path = dir + "/" + name;
    std::ofstream(path) << text;
    return path;
}

// An orthographic camera where one unit is one pixel (raster x = x, raster y = 16 - y).
std::string header(const std::string& extra = "") {
    return "Format 32 16 1\nProjection \"orthographic\"\nScreenWindow 0 32 0 16\nPixelSamples 2 2\n"
           "PixelFilter \"box\" 1 1\n" + extra + "WorldBegin\nSurface \"constant\"\n";
}

const char* kSquare = "Patch \"bilinear\" \"P\" [0 0 0  4 0 0  0 4 0  4 4 0]\n";

TEST(Procedural, ExpandsOnlyWhenItsBoundIsInView) {
    const test::TempDir tempDir("proc-view");
    const std::string& dir = tempDir.path();
    std::string archive = writeArchive(dir, "square.rib", kSquare);
    // Seen: bound [2, 6] x [2, 6]; translated so the square lands there. Unseen: far to the right.
    RenderResult r = test::renderRib(header() + "Color [1 0 0]\nTranslate 2 2 5\n"
                                     "Procedural \"DelayedReadArchive\" [\"" + archive + "\"] [0 4 0 4 0 0]\n"
                                     "Translate 100 0 0\n"
                                     "Procedural \"DelayedReadArchive\" [\"" + archive + "\"] [0 4 0 4 0 0]\nWorldEnd\n");
    EXPECT_EQ(r.stats.procedurals, 2u);
    EXPECT_EQ(r.stats.counters.proceduralsExpanded, 1u);
    // The children inherit the colour in force at the Procedural request: red at (4, 12).
    EXPECT_NEAR(r.channel(0, 3, 12, 0), 1.0f, 1e-5f);
    EXPECT_NEAR(r.alpha(0, 3, 12), 1.0f, 1e-5f);
    EXPECT_EQ(r.alpha(0, 10, 12), 0.0f);
}

TEST(Procedural, HiddenBehindAWallExpandsOnlyWithoutOcclusionCulling) {
    const test::TempDir tempDir("proc-wall");
    const std::string& dir = tempDir.path();
    std::string archive = writeArchive(dir, "square.rib", kSquare);
    const std::string rib = header() + "Patch \"bilinear\" \"P\" [0 0 1  32 0 1  0 16 1  32 16 1]\n"
                            "Translate 4 4 5\nProcedural \"DelayedReadArchive\" [\"" + archive + "\"] [0 4 0 4 0 0]\nWorldEnd\n";
    RenderResult culled = test::renderRib(rib, test::optionsFor(Algorithm::SpacetimeOcclusion));
    RenderResult open = test::renderRib(rib, test::optionsFor(Algorithm::Spacetime));
    EXPECT_EQ(culled.stats.counters.proceduralsExpanded, 0u);
    EXPECT_GT(culled.stats.counters.culledOcclusion, 0u);
    EXPECT_EQ(open.stats.counters.proceduralsExpanded, 1u);
    EXPECT_TRUE(test::identicalPixels(culled, open));
    RenderResult c2 = test::renderRib(rib, test::optionsFor(Algorithm::FramesOcclusion));
    EXPECT_EQ(c2.stats.counters.proceduralsExpanded, 0u);
}

TEST(Procedural, ChildrenOutsideTheDeclaredBoundAreNotLost) {
    const test::TempDir tempDir("proc-bound");
    const std::string& dir = tempDir.path();
    std::string archive = writeArchive(dir, "big.rib", "Patch \"bilinear\" \"P\" [0 0 0  20 0 0  0 10 0  20 10 0]\n");
    // The patch spans raster x [4, 24] but the procedural declares only [4, 5]: with 4-pixel
    // buckets, most of the buckets it covers never see the declared bound.
    auto scene = [&](const char* bound) {
        return header() + "Translate 4 4 5\nProcedural \"DelayedReadArchive\" [\"" + archive + "\"] [" + bound +
               "]\nWorldEnd\n";
    };
    RenderOptions o;
    o.bucketSize = 4;
    o.freeExpansions = RenderOptions::FreeExpansions::Always;
    RenderResult tooSmall = test::renderRib(scene("0 1 0 1 0 0"), o);
    RenderResult right = test::renderRib(scene("0 20 0 10 0 0"), o);
    EXPECT_TRUE(test::identicalPixels(tooSmall, right));
    EXPECT_EQ(tooSmall.stats.passes, 2);
    EXPECT_EQ(right.stats.passes, 1);
    // The expansion that outgrew is kept for the second pass; the right one is let go when its
    // last bucket is done (render/expansion_release.h).
    EXPECT_EQ(tooSmall.stats.counters.proceduralsReleased, 0u);
    EXPECT_EQ(right.stats.counters.proceduralsReleased, 1u);
    EXPECT_NEAR(tooSmall.alpha(0, 20, 4), 1.0f, 1e-6f);  // far outside the declared bound
    bool warned = false;
    for (const std::string& w : tooSmall.warnings) warned = warned || w.find("outside the declared bound") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(Procedural, SelfGeneratingStopsAtTheDepthLimitWithAWarning) {
    const test::TempDir tempDir("proc-self");
    const std::string& dir = tempDir.path();
    std::string path = dir + "/self.rib";
    writeArchive(dir, "self.rib", std::string(kSquare) + "Translate 0.01 0 0\nProcedural \"DelayedReadArchive\" [\"" +
                                      path + "\"] [0 5 0 4 0 0]\n");
    RenderResult r = test::renderRib(header() + "Translate 2 2 5\nProcedural \"DelayedReadArchive\" [\"" + path +
                                     "\"] [0 5 0 4 0 0]\nWorldEnd\n");
    bool warned = false;
    for (const std::string& w : r.warnings) warned = warned || w.find("nested more than 32") != std::string::npos;
    EXPECT_TRUE(warned);
    EXPECT_EQ(r.stats.counters.proceduralsExpanded, 33u);  // depths 0..32
    EXPECT_NEAR(r.alpha(0, 3, 12), 1.0f, 1e-6f);
}

TEST(Procedural, RunProgramInPythonWorksEndToEnd) {
    const std::string script = test::sourcePath("tests/data/squares.py");
    // Two requests to the same program (it stays running): 3 and 2 squares of 2 pixels.
    RenderResult r = test::renderRib(header() + "Color [0 1 0]\n"
                                     "Procedural \"RunProgram\" [\"/usr/bin/python3 " + script + "\" \"3 1 1 2 5\"] [1 11 1 3 5 5]\n"
                                     "Procedural \"RunProgram\" [\"/usr/bin/python3 " + script + "\" \"2 1 9 2 5\"] [1 7 9 11 5 5]\nWorldEnd\n");
    EXPECT_EQ(r.stats.counters.proceduralsExpanded, 2u);
    // Squares at x in [1,3], [5,7], [9,11] on rows y in [1,3] (raster rows 13..14), and two more at y in [9, 11].
    for (int x : {1, 2, 5, 6, 9, 10}) EXPECT_NEAR(r.alpha(0, x, 14), 1.0f, 1e-6f) << x;
    for (int x : {3, 4, 7, 8, 11, 12}) EXPECT_EQ(r.alpha(0, x, 14), 0.0f) << x;
    EXPECT_NEAR(r.channel(0, 5, 6, 1), 1.0f, 1e-5f);
    EXPECT_EQ(r.alpha(0, 9, 6), 0.0f);
}

// A program's answer may be binary RIB or gzip-compressed, read as a file would be.
TEST(Procedural, RunProgramAnswersInBinaryAndGzip) {
    const std::string script = test::sourcePath("tests/data/squares.py");
    auto render = [&](const std::string& a, const std::string& b) {
        return test::renderRib(header() + "Procedural \"RunProgram\" [\"/usr/bin/python3 " + script + "\" \"3 1 1 2 5" +
                               a + "\"] [1 11 1 3 5 5]\nProcedural \"RunProgram\" [\"/usr/bin/python3 " + script +
                               "\" \"2 1.5 9 2 5" + b + "\"] [1.5 7.5 9 11 5 5]\nWorldEnd\n");
    };
    const RenderResult ascii = render("", ""), stored = render(" binary", " gzip");
    EXPECT_EQ(stored.stats.counters.proceduralsExpanded, 2u);
    EXPECT_NEAR(test::alphaSum(ascii), 5 * 4.0, 1e-4);
    EXPECT_TRUE(test::identicalPixels(ascii, stored));
}

// The line number of `needle` in `text`, from 1.
int lineOf(const std::string& text, const std::string& needle) {
    size_t at = text.find(needle);
    return 1 + int(std::count(text.begin(), text.begin() + long(at), '\n'));
}

TEST(Procedural, RunProgramErrorsNameTheProcedural) {
    const std::string missing = header() + "Procedural \"RunProgram\" [\"no-such-program-xyz\" \"\"] [0 1 0 1 0 1]\nWorldEnd\n";
    try {
        test::renderRib(missing);  // found when bodies are made, before anything renders
        FAIL() << "a missing program must be an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("test.rib:" + std::to_string(lineOf(missing, "Procedural"))), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("no-such-program-xyz"), std::string::npos);
    }
    const std::string failing = header() + "Procedural \"RunProgram\" [\"/bin/false\" \"\"] [0 4 0 4 0 1]\nWorldEnd\n";
    try {
        test::renderRib(failing);
        FAIL() << "a failing program must be an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("test.rib:" + std::to_string(lineOf(failing, "Procedural"))), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("exited with status 1"), std::string::npos) << e.what();
    }
}

TEST(Procedural, ReadArchiveIncludesInPlace) {
    const test::TempDir tempDir("proc-read");
    const std::string& dir = tempDir.path();
    std::string archive = writeArchive(dir, "square.rib", kSquare);
    RenderResult r = test::renderRib(header() + "Color [0 0 1]\nTranslate 20 2 5\nReadArchive \"" + archive + "\"\nWorldEnd\n");
    EXPECT_NEAR(r.channel(0, 21, 12, 2), 1.0f, 1e-5f);
    EXPECT_EQ(r.stats.procedurals, 0u);
}

// A tilted wall between the camera and the small forest: once the wall has hit every sample, no
// first hits come any more, yet coverage must still grow as depth passes the wall, so nothing of
// the forest (all behind the wall) may expand. (Adaptive layers once stalled here.)
TEST(Procedural, NothingOfAForestBehindAWallExpands) {
    Log log;
    std::string rib;
    {
        std::ifstream in(test::sourcePath("scenes/forest-small.rib"));
        rib.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    const std::string wall = "WorldBegin\nAttributeBegin\nPatch \"bilinear\" \"P\" "
                             "[-60 -20 -44  60 -20 -44  -60 80 -42  60 80 -42]\nAttributeEnd\n";
    rib.replace(rib.find("WorldBegin\n"), 11, wall);
    // Move the forest 20 m back, so that every cell's bound (trees' reach and sway included) lies
    // behind the wall.
    rib.replace(rib.find("Procedural"), 10, "Translate 0 0 20\nProcedural");
    Scene scene = parseRibString(rib, "wall.rib", log);
    RenderOptions o;
    o.xres = 96;
    o.yres = 54;
    o.hasFrames = true;
    o.firstFrame = o.lastFrame = 1;
    RenderResult r = test::renderScene(scene, o);
    EXPECT_EQ(r.stats.counters.proceduralsExpanded, 0u);  // not even the forest: it is all behind the wall
    EXPECT_GT(r.stats.counters.culledOcclusion, 0u);
    o.algorithm = Algorithm::Spacetime;  // without culling every cell in view expands
    RenderResult open = test::renderScene(scene, o);
    ASSERT_GE(open.stats.counters.proceduralsExpandedByDepth.size(), 3u);
    EXPECT_GT(open.stats.counters.proceduralsExpandedByDepth[1], 5u);
    EXPECT_TRUE(test::identicalPixels(r, open));
}

// The forest's `detail` scales its level-of-detail thresholds: more detail may only ever add
// bodies, for a tree of any projected size. (Once the near threshold grew with `detail`, so a
// tree 60 pixels across lost its branches at detail=4.)
TEST(Procedural, MoreDetailNeverMeansFewerBodies) {
    const double distances[] = {300, 100, 30, 15};  // the tree's bound about 3, 10, 30, 60 pixels across
    const double details[] = {0.25, 1, 4};
    bool detailMatters = false;
    for (double d : distances) {
        uint64_t previous = 0;
        for (double detail : details) {
            std::ostringstream rib;
            rib << "Format 64 64 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 1 1\n"
                << "Translate 0 -5 " << d << "\nWorldBegin\n"
                << "Procedural \"DynamicLoad\" [\"tree\" \"kind=broadleaf height=10 seed=3 detail=" << detail
                << "\"] [-10 10 0 20 -10 10]\nWorldEnd\n";
            RenderOptions o;
            o.algorithm = Algorithm::Spacetime;
            const uint64_t bodies = test::renderRib(rib.str(), o).stats.bodiesGenerated;
            EXPECT_GE(bodies, previous) << "distance " << d << ", detail " << detail;
            detailMatters |= previous > 0 && bodies > previous;
            previous = bodies;
        }
    }
    EXPECT_TRUE(detailMatters);
}

// shaders=BARK,LEAF: a near tree's bark and leaves run those Shading Language surfaces (the
// leaves cut out by their opacity: see-through fragments, and less covered than the flat quads),
// the rest of the tree keeps the procedural's own surface; a malformed value is an error at the
// Procedural's line.
TEST(Procedural, TreeShadersShadeBarkAndCutOutLeaves) {
    auto rib = [](const std::string& extra) {
        return "Format 96 96 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 2 2\nTranslate 0 -7 22\nWorldBegin\n"
               "LightSource \"distantlight\" 1\nSurface \"matte\"\n"
               "Procedural \"DynamicLoad\" [\"tree\" \"kind=broadleaf height=12 seed=3 wind=0 " +
               extra + "\"] [-10 10 0 20 -10 10]\nWorldEnd\n";
    };
    RenderOptions o;
    o.algorithm = Algorithm::Spacetime;
    const test::RenderResult flat = test::renderRib(rib(""), o);
    const test::RenderResult shaded = test::renderRib(rib("shaders=bark,leaf"), o);
    EXPECT_EQ(flat.stats.counters.pointsShadedSurface, 0u);  // matte: the built-in
    EXPECT_EQ(flat.stats.counters.sampleFragments, 0u);
    EXPECT_GT(shaded.stats.counters.pointsShadedSurface, 1000u);
    EXPECT_GT(shaded.stats.counters.pointsShadedBuiltin, 0u);  // the undergrowth keeps matte
    EXPECT_GT(shaded.stats.counters.sampleFragments, 100u);    // the leaves' cut edges
    EXPECT_EQ(shaded.stats.bodiesGenerated, flat.stats.bodiesGenerated);  // the same geometry
    EXPECT_LT(test::alphaSum(shaded), test::alphaSum(flat) - 20);  // leaf shapes cover less than their quads
    for (const char* bad : {"shaders=bark", "shaders=bark,", "shaders=,leaf", "shaders=a,b,c"}) {
        const std::string text = rib(bad);
        try {
            test::renderRib(text, o);  // the generator is made when bodies are, before anything renders
            ADD_FAILURE() << bad << " must be an error";
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("test.rib:" + std::to_string(lineOf(text, "Procedural"))), std::string::npos) << what;
            EXPECT_NE(what.find("shaders takes two surface names"), std::string::npos) << what;
        }
    }
}

// The small forest's frames 1-3 at 96 x 54, as the forest tests render it.
RenderOptions smallForestOptions() {
    RenderOptions o;
    o.xres = 96;
    o.yres = 54;
    o.hasFrames = true;
    o.firstFrame = 1;
    o.lastFrame = 3;
    return o;
}

TEST(Procedural, ForestIsTheSameWhateverTheThreadCount) {
    Log log;
    Scene scene = parseRibFile(test::sourcePath("scenes/forest-small.rib"), log);
    RenderOptions o = smallForestOptions();
    o.threads = 1;
    RenderResult one = test::renderScene(scene, o);
    o.threads = 2;
    RenderResult two = test::renderScene(scene, o);
    EXPECT_TRUE(test::identicalPixels(one, two));
    EXPECT_EQ(test::differingCounts(one.stats.counters, two.stats.counters), std::vector<std::string>{});
    EXPECT_EQ(one.stats.bodiesGenerated, two.stats.bodiesGenerated);
    EXPECT_GT(one.stats.counters.proceduralsExpanded, 10u);
}

// What the forest's procedurals expand into is let go once no bucket left reaches it
// (render/expansion_release.h): the same pixels and the same counts as when it is all kept to
// the end, on one thread and on two, with every kept expansion let go by the end of a single
// block, and none made again. By default that happens only under memory pressure. Over several
// blocks only the last one lets go (the others would make it all again).
TEST(Procedural, ForestLetsGoOfWhatNoBucketLeftReachesWithTheSamePixels) {
    Log log;
    Scene scene = parseRibFile(test::sourcePath("scenes/forest-small.rib"), log);
    RenderOptions o = smallForestOptions();
    o.bucketSize = 16;  // 24 buckets; 6 under the sanitizers, at 48 x 27
    test::halfResolutionUnderSanitizers(o, 96, 54);
    o.freeExpansions = RenderOptions::FreeExpansions::Never;
    RenderResult kept = test::renderScene(scene, o);
    EXPECT_EQ(kept.stats.counters.proceduralsReleased, 0u);
    ASSERT_GT(kept.stats.counters.proceduralsExpanded, 10u);
    o.freeExpansions = RenderOptions::FreeExpansions::Always;
    for (int threads : {1, 2}) {
        o.threads = threads;
        RenderResult released = test::renderScene(scene, o);
        EXPECT_TRUE(test::identicalPixels(kept, released)) << threads << " threads";
        RenderCounters a = kept.stats.counters, b = released.stats.counters;
        EXPECT_EQ(b.proceduralsReleased, b.proceduralsExpanded) << threads << " threads";
        EXPECT_EQ(b.proceduralsMadeAgain, 0u) << "let go while a bucket could still reach it";
        a.proceduralsReleased = b.proceduralsReleased = 0;
        EXPECT_EQ(test::differingCounts(a, b), std::vector<std::string>{}) << threads << " threads";
        EXPECT_EQ(kept.stats.bodiesGenerated, released.stats.bodiesGenerated);
        EXPECT_EQ(kept.stats.memoryBodiesBytes, released.stats.memoryBodiesBytes);
    }
    // By default only under pressure: once the bodies made hold a quarter of the budget.
    o.freeExpansions = RenderOptions::FreeExpansions::UnderPressure;
    o.threads = 2;
    o.maxMemoryBytes = kept.stats.memoryBodiesBytes * 2;
    RenderResult pressed = test::renderScene(scene, o);
    EXPECT_TRUE(test::identicalPixels(kept, pressed));
    EXPECT_EQ(pressed.stats.counters.proceduralsReleased, pressed.stats.counters.proceduralsExpanded);
    o.maxMemoryBytes = uint64_t(64) << 30;
    EXPECT_EQ(test::renderScene(scene, o).stats.counters.proceduralsReleased, 0u);
    o.maxMemoryBytes = 0;
    o.freeExpansions = RenderOptions::FreeExpansions::Always;
    o.maxFrameBlock = 1;  // three blocks: the last lets go of what it made
    RenderResult blocks = test::renderScene(scene, o);
    EXPECT_TRUE(test::identicalPixels(kept, blocks));
    EXPECT_GT(blocks.stats.counters.proceduralsReleased, 0u);
    EXPECT_LT(blocks.stats.counters.proceduralsReleased, blocks.stats.counters.proceduralsExpanded);
    EXPECT_EQ(blocks.stats.counters.proceduralsMadeAgain, 0u);
}

// The same under a moving camera: the flyover's procedurals move in camera space, expand per
// level of detail and are pushed as views; each level is let go once its last bucket is done.
TEST(Procedural, FlyoverLetsGoOfWhatNoBucketLeftReachesWithTheSamePixels) {
    Log log;
    Scene scene = parseRibFile(test::sourcePath("scenes/forest-flyover.rib"), log);
    RenderOptions o = smallForestOptions();
    o.bucketSize = 16;
    test::halfResolutionUnderSanitizers(o, 96, 54);
    o.freeExpansions = RenderOptions::FreeExpansions::Never;
    RenderResult kept = test::renderScene(scene, o);
    ASSERT_GT(kept.stats.counters.proceduralsExpanded, 10u);
    o.freeExpansions = RenderOptions::FreeExpansions::Always;
    o.threads = 2;
    RenderResult released = test::renderScene(scene, o);
    EXPECT_TRUE(test::identicalPixels(kept, released));
    EXPECT_EQ(released.stats.counters.proceduralsReleased, released.stats.counters.proceduralsExpanded);
    EXPECT_EQ(released.stats.counters.proceduralsMadeAgain, 0u);
    EXPECT_EQ(kept.stats.bodiesGenerated, released.stats.bodiesGenerated);
}

}  // namespace
}  // namespace streyes
