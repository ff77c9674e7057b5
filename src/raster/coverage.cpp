#include "raster/coverage.h"

namespace streyes {

uint64_t updateCoverage(const ImageBlock& block, float boundary, std::vector<uint8_t>& coverage) {
    const PixelRect& R = block.rect();
    const int W = R.width(), H = R.height(), F = block.frameCount(), S = block.slices();
    coverage.resize(size_t(W) * size_t(H) * size_t(F), 0);
    const SampleHit* hits = block.hits();
    uint64_t added = 0;
    for (int y = R.y0; y <= R.y1; ++y)
        for (int x = R.x0; x <= R.x1; ++x) {
            const SampleHit* pixel = hits + block.pixelOffset(x, y);
            for (int fi = 0; fi < F; ++fi) {
                uint8_t& cell = coverage[(size_t(fi) * size_t(H) + size_t(y - R.y0)) * size_t(W) + size_t(x - R.x0)];
                if (cell) continue;
                const SampleHit* s = pixel + size_t(fi) * size_t(S);
                bool covered = true;
                for (int k = 0; k < S && covered; ++k) covered = s[k].a >= 1.0f && s[k].z < boundary;
                if (covered) {
                    cell = 1;
                    ++added;
                }
            }
        }
    return added;
}

}  // namespace streyes
