// The samples of one bucket: a block of pixels (a tile plus the filter's guard band) times a
// block of frames, S samples per pixel per frame.
//
// Each pixel's S samples in a frame are stratified in (x, y) on an sx x sy grid and in time on
// S strata ("slices"), with the time strata shuffled against the (x, y) strata so that motion
// blur does not correlate with position.
//
// Layout: pixel-major, then frame, then (x, y) stratum j = iy * sx + ix. All samples of one
// pixel over the block are contiguous, and a still micropolygon visits only the strata its bound
// overlaps. A moving micropolygon is bounded over one time slice at a time and needs the one
// sample per pixel in that slice: sliceStratum() maps slice k to its stratum. Positions (read by
// every test) are kept apart from hit results (written only on a hit).
#pragma once

#include <cstdint>
#include <vector>

#include "streyes/render_options.h"
#include "streyes/vecmath.h"

namespace streyes {

struct SamplePosition {
    float x, y;   // raster position
    float tf;     // time within the frame's exposure in [0, 1): t = f + open + tf * (close - open)
};

// The id of "no primitive": no hit yet.
constexpr uint64_t kNoPrimitive = UINT64_MAX;

struct SampleHit {
    float z;      // camera-space depth of the nearest hit so far; +inf when none
    Color c;      // colour of that hit
    float a;      // its coverage (1 for an opaque hit)
    uint64_t id;  // primitive of that hit (kNoPrimitive when none)

    // Whether a hit (z, id, c) beats this one. Lexicographic on (depth, primitive, colour): the
    // result does not depend on the order hits arrive in, and at equal depth the primitive
    // declared first wins.
    bool beatenBy(float z2, uint64_t id2, Color c2) const {
        if (z2 != z) return z2 < z;
        if (id2 != id) return id2 < id;
        if (c2.x != c.x) return c2.x < c.x;
        if (c2.y != c.y) return c2.y < c.y;
        return c2.z < c.z;
    }
};

// The S sample positions of pixel (px, py) in frame `frame`, written to out[stratum], and the
// stratum of each time slice to sliceStratum[slice]. A pure function of its arguments: the same
// in every bucket and on every thread.
void generatePixelSamples(int px, int py, int frame, const SamplePattern& pattern, SamplePosition* out,
                          uint16_t* sliceStratum);

class ImageBlock {
  public:
    // Sizes the block, fills in the sample positions and clears the hits (reusing memory).
    // shadowSlots > 0 also keeps, with each sample's hit, the contribution of each light that
    // casts shadows before its shadow test (shadowed()), for the shadow pass (trace.h).
    void reset(const PixelRect& rect, int firstFrame, int frameCount, const SamplePattern& pattern,
               int shadowSlots = 0);

    const PixelRect& rect() const { return rect_; }
    int firstFrame() const { return firstFrame_; }
    int frameCount() const { return frameCount_; }
    const SamplePattern& pattern() const { return pattern_; }
    int slices() const { return slices_; }
    int samplesPerPixel() const { return frameCount_ * slices_; }  // over the whole block

    // Offset of pixel (x, y)'s first sample; its sample in stratum j of frame fi is at
    // + fi * slices() + j.
    size_t pixelOffset(int x, int y) const {
        return (size_t(y - rect_.y0) * size_t(rect_.width()) + size_t(x - rect_.x0)) * size_t(samplesPerPixel());
    }
    // The sample of pixel (x, y) in time slice k of frame fi.
    size_t sliceIndex(int fi, int k, int x, int y) const {
        size_t frameBase = pixelOffset(x, y) + size_t(fi) * size_t(slices_);
        return frameBase + sliceStratum_[frameBase + size_t(k)];
    }

    SamplePosition* positions() { return positions_.data(); }
    const SamplePosition* positions() const { return positions_.data(); }
    SampleHit* hits() { return hits_.data(); }
    const SampleHit* hits() const { return hits_.data(); }
    int shadowSlots() const { return shadowSlots_; }
    Color* shadowed(size_t sample) { return &shadowed_[sample * size_t(shadowSlots_)]; }

    size_t sampleCount() const { return positions_.size(); }
    size_t bytes() const {
        return positions_.capacity() * sizeof(SamplePosition) + hits_.capacity() * sizeof(SampleHit) +
               shadowed_.capacity() * sizeof(Color);
    }

  private:
    PixelRect rect_;
    int firstFrame_ = 0, frameCount_ = 0, slices_ = 0;
    SamplePattern pattern_;
    std::vector<SamplePosition> positions_;
    std::vector<SampleHit> hits_;
    std::vector<uint16_t> sliceStratum_;
    int shadowSlots_ = 0;
    std::vector<Color> shadowed_;  // shadowSlots_ per sample, valid where the sample has a hit
};

}  // namespace streyes
