#include "streyes/occlusion.h"

namespace streyes {

template <typename Count>
void SummedVolumeTable<Count>::build(const uint8_t* c, int width, int height, int depth) {
    w_ = width;
    h_ = height;
    d_ = depth;
    const size_t W = size_t(width), H = size_t(height), D = size_t(depth);
    t_.resize(W * H * D);
    // Pass 1: prefix sums along x, row by row (this also copies the 0/1 volume in).
    for (size_t row = 0; row < H * D; ++row) {
        Count run = 0;
        const uint8_t* src = c + row * W;
        Count* dst = &t_[row * W];
        for (size_t x = 0; x < W; ++x) dst[x] = run += Count(src[x]);
    }
    // Pass 2: along y, within each frame.
    for (size_t f = 0; f < D; ++f)
        for (size_t y = 1; y < H; ++y) {
            Count* dst = &t_[(f * H + y) * W];
            const Count* above = dst - W;
            for (size_t x = 0; x < W; ++x) dst[x] += above[x];
        }
    // Pass 3: along frames.
    for (size_t f = 1; f < D; ++f) {
        Count* dst = &t_[f * H * W];
        const Count* before = dst - H * W;
        for (size_t i = 0; i < H * W; ++i) dst[i] += before[i];
    }
}

template class SummedVolumeTable<uint32_t>;
template class SummedVolumeTable<uint64_t>;

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
