// The work the RIB fuzzer does with one input, shared by the libFuzzer target (rib_fuzz.cpp) and
// the regression test that replays what it once found (tests/core/fuzz_regression_test.cpp).
//
// Parse the input as a scene; when it parses, render one frame of it at 8 x 8 pixels with one
// sample, so that whatever the parser accepts also goes through camera, bodies, split loop,
// dicing, shading and sampling. Malformed input must end in an InputError (exit 2 in the
// command); anything else (another exception, a crash, a sanitizer report, a hang) is a bug.
#pragma once

#include <string>
#include <string_view>

#include "streyes/renderer.h"
#include "streyes/rib.h"

namespace streyes::fuzz {

enum class Outcome { Rendered, BadInput };

// Inputs are mutated scenes: while one is read and rendered, it may not run programs or read
// other files.
struct RestrictedAccess {
    SceneAccess before = sceneAccess();
    RestrictedAccess() {
        SceneAccess none;
        none.programs = none.files = false;
        setSceneAccess(none);
    }
    ~RestrictedAccess() { setSceneAccess(before); }
    RestrictedAccess(const RestrictedAccess&) = delete;
    RestrictedAccess& operator=(const RestrictedAccess&) = delete;
};

// A render of size x size pixels, one sample, one thread, with a split budget small enough that
// hard inputs do not take seconds each.
inline RenderOptions tinyRenderOptions(int size) {
    RenderOptions o;
    o.xres = o.yres = size;
    o.samples = 1;
    o.threads = 1;
    o.maxSplitsPerPrimitive = 1 << 14;
    return o;
}

inline Outcome parseAndRender(std::string_view text) {
    const RestrictedAccess restricted;
    Log log;
    log.setQuiet(true);
    try {
        Scene scene = parseRibString(std::string(text), "fuzz.rib", log);
        RenderOptions o = tinyRenderOptions(8);
        o.hasFrames = true;
        o.firstFrame = o.lastFrame = scene.settings.hasFrames ? scene.settings.firstFrame : 0;
        Renderer renderer(scene, o, log);
        renderer.render([](const FrameImage&) {});
        return Outcome::Rendered;
    } catch (const InputError&) {
        return Outcome::BadInput;
    }
}

}  // namespace streyes::fuzz
