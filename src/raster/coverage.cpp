#include "raster/coverage.h"

#include <algorithm>
#include <limits>

namespace streyes {

namespace {

// The farthest of a pixel's S hits, +inf unless every one is opaque. The pixel is covered when
// that lies nearer than the boundary.
float farthestHit(const SampleHit* s, int S) {
    float z = -std::numeric_limits<float>::infinity();
    for (int k = 0; k < S; ++k) {
        if (!(s[k].a >= 1.0f) || s[k].z != s[k].z) return std::numeric_limits<float>::infinity();
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
    uint64_t added = 0;
    for (int y = R.y0; y <= R.y1; ++y)
        for (int x = R.x0; x <= R.x1; ++x) {
            const size_t i = block.pixelIndex(x, y);
            // The still layer is what every frame without a record of the pixel sees: tested once.
            bool stillDone = false;
            float stillFarthest = 0;
            for (int fi = 0; fi < F; ++fi) {
                const size_t ci = (size_t(fi) * size_t(H) + size_t(y - R.y0)) * size_t(W) + size_t(x - R.x0);
                uint8_t& cell = coverage[ci];
                if (cell) continue;
                float z;
                if (const SampleHit* r = block.record(fi, i)) {
                    z = farthestHit(r, S);
                } else {
                    if (!stillDone) stillFarthest = farthestHit(block.still(i), S), stillDone = true;
                    z = stillFarthest;
                }
                if (farthest) (*farthest)[ci] = z;
                if (z < boundary) {
                    cell = 1;
                    ++added;
                }
            }
        }
    return added;
}

}  // namespace streyes
