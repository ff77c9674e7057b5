// Frame sequences (streyes/sequence.h): each frame of a sequence renders what its RIB alone
// renders; still runs are one body; bad sequences are refused naming file and line.
#include <gtest/gtest.h>

#include <map>

#include "scene/rib_parser.h"
#include "streyes/rib.h"
#include "streyes/passes.h"
#include "streyes/sequence.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::renderScene;
using test::RenderResult;
using test::sourcePath;

const int kFrames = 8;

// Frame f's own file read as an ordinary scene (its FrameBegin skipped), rendering frame f: the
// frame's RIB alone, through the renderer as it was before sequences.
Scene frameAlone(int f) {
    Log log;
    char name[64];
    std::snprintf(name, sizeof name, "scenes/sequence/shot.%04d.rib", f);
    Scene s = parseRibFile(sourcePath(name), log);
    s.settings.hasFrames = true;
    s.settings.firstFrame = s.settings.lastFrame = f;
    return s;
}

Sequence readShot(const std::string& name, FrameRequest req = {}) {
    Log log;
    return readScene(sourcePath("scenes/sequence/" + name), req, log);
}

RenderResult oneFrame(const RenderResult& r, int f) {
    RenderResult one;
    one.frames.push_back(r.frame(f));
    return one;
}

TEST(Sequence, EveryFrameIsBitIdenticalToItsRibAloneWithAlgorithmFrames) {
    const Sequence seq = readShot("shot.rib");
    ASSERT_TRUE(seq.isSequence);
    EXPECT_EQ(seq.scene.settings.firstFrame, 1);
    EXPECT_EQ(seq.scene.settings.lastFrame, kFrames);
    const RenderOptions o = test::optionsFor(Algorithm::Frames);
    const RenderResult all = renderScene(seq.scene, o);
    ASSERT_EQ(all.frames.size(), size_t(kFrames));
    for (int f = 1; f <= kFrames; ++f) {
        const RenderResult alone = renderScene(frameAlone(f), o);
        EXPECT_TRUE(test::identicalPixels(oneFrame(all, f), alone)) << "frame " << f;
        EXPECT_GT(test::meanAbsDifference(oneFrame(all, f), oneFrame(all, f == 1 ? 2 : f - 1)), 0.0f);
    }
}

// Read three frames at a time, the shot comes in blocks 1-3, 4-6, 7-8, each rendering its frames
// as the whole shot does.
TEST(Sequence, ReadABlockAtATimeEachBlockRendersItsFramesTheSame) {
    Log log;
    std::vector<Sequence> blocks;
    PassRequest req;
    req.blockFrames = 3;
    readPasses(sourcePath("scenes/sequence/shot.####.rib"), req, log,
               [&](PassJob&& j) { blocks.push_back(std::move(j.sequence)); });
    ASSERT_EQ(blocks.size(), 3u);
    const int firsts[] = {1, 4, 7}, lasts[] = {3, 6, 8};
    const RenderResult whole = renderScene(readShot("shot.rib").scene, test::optionsFor(Algorithm::Frames));
    for (size_t b = 0; b < 3; ++b) {
        EXPECT_EQ(blocks[b].scene.settings.firstFrame, firsts[b]);
        EXPECT_EQ(blocks[b].scene.settings.lastFrame, lasts[b]);
        const RenderResult r = renderScene(blocks[b].scene, test::optionsFor(Algorithm::Frames));
        for (int f = firsts[b]; f <= lasts[b]; ++f) EXPECT_TRUE(test::identicalPixels(oneFrame(r, f), oneFrame(whole, f))) << f;
    }
    // Frames 1-3 (the camera pans): every primitive per frame, 47 a frame. From 4 on one run each
    // for the still set (36 tiles, wall, pillar, newcomer), the changer's runs (4 | 5-), and per
    // frame the mover's 6 faces, the blob and the statue.
    EXPECT_EQ(blocks[0].runs.size(), 3u * 47);
    EXPECT_EQ(blocks[1].runs.size(), 39u + 2 + 3 * 8);
    EXPECT_EQ(blocks[2].runs.size(), 39u + 1 + 2 * 8);
}

TEST(Sequence, PatternAndFrameBlocksGiveTheSameScene) {
    const RenderResult blocks = renderScene(readShot("shot.rib").scene);
    const RenderResult files = renderScene(readShot("shot.####.rib").scene);
    EXPECT_TRUE(test::identicalPixels(blocks, files));
}

// The default algorithm renders every frame of the block in one bucket; a frame's samples are
// the same wherever it is rendered (the pattern table is per frame), its pieces are cut per frame
// or per chunk of frames aligned in absolute frame numbers, and a still run's body is the one
// the frame alone makes: each frame is bit-identical to its RIB alone (RGBA and Z). (This test
// once allowed a tenth of the sampling noise; this shot has held bit for bit for a while.)
TEST(Sequence, EveryFrameIsBitIdenticalToItsRibAloneWithTheDefaultAlgorithm) {
    const RenderResult all = renderScene(readShot("shot.rib").scene);
    for (int f = 1; f <= kFrames; ++f) {
        const RenderResult alone = renderScene(frameAlone(f));
        EXPECT_TRUE(test::identicalPixels(oneFrame(all, f), alone)) << "frame " << f;
        EXPECT_GT(test::meanAbsDifference(oneFrame(all, f), oneFrame(all, f == 1 ? 2 : f - 1)), 0.0f);
    }
}

// What the shot's runs are: the camera pans over frames 1-3 (every primitive its own per frame)
// and stands still from 4 on, where the still set is one run over frames 4-8.
TEST(Sequence, StoppedCameraRunIsOneStillRun) {
    const Sequence seq = readShot("shot.rib");
    std::map<std::string, std::vector<std::pair<int, int>>> runs;
    for (const SequenceRun& r : seq.runs) runs[r.name].push_back({r.firstFrame, r.lastFrame});
    auto count = [&](const std::string& name, int a, int b) {
        int n = 0;
        for (auto& r : runs[name]) n += r.first == a && r.second == b;
        return n;
    };
    for (int f = 1; f <= 3; ++f) EXPECT_EQ(count("floor", f, f), 36) << f;
    EXPECT_EQ(count("floor", 4, 8), 36);
    EXPECT_EQ(runs["floor"].size(), 36u * 4);
    EXPECT_EQ(count("wall", 4, 8), 1);
    EXPECT_EQ(count("pillar", 4, 8), 1);
    EXPECT_EQ(count("newcomer", 4, 8), 1);  // appears in frame 4
    EXPECT_EQ(runs["newcomer"].size(), 1u);
    EXPECT_EQ(count("changer", 4, 4), 1);  // its topology changes in frame 5
    EXPECT_EQ(count("changer", 5, 8), 1);
    EXPECT_EQ(runs["mover"].size(), 6u * kFrames);  // moves within every frame: 6 faces a frame
    EXPECT_EQ(runs["blob"].size(), size_t(kFrames));
    EXPECT_EQ(runs["statue"].size(), size_t(kFrames));  // its Kd changes every frame
    EXPECT_EQ(seq.stats.frames, kFrames);
    EXPECT_EQ(seq.stats.runs, seq.runs.size());
    // Lights in camera space: the three fixed ones are the same from frame 4 on (the camera
    // stands), the mover's changes every frame: at most 3 x 4 + 8 of the 5 x 8 declared.
    EXPECT_LE(seq.scene.lights.size(), 3u * 4 + kFrames);
}

// A still set seen by a still camera, N frames: split and diced once, whatever N.
std::string stillFrame(int f, const std::string& shutter = "0 0.5") {
    std::string s = "FrameBegin " + std::to_string(f) +
                    "\nFormat 96 64 1\nProjection \"perspective\" \"fov\" [40]\nShutter " + shutter +
                    "\nPixelSamples 2 2\nTranslate 0 -1 8\nWorldBegin\n"
                    "LightSource \"distantlight\" 1 \"from\" [1 3 -2] \"to\" [0 0 0]\n"
                    "Surface \"matte\"\n";
    for (int i = 0; i < 6; ++i)
        s += "Patch \"bilinear\" \"P\" [" + std::to_string(-3 + i) + " 0 -2  " + std::to_string(-2 + i) + " 0 -2  " +
             std::to_string(-3 + i) + " " + std::to_string(1 + i % 3) + " 2  " + std::to_string(-2 + i) + " " +
             std::to_string(1 + i % 3) + " 2]\n";
    s += "Sphere 1 -1 1 360\nWorldEnd\nFrameEnd\n";
    return s;
}

Sequence buildFrames(const std::vector<std::string>& frames, Log& log) {
    SequenceBuilder b(log);
    for (size_t i = 0; i < frames.size(); ++i) {
        RibParser::FrameHandler add = [&](Scene&& s) { b.add(std::move(s)); };
        Scene scene;
        RibParser p(scene, log);
        p.setFrameHandler(add);
        p.parseString(frames[i], "frame" + std::to_string(i) + ".rib");
        p.finish();
    }
    return b.finish();
}

TEST(Sequence, StillSetIsSplitAndDicedOnceWhateverTheFrameCount) {
    Log log;
    const Sequence one = buildFrames({stillFrame(1)}, log);
    std::vector<std::string> eight;
    for (int f = 1; f <= 8; ++f) eight.push_back(stillFrame(f));
    const Sequence many = buildFrames(eight, log);
    EXPECT_EQ(many.stats.runs, one.stats.runs);  // 6 patches and a sphere, one run each
    EXPECT_EQ(many.stats.stillRuns, 7u);
    for (Algorithm a : {Algorithm::Spacetime, Algorithm::SpacetimeOcclusion}) {
        const RenderResult r1 = renderScene(one.scene, test::optionsFor(a));
        const RenderResult r8 = renderScene(many.scene, test::optionsFor(a));
        ASSERT_EQ(r8.frames.size(), 8u);
        EXPECT_GT(r1.stats.counters.gridsDiced, 0u);
        EXPECT_EQ(r8.stats.counters.gridsDiced, r1.stats.counters.gridsDiced);
        EXPECT_EQ(r8.stats.counters.splits(), r1.stats.counters.splits());
        EXPECT_EQ(r8.stats.counters.micropolygons, r1.stats.counters.micropolygons);
        for (int f = 2; f <= 8; ++f) {
            // The same picture every frame, but for the samples' own times (nothing moves).
            EXPECT_LT(test::maxAbsDifference(oneFrame(r8, f), oneFrame(r8, 1)), 1e-6f);
        }
    }
}

// Shutter 0 1: frame f is exposed during [f, f + 1], and frame f + 1 from the instant frame f's
// exposure ends. A square that jumps between frames is where each frame puts it in that frame
// only: the instant they share is the later frame's (runs end open there).
TEST(Sequence, TouchingExposuresAreJoinedWithoutBleeding) {
    Log log;
    auto frame = [](int f, double x, bool moves) {
        std::string s = "FrameBegin " + std::to_string(f) + "\n" + test::orthoHeader(64, 16, "Shutter 0 1\nPixelSamples 4 4\n");
        if (moves)
            s += "MotionBegin [" + std::to_string(f) + " " + std::to_string(f + 1) + "]\nTranslate " +
                 std::to_string(x) + " 0 0\nTranslate " + std::to_string(x + 4) + " 0 0\nMotionEnd\n";
        else
            s += "Translate " + std::to_string(x) + " 0 0\n";
        return s + "Patch \"bilinear\" \"P\" [0 4 1  8 4 1  0 12 1  8 12 1]\nWorldEnd\nFrameEnd\n";
    };
    const std::vector<std::string> frames = {frame(1, 4, false), frame(2, 4, false), frame(3, 30, true),
                                             frame(4, 50, false)};
    const Sequence seq = buildFrames(frames, log);
    ASSERT_EQ(seq.runs.size(), 3u);  // frames 1-2 still, 3 moving, 4 still
    for (Algorithm a : {Algorithm::Frames, Algorithm::Spacetime, Algorithm::SpacetimeOcclusion}) {
        const RenderResult all = renderScene(seq.scene, test::optionsFor(a));
        for (int f = 1; f <= 4; ++f) {
            Log l;
            Scene alone = parseRibString(frames[size_t(f - 1)], "alone.rib", l);
            alone.settings.hasFrames = true;
            alone.settings.firstFrame = alone.settings.lastFrame = f;
            EXPECT_TRUE(test::identicalPixels(oneFrame(all, f), renderScene(alone, test::optionsFor(a))))
                << "frame " << f << " algorithm " << int(a);
        }
        // Frame 2's square is where frames 1-2 put it, nothing of frame 3's left of it.
        EXPECT_EQ(all.alpha(2, 30, 8), 0.0f);
        EXPECT_EQ(all.alpha(2, 6, 8), 1.0f);
    }
}

// RenderMan's default shutter (Shutter 0 0: every frame an instant) under a camera that moves from
// frame to frame: the last frame's camera is a body of its own starting at the block's last
// instant, which is sampled. It was left out of blocks (the last frame empty) and rendered alone.
TEST(Sequence, InstantExposuresUnderAMovingCameraKeepEveryFrame) {
    Log log;
    auto frame = [](int f) {
        const std::string camera = "Translate " + std::to_string(-4 * f) + " 0 0\n";
        return "FrameBegin " + std::to_string(f) + "\n" + test::orthoHeader(64, 16, camera) +
               test::square(20, 28, 4, 12, 1) + "WorldEnd\nFrameEnd\n";
    };
    const std::vector<std::string> frames = {frame(1), frame(2), frame(3)};
    const Sequence seq = buildFrames(frames, log);
    for (Algorithm a : {Algorithm::Frames, Algorithm::Spacetime, Algorithm::SpacetimeOcclusion}) {
        const RenderResult all = renderScene(seq.scene, test::optionsFor(a));
        for (int f = 1; f <= 3; ++f) {
            EXPECT_DOUBLE_EQ(test::alphaSum(all, f), 64.0) << "frame " << f << " algorithm " << int(a);
            EXPECT_EQ(all.alpha(f, 24 - 4 * f, 8), 1.0f) << "frame " << f << " algorithm " << int(a);
            Log l;
            Scene alone = parseRibString(frames[size_t(f - 1)], "alone.rib", l);
            alone.settings.hasFrames = true;
            alone.settings.firstFrame = alone.settings.lastFrame = f;
            EXPECT_TRUE(test::identicalPixels(oneFrame(all, f), renderScene(alone, test::optionsFor(a))))
                << "frame " << f << " algorithm " << int(a);
        }
    }
}

// A light declared before WorldBegin is placed in camera space: a headlight.
TEST(Sequence, LightsBeforeWorldBeginAreInCameraSpace) {
    const std::string header = "Format 32 32 1\nProjection \"perspective\" \"fov\" [60]\n";
    const std::string world = "WorldBegin\nSurface \"matte\"\nPatch \"bilinear\" \"P\" [-1 -1 0  1 -1 0  -1 1 -1  1 1 -1]\nWorldEnd\n";
    Log log;
    const Scene before = parseRibString(header + "LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n" +
                                            "Translate 0 0 4\nRotate 30 0 1 0\n" + world,
                                        "before.rib", log);
    ASSERT_EQ(before.lights.size(), 1u);
    // The same light in the world: from the eye along its view direction.
    const Matrix4 w2c = before.camera.worldToCamera.at(0);
    Matrix4 c2w;
    ASSERT_TRUE(invert(w2c, &c2w));
    const Vec3d from = c2w.point({0, 0, 0}), to = c2w.point({0, 0, 1});
    char light[256];
    std::snprintf(light, sizeof light, "LightSource \"distantlight\" 1 \"from\" [%.17g %.17g %.17g] \"to\" [%.17g %.17g %.17g]\n",
                  from.x, from.y, from.z, to.x, to.y, to.z);
    const std::string inWorld = header + "Translate 0 0 4\nRotate 30 0 1 0\n" + world;
    const Scene after = parseRibString(inWorld.substr(0, inWorld.find("WorldBegin\n") + 11) + light +
                                           inWorld.substr(inWorld.find("WorldBegin\n") + 11),
                                       "after.rib", log);
    const RenderResult a = renderScene(before), b = renderScene(after);
    EXPECT_LT(test::maxAbsDifference(a, b), 1e-5f);
    EXPECT_GT(a.channel(0, 16, 16, 0), 0.5f);  // lit head-on
}

// An area light's shape in a frame sequence is in the frame's camera space like everything else:
// under a camera that is turned and moved (and mirrored, as exporters from right-handed tools
// write it) and that pans within the frames' exposures, each frame renders as its RIB alone. Two
// area lights alike but for their shapes (declared under the same transform) stay two lights.
TEST(Sequence, AreaLightsAreInTheFramesCameraSpace) {
    auto frame = [](int f) {
        const std::string t0 = std::to_string(f - 0.25), t1 = std::to_string(f + 0.25);
        const std::string pan = f >= 3 ? std::to_string(4 * (f - 2)) : "0", pan1 = f >= 3 ? std::to_string(4 * (f - 2) + 2) : "0";
        return "FrameBegin " + std::to_string(f) +
               "\nFormat 48 32 1\nProjection \"perspective\" \"fov\" [50]\nShutter -0.25 0.25\nPixelSamples 2 2\n"
               "Scale 1 1 -1\nMotionBegin [" + t0 + " " + t1 + "]\nRotate " + pan + " 0 1 0\nRotate " + pan1 +
               " 0 1 0\nMotionEnd\nRotate -56 1 0 0\nTranslate -0.5 6 -4\nWorldBegin\n"
               "AttributeBegin\nOpacity [0 0 0]\nSurface \"constant\"\n"
               "AreaLightSource \"arealight\" 7 \"intensity\" [8] \"string shadowname\" [\"raytrace\"]\n"
               "Translate -2 -1 3\nPatch \"bilinear\" \"P\" [-0.5 -0.5 0  0.5 -0.5 0  -0.5 0.5 0  0.5 0.5 0]\nAttributeEnd\nIlluminate 7 1\n"
               "AttributeBegin\nOpacity [0 0 0]\nSurface \"constant\"\n"
               "AreaLightSource \"arealight\" 8 \"intensity\" [8] \"string shadowname\" [\"raytrace\"]\n"
               "Translate 2 1 3\nPatch \"bilinear\" \"P\" [-0.2 -0.2 0  0.2 -0.2 0  -0.2 0.2 0  0.2 0.2 0]\nAttributeEnd\nIlluminate 8 1\n"
               "Surface \"matte\"\nPolygon \"P\" [-6 -6 0  6 -6 0  6 6 0  -6 6 0]\n"
               "Translate 0 0 0.5\nSphere 0.5 -0.5 0.5 360\nWorldEnd\nFrameEnd\n";
    };
    std::vector<std::string> frames;
    for (int f = 1; f <= 4; ++f) frames.push_back(frame(f));
    Log log;
    const Sequence seq = buildFrames(frames, log);
    ASSERT_EQ(seq.scene.lights.size(), 6u);  // frames 1-2 share their two lights; 3 and 4 pan
    const RenderResult all = renderScene(seq.scene, test::optionsFor(Algorithm::Frames));
    for (int f = 1; f <= 4; ++f) {
        Log l;
        Scene alone = parseRibString(frames[size_t(f - 1)], "alone.rib", l);
        alone.settings.hasFrames = true;
        alone.settings.firstFrame = alone.settings.lastFrame = f;
        // Shadows per sample, as a merged sequence tests them (nothing in it lasts the whole shot;
        // alone, the still sphere's shadow would be tested at the floor's vertices).
        RenderOptions perSample = test::optionsFor(Algorithm::Frames);
        perSample.shadowsPerSample = true;
        const RenderResult one = renderScene(alone, perSample);
        EXPECT_GT(one.channel(f, 24, 20, 0), 0.05f) << "frame " << f << ": the floor is lit";
        EXPECT_TRUE(test::identicalPixels(oneFrame(all, f), one)) << "frame " << f;
    }
}

// ---- Bad sequences ------------------------------------------------------------------------------------
std::string errorOf(const std::vector<std::string>& frames) {
    Log log;
    try {
        buildFrames(frames, log);
    } catch (const InputError& e) {
        return e.report();
    }
    return "";
}

// A builder takes one pass's frames (streyes/passes.h sorts frames into passes, so frames of
// other resolutions, shutters or lenses are other passes, not errors): in increasing order, gaps
// allowed (another pass's frames), with one shutter.
TEST(Sequence, ABuilderTakesOnePassesFramesInIncreasingOrder) {
    std::string e = errorOf({stillFrame(2), stillFrame(1)});
    EXPECT_NE(e.find("frame1.rib:1: error: frame 1 comes after frame 2"), std::string::npos) << e;
    e = errorOf({stillFrame(1), stillFrame(2, "0 0.25")});
    EXPECT_NE(e.find("frame1.rib:1: error: frame 2 has Shutter 0 0.25, not the other frames' Shutter 0 0.5"),
              std::string::npos)
        << e;
    e = errorOf({stillFrame(1, "0 1.5"), stillFrame(2, "0 1.5")});
    EXPECT_NE(e.find("overlap"), std::string::npos) << e;
    EXPECT_EQ(errorOf({stillFrame(1, "0 1.5")}), "");  // alone it renders
    // A gap (frame 2 another pass's): the still set is one run over it.
    Log log;
    const Sequence gap = buildFrames({stillFrame(1), stillFrame(3)}, log);
    EXPECT_EQ(gap.stats.stillRuns, 7u);
    EXPECT_EQ(gap.scene.settings.firstFrame, 1);
    EXPECT_EQ(gap.scene.settings.lastFrame, 3);
    EXPECT_EQ(gap.displays.count(2), 0u);
}

TEST(Sequence, FrameBlocksMustHoldAWorld) {
    Log log;
    auto err = [&](const std::string& text) {
        try {
            buildFrames({text}, log);
        } catch (const InputError& e) {
            return e.report();
        }
        return std::string();
    };
    EXPECT_NE(err("FrameBegin 1\nFormat 8 8 1\nFrameEnd\n").find("frame0.rib:3: error: the frame begun at line 1 has no WorldBegin"),
              std::string::npos);
    EXPECT_NE(err("FrameBegin 1\nWorldBegin\nFrameEnd\n").find("frame0.rib:3: error: FrameEnd before WorldEnd"),
              std::string::npos);
    EXPECT_NE(err("FrameBegin 1\nWorldBegin\nWorldEnd\n").find("frame0.rib:1: error: FrameBegin is never closed"),
              std::string::npos);
    EXPECT_NE(err("FrameBegin 1\nFrameBegin 2\n").find("frame0.rib:2: error: FrameBegin inside the frame begun at line 1"),
              std::string::npos);
}

TEST(Sequence, AnIdentifierGivenTwiceInOneFrameWarnsNamingTheLine) {
    Log log;
    const std::string named = "Attribute \"identifier\" \"name\" [\"rock\"]\n";
    auto frame = [&](int n) {
        std::string f = stillFrame(n);
        f.replace(f.find("Surface"), 0, "AttributeBegin\n" + named + "Sphere 1 -1 1 360\nAttributeEnd\nAttributeBegin\n" +
                                            named + "Sphere 2 -2 2 360\nAttributeEnd\n");
        return f;
    };
    const Sequence seq = buildFrames({frame(1), frame(2)}, log);
    bool warned = false;
    for (const std::string& w : log.warnings())
        warned = warned || (w.find("frame0.rib:14") != std::string::npos && w.find("\"rock\"") != std::string::npos &&
                            w.find("line 10") != std::string::npos);
    EXPECT_TRUE(warned) << ::testing::PrintToString(log.warnings());
    // Matched in order all the same: both spheres are still runs over both frames.
    int rocks = 0;
    for (const SequenceRun& r : seq.runs) rocks += r.name == "rock" && r.firstFrame == 1 && r.lastFrame == 2;
    EXPECT_EQ(rocks, 2);
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// Frames that differ only in what shades a primitive (a primitive variable, a displacement, its
// sides) are not one still run: each keeps its own.
TEST(Sequence, ShadingChangesBetweenFramesAreNotMerged) {
    auto frame = [](int f, const std::string& extra, const std::string& params) {
        return "FrameBegin " + std::to_string(f) + "\nFormat 32 32 1\nWorldBegin\n" + extra +
               "Patch \"bilinear\" \"P\" [-1 -1 5  1 -1 5  -1 1 5  1 1 5] " + params + "\nWorldEnd\nFrameEnd\n";
    };
    Log log;
    const Sequence same = buildFrames({frame(1, "", "\"constant float Kd\" [0.5]"), frame(2, "", "\"constant float Kd\" [0.5]")}, log);
    EXPECT_EQ(same.stats.runs, 1u);
    const Sequence primvar = buildFrames({frame(1, "", "\"constant float Kd\" [0.5]"), frame(2, "", "\"constant float Kd\" [0.25]")}, log);
    EXPECT_EQ(primvar.stats.runs, 2u);
    const Sequence displaced = buildFrames({frame(1, "", ""), frame(2, "Displacement \"bumpy\"\n", "")}, log);
    EXPECT_EQ(displaced.stats.runs, 2u);
    const Sequence sides = buildFrames({frame(1, "", ""), frame(2, "Sides 1\n", "")}, log);
    EXPECT_EQ(sides.stats.runs, 2u);
}

// A procedural whose output depends on its size on screen (a Weber-Penn tree: its branches, or
// the paper's far-tree volume under 40 pixels a side; the share of a branch's leaves it keeps) is
// measured in the world its frame was written in: a frame sequence, whose frames are baked into
// the camera's space, draws what the frames written as one world draw. Under a camera rolled by 45
// degrees the tree's bound is 1.4 times as long in camera space as in the world: at 110 m the one
// world grows the tree's 50 branches, where the sequence made it a crown volume before; at 35 m
// in the wind the sequence kept other leaves (4203 bodies against 2756).
TEST(Sequence, AProceduralsOutputIsMeasuredInItsFramesWorld) {
    struct Case {
        double distance;
        std::string params, bound;
    };
    for (const Case& c : {Case{110, "", "-10 10 -1 20 -10 10"},
                          Case{35, " WindSpeed=4 WindGust=2 keystep=4", "-30 30 -10 40 -30 30"}}) {
        SCOPED_TRACE(c.distance);
        const std::string camera =
            "Format 96 96 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 2 2\nShutter 0 0.5\n"
            "Rotate 45 0 0 1\nTranslate 0 -7 " + std::to_string(c.distance) + "\n";
        const std::string world =
            "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [-1 2 -1] \"to\" [0 0 0]\nSurface \"matte\"\n"
            "Procedural \"DynamicLoad\" [\"tree\" \"model=weberpenn preset=quaking_aspen seed=2" + c.params + "\"] [" +
            c.bound + "]\nWorldEnd\n";
        const RenderResult one = test::renderRib("Option \"streyes\" \"int frames\" [1 2]\n" + camera + world);
        Log log;
        const Sequence seq = buildFrames({"FrameBegin 1\n" + camera + world + "FrameEnd\n",
                                          "FrameBegin 2\n" + camera + world + "FrameEnd\n"}, log);
        EXPECT_EQ(seq.stats.stillRuns, 1u);  // the tree: one still procedural over both frames
        const RenderResult two = renderScene(seq.scene);
        ASSERT_EQ(one.frames.size(), 2u);
        ASSERT_EQ(two.frames.size(), 2u);
        EXPECT_EQ(one.stats.proceduralsByDepth, (std::vector<uint64_t>{1, 50}));  // the tree and its branches
        EXPECT_EQ(two.stats.proceduralsByDepth, one.stats.proceduralsByDepth);
        EXPECT_EQ(two.stats.bodiesGenerated, one.stats.bodiesGenerated);
        EXPECT_EQ(two.stats.counters.micropolygons, one.stats.counters.micropolygons);
        EXPECT_GT(test::alphaSum(one, 1), 20.0);  // the tree is in the picture
        EXPECT_LT(test::maxAbsDifference(two, one), 1e-5f);
    }
}

}  // namespace
}  // namespace streyes
