// Helpers for tests that render with shaders of their own: a temporary shader folder on the
// search path, and an orthographic view one unit a pixel.
#pragma once

#include <fstream>
#include <string>

#include "test_util.h"

namespace streyes::test {

// A temporary folder of .sl files, found by the scene through `option()` (then the default path).
struct ShaderDir {
    explicit ShaderDir(const std::string& tag = "shaders") : dir(tag) {}
    TempDir dir;
    void add(const std::string& name, const std::string& source) const {
        std::ofstream(dir.path() + "/" + name + ".sl") << source;
    }
    std::string option() const { return "Option \"searchpath\" \"shader\" \"" + dir.path() + ":@\"\n"; }
};

// An orthographic W x H view of [0, W] x [0, H] (one unit a pixel), box filter, 2 x 2 samples,
// then `extra`.
inline std::string orthographicView(int w, int h, const std::string& extra) {
    return "Format " + std::to_string(w) + " " + std::to_string(h) + " 1\nProjection \"orthographic\"\n" +
           "ScreenWindow 0 " + std::to_string(w) + " 0 " + std::to_string(h) + "\nPixelFilter \"box\" 1 1\n" +
           "PixelSamples 2 2\n" + extra;
}

}  // namespace streyes::test
