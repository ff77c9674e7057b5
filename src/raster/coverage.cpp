#include "raster/coverage.h"

namespace streyes {

namespace {

// Whether every one of a pixel's S hits is opaque and nearer than the boundary.
bool covered(const SampleHit* s, int S, float boundary) {
    for (int k = 0; k < S; ++k)
        if (!(s[k].a >= 1.0f && s[k].z < boundary)) return false;
    return true;
}

}  // namespace

uint64_t updateCoverage(const ImageBlock& block, float boundary, std::vector<uint8_t>& coverage, int frames) {
    const PixelRect& R = block.rect();
    const int W = R.width(), H = R.height(), S = block.samplesPerPixel();
    const int F = frames < 0 ? block.frameCount() : frames;
    coverage.resize(size_t(W) * size_t(H) * size_t(block.frameCount()), 0);
    uint64_t added = 0;
    for (int y = R.y0; y <= R.y1; ++y)
        for (int x = R.x0; x <= R.x1; ++x) {
            const size_t i = block.pixelIndex(x, y);
            // The still layer is what every frame without a record of the pixel sees: tested once.
            int stillCovered = -1;
            for (int fi = 0; fi < F; ++fi) {
                uint8_t& cell = coverage[(size_t(fi) * size_t(H) + size_t(y - R.y0)) * size_t(W) + size_t(x - R.x0)];
                if (cell) continue;
                bool c;
                if (const SampleHit* r = block.record(fi, i)) {
                    c = covered(r, S, boundary);
                } else {
                    if (stillCovered < 0) stillCovered = covered(block.still(i), S, boundary);
                    c = stillCovered != 0;
                }
                if (c) {
                    cell = 1;
                    ++added;
                }
            }
        }
    return added;
}

}  // namespace streyes
