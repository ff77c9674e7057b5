#include "test_util.h"

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <filesystem>
#include <stdexcept>

#include "streyes/rib.h"

namespace streyes::test {

std::string sourcePath(const std::string& relative) { return std::string(STREYES_SOURCE_DIR) + "/" + relative; }

std::string makeTempDir(const std::string& tag) {
    std::string tmpl = (std::filesystem::temp_directory_path() / ("streyes-" + tag + "-XXXXXX")).string();
    if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed for " + tmpl);
    return tmpl;
}

const FrameImage& RenderResult::frame(int f) const {
    for (const FrameImage& img : frames)
        if (img.frame == f) return img;
    throw std::runtime_error("frame " + std::to_string(f) + " was not rendered");
}

static RenderResult renderWithLog(const Scene& scene, const RenderOptions& options, Log& log) {
    RenderResult r;
    Renderer renderer(scene, options, log);
    // A frame may come again (a second pass for procedurals that outgrew their bounds).
    r.stats = renderer.render([&](const FrameImage& img) {
        for (FrameImage& f : r.frames)
            if (f.frame == img.frame) {
                f = img;
                return;
            }
        r.frames.push_back(img);
    });
    r.warnings = log.warnings();
    return r;
}

RenderResult renderRib(const std::string& rib, const RenderOptions& options) {
    Log log;
    Scene scene = parseRibString(rib, "test.rib", log);
    return renderWithLog(scene, options, log);
}

RenderResult renderScene(const Scene& scene, const RenderOptions& options) {
    Log log;
    return renderWithLog(scene, options, log);
}

RenderResult renderFile(const std::string& path, const RenderOptions& options) {
    Log log;
    Scene scene = parseRibFile(path, log);
    return renderWithLog(scene, options, log);
}

bool identicalPixels(const RenderResult& a, const RenderResult& b) {
    if (a.frames.size() != b.frames.size()) return false;
    for (size_t i = 0; i < a.frames.size(); ++i) {
        const FrameImage &x = a.frames[i], &y = b.frames[i];
        if (x.frame != y.frame || x.width != y.width || x.height != y.height) return false;
        if (std::memcmp(x.rgba.data(), y.rgba.data(), x.rgba.size() * sizeof(float)) != 0) return false;
        if (std::memcmp(x.z.data(), y.z.data(), x.z.size() * sizeof(float)) != 0) return false;
    }
    return true;
}

static void forEachPair(const RenderResult& a, const RenderResult& b, const std::function<void(float, float)>& fn) {
    if (a.frames.size() != b.frames.size()) throw std::runtime_error("frame counts differ");
    for (size_t i = 0; i < a.frames.size(); ++i) {
        if (a.frames[i].rgba.size() != b.frames[i].rgba.size()) throw std::runtime_error("sizes differ");
        for (size_t k = 0; k < a.frames[i].rgba.size(); ++k) fn(a.frames[i].rgba[k], b.frames[i].rgba[k]);
    }
}

float maxAbsDifference(const RenderResult& a, const RenderResult& b) {
    float m = 0;
    forEachPair(a, b, [&](float x, float y) { m = std::max(m, std::fabs(x - y)); });
    return m;
}

float meanAbsDifference(const RenderResult& a, const RenderResult& b) {
    double s = 0;
    size_t n = 0;
    forEachPair(a, b, [&](float x, float y) {
        s += std::fabs(x - y);
        ++n;
    });
    return n ? float(s / double(n)) : 0.0f;
}

}  // namespace streyes::test
