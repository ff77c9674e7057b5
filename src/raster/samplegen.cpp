// Sample generation: stratified (x, y) jitter, stratified time with a per-pixel shuffle.
#include <limits>

#include "raster/image_block.h"
#include "util/sampling.h"

namespace streyes {

void generatePixelSamples(int px, int py, int frame, const SamplePattern& pattern, SamplePosition* out,
                          uint16_t* sliceStratum) {
    const int sx = pattern.sx, sy = pattern.sy, n = sx * sy;
    uint64_t key = hashCombine(hashCombine(hashCombine(mix64(pattern.seed), uint64_t(uint32_t(px))),
                                           uint64_t(uint32_t(py))),
                               uint64_t(uint32_t(frame)));
    HashRng rng(key);
    // Time strata: a random permutation of 0..n-1 (Fisher-Yates), one per (x, y) stratum.
    int perm[64 * 64];
    for (int i = 0; i < n; ++i) perm[i] = i;
    for (int i = n - 1; i > 0; --i) {
        int j = int(rng.nextBelow(uint32_t(i + 1)));
        std::swap(perm[i], perm[j]);
    }
    const float invX = 1.0f / float(sx), invY = 1.0f / float(sy), invN = 1.0f / float(n);
    for (int j = 0; j < n; ++j) {
        int ix = j % sx, iy = j / sx, k = perm[j];
        SamplePosition& s = out[j];
        sliceStratum[k] = uint16_t(j);
        s.x = float(px) + std::min((float(ix) + rng.nextFloat()) * invX, kOneMinusEpsilon);
        s.y = float(py) + std::min((float(iy) + rng.nextFloat()) * invY, kOneMinusEpsilon);
        s.tf = std::min((float(k) + rng.nextFloat()) * invN, kOneMinusEpsilon);
    }
}

void ImageBlock::reset(const PixelRect& rect, int firstFrame, int frameCount, const SamplePattern& pattern,
                       int shadowSlots) {
    rect_ = rect;
    firstFrame_ = firstFrame;
    frameCount_ = frameCount;
    pattern_ = pattern;
    slices_ = pattern.count();
    const size_t n = size_t(rect.area()) * size_t(frameCount) * size_t(slices_);
    // A larger bucket than the last (edge tiles are smaller): free the old arrays before making
    // new ones, rather than holding both while they are copied (everything is rewritten anyway),
    // and make them exactly n long (resize() alone may double the capacity). memory.h counts one.
    if (n > positions_.capacity() || n > hits_.capacity() || n > sliceStratum_.capacity()) {
        positions_ = {};
        hits_ = {};
        sliceStratum_ = {};
        positions_.reserve(n);
        hits_.reserve(n);
        sliceStratum_.reserve(n);
    }
    positions_.resize(n);
    hits_.assign(n, SampleHit{std::numeric_limits<float>::infinity(), {0, 0, 0}, 0.0f, kNoPrimitive});
    sliceStratum_.resize(n);
    shadowSlots_ = shadowSlots;
    if (shadowSlots > 0) shadowed_.resize(n * size_t(shadowSlots));
    for (int y = rect.y0; y <= rect.y1; ++y)
        for (int x = rect.x0; x <= rect.x1; ++x)
            for (int fi = 0; fi < frameCount; ++fi) {
                const size_t base = pixelOffset(x, y) + size_t(fi) * size_t(slices_);
                generatePixelSamples(x, y, firstFrame + fi, pattern, &positions_[base], &sliceStratum_[base]);
            }
}

}  // namespace streyes
