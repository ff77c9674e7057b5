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

std::vector<std::string> everyScene() { return test::sceneFiles(false); }

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
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        if (a == Algorithm::Raytrace && test::tooLargeToRayTrace(GetParam())) continue;
        if (a == Algorithm::Raytrace && test::slowUnderSanitizers(GetParam())) continue;  // minutes there
        o.algorithm = a;
        EXPECT_EQ(test::checkRecordedChecksum(GetParam() + ":" + algorithmName(a), test::pixelChecksum(test::renderScene(scene, o))), "");
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
