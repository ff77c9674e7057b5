// The scene-wide tests of tests/core (frame-block invariance, the epsilon = 0 identity, RIB
// encodings, recorded checksums) on the scene files of scenes/ and scenes/hard/ that hold several
// worlds: per frame a depth frame rendered from a light, MakeShadow, then the picture reading its
// own frame's map, as exporters write a shadow-mapped light (scenes/forest-wp-maps.rib). tests/core
// reads a file as one world; here a file renders as `streyes render` renders it (readPasses, and
// the command's PassRunner for the depth jobs, MakeShadow and each picture's maps), in this process,
// so that the pictures compare bit for bit in float (a file's RGB is half).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <Imath/half.h>

#include "cli/pass_runner.h"
#include "cli_run.h"
#include "scene/rib_gzip.h"
#include "scene/rib_writer.h"
#include "streyes/image_io.h"
#include "streyes/passes.h"
#include "streyes/textures.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> multiPassScenes() { return test::sceneFiles(true); }

// The maps a file's depth frames write go to the working folder (their Display names), as the
// command's do: a test renders in a folder of its own.
class InFolder {
  public:
    explicit InFolder(const std::string& dir) : back_(fs::current_path()) { fs::current_path(dir); }
    ~InFolder() {
        std::error_code ignore;
        fs::current_path(back_, ignore);
    }
    InFolder(const InFolder&) = delete;
    InFolder& operator=(const InFolder&) = delete;

  private:
    fs::path back_;
};

struct PassRender {
    test::RenderResult pictures;  // the pictures' frames (a file's RGBA and Z, as floats)
    int depthFrames = 0;          // depth frames rendered for them
};

// Pictures [first, last] of the file at `path` as `streyes render PATH --frames first-last` renders
// them (src/cli/render_command.cpp): depth jobs at their frames' own Format and PixelSamples,
// rasterized, their maps kept per frame; MakeShadow; each picture job with its frames' maps. `o`
// is the pictures' options (--algorithm, --samples, --frame-block as maxFrameBlock); `width`, the
// pictures' width, their height from their Format's aspect (--res); `depthWidth` > 0, the depth
// frames' (kCheapDepthWidth), else their Format's.
// Tests that compare renders of one file with each other (blocks, tolerance 0, encodings) render its
// depth frames 512 wide: the maps' detail is not what they test, and scenes/forest-wp-maps.rib's
// 2048-wide depth frames were most of their time. The command's own render and the recorded
// checksums keep the file's.
constexpr int kCheapDepthWidth = 512;

PassRender renderPasses(const std::string& path, RenderOptions o, int first, int last, int width, int depthWidth = 0) {
    PassRender result;
    Log log;
    log.setQuiet(true);
    cli::PassRunner runner(log);
    RenderOptions depthOpts = o;
    depthOpts.xres = depthOpts.yres = depthOpts.samples = 0;
    depthOpts.textureSource = openImageTextures;
    if (depthOpts.algorithm == Algorithm::Raytrace) depthOpts.algorithm = Algorithm::SpacetimeOcclusion;
    if (depthOpts.algorithm == Algorithm::RaytraceFrames) depthOpts.algorithm = Algorithm::FramesOcclusion;
    FrameWriter writer;  // MakeTexture's (it writes nothing here)
    auto picture = [&](PassJob& job) {
        Scene& scene = job.sequence.scene;
        RenderOptions b = o;
        b.xres = width;
        b.yres = std::max(1, scene.camera.yres * width / scene.camera.xres);
        if (job.sequence.isSequence) {
            b.hasFrames = true;
            b.firstFrame = scene.settings.firstFrame;
            b.lastFrame = scene.settings.lastFrame;
        }
        const bool isSequence = job.sequence.isSequence;
        // Frames of the block another pass has: rendered with it, not kept.
        b.frameDone = [&job, isSequence](int f) { return isSequence && !job.frames.count(f); };
        b.textureSource = openImageTextures;
        b.shadowMaps = runner.binding(job);
        runner.cutBlobbies(job);
        const double open = scene.settings.shutterOpen;
        Renderer(scene, b, log).render([&](FrameImage& img) {
            auto frame = job.frames.find(img.frame);
            if (frame != job.frames.end()) runner.keep(frame->second, img, open);
            if (isSequence && frame == job.frames.end()) return;
            for (FrameImage& f : result.pictures.frames)
                if (f.frame == img.frame) {  // a second pass (procedurals that outgrew their bounds)
                    f = img;
                    return;
                }
            result.pictures.frames.push_back(img);
        });
    };
    auto onJob = [&](PassJob&& job) {
        switch (job.kind) {
            case PassJob::Kind::Render:
                if (job.depth) {
                    RenderOptions d = depthOpts;
                    if (depthWidth > 0) {  // the depth frame's aspect kept
                        const CameraDesc& c = job.sequence.scene.camera;
                        d.xres = depthWidth;
                        d.yres = std::max(1, c.yres * depthWidth / c.xres);
                    }
                    runner.renderDepth(job, d);
                    result.depthFrames += int(job.frames.size());
                } else {
                    picture(job);
                }
                break;
            case PassJob::Kind::MakeShadow: runner.makeShadow(job); break;
            case PassJob::Kind::MakeTexture: runner.makeTexture(job, writer); break;
        }
        runner.release(job.release);
    };
    PassRequest request;
    request.frames.given = true;
    request.frames.first = first, request.frames.last = last;
    request.blockFrames = o.maxFrameBlock;
    ReadDetail detail;
    detail.deferRepellingMaps = true;  // a Blobby's repelling planes read their maps when their pass renders
    readPasses(path, request, log, onJob, detail);
    writer.finish();
    std::sort(result.pictures.frames.begin(), result.pictures.frames.end(),
              [](const FrameImage& a, const FrameImage& b) { return a.frame < b.frame; });
    result.pictures.warnings = log.warnings();
    return result;
}

// The first picture frame of a file: the lowest FrameBegin number.
int firstFrameOf(const std::string& path) {
    std::ifstream in(path);
    std::string word;
    int first = 0;
    bool any = false;
    while (in >> word)
        if (word == "FrameBegin") {
            int f = 0;
            if (in >> f) first = any ? std::min(first, f) : f, any = true;
        }
    return first;
}

test::RenderResult onlyFrame(const test::RenderResult& r, int frame) {
    test::RenderResult one;
    one.frames = {r.frame(frame)};
    return one;
}

std::string paramName(const testing::TestParamInfo<std::string>& info) {
    std::string name = info.param.substr(0, info.param.size() - 4);
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
}

class MultiPassScenes : public testing::TestWithParam<std::string> {};

// The renders here are the command's: `streyes render FILE --frames a-b --res WxH --samples 4`
// writes the pictures renderPasses makes, RGBA as their halves and Z bit for bit.
TEST_P(MultiPassScenes, RendersWhatTheCommandRenders) {
    if (test::slowUnderSanitizers(GetParam())) GTEST_SKIP() << "minutes under the sanitizers: the release suite runs it";
    const std::string path = test::sourcePath(GetParam());
    const test::TempDir dir("multipass-command");
    const int first = firstFrameOf(path);
    RenderOptions o;
    o.samples = 4;
    PassRender r;
    {
        const InFolder in(dir.path());
        r = renderPasses(path, o, first, first + 1, 64);
    }
    ASSERT_EQ(r.pictures.frames.size(), 2u);
    const FrameImage& f0 = r.pictures.frames[0];
    const test::CliRun run = test::runStreyesWith(
        "cd " + dir.path() + " && ", "render " + path + " -q --frames " + std::to_string(first) + "-" +
                                         std::to_string(first + 1) + " --res 64x" + std::to_string(f0.height) +
                                         " --samples 4 -o pic.####.exr");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    for (const FrameImage& f : r.pictures.frames) {
        SCOPED_TRACE(f.frame);
        char name[32];
        std::snprintf(name, sizeof name, "/pic.%04d.exr", f.frame);
        const ImageData file = readImage(dir.path() + name);
        ASSERT_EQ(file.width, f.width);
        ASSERT_EQ(file.height, f.height);
        const int z = file.channelIndex("Z");
        ASSERT_GE(z, 0);
        size_t colourDiffer = 0, depthDiffer = 0;
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                const size_t i = size_t(y) * size_t(f.width) + size_t(x);
                for (int c = 0; c < 4; ++c)
                    colourDiffer += float(Imath::half(f.rgba[i * 4 + size_t(c)])) != file.at(x, y, c);
                depthDiffer += std::memcmp(&f.z[i], &file.pixels[i * file.channels.size() + size_t(z)], sizeof(float)) != 0;
            }
        EXPECT_EQ(colourDiffer, 0u);
        EXPECT_EQ(depthDiffer, 0u);
    }
}

// As FrameBlockInvariance in tests/core: the second frame rendered alone (with the depth frame it
// reads), in a block of the first two (--frame-block 2) and in blocks of one: the same pictures,
// bit for bit, with the rasterizers and with the ray tracer (whose depth frames are rasterized).
// The default algorithm's pictures at 320 pixels wide: there forest-wp-maps.rib's windy forest
// differed alone and in a block while its runs ended at the block's (RMSE 2.8e-4; 64 pixels did
// not show it); the others at 64.
TEST_P(MultiPassScenes, AFramesPixelsDoNotDependOnItsBlock) {
    if (test::slowUnderSanitizers(GetParam())) GTEST_SKIP() << "minutes under the sanitizers: the release suite runs it";
    const std::string path = test::sourcePath(GetParam());
    const test::TempDir dir("multipass-block");
    const InFolder in(dir.path());
    const int first = firstFrameOf(path);
    RenderOptions o;
    o.samples = 4;
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Frames, Algorithm::Raytrace}) {
        SCOPED_TRACE(algorithmName(a));
        o.algorithm = a;
        const int width = a == Algorithm::SpacetimeOcclusion ? 320 : 64;
        o.maxFrameBlock = 2;
        const PassRender together = renderPasses(path, o, first, first + 1, width, kCheapDepthWidth);
        o.maxFrameBlock = 1;
        const PassRender apart = renderPasses(path, o, first, first + 1, width, kCheapDepthWidth);
        o.maxFrameBlock = 64;
        const PassRender alone = renderPasses(path, o, first + 1, first + 1, width, kCheapDepthWidth);
        ASSERT_EQ(together.pictures.frames.size(), 2u);
        ASSERT_EQ(alone.pictures.frames.size(), 1u);
        EXPECT_EQ(together.depthFrames, apart.depthFrames);
        EXPECT_GT(test::alphaSum(together.pictures, first + 1), 0.0);
        // As in tests/core: geometry that exhausts its split budget under occlusion culling.
        const std::vector<std::string>& w = together.pictures.warnings;
        const bool dropped = std::any_of(w.begin(), w.end(), [](const std::string& s) {
            return s.find("splits in one bucket") != std::string::npos;
        });
        if (dropped && usesOcclusion(a)) continue;
        EXPECT_TRUE(test::identicalPixels(together.pictures, apart.pictures))
            << "blocks of two frames and of one differ: max " << test::maxAbsDifference(together.pictures, apart.pictures);
        EXPECT_TRUE(test::identicalPixels(onlyFrame(together.pictures, first + 1), alone.pictures))
            << "the second frame rendered alone differs: max "
            << test::maxAbsDifference(onlyFrame(together.pictures, first + 1), alone.pictures);
    }
}

// As EveryScene.ToleranceZeroIsBitIdentical in tests/core: occlusion culling at tolerance 0 (the
// depth frames' and the pictures') gives the exact algorithm's pixels, in spacetime and frame by
// frame; the first two frames at 64 pixels wide.
TEST_P(MultiPassScenes, ToleranceZeroIsBitIdentical) {
    if (test::slowUnderSanitizers(GetParam())) GTEST_SKIP() << "minutes under the sanitizers: the release suite runs it";
    const std::string path = test::sourcePath(GetParam());
    const test::TempDir dir("multipass-tolerance");
    const InFolder in(dir.path());
    const int first = firstFrameOf(path);
    RenderOptions o;
    o.samples = 4;
    o.bucketSize = 16;
    for (const auto& [exact, culled] : {std::pair{Algorithm::Spacetime, Algorithm::SpacetimeOcclusion},
                                        std::pair{Algorithm::Frames, Algorithm::FramesOcclusion}}) {
        SCOPED_TRACE(algorithmName(culled));
        o.algorithm = exact;
        const PassRender base = renderPasses(path, o, first, first + 1, 64, kCheapDepthWidth);
        o.algorithm = culled;
        const PassRender occlusion = renderPasses(path, o, first, first + 1, 64, kCheapDepthWidth);
        ASSERT_EQ(base.pictures.frames.size(), 2u);
        EXPECT_TRUE(test::identicalPixels(base.pictures, occlusion.pictures))
            << "max " << test::maxAbsDifference(base.pictures, occlusion.pictures);
    }
}

// As RibEncodings in tests/core: the file gzip-compressed and in binary RIB (64-bit reals) renders
// the ASCII file's pictures; in binary with 32-bit floats, what its ASCII form written with those
// floats' values renders. The first frame at 48 pixels wide, 2 samples, each encoding in a folder
// of its own (the maps are written there).
TEST_P(MultiPassScenes, GzipAndBinaryRenderAsTheAsciiDoes) {
    if (test::slowUnderSanitizers(GetParam())) GTEST_SKIP() << "minutes under the sanitizers: the release suite runs it";
    const std::string source = test::sourcePath(GetParam());
    const std::string ascii = test::readFile(source);
    const test::TempDir dir("multipass-encodings");
    const int first = firstFrameOf(source);
    RenderOptions o;
    o.samples = 2;
    auto render = [&](const std::string& name, const std::string& bytes) {
        const std::string at = dir.path() + "/" + name;
        fs::create_directory(at);
        test::writeFile(at, "scene.rib", bytes);
        const InFolder in(at);
        return renderPasses(at + "/scene.rib", o, first, first, 48, kCheapDepthWidth).pictures;
    };
    const test::RenderResult expected = render("ascii", ascii);
    ASSERT_EQ(expected.frames.size(), 1u);
    const std::string binary = encodeRib(ascii, source, {true, false, false});
    ASSERT_TRUE(isGzip(gzip(ascii)));
    ASSERT_EQ(binary[0], '\314') << "binary RIB starts with its first request's definition";
    for (const auto& [name, bytes] :
         {std::pair{"gzip", gzip(ascii)}, std::pair{"binary", binary}, std::pair{"binary-gzip", gzip(binary)}}) {
        SCOPED_TRACE(name);
        const test::RenderResult r = render(name, bytes);
        EXPECT_TRUE(test::identicalPixels(expected, r)) << "max difference " << test::maxAbsDifference(expected, r);
    }
    const test::RenderResult binary32 = render("binary32", encodeRib(ascii, source, {true, true, false}));
    const test::RenderResult ascii32 = render("ascii32", encodeRib(ascii, source, {false, true, false}));
    ASSERT_EQ(ascii32.frames.size(), 1u);
    EXPECT_TRUE(test::identicalPixels(ascii32, binary32));
}

// As SceneChecksums in tests/core (and recorded in the same file, tests/data/scene_checksums.txt,
// STREYES_RECORD_CHECKSUMS=1): the first two pictures at 64 pixels wide, 4 samples, with the
// default algorithm and with the ray tracer.
TEST_P(MultiPassScenes, PixelsMatchTheRecordedChecksums) {
    const std::string path = test::sourcePath(GetParam());
    const test::TempDir dir("multipass-checksums");
    const InFolder in(dir.path());
    const int first = firstFrameOf(path);
    RenderOptions o;
    o.samples = 4;
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        if (a == Algorithm::Raytrace && test::tooLargeToRayTrace(GetParam())) continue;
        if (a == Algorithm::Raytrace && test::slowUnderSanitizers(GetParam())) continue;  // minutes there
        o.algorithm = a;
        const PassRender r = renderPasses(path, o, first, first + 1, 64);
        ASSERT_EQ(r.pictures.frames.size(), 2u);
        EXPECT_EQ(test::checkRecordedChecksum(GetParam() + ":" + algorithmName(a), test::pixelChecksum(r.pictures)), "");
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, MultiPassScenes, testing::ValuesIn(multiPassScenes()), paramName);

// The list is not empty (else the tests above would silently test nothing).
TEST(MultiPassSceneFiles, ThereAreScenesToCheck) { EXPECT_FALSE(multiPassScenes().empty()); }

}  // namespace
}  // namespace streyes
