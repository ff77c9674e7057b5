// A rendered frame: what the renderer hands to its sink and image files are written from.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace streyes {

// One resolved frame: RGBA and Z per pixel (and any output variables), row-major from the top-left.
struct FrameImage {
    int frame = 0;
    int width = 0, height = 0;
    std::vector<float> rgba;  // 4 per pixel
    std::vector<float> z;     // 1 per pixel
    void resize(int w, int h) {
        width = w;
        height = h;
        rgba.assign(size_t(w) * size_t(h) * 4, 0.0f);
        z.assign(size_t(w) * size_t(h), 0.0f);
        aov.assign(size_t(w) * size_t(h) * aovNames.size(), 0.0f);
    }
    // Output variables beside colour (util/aov.h): their EXR channel names, and aovNames.size()
    // floats per pixel. Empty unless a display asks for them.
    std::vector<std::string> aovNames;
    std::vector<float> aov;
};

}  // namespace streyes
