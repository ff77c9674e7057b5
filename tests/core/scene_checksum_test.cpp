// The pixels of every scene in scenes/ and scenes/hard/, rendered small and short, against the
// checksums recorded in tests/data/scene_checksums.txt: a refactor must not change a bit.
//
// A change that alters pixels on purpose (a new sample pattern, a fix) records them again:
//   STREYES_RECORD_CHECKSUMS=1 build/streyes_tests --gtest_filter='SceneChecksums*'
// and says in its commit message why the pixels changed. Files of several worlds (depth frames and
// pictures) have theirs checked by tests/cli/multipass_scenes_test.cpp, which renders passes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

std::vector<std::string> everyScene() {
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    for (const char* dir : {"scenes", "scenes/hard"})
        for (const auto& entry : fs::directory_iterator(test::sourcePath(dir)))
            if (entry.path().extension() == ".rib" && !test::multiPassScene(entry.path().string()))
                files.push_back(std::string(dir) + "/" + entry.path().filename().string());
    std::sort(files.begin(), files.end());
    return files;
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
    const std::map<std::string, std::string> recorded = record ? std::map<std::string, std::string>{} : test::recordedChecksums();
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        if (a == Algorithm::Raytrace && test::tooLargeToRayTrace(GetParam())) continue;
        if (a == Algorithm::Raytrace && test::slowUnderSanitizers(GetParam())) continue;  // minutes there
        o.algorithm = a;
        char hex[17];
        std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)test::pixelChecksum(test::renderScene(scene, o)));
        const std::string key = GetParam() + ":" + algorithmName(a);
        if (record) {
            test::recordChecksum(key, hex);
            continue;
        }
        auto it = recorded.find(key);
        ASSERT_NE(it, recorded.end()) << key << " has no recorded checksum in " << test::kChecksumFile;
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
