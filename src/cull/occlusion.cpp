#include "cull/occlusion.h"

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

}  // namespace streyes
