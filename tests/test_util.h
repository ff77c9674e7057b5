// Helpers shared by the tests: source paths, temporary folders, and rendering a RIB string
// in memory (no files, no OpenImageIO).
#pragma once

#include <string>
#include <vector>

#include "streyes/film.h"
#include "streyes/renderer.h"
#include "streyes/scene.h"
#include "streyes/stats.h"

namespace streyes::test {

// Absolute path of a file in the source tree, e.g. sourcePath("scenes/ramp.rib").
std::string sourcePath(const std::string& relative);

// A fresh, empty temporary directory for one test.
std::string makeTempDir(const std::string& tag);

struct RenderResult {
    std::vector<FrameImage> frames;
    RenderStats stats;
    std::vector<std::string> warnings;
    const FrameImage& frame(int f) const;  // by frame number
    float alpha(int f, int x, int y) const { return frame(f).rgba[(size_t(y) * size_t(frame(f).width) + size_t(x)) * 4 + 3]; }
    float channel(int f, int x, int y, int c) const {
        return frame(f).rgba[(size_t(y) * size_t(frame(f).width) + size_t(x)) * 4 + size_t(c)];
    }
    float z(int f, int x, int y) const { return frame(f).z[size_t(y) * size_t(frame(f).width) + size_t(x)]; }
};

RenderResult renderRib(const std::string& rib, const RenderOptions& options = {});
RenderResult renderScene(const Scene& scene, const RenderOptions& options = {});
RenderResult renderFile(const std::string& path, const RenderOptions& options = {});

// True when every pixel of every frame is bit-identical (RGBA and Z).
bool identicalPixels(const RenderResult& a, const RenderResult& b);
// Largest absolute RGBA difference over all frames and pixels.
float maxAbsDifference(const RenderResult& a, const RenderResult& b);
float meanAbsDifference(const RenderResult& a, const RenderResult& b);

}  // namespace streyes::test
