// Passes (streyes/passes.h): frames grouped into jobs, make requests among them, versions of
// names, and the order jobs come in.
#include "streyes/passes.h"

#include <gtest/gtest.h>

#include <fstream>

#include "test_util.h"

namespace streyes {
namespace {

// A depth frame from a light: writes `map` (a zfile).
std::string depthFrame(int n, const std::string& map, double x = 0) {
    return "FrameBegin " + std::to_string(n) + "\nDisplay \"" + map +
           "\" \"zfile\" \"z\"\nFormat 32 32 1\nProjection \"perspective\" \"fov\" 40\nWorldBegin\nTranslate " +
           std::to_string(x) + " 0 5\nSphere 1 -1 1 360\nWorldEnd\nFrameEnd\n";
}
// A picture frame whose light reads `map`.
std::string pictureFrame(int n, const std::string& map, const std::string& format = "Format 64 48 1") {
    return "FrameBegin " + std::to_string(n) + "\nDisplay \"pic.####.exr\" \"file\" \"rgba\"\n" + format +
           "\nProjection \"perspective\" \"fov\" 30\nWorldBegin\nLightSource \"shadowspot\" 1 \"shadowname\" \"" + map +
           "\"\nTranslate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\nFrameEnd\n";
}

struct Read {
    std::vector<PassJob> jobs;
    std::vector<PassJob> renders() const {
        std::vector<PassJob> r;
        for (const PassJob& j : jobs)
            if (j.kind == PassJob::Kind::Render) r.push_back(j);
        return r;
    }
};

Read readText(const std::string& text, PassRequest req = {}) {
    test::TempDir tmp("passes");
    const std::string path = tmp.path() + "/in.rib";
    std::ofstream(path) << text;
    Log log;
    log.setQuiet(true);
    Read r;
    readPasses(path, req, log, [&](PassJob&& j) { r.jobs.push_back(std::move(j)); });
    return r;
}

std::vector<int> framesOf(const PassJob& j) {
    std::vector<int> f;
    for (const auto& [n, frame] : j.frames) f.push_back(n);
    return f;
}

// As exporters write a shot: per frame a depth frame, MakeShadow, a picture, every frame reusing
// one map name. The depth frames are one job, the pictures another after the MakeShadows, and
// each picture reads the version its own frame made.
TEST(Passes, InterleavedDepthAndPictureFramesAreTwoJobsEachFrameReadingItsOwnMap) {
    std::string text;
    for (int f = 1; f <= 4; ++f)
        text += depthFrame(f, "shad.z", 0.1 * f) + "MakeShadow \"shad.z\" \"shad.shd\"\n" + pictureFrame(f, "shad.shd");
    const Read r = readText(text);
    ASSERT_EQ(r.jobs.size(), 6u);
    EXPECT_EQ(r.jobs[0].kind, PassJob::Kind::Render);
    EXPECT_TRUE(r.jobs[0].depth);
    EXPECT_EQ(framesOf(r.jobs[0]), (std::vector<int>{1, 2, 3, 4}));
    std::vector<FileVersion> made;  // each frame's shadow map version, as the MakeShadows make them
    for (int k = 1; k <= 4; ++k) {
        const PassJob& m = r.jobs[size_t(k)];
        ASSERT_EQ(m.kind, PassJob::Kind::MakeShadow);
        EXPECT_EQ(m.input, r.jobs[0].frames.at(k).maps.at(0).second);  // frame k's depth map
        made.push_back(m.output);
    }
    const PassJob& pictures = r.jobs[5];
    EXPECT_FALSE(pictures.depth);
    EXPECT_EQ(framesOf(pictures), (std::vector<int>{1, 2, 3, 4}));
    EXPECT_TRUE(pictures.sequence.isSequence);
    for (int k = 1; k <= 4; ++k) EXPECT_EQ(pictures.frames.at(k).reads.at("shad.shd"), made[size_t(k - 1)]) << k;
    EXPECT_NE(r.jobs[0].pass, pictures.pass);
}

// Aqsis's vase: two depth frames of other cameras and resolutions, MakeShadow of each, a picture.
// --frames 3 asks for the picture: the depth frames it reads come too.
TEST(Passes, ThePictureTakesTheDepthFramesItReadsAlong) {
    const std::string text = depthFrame(1, "a.z") + depthFrame(2, "b.z", 3) + "MakeShadow \"a.z\" \"a.shd\"\n" +
                             "MakeShadow \"b.z\" \"b.shd\"\n" + pictureFrame(3, "a.shd");
    Read all = readText(text);
    ASSERT_EQ(all.jobs.size(), 4u);
    // Frames 1 and 2 have other cameras but the same settings: one pass (the numbers increase).
    EXPECT_EQ(framesOf(all.jobs[0]), (std::vector<int>{1, 2}));
    PassRequest three;
    three.frames = {true, 3, 3};
    Read some = readText(text, three);
    ASSERT_EQ(some.jobs.size(), 3u);  // b.shd is read by nothing wanted: frame 2 and its MakeShadow stay out
    EXPECT_EQ(framesOf(some.jobs[0]), (std::vector<int>{1}));
    EXPECT_EQ(some.jobs[1].kind, PassJob::Kind::MakeShadow);
    EXPECT_EQ(some.jobs[1].makeShadow.input, "a.z");
    EXPECT_EQ(framesOf(some.jobs.back()), (std::vector<int>{3}));
    PassRequest one;
    one.frames = {true, 1, 1};
    Read depthOnly = readText(text, one);  // a depth frame asked for by number
    ASSERT_EQ(depthOnly.renders().size(), 1u);
    EXPECT_TRUE(depthOnly.renders()[0].depth);
}

// Frames that differ in resolution, shutter or projection are not refused: each set its own pass.
TEST(Passes, FramesWithOtherSettingsAreOtherPasses) {
    const std::string text = pictureFrame(1, "") + pictureFrame(2, "", "Format 32 24 1") + pictureFrame(3, "") +
                             pictureFrame(4, "", "Format 32 24 1");
    const Read r = readText(text);
    const std::vector<PassJob> jobs = r.renders();
    ASSERT_EQ(jobs.size(), 2u);
    EXPECT_EQ(framesOf(jobs[0]), (std::vector<int>{1, 3}));  // frame 2 between: another pass's, not written
    EXPECT_EQ(framesOf(jobs[1]), (std::vector<int>{2, 4}));
    EXPECT_EQ(jobs[0].sequence.scene.settings.firstFrame, 1);
    EXPECT_EQ(jobs[0].sequence.scene.settings.lastFrame, 3);
    // Numbers that do not increase start another job of the same pass (two shots numbered alike).
    const Read shots = readText(pictureFrame(1, "") + pictureFrame(2, "") + pictureFrame(1, "") + pictureFrame(2, ""));
    ASSERT_EQ(shots.renders().size(), 2u);
    EXPECT_EQ(shots.renders()[0].pass, shots.renders()[1].pass);
}

// A zoom (field of view, screen window or frame aspect ratio changing) is one pass whose merged
// scene keeps each frame's projection; another kind of projection is another pass, and so is a
// depth frame from a light with another cone (each light's maps one pass).
TEST(Passes, AZoomIsOnePassKeepingEachFramesProjection) {
    auto frame = [](int n, const std::string& projection, const std::string& more) {
        return "FrameBegin " + std::to_string(n) + "\nDisplay \"pic.####.exr\" \"file\" \"rgba\"\nFormat 64 48 1\n" +
               projection + "\n" + more + "WorldBegin\nTranslate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\nFrameEnd\n";
    };
    const std::string fov40 = "Projection \"perspective\" \"fov\" 40", fov30 = "Projection \"perspective\" \"fov\" 30";
    const Read zoom = readText(frame(1, fov40, "") + frame(2, fov30, "") + frame(3, fov40, "ScreenWindow -0.5 0.5 -0.5 0.5\n") +
                               frame(4, fov40, "FrameAspectRatio 2\n") + frame(5, fov40, ""));
    const std::vector<PassJob> jobs = zoom.renders();
    ASSERT_EQ(jobs.size(), 1u);
    const Scene& merged = jobs[0].sequence.scene;
    EXPECT_EQ(framesOf(jobs[0]), (std::vector<int>{1, 2, 3, 4, 5}));
    EXPECT_EQ(merged.camera.fov, 40);
    ASSERT_EQ(merged.frameCamera.size(), 3u);  // frames 2, 3, 4: frame 5 projects as frame 1
    EXPECT_EQ(merged.frameCamera.at(2).fov, 30);
    EXPECT_TRUE(merged.frameCamera.at(3).hasScreenWindow);
    EXPECT_EQ(merged.frameCamera.at(3).screenWindow[1], 0.5);
    EXPECT_EQ(merged.frameCamera.at(4).frameAspect, 2);
    // The sphere is a still primitive, but its run ends at each change of projection.
    EXPECT_EQ(merged.quadrics.size(), 5u);
    const Read kinds = readText(frame(1, fov40, "") + frame(2, "Projection \"orthographic\"", "") + frame(3, fov30, ""));
    ASSERT_EQ(kinds.renders().size(), 2u);
    EXPECT_EQ(framesOf(kinds.renders()[0]), (std::vector<int>{1, 3}));
    const Read lights = readText(depthFrame(1, "a.z") + depthFrame(2, "b.z") +
                                 [] {
                                     std::string d = depthFrame(3, "c.z");
                                     d.replace(d.find("\"fov\" 40"), 8, "\"fov\" 60");
                                     return d;
                                 }());
    ASSERT_EQ(lights.renders().size(), 2u);
    EXPECT_EQ(framesOf(lights.renders()[0]), (std::vector<int>{1, 2}));
    EXPECT_EQ(framesOf(lights.renders()[1]), (std::vector<int>{3}));
}

// At most a block of frames a job; a flush renders what is held, in an order that makes what each
// job reads first.
TEST(Passes, JobsHoldABlockOfFramesAtMost) {
    std::string text;
    for (int f = 1; f <= 7; ++f)
        text += depthFrame(f, "shad.z") + "MakeShadow \"shad.z\" \"shad.shd\"\n" + pictureFrame(f, "shad.shd");
    PassRequest req;
    req.blockFrames = 3;
    const Read r = readText(text, req);
    std::vector<std::vector<int>> depth, pictures;
    for (const PassJob& j : r.renders()) (j.depth ? depth : pictures).push_back(framesOf(j));
    EXPECT_EQ(depth, (std::vector<std::vector<int>>{{1, 2, 3}, {4, 5, 6}, {7}}));
    EXPECT_EQ(pictures, (std::vector<std::vector<int>>{{1, 2, 3}, {4, 5, 6}, {7}}));
    // Each MakeShadow comes after the depth job with its frame and before the pictures reading it.
    std::set<FileVersion> made;
    for (const PassJob& j : r.jobs) {
        if (j.kind == PassJob::Kind::Render && j.depth)
            for (const auto& [f, frame] : j.frames) made.insert(frame.maps.at(0).second);
        if (j.kind == PassJob::Kind::MakeShadow) {
            EXPECT_TRUE(made.count(j.input)) << j.input;
            made.insert(j.output);
        }
        if (j.kind == PassJob::Kind::Render && !j.depth) {
            for (const auto& [f, frame] : j.frames) EXPECT_TRUE(made.count(frame.reads.at("shad.shd"))) << f;
        }
    }
    // Versions no later job reads are let go: each depth map once its MakeShadow ran, each shadow
    // map once its picture did (the last of each name stays: nothing wrote over it).
    std::multiset<FileVersion> released;
    for (const PassJob& j : r.jobs) released.insert(j.release.begin(), j.release.end());
    EXPECT_EQ(released.size(), 12u);
    for (FileVersion v : released) EXPECT_EQ(released.count(v), 1u);
}

// A MakeTexture reads a file a frame before it may write, and the frames after it that name its
// texture read what it makes: it comes after the frames before it, and those after come after it.
TEST(Passes, MakeTextureRunsAfterTheFramesBeforeIt) {
    const std::string text = pictureFrame(1, "") +
                             "MakeTexture \"pic.0001.exr\" \"pic.tx\" \"clamp\" \"clamp\" \"box\" 1 1\n" +
                             pictureFrame(2, "pic.tx") + pictureFrame(3, "");
    const Read r = readText(text);
    ASSERT_EQ(r.jobs.size(), 3u);
    EXPECT_EQ(framesOf(r.jobs[0]), (std::vector<int>{1}));
    EXPECT_EQ(r.jobs[1].kind, PassJob::Kind::MakeTexture);
    EXPECT_EQ(framesOf(r.jobs[2]), (std::vector<int>{2, 3}));
}

// Aqsis's occlusion maps (occlmap.rib): frame 1 writes the file, frames 2.. append to it with
// "float append" [1]. The frames stay one depth job (a job keeps its maps in frame order), each
// appending frame adds to the version the frame before it made, and the picture reads the last.
TEST(Passes, AppendingDepthFramesAddToTheVersionBeforeThemInOneJob) {
    std::string text;
    for (int f = 1; f <= 4; ++f) {
        std::string frame = depthFrame(f, "occl.sm", 0.1 * f);
        if (f > 1) frame.replace(frame.find("\"zfile\" \"z\""), 12, "\"shadow\" \"z\" \"float append\" [1]");
        text += frame;
    }
    text += pictureFrame(5, "occl.sm");
    const Read r = readText(text);
    const std::vector<PassJob> jobs = r.renders();
    ASSERT_EQ(jobs.size(), 2u);
    EXPECT_EQ(framesOf(jobs[0]), (std::vector<int>{1, 2, 3, 4}));
    const auto& frames = jobs[0].frames;
    EXPECT_TRUE(frames.at(1).appends.empty());
    for (int f = 2; f <= 4; ++f) {
        ASSERT_EQ(frames.at(f).maps.size(), 1u);
        EXPECT_TRUE(frames.at(f).maps[0].first.append);
        ASSERT_EQ(frames.at(f).appends.size(), 1u);
        EXPECT_EQ(frames.at(f).appends.begin()->first, frames.at(f).maps[0].second);
        EXPECT_EQ(frames.at(f).appends.begin()->second, frames.at(f - 1).maps[0].second) << "frame " << f;
    }
    EXPECT_EQ(jobs[1].frames.at(5).reads.at("occl.sm"), frames.at(4).maps[0].second);
}

}  // namespace
}  // namespace streyes
