// RIB as it is stored: every scene in scenes/ and scenes/hard/, gzip-compressed and in binary RIB
// (reals as 64-bit floats), reads as the same scene and renders bit-identical to its ASCII form;
// in binary RIB with 32-bit floats it renders what its ASCII form written with those floats'
// values renders. Frame sequences and archives read compressed and binary as they read as text.
// (Files of several worlds render as passes: tests/cli/multipass_scenes_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene/rib_gzip.h"
#include "scene/rib_writer.h"
#include "scene/sequence_equal.h"
#include "streyes/rib.h"
#include "streyes/sequence.h"
#include "test_util.h"

namespace streyes {
namespace {

std::vector<std::string> everyScene() { return test::sceneFiles(false); }

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

template <class T>
bool sameList(const std::vector<T>& a, const std::vector<T>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (!sameData(a[i], b[i])) return false;
    return true;
}

// What the renderer reads of a scene's primitives and lights, the same (sequence_equal.h).
::testing::AssertionResult sameScene(const Scene& a, const Scene& b) {
    if (a.lights.size() != b.lights.size()) return ::testing::AssertionFailure() << "light counts differ";
    for (size_t i = 0; i < a.lights.size(); ++i)
        if (!sameLight(a.lights[i], b.lights[i])) return ::testing::AssertionFailure() << "light " << i << " differs";
    if (!sameList(a.patches, b.patches)) return ::testing::AssertionFailure() << "patches differ";
    if (!sameList(a.procedurals, b.procedurals)) return ::testing::AssertionFailure() << "procedurals differ";
    if (!sameList(a.patchMeshes, b.patchMeshes)) return ::testing::AssertionFailure() << "patch meshes differ";
    if (!sameList(a.subdivisionMeshes, b.subdivisionMeshes))
        return ::testing::AssertionFailure() << "subdivision meshes differ";
    if (!sameList(a.quadrics, b.quadrics)) return ::testing::AssertionFailure() << "quadrics differ";
    if (!sameList(a.polygonMeshes, b.polygonMeshes)) return ::testing::AssertionFailure() << "polygons differ";
    if (!sameList(a.curves, b.curves)) return ::testing::AssertionFailure() << "curves differ";
    if (!sameList(a.points, b.points)) return ::testing::AssertionFailure() << "points differ";
    if (!sameList(a.nuPatches, b.nuPatches)) return ::testing::AssertionFailure() << "NuPatches differ";
    return ::testing::AssertionSuccess();
}

// Small and short: the first frame at 48 pixels wide, hard cases cut short (as the fuzzer does:
// the comparisons are between encodings, with the same options).
RenderOptions smallOptions(const Scene& scene) {
    RenderOptions o;
    o.xres = 48;
    o.yres = std::max(1, scene.camera.yres * 48 / scene.camera.xres);
    o.samples = 2;
    o.maxSplitsPerPrimitive = 1 << 14;
    o.hasFrames = true;
    o.firstFrame = o.lastFrame = scene.settings.hasFrames ? scene.settings.firstFrame : 0;
    return o;
}

class RibEncodings : public testing::TestWithParam<std::string> {};

// Read from memory under the file's own name: shaders and archives are found beside it.
TEST_P(RibEncodings, GzipAndBinaryRenderAsTheAsciiDoes) {
    if (test::slowUnderSanitizers(GetParam())) GTEST_SKIP() << "minutes under the sanitizers: the release suite runs it";
    const std::string path = test::sourcePath(GetParam());
    const std::string ascii = readBytes(path);
    Log log;
    const Scene reference = parseRibString(ascii, path, log);
    const RenderOptions o = smallOptions(reference);
    const test::RenderResult expected = test::renderScene(reference, o);

    const std::string gz = gzip(ascii);
    const std::string binary = encodeRib(ascii, path, {true, false, false});
    ASSERT_TRUE(isGzip(gz));
    ASSERT_EQ(binary[0], '\314') << "binary RIB starts with its first request's definition";
    for (const auto& [name, bytes] : {std::pair{"gzip", gz}, std::pair{"binary", binary}}) {
        SCOPED_TRACE(name);
        const Scene scene = parseRibString(bytes, path, log);
        EXPECT_TRUE(sameScene(reference, scene));
        const test::RenderResult r = test::renderScene(scene, o);
        EXPECT_TRUE(test::identicalPixels(expected, r)) << "max difference " << test::maxAbsDifference(expected, r);
    }
    EXPECT_TRUE(sameScene(reference, parseRibString(gzip(binary), path, log))) << "gzip of binary";

    // 32-bit floats: the binary file and the ASCII file of the same rounded values.
    const Scene binary32 = parseRibString(encodeRib(ascii, path, {true, true, false}), path, log);
    const Scene ascii32 = parseRibString(encodeRib(ascii, path, {false, true, false}), path, log);
    EXPECT_TRUE(sameScene(ascii32, binary32));
    EXPECT_TRUE(test::identicalPixels(test::renderScene(ascii32, o), test::renderScene(binary32, o)));
}

INSTANTIATE_TEST_SUITE_P(Scenes, RibEncodings, testing::ValuesIn(everyScene()),
                         [](const testing::TestParamInfo<std::string>& info) {
                             std::string name = info.param.substr(0, info.param.size() - 4);
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

TEST(RibEncodings, ThereAreScenesToCheck) { EXPECT_GE(everyScene().size(), 20u); }

// Rounding to 32-bit floats is a real change: some scene reads differently (else the float32
// comparison above could not fail for the wrong reason).
TEST(RibEncodings, Float32ValuesDifferFromTheOriginal) {
    const std::string path = test::sourcePath("scenes/vase.rib");
    const std::string ascii = readBytes(path);
    Log log;
    const Scene original = parseRibString(ascii, path, log);
    const Scene rounded = parseRibString(encodeRib(ascii, path, {true, true, false}), path, log);
    EXPECT_FALSE(sameScene(original, rounded));
}

// ---- Frame sequences and archives ------------------------------------------------------------------
// A file per frame (shot.####.rib) and a file of FrameBegin blocks, gzip-compressed under their
// own names and in binary RIB: the same frames as the text files.
TEST(RibEncodings, FrameSequencesReadCompressedAndBinary) {
    const test::TempDir dir("rib-seq");
    const std::string src = test::sourcePath("scenes/sequence");
    for (int f = 1; f <= 8; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "shot.%04d.rib", f);
        const std::string text = readBytes(src + "/" + name);
        writeBytes(dir.path() + "/" + name, f % 2 ? gzip(text) : encodeRib(text, name, {true, false, f == 4}));
    }
    const std::string blocks = readBytes(src + "/shot.rib");
    writeBytes(dir.path() + "/blocks.rib", gzip(encodeRib(blocks, "shot.rib", {true, false, false})));

    Log log;
    RenderOptions o;
    o.xres = 40;
    o.yres = 24;
    o.samples = 2;
    auto read = [&](const std::string& path) {
        const Sequence seq = readScene(path, FrameRequest{}, log);
        EXPECT_TRUE(seq.isSequence) << path;
        EXPECT_EQ(seq.scene.settings.lastFrame - seq.scene.settings.firstFrame, 7) << path;
        return seq.scene;
    };
    const Scene text = read(src + "/shot.####.rib");
    const Scene stored = read(dir.path() + "/shot.####.rib");
    const Scene textBlocks = read(src + "/shot.rib");
    const Scene storedBlocks = read(dir.path() + "/blocks.rib");
    EXPECT_TRUE(sameScene(text, stored));
    EXPECT_TRUE(sameScene(textBlocks, storedBlocks));
    const test::RenderResult expected = test::renderScene(text, o);
    ASSERT_EQ(expected.frames.size(), 8u);
    EXPECT_TRUE(test::identicalPixels(expected, test::renderScene(stored, o)));
    EXPECT_TRUE(test::identicalPixels(test::renderScene(textBlocks, o), test::renderScene(storedBlocks, o)));
}

// ReadArchive and DelayedReadArchive of gzip and binary files: the same primitives as the text
// archive, and a damaged one an error naming the archive.
TEST(RibEncodings, ArchivesReadCompressedAndBinary) {
    const test::TempDir dir("rib-archive");
    const std::string archive =
        "AttributeBegin\nColor [1 0.5 0.25]\nTranslate 0.1 0.2 0.3\n"
        "Patch \"bilinear\" \"P\" [-1 -1 4  1 -1 4  -1 1 4  1 1 4]\nSphere 0.5 -0.5 0.5 360\nAttributeEnd\n";
    writeBytes(dir.path() + "/text.rib", archive);
    writeBytes(dir.path() + "/z.rib", gzip(archive));
    writeBytes(dir.path() + "/b.rib.gz", gzip(encodeRib(archive, "b", {true, false, false})));
    writeBytes(dir.path() + "/cut.rib", gzip(archive).substr(0, 40));
    auto scene = [&](const std::string& name, bool delayed) {
        const std::string read = delayed ? "Procedural \"DelayedReadArchive\" [\"" + name + "\"] [-2 2 -2 2 3 5]\n"
                                         : "ReadArchive \"" + name + "\"\n";
        const std::string rib = "Format 32 32 1\nProjection \"perspective\" \"fov\" 60\nWorldBegin\n" + read + "WorldEnd\n";
        const std::string file = dir.path() + "/main-" + (delayed ? "d-" : "r-") + name;
        writeBytes(file, rib);
        Log log;
        return parseRibFile(file, log);
    };
    RenderOptions o;
    o.samples = 2;
    for (bool delayed : {false, true}) {
        SCOPED_TRACE(delayed ? "DelayedReadArchive" : "ReadArchive");
        const Scene text = scene("text.rib", delayed);
        const test::RenderResult expected = test::renderScene(text, o);
        EXPECT_GT(test::alphaSum(expected), 100);
        for (const char* name : {"z.rib", "b.rib.gz"}) {
            const Scene s = scene(name, delayed);
            if (!delayed) {  // (a delayed archive is its file's name until it is seen)
                EXPECT_TRUE(sameScene(text, s)) << name;
            }
            EXPECT_TRUE(test::identicalPixels(expected, test::renderScene(s, o))) << name;
        }
        try {
            test::renderScene(scene("cut.rib", delayed), o);  // a delayed archive is read when seen
            ADD_FAILURE() << "a truncated archive read";
        } catch (const InputError& e) {
            EXPECT_EQ(e.loc.str(), dir.path() + "/cut.rib, byte 40");
            EXPECT_NE(e.message.find("truncated gzip stream"), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace streyes
