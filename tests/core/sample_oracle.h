// Checking a render sample by sample against an analytic answer (hard-case tests).
//
// The scenes use a one-pixel box filter, so a pixel is exactly the mean of its own samples and
// no sample is shared between buckets. The test gives `inside(x, y, t)`: does the sample at raster
// (x, y) and time t (frames) see the shape? The oracle regenerates every sample the renderer used
// (generatePixelSamples is a pure function) and checks
//   - a pixel whose samples are all clearly inside has alpha exactly 1 (no cracks);
//   - a pixel whose samples are all clearly outside has alpha exactly 0 (nothing stray);
//   - the renderer's hit count (every micropolygon a sample falls in, before the depth test) is
//     `layers` times the samples inside: each sample is hit once per surface layer over it, so a
//     crack hidden by a surface behind, or a double hit on a shared edge, shows;
// where "clearly" means that points `hair` pixels away agree: samples that close to the shape's
// outline may go either way, and are counted apart.
#pragma once

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "streyes/image_block.h"
#include "test_util.h"

namespace streyes::test {

struct OracleReport {
    uint64_t samplesInside = 0, samplesOutside = 0, samplesOnOutline = 0;
    uint64_t hits = 0;
    int pixelsInside = 0, pixelsOutside = 0;  // pixels whose samples are all clearly in (out)
    int crackedPixels = 0;                    // ... of which alpha is not 1
    int strayPixels = 0;                      // ... of which alpha is not 0
    int alphaAboveOne = 0;
};

template <typename Inside>
OracleReport checkSamples(const Scene& scene, const RenderResult& r, Inside inside, double hair = 1e-4) {
    const ResolvedSettings s = resolveSettings(scene, RenderOptions{});
    const double open = scene.settings.shutterOpen, close = scene.settings.shutterClose;
    EXPECT_EQ(scene.settings.filter.type, "box");
    EXPECT_EQ(scene.settings.filter.xwidth, 1.0);
    OracleReport rep;
    rep.hits = r.stats.counters.sampleHits;
    std::vector<SamplePosition> pos(static_cast<size_t>(s.pattern.count()));
    std::vector<uint16_t> slices(pos.size());
    for (const FrameImage& img : r.frames) {
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                generatePixelSamples(x, y, img.frame, s.pattern, pos.data(), slices.data());
                int in = 0, out = 0;
                for (const SamplePosition& p : pos) {
                    const double t = img.frame + open + (close - open) * double(p.tf);
                    const bool c = inside(double(p.x), double(p.y), t);
                    bool clear = true;
                    for (auto [dx, dy] : {std::pair{hair, 0.0}, {-hair, 0.0}, {0.0, hair}, {0.0, -hair}})
                        clear = clear && inside(p.x + dx, p.y + dy, t) == c;
                    if (!clear) ++rep.samplesOnOutline;
                    else if (c) ++rep.samplesInside, ++in;
                    else ++rep.samplesOutside, ++out;
                }
                const float a = r.alpha(img.frame, x, y);
                rep.alphaAboveOne += a > 1.0f;
                if (in == int(pos.size())) {
                    ++rep.pixelsInside;
                    rep.crackedPixels += a != 1.0f;
                } else if (out == int(pos.size())) {
                    ++rep.pixelsOutside;
                    rep.strayPixels += a != 0.0f;
                }
            }
    }
    return rep;
}

// The assertions every hard case shares; `layers` surfaces lie over each inside sample.
inline void expectMatchesOracle(const OracleReport& rep, uint64_t layers = 1) {
    EXPECT_EQ(rep.crackedPixels, 0);
    EXPECT_EQ(rep.strayPixels, 0);
    EXPECT_EQ(rep.alphaAboveOne, 0);
    EXPECT_GE(rep.hits, layers * rep.samplesInside);
    EXPECT_LE(rep.hits, layers * (rep.samplesInside + rep.samplesOnOutline));
    ::testing::Test::RecordProperty("samples_inside", std::to_string(rep.samplesInside));
    ::testing::Test::RecordProperty("samples_on_outline", std::to_string(rep.samplesOnOutline));
    ::testing::Test::RecordProperty("hits", std::to_string(rep.hits));
}

}  // namespace streyes::test
