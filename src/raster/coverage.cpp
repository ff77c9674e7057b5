#include "raster/coverage.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace streyes {

namespace {

// The farthest of a pixel's S hits, +inf unless every one is opaque. The pixel is covered when
// that lies nearer than the boundary.
float farthestHit(const SampleHit* s, int S) {
    float z = -std::numeric_limits<float>::infinity();
    for (int k = 0; k < S; ++k) {
        if (!(s[k].z < std::numeric_limits<float>::infinity())) return std::numeric_limits<float>::infinity();
        z = std::max(z, s[k].z);
    }
    return z;
}

}  // namespace

uint64_t updateCoverage(const ImageBlock& block, float boundary, std::vector<uint8_t>& coverage, int frames,
                        std::vector<float>* farthest) {
    const PixelRect& R = block.rect();
    const int W = R.width(), H = R.height(), S = block.samplesPerPixel();
    const int F = frames < 0 ? block.frameCount() : frames;
    coverage.resize(size_t(W) * size_t(H) * size_t(block.frameCount()), 0);
    if (farthest) farthest->resize(coverage.size(), std::numeric_limits<float>::infinity());
    // The still layer is what every frame without a record of a pixel sees: its farthest hit is
    // found once a pixel, when first needed (NaN: not yet).
    std::vector<float> stillFarthest(size_t(W) * size_t(H), std::numeric_limits<float>::quiet_NaN());
    // Frame by frame, row by row, in the order cells and records are stored. Most cells are
    // covered after the first layers: eight at a time are skipped when all are.
    constexpr uint64_t kEightCovered = 0x0101010101010101ull;
    uint64_t added = 0;
    for (int fi = 0; fi < F; ++fi)
        for (int y = 0; y < H; ++y) {
            const size_t row = (size_t(fi) * size_t(H) + size_t(y)) * size_t(W);
            for (int x = 0; x < W; ++x) {
                if ((x & 7) == 0 && x + 8 <= W) {
                    uint64_t eight;
                    std::memcpy(&eight, &coverage[row + size_t(x)], sizeof eight);
                    if (eight == kEightCovered) {
                        x += 7;
                        continue;
                    }
                }
                uint8_t& cell = coverage[row + size_t(x)];
                if (cell) continue;
                const size_t i = size_t(y) * size_t(W) + size_t(x);  // block.pixelIndex(R.x0 + x, R.y0 + y)
                float z;
                if (farthest && !block.touched(i)) {  // nothing written since it was measured
                    z = (*farthest)[row + size_t(x)];
                } else {
                    if (const SampleHit* r = block.record(fi, i)) {
                        z = farthestHit(r, S);
                    } else {
                        float& still = stillFarthest[i];
                        if (still != still) still = farthestHit(block.still(i), S);
                        z = still;
                    }
                    if (farthest) (*farthest)[row + size_t(x)] = z;
                }
                if (z < boundary) {
                    cell = 1;
                    ++added;
                }
            }
        }
    return added;
}

}  // namespace streyes
