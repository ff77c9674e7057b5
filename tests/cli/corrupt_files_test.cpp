// Corrupt images on purpose: EXR and TIFF files truncated, garbage after a valid magic number, cut
// in their pixels, or with a header claiming a size the file cannot hold ("forged"). Read as frames
// (compare, sheet, --resume), as textures and as MakeTexture's picture, each gives an error or a
// warning naming the file, never a crash, and never takes more memory than a small render does:
// every run's address space is capped (4 GiB) so that a reader believing a forged header fails
// here instead of taking the machine's memory, and its peak resident memory is checked.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;
using test::MeasuredRun;
using test::readFile;
using test::runStreyesMeasured;
using test::writeFile;

// (AddressSanitizer reserves terabytes of address space for its shadow memory: no cap under it;
// the peak resident memory still catches a reader believing a forged header.)
constexpr unsigned long kAddressSpace = test::kAddressSanitizer ? 0 : 4ul << 30;
// A render of a few pixels with OpenImageIO loaded peaks near 130 MiB (more under the sanitizers);
// believing a forged header (40000 x 40000 pixels) would take gigabytes.
constexpr long kPeakLimit = (test::kAddressSanitizer ? 1024l : 512l) << 20;

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

// 128 x 128 RGB about 0.5 grey (so that a texture read from it does not look like the fill value),
// noisy so that it does not compress: the EXR holds more than the line offsets of a forged one.
void writeGood(const std::string& path, const char* compression = nullptr) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << path;
    OIIO::ImageSpec spec(128, 128, 3, path.size() > 4 && path.substr(path.size() - 4) == ".tif" ? OIIO::TypeDesc::UINT8
                                                                                                : OIIO::TypeDesc::HALF);
    if (compression) spec.attribute("compression", compression);
    std::mt19937 rng(3);
    std::vector<float> px(128 * 128 * 3);
    for (float& p : px) p = 0.5f + float(rng() % 64) / 4096.0f;
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data())) << out->geterror();
    ASSERT_TRUE(out->close());
}

std::string randomBytes(size_t n) {
    std::mt19937 rng(7);
    std::string s(n, '\0');
    for (char& c : s) c = char(rng() & 0xff);
    return s;
}

// The EXR with its data window made 40000 x 40000 pixels (the header's "dataWindow" box2i): 9 GiB
// of half samples in a file of about 100 KB, which holds the 2,500 line offsets such a size needs.
std::string forgedExr(std::string bytes) {
    const std::string key("dataWindow\0box2i\0", 17);
    const size_t at = bytes.find(key);
    EXPECT_NE(at, std::string::npos);
    const int32_t max[2] = {39999, 39999};
    std::memcpy(&bytes[at + key.size() + 4 + 8], max, sizeof max);  // after the size: xmin ymin xmax ymax
    return bytes;
}

// The little-endian TIFF with ImageWidth and ImageLength (tags 256, 257) made 60000.
std::string forgedTiff(std::string bytes) {
    EXPECT_EQ(bytes.substr(0, 2), "II");
    uint32_t ifd = 0;
    std::memcpy(&ifd, &bytes[4], 4);
    uint16_t entries = 0;
    std::memcpy(&entries, &bytes[ifd], 2);
    int patched = 0;
    for (uint16_t i = 0; i < entries; ++i) {
        char* e = &bytes[ifd + 2 + 12 * size_t(i)];
        uint16_t tag = 0, type = 0;
        std::memcpy(&tag, e, 2);
        std::memcpy(&type, e + 2, 2);
        if (tag != 256 && tag != 257) continue;
        if (type == 3) {
            const uint16_t v = 60000;
            std::memcpy(e + 8, &v, 2);
        } else {
            const uint32_t v = 60000;
            std::memcpy(e + 8, &v, 4);
        }
        ++patched;
    }
    EXPECT_EQ(patched, 2);
    return bytes;
}

struct Corrupt {
    std::string name;  // the file, in the test's folder
    std::string what;  // for the trace
};

// Writes the corrupt files and returns them; good.exr and good.tif are the originals.
std::vector<Corrupt> writeCorruptFiles(const std::string& dir) {
    writeGood(dir + "/good.exr");
    writeGood(dir + "/good.tif", "none");  // uncompressed: cut in its pixels, the header stays good
    const std::string exr = readFile(dir + "/good.exr"), tif = readFile(dir + "/good.tif");
    writeBytes(dir + "/truncated.exr", exr.substr(0, 300));
    writeBytes(dir + "/garbage.exr", exr.substr(0, 8) + randomBytes(2000));
    writeBytes(dir + "/cut.exr", exr.substr(0, exr.size() / 2));
    writeBytes(dir + "/forged.exr", forgedExr(exr));
    writeBytes(dir + "/truncated.tif", tif.substr(0, 100));
    writeBytes(dir + "/garbage.tif", tif.substr(0, 8) + randomBytes(3000));
    writeBytes(dir + "/cut.tif", tif.substr(0, tif.size() / 2));
    writeBytes(dir + "/forged.tif", forgedTiff(tif));
    return {{"truncated.exr", "the first 300 bytes"},      {"garbage.exr", "random bytes after the magic number"},
            {"cut.exr", "the header and half the pixels"}, {"forged.exr", "a 40000 x 40000 data window"},
            {"truncated.tif", "the first 100 bytes"},      {"garbage.tif", "random bytes after the header"},
            {"cut.tif", "the header and half the pixels"}, {"forged.tif", "60000 x 60000 in the header"}};
}

void expectBounded(const MeasuredRun& r) {
    EXPECT_NE(r.exitCode, -1) << "crashed:\n" << r.output;
    EXPECT_EQ(r.output.find("bad_alloc"), std::string::npos) << r.output;
    EXPECT_LT(r.peakResidentBytes, kPeakLimit) << r.output;
}

TEST(CorruptFiles, AsFramesTheyAreAnErrorNamingTheFile) {
    const test::TempDir dir("corrupt");
    for (const Corrupt& c : writeCorruptFiles(dir.path())) {
        SCOPED_TRACE(c.name + ": " + c.what);
        const MeasuredRun r = runStreyesMeasured({"compare", "good.exr", c.name}, dir.path(), kAddressSpace);
        expectBounded(r);
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("cannot read '" + c.name + "'"), std::string::npos) << r.output;
        if (c.name.rfind("forged", 0) == 0) {
            EXPECT_NE(r.output.find("more than a file of"), std::string::npos) << r.output;
        }
    }
    // A contact sheet of frames one of which is corrupt.
    fs::create_directories(dir.path() + "/frames");
    fs::copy_file(dir.path() + "/good.exr", dir.path() + "/frames/f.0001.exr");
    fs::copy_file(dir.path() + "/forged.exr", dir.path() + "/frames/f.0002.exr");
    const MeasuredRun sheet =
        runStreyesMeasured({"sheet", "frames/f.####.exr", "-o", "sheet.png"}, dir.path(), kAddressSpace);
    expectBounded(sheet);
    EXPECT_EQ(sheet.exitCode, 2) << sheet.output;
    EXPECT_NE(sheet.output.find("frames/f.0002.exr"), std::string::npos) << sheet.output;
    EXPECT_FALSE(fs::exists(dir.path() + "/sheet.png"));
}

// A scene whose square shows `map` through texture() with a fill of 0.25.
std::string textureScene(const std::string& dir, const std::string& map) {
    writeFile(dir, "tex.sl", "surface tex(string map = \"\") { Ci = color texture(map, s, t, \"fill\", 0.25); Oi = 1; }\n");
    return writeFile(dir, "scene.rib",
                     "Format 8 8 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 8\nPixelFilter \"box\" 1 1\n"
                     "WorldBegin\nSurface \"tex\" \"string map\" \"" + map + "\"\n"
                     "Patch \"bilinear\" \"P\" [0 0 5  8 0 5  0 8 5  8 8 5]\nWorldEnd\n");
}

TEST(CorruptFiles, AsTexturesTheyWarnNamingTheFileAndGiveTheFill) {
    const test::TempDir dir("corrupt");
    textureScene(dir.path(), "good.tif");
    writeCorruptFiles(dir.path());
    // The good map shows (0.5): the fill below is the corrupt map's, not a scene that reads nothing.
    MeasuredRun good = runStreyesMeasured({"render", "scene.rib", "-o", "good-out.exr"}, dir.path(), kAddressSpace);
    ASSERT_EQ(good.exitCode, 0) << good.output;
    EXPECT_NEAR(readImage(dir.path() + "/good-out.exr").at(4, 4, 0), 0.5f, 0.02f);
    for (const Corrupt& c : writeCorruptFiles(dir.path())) {
        SCOPED_TRACE(c.name + ": " + c.what);
        textureScene(dir.path(), c.name);
        const MeasuredRun r = runStreyesMeasured({"render", "scene.rib", "-o", "out.exr"}, dir.path(), kAddressSpace);
        expectBounded(r);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find("warning: texture(\"" + c.name + "\") in shader \"tex\": "), std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find("using the fill value"), std::string::npos) << r.output;
        const ImageData img = readImage(dir.path() + "/out.exr");
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) EXPECT_EQ(img.at(x, y, 0), 0.25f) << x << "," << y;
    }
}

TEST(CorruptFiles, AsMakeTexturesPictureTheyAreAnErrorAtItsLine) {
    const test::TempDir dir("corrupt");
    for (const Corrupt& c : writeCorruptFiles(dir.path())) {
        SCOPED_TRACE(c.name + ": " + c.what);
        fs::remove(dir.path() + "/out.exr");
        fs::remove(dir.path() + "/made.tx");
        writeFile(dir.path(), "scene.rib",
                  "MakeTexture \"" + c.name + "\" \"made.tx\" \"clamp\" \"clamp\" \"box\" 1 1\n"
                  "Format 8 8 1\nWorldBegin\nWorldEnd\n");
        const MeasuredRun r = runStreyesMeasured({"render", "scene.rib", "-o", "out.exr"}, dir.path(), kAddressSpace);
        expectBounded(r);
        EXPECT_EQ(r.exitCode, 2) << r.output;
        EXPECT_NE(r.output.find("scene.rib:1: error: MakeTexture"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find(c.name), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(dir.path() + "/out.exr"));
        EXPECT_FALSE(fs::exists(dir.path() + "/made.tx"));
    }
}

// --resume reads every frame there back: a corrupt one is rendered again.
TEST(CorruptFiles, ResumeRendersACorruptFrameAgain) {
    const test::TempDir dir("corrupt");
    const std::vector<Corrupt> files = writeCorruptFiles(dir.path());
    writeFile(dir.path(), "scene.rib",
              "Format 8 8 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 8\nWorldBegin\nSurface \"constant\"\n"
              "Patch \"bilinear\" \"P\" [0 0 5  8 0 5  0 8 5  8 8 5]\nWorldEnd\n");
    for (const Corrupt& c : files) {
        if (c.name.find(".exr") == std::string::npos) continue;
        SCOPED_TRACE(c.name + ": " + c.what);
        fs::copy_file(dir.path() + "/" + c.name, dir.path() + "/frame.exr", fs::copy_options::overwrite_existing);
        const MeasuredRun r =
            runStreyesMeasured({"render", "scene.rib", "-o", "frame.exr", "--resume"}, dir.path(), kAddressSpace);
        expectBounded(r);
        EXPECT_EQ(r.exitCode, 0) << r.output;
        EXPECT_EQ(r.output.find("already complete"), std::string::npos) << r.output;
        EXPECT_TRUE(isCompleteFrame(dir.path() + "/frame.exr", 8, 8, "rgbaz"));
    }
}

}  // namespace
}  // namespace streyes
