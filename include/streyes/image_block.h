// The samples of one bucket: a block of pixels (a tile plus the filter's guard band) times a
// block of frames, S samples per pixel per frame.
//
// Each pixel's S samples in a frame are stratified in (x, y) on an sx x sy grid and in time on
// S strata, with the time strata shuffled against the (x, y) strata (so motion blur does not
// correlate with position). The samples are stored by time stratum ("slice"): slice k of frame
// f holds exactly one sample per pixel, so the rasterizer can bound a micropolygon over one
// slice's time interval and visit only the pixels that bound covers.
#pragma once

#include <cstdint>
#include <vector>

#include "streyes/util/vecmath.h"

namespace streyes {

struct Sample {
    float x, y;   // raster position
    float tf;     // time within the frame's exposure in [0, 1): t = f + open + tf * (close - open)
    float z;      // camera-space depth of the nearest hit so far; +inf when none
    Color c;      // colour of that hit
    float a;      // its coverage (1 for an opaque hit)
};

struct SamplePattern {
    int sx = 2, sy = 2;      // strata per pixel in x and y; sx * sy time slices
    uint64_t seed = 0;
    int count() const { return sx * sy; }
};

// The S samples of pixel (px, py) in frame `frame`, written to out[slice] (out has S entries).
// A pure function of its arguments: the same in every bucket and on every thread.
void generatePixelSamples(int px, int py, int frame, const SamplePattern& pattern, Sample* out);

class ImageBlock {
  public:
    // Sizes the block and fills in the sample positions (reusing memory across buckets).
    void reset(const PixelRect& rect, int firstFrame, int frameCount, const SamplePattern& pattern);

    const PixelRect& rect() const { return rect_; }
    int firstFrame() const { return firstFrame_; }
    int frameCount() const { return frameCount_; }
    int slices() const { return slices_; }

    // Samples of row y (absolute raster row) in slice k of frame index fi; index by x - rect().x0.
    Sample* row(int fi, int k, int y) {
        return &samples_[((size_t(fi) * size_t(slices_) + size_t(k)) * size_t(rect_.height()) +
                          size_t(y - rect_.y0)) * size_t(rect_.width())];
    }
    const Sample* row(int fi, int k, int y) const { return const_cast<ImageBlock*>(this)->row(fi, k, y); }
    size_t sampleCount() const { return samples_.size(); }
    size_t bytes() const { return samples_.capacity() * sizeof(Sample); }

  private:
    PixelRect rect_;
    int firstFrame_ = 0, frameCount_ = 0, slices_ = 0;
    std::vector<Sample> samples_;
    std::vector<Sample> scratch_;
};

}  // namespace streyes
