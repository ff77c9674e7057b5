// The pixels of every scene in scenes/ and scenes/hard/, rendered small and short, against the
// checksums recorded in tests/data/scene_checksums.txt: a refactor must not change a bit.
//
// A change that alters pixels on purpose (a new sample pattern, a fix) records them again:
//   STREYES_RECORD_CHECKSUMS=1 build/streyes_tests --gtest_filter='SceneChecksums*'
// and says in its commit message why the pixels changed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

const char* kChecksumFile = "tests/data/scene_checksums.txt";

std::vector<std::string> everyScene() {
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    for (const char* dir : {"scenes", "scenes/hard"})
        for (const auto& entry : fs::directory_iterator(test::sourcePath(dir)))
            if (entry.path().extension() == ".rib") files.push_back(std::string(dir) + "/" + entry.path().filename().string());
    std::sort(files.begin(), files.end());
    return files;
}

// FNV-1a over the bits of every RGBA and Z value of every frame, in frame order.
uint64_t pixelChecksum(const test::RenderResult& r) {
    uint64_t h = 1469598103934665603ull;
    auto add = [&](const std::vector<float>& v) {
        for (float f : v) {
            uint32_t bits;
            std::memcpy(&bits, &f, sizeof bits);
            for (int i = 0; i < 4; ++i) {
                h ^= (bits >> (8 * i)) & 0xffu;
                h *= 1099511628211ull;
            }
        }
    };
    std::vector<const FrameImage*> frames;
    for (const FrameImage& f : r.frames) frames.push_back(&f);
    std::sort(frames.begin(), frames.end(), [](const FrameImage* a, const FrameImage* b) { return a->frame < b->frame; });
    for (const FrameImage* f : frames) {
        add(f->rgba);
        add(f->z);
    }
    return h;
}

std::map<std::string, std::string> readChecksums() {
    std::map<std::string, std::string> m;
    std::ifstream in(test::sourcePath(kChecksumFile));
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream s(line);
        std::string key, value;
        if (s >> key >> value) m[key] = value;
    }
    return m;
}

// Rewrites one entry of the checksum file (record mode; tests may run in parallel processes, so
// the file is read, changed and written under a lock file).
void recordChecksum(const std::string& key, const std::string& value) {
    static std::mutex mutex;
    std::lock_guard<std::mutex> lock(mutex);
    std::map<std::string, std::string> m = readChecksums();
    m[key] = value;
    std::ofstream out(test::sourcePath(kChecksumFile));
    out << "# Pixel checksums of every scene, rendered small and short by tests/core/scene_checksum_test.cpp.\n"
           "# Record again (STREYES_RECORD_CHECKSUMS=1) only when a change alters pixels on purpose.\n";
    for (const auto& [k, v] : m) out << k << " " << v << "\n";
}

class SceneChecksums : public testing::TestWithParam<std::string> {};

// Two frames at 64 pixels wide, 4 samples, with the default algorithm and with the ray tracer.
TEST_P(SceneChecksums, PixelsMatchTheRecordedChecksums) {
    Log log;
    Scene scene = parseRibFile(test::sourcePath(GetParam()), log);
    RenderOptions o;
    o.xres = 64;
    o.yres = std::max(1, scene.camera.yres * 64 / scene.camera.xres);
    o.hasFrames = true;
    o.firstFrame = scene.settings.hasFrames ? scene.settings.firstFrame : 0;
    o.lastFrame = o.firstFrame + 1;
    o.samples = 4;
    const bool record = std::getenv("STREYES_RECORD_CHECKSUMS") != nullptr;
    const std::map<std::string, std::string> recorded = record ? std::map<std::string, std::string>{} : readChecksums();
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        if (a == Algorithm::Raytrace && test::tooLargeToRayTrace(GetParam())) continue;
        if (a == Algorithm::Raytrace && test::slowUnderSanitizers(GetParam())) continue;  // minutes there
        o.algorithm = a;
        char hex[17];
        std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)pixelChecksum(test::renderScene(scene, o)));
        const std::string key = GetParam() + ":" + algorithmName(a);
        if (record) {
            recordChecksum(key, hex);
            continue;
        }
        auto it = recorded.find(key);
        ASSERT_NE(it, recorded.end()) << key << " has no recorded checksum in " << kChecksumFile;
        EXPECT_EQ(it->second, hex) << key << ": the pixels changed";
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, SceneChecksums, testing::ValuesIn(everyScene()),
                         [](const testing::TestParamInfo<std::string>& info) {
                             std::string name = info.param.substr(0, info.param.size() - 4);
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

}  // namespace
}  // namespace streyes
