// RIB as it is stored, through the command: `streyes catrib` converts between ASCII, binary and
// gzip; `streyes render` reads any of them; a damaged compressed or binary file stops it with
// exit 2, naming the file and the byte offset, and writes nothing.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.h"
#include "scene/rib_gzip.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

using test::CliRun;
using test::listDir;
using test::readFile;
using test::runStreyes;

void writeBytes(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

template <size_t N>
std::string bytes(const char (&s)[N]) {
    return std::string(s, N - 1);
}

TEST(Catrib, ConvertsToBinaryAndGzipAndBackWithTheSamePixels) {
    const test::TempDir dir("catrib");
    const std::string vase = test::sourcePath("scenes/vase.rib");
    const std::string bin = dir.path() + "/vase.rib", ascii = dir.path() + "/vase-ascii.rib";
    CliRun r = runStreyes("catrib --binary --gzip " + vase + " -o " + bin);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string stored = readFile(bin);
    ASSERT_TRUE(isGzip(stored));
    EXPECT_LT(stored.size(), readFile(vase).size() / 2);
    // Back to ASCII, from the binary file and from the original: the same text.
    r = runStreyes("catrib " + bin + " -o " + ascii);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const CliRun direct = runStreyes("catrib " + vase, false);
    ASSERT_EQ(direct.exitCode, 0);
    EXPECT_EQ(readFile(ascii), direct.output);
    EXPECT_EQ(readFile(vase).substr(0, 2), "# ");
    EXPECT_NE(direct.output.substr(0, 1), "#");  // comments dropped
    EXPECT_EQ(direct.output.find("\n#"), std::string::npos);
    // The compressed binary file renders the same pixels (the vase's shaders are the standard ones).
    const std::string args = " --frames 2 --res 48x36 --samples 2 --quiet -o ";
    const CliRun a = runStreyes("render " + vase + args + dir.path() + "/a.####.exr");
    const CliRun b = runStreyes("render " + bin + args + dir.path() + "/b.####.exr");
    ASSERT_EQ(a.exitCode, 0) << a.output;
    ASSERT_EQ(b.exitCode, 0) << b.output;
    const ImageData x = readImage(dir.path() + "/a.0002.exr"), y = readImage(dir.path() + "/b.0002.exr");
    ASSERT_EQ(x.pixels.size(), y.pixels.size());
    ASSERT_GT(x.pixels.size(), 0u);
    EXPECT_EQ(std::memcmp(x.pixels.data(), y.pixels.data(), x.pixels.size() * sizeof(float)), 0);
}

// The multi-pass scenes of scenes/shadows/ (depth frames, MakeShadow, pictures reading the maps,
// a zoom; RibEncodings in tests/core covers scenes/ and scenes/hard/ through the library) render
// bit for bit the same pictures from gzip, binary and gzip-compressed binary RIB as from the
// ASCII file, each in a folder of its own (the maps are written beside the scene).
TEST(Catrib, MultiPassScenesRenderTheSameFromGzipAndBinary) {
    const test::TempDir dir("catrib-passes");
    for (const char* scene : {"autoshadow", "lamps", "shot", "zoom"}) {
        SCOPED_TRACE(scene);
        const std::string source = test::sourcePath(std::string("scenes/shadows/") + scene + ".rib");
        const std::vector<std::pair<std::string, std::string>> encodings = {
            {"ascii", ""}, {"gzip", "--gzip"}, {"binary", "--binary"}, {"binary-gzip", "--binary --gzip"}};
        std::vector<std::vector<std::string>> outputs;
        for (const auto& [name, flags] : encodings) {
            const std::string at = dir.path() + "/" + scene + "-" + name;
            std::filesystem::create_directory(at);
            const CliRun c = runStreyes("catrib " + flags + " " + source + " -o " + at + "/scene.rib");
            ASSERT_EQ(c.exitCode, 0) << c.output;
            EXPECT_EQ(isGzip(readFile(at + "/scene.rib")), name.find("gzip") != std::string::npos) << name;
            const CliRun r = test::runStreyesWith("cd " + at + " && ",
                                                  "render scene.rib --res 48x36 --samples 2 -q -o pic.####.exr");
            ASSERT_EQ(r.exitCode, 0) << name << ": " << r.output;
            std::vector<std::string> pictures;
            for (const std::string& f : listDir(at))
                if (f.size() > 4 && f.compare(f.size() - 4, 4, ".exr") == 0) pictures.push_back(f);
            ASSERT_FALSE(pictures.empty()) << name;
            outputs.push_back(pictures);
            for (const std::string& f : pictures) {
                const ImageData x = readImage(dir.path() + "/" + scene + "-ascii/" + f), y = readImage(at + "/" + f);
                ASSERT_GT(x.pixels.size(), 0u);
                EXPECT_TRUE(x.width == y.width && x.height == y.height && x.pixels == y.pixels) << name << " " << f;
            }
        }
        for (const auto& o : outputs) EXPECT_EQ(o, outputs.front());
    }
}

TEST(Catrib, BadUsageAndBadInput) {
    const test::TempDir dir("catrib");
    CliRun r = runStreyes("catrib");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("no RIB file given"), std::string::npos) << r.output;
    r = runStreyes("catrib --octal x.rib");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("unknown option '--octal'"), std::string::npos) << r.output;
    const std::string bad = test::writeFile(dir.path(), "bad.rib", "Color [1 2\nWorldBegin\n");
    r = runStreyes("catrib --binary " + bad + " -o " + dir.path() + "/out.rib");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("bad.rib:1: error: unterminated array"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.path() + "/out.rib"));
}

// ---- Damaged files: exit 2, "bad.rib, byte N: error: ...", nothing written --------------------------
struct Damaged {
    const char* name;
    std::string bytes;
    long long offset;
    const char* mentions;
};

std::vector<Damaged> damagedCases() {
    const std::string scene = "Format 16 16 1\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n";
    const std::string z = gzip(scene);
    const std::string head = "Format 16 16 1\nWorldBegin\n";  // 26 bytes, then binary
    return {
        {"TruncatedGzip", z.substr(0, z.size() - 9), (long long)z.size() - 9, "truncated gzip stream"},
        {"BadToken", head + bytes("\200\001\250WorldEnd\n"), 28, "0250 is not a binary RIB token"},
        {"StringIndexOutOfRange", head + bytes("\315\001\222Kd\320\000\002\nWorldEnd\n"), 31,
         "string index 2 is used (0320) but was never defined"},
        {"TruncatedArray", head + bytes("\314\000\225Color\246\000\310\003\000\000\000\000"), 36,
         "truncated float array: 3 floats need 12 bytes, only 4 left"},
        {"UndefinedRequest", head + bytes("\246\007\nWorldEnd\n"), 26, "request code 7 is used (0246)"},
        {"GzipOfBadBinary", gzip(head + bytes("\246\007\nWorldEnd\n")), 26, "request code 7 is used (0246)"},
    };
}

void PrintTo(const Damaged& d, std::ostream* os) { *os << d.name; }

class DamagedRib : public testing::TestWithParam<Damaged> {};

TEST_P(DamagedRib, Exits2NamingFileAndByteAndWritesNothing) {
    const Damaged& c = GetParam();
    const test::TempDir dir("damaged-rib");
    writeBytes(dir.path() + "/bad.rib", c.bytes);
    const CliRun r = runStreyes("render " + dir.path() + "/bad.rib -o " + dir.path() + "/f.####.exr");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("bad.rib, byte " + std::to_string(c.offset) + ": error: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.mentions), std::string::npos) << r.output;
    EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"bad.rib"});
}

INSTANTIATE_TEST_SUITE_P(Cli, DamagedRib, testing::ValuesIn(damagedCases()),
                         [](const testing::TestParamInfo<Damaged>& info) { return info.param.name; });

}  // namespace
}  // namespace streyes
