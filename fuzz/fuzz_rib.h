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

inline Outcome parseAndRender(std::string_view text) {
    // Inputs are mutated scenes: they must not run programs or read other files.
    struct Restricted {
        SceneAccess before = sceneAccess();
        Restricted() {
            SceneAccess none;
            none.programs = none.files = false;
            setSceneAccess(none);
        }
        ~Restricted() { setSceneAccess(before); }
    } restricted;
    Log log;
    log.setQuiet(true);
    try {
        Scene scene = parseRibString(std::string(text), "fuzz.rib", log);
        RenderOptions o;
        o.xres = o.yres = 8;
        o.samples = 1;
        o.threads = 1;
        o.maxSplitsPerPrimitive = 1 << 14;  // hard inputs need not take seconds each
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
