#include "raster/image_block.h"

#include "geom/grid.h"

#include <algorithm>
#include <limits>

namespace streyes {

void ImageBlock::reset(const PixelRect& rect, int firstFrame, int frameCount, const PatternTable& patterns, bool dense,
                       int shadowSlots, bool lens) {
    rect_ = rect;
    width_ = rect.width();
    pixels_ = int(rect.area());
    firstFrame_ = firstFrame;
    frameCount_ = frameCount;
    patterns_ = &patterns;
    S_ = patterns.samples();
    dense_ = dense;
    shadowSlots_ = shadowSlots;
    const size_t pixels = size_t(rect.area()), n = pixels * size_t(S_);
    // Padded: the SIMD kernels read whole vectors past a pixel's last sample (sample_kernels.h).
    xs_.resize(n + 64);
    ys_.resize(n + 64);
    pattern_.resize(pixels);
    for (int y = rect.y0; y <= rect.y1; ++y)
        for (int x = rect.x0; x <= rect.x1; ++x) {
            const size_t i = pixelIndex(x, y);
            pattern_[i] = uint8_t(patterns.patternOf(x, y));
            const float* o = patterns.offsets(pattern_[i]);
            for (int j = 0; j < S_; ++j) {
                xs_[i * size_t(S_) + size_t(j)] = float(x) + o[2 * j];
                ys_[i * size_t(S_) + size_t(j)] = float(y) + o[2 * j + 1];
            }
        }
    lens_ = lens;
    if (lens) {
        lus_.resize(n + 64);  // padded as xs_ and ys_
        lvs_.resize(n + 64);
        for (size_t i = 0; i < pixels; ++i) {
            const float* l = patterns.lens(pattern_[i]);
            for (int j = 0; j < S_; ++j) {
                lus_[i * size_t(S_) + size_t(j)] = l[2 * j];
                lvs_[i * size_t(S_) + size_t(j)] = l[2 * j + 1];
            }
        }
    }
    permutation_.resize(size_t(frameCount) * pixels);
    timesMade_.assign(size_t(frameCount), 0);
    permutationKeys_.resize(pixels);  // made a pixel at a time (makePermutation)
    keyMade_.assign(pixels, 0);
    if (dense)
        for (int fi = 0; fi < frameCount; ++fi) makeTimes(fi);

    // Records are kept in chunks from bucket to bucket (a bucket with as many samples per pixel
    // reuses them); the still layer and the slots are rewritten.
    if (chunkSamples_ != size_t(S_) * kRecordsPerChunk || aovChunkWidth_ != aovs_) {
        chunks_.clear();
        aovChunks_.clear();
        chunkSamples_ = size_t(S_) * kRecordsPerChunk;
        aovChunkWidth_ = aovs_;
    }
    records_ = 0;
    slot_.resize(size_t(frameCount) * pixels);  // each frame's row written by makeRow
    farthest_.resize(size_t(frameCount) * pixels);
    rowMade_.assign(size_t(frameCount), 0);
    recordsOf_.assign(dense ? 0 : pixels, 0);
    touched_.assign(pixels, 0);
    if (dense) {
        still_.clear();
        for (int fi = 0; fi < frameCount; ++fi) {
            makeRow(fi);
            for (size_t i = 0; i < pixels; ++i) {
                if (records_ / kRecordsPerChunk >= chunks_.size()) addChunk();
                slot_[size_t(fi) * pixels + i] = int32_t(records_);
                SampleHit* h = recordAt(records_++);
                std::fill(h, h + S_, kNoHit);
            }
        }
        if (shadowSlots > 0) shadowed_.assign(size_t(frameCount) * n * size_t(shadowSlots), Color{0, 0, 0});
        stillTested_.assign(shadowSlots > 0 ? size_t(frameCount) * n : 0, 0);
    } else {
        still_.assign(n, kNoHit);
        shadowed_.clear();  // grown record by record (makeRecord)
        stillTested_.clear();
    }
    // Read only where a sample has a hit, which writes them: no clearing needed beyond sizing.
    stillAov_.resize(dense ? 0 : n * size_t(aovs_));
    fragmentsOn_ = false;
    fragments_.clear();
    fragmentShadowed_.clear();
    fragmentStillTested_.clear();
    fragmentAov_.clear();
}

void ImageBlock::makeFragmentHeads() {
    fragmentsOn_ = true;
    stillHeads_.assign(dense_ ? 0 : size_t(pixelCount()) * size_t(S_), -1);
    recordHeads_.assign(size_t(records_) * size_t(S_), -1);
}

void ImageBlock::makeTimes(int fi) const {
    const size_t pixels = size_t(pixelCount());
    std::fill_n(&permutation_[size_t(fi) * pixels], pixels, kUnmade);
    timesMade_[size_t(fi)] = 1;
}

uint8_t ImageBlock::makePermutation(int fi, size_t i) const {
    if (!keyMade_[i]) {  // a pixel's key is hashed once for every frame, when first needed
        const int x = rect_.x0 + int(i % size_t(width_)), y = rect_.y0 + int(i / size_t(width_));
        permutationKeys_[i] = patterns_->permutationKeyOf(x, y);
        keyMade_[i] = 1;
    }
    return uint8_t(patterns_->permutationAt(permutationKeys_[i], firstFrame_ + fi));
}

void ImageBlock::addChunk() {
    chunks_.push_back(std::make_unique<SampleHit[]>(chunkSamples_));
    if (aovs_ > 0) aovChunks_.push_back(std::make_unique<float[]>(chunkSamples_ * size_t(aovs_)));
}

void ImageBlock::makeRow(int fi) {
    const size_t pixels = size_t(pixelCount()), at = size_t(fi) * pixels;
    std::fill(slot_.begin() + ptrdiff_t(at), slot_.begin() + ptrdiff_t(at + pixels), -1);
    std::fill(farthest_.begin() + ptrdiff_t(at), farthest_.begin() + ptrdiff_t(at + pixels),
              -std::numeric_limits<float>::infinity());  // stale
    rowMade_[size_t(fi)] = 1;
}

SampleHit* ImageBlock::makeRecord(int fi, size_t i) {
    if (!rowMade_[size_t(fi)]) makeRow(fi);
    if (records_ / kRecordsPerChunk >= chunks_.size()) addChunk();
    slot_[size_t(fi) * size_t(pixelCount()) + i] = int32_t(records_);
    ++recordsOf_[i];
    SampleHit* r = recordAt(records_);
    if (aovs_ > 0) {
        const float* a = stillAov(i);
        std::copy(a, a + size_t(S_) * size_t(aovs_), recordAovAt(records_));
    }
    ++records_;
    if (fragmentsOn_) recordHeads_.resize(size_t(records_) * size_t(S_), -1);
    if (shadowSlots_ > 0) {
        // The still layer holds only grids whose shadows are in their colour: no parts to add.
        shadowed_.resize(size_t(records_) * size_t(S_) * size_t(shadowSlots_), Color{0, 0, 0});
        stillTested_.resize(size_t(records_) * size_t(S_), kFoldedShadows);
    }
    std::copy(still(i), still(i) + S_, r);
    return r;
}

// By record (a dense block's record of frame fi, pixel i is fi x pixels + i).
Color* ImageBlock::shadowed(int fi, size_t i) {
    return &shadowed_[size_t(slotOf(fi, i)) * size_t(S_) * size_t(shadowSlots_)];
}

size_t ImageBlock::bytes() const {
    return (xs_.capacity() + ys_.capacity() + lus_.capacity() + lvs_.capacity()) * sizeof(float) +
           permutation_.capacity() + permutationKeys_.capacity() * sizeof(uint64_t) + keyMade_.capacity() +
           still_.capacity() * sizeof(SampleHit) + slot_.capacity() * sizeof(int32_t) +
           chunks_.size() * chunkSamples_ * sizeof(SampleHit) + shadowed_.capacity() * sizeof(Color) +
           stillTested_.capacity() + fragmentStillTested_.capacity() +
           (stillAov_.capacity() + aovChunks_.size() * chunkSamples_ * size_t(aovs_)) * sizeof(float) +
           (stillHeads_.capacity() + recordHeads_.capacity()) * sizeof(int32_t) +
           fragments_.capacity() * sizeof(SampleFragment) + fragmentShadowed_.capacity() * sizeof(Color) +
           fragmentAov_.capacity() * sizeof(float);
}

}  // namespace streyes
