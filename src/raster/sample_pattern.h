// Sample patterns: where in a pixel, and when in a frame's exposure, its samples lie.
//
// Positions are a pure function of the pixel: every frame uses the same sub-pixel positions, so
// that what is still in raster space is sampled once for a whole block of frames and resolved
// once (image_block.h). They come from a table of correlated multi-jittered patterns (Kensler,
// "Correlated Multi-Jittered Sampling", 2013): sample j of an sx x sy pattern lies in stratum
// (j % sx, j / sx) of the pixel, and the x and y projections of the S samples are stratified too
// (one sample in each of S columns and S rows). A pixel takes pattern patternOf(x, y) of P.
//
// Times are stratified too: the S samples of a pixel in a frame take S time strata ("slices"),
// in an order (a permutation of the samples) that the table draws per pixel and per frame from Q
// permutations, each with its own jitter within the strata. Time is thus decorrelated from
// position, and from frame to frame, while positions stay.
//
// Lens positions (depth of field) are a pure function of the pixel too, the same in every frame,
// so still geometry stays in the still layer: pattern p's sample j takes a point of another
// correlated multi-jittered pattern (its own scramble), in a stratum drawn by a permutation of
// the samples, so that the lens stratum is decorrelated from the sample's (x, y) stratum, mapped
// to the unit disc with Shirley and Chiu's concentric map (which keeps the strata's areas).
//
// Everything is a pure function of (pixel, frame, seed): the same in every bucket, every block
// and on every thread.
#pragma once

#include <cstdint>
#include <vector>

#include "streyes/render_options.h"
#include "util/sampling.h"

namespace streyes {

struct SamplePosition {
    float x, y;   // raster position
    float tf;     // time within the frame's exposure in [0, 1): t = f + open + tf * (close - open)
};

class PatternTable {
  public:
    PatternTable() = default;
    explicit PatternTable(const SamplePattern& pattern);
    // For tests that need samples at chosen times and places: one permutation per entry of
    // `stratumTimes` (S times each, one a stratum, in the identity order), and, when `offsets`
    // is given (S x, y pairs), one pattern for every pixel.
    PatternTable(const SamplePattern& pattern, const std::vector<std::vector<float>>& stratumTimes,
                 const std::vector<float>& offsets = {});

    const SamplePattern& pattern() const { return pattern_; }
    int samples() const { return S_; }
    int patternCount() const { return P_; }
    int permutationCount() const { return Q_; }

    // The pattern of pixel (x, y), and its S sub-pixel positions in [0, 1)^2 (x, y pairs).
    int patternOf(int x, int y) const;
    const float* offsets(int pattern) const { return &offsets_[size_t(pattern) * size_t(S_) * 2]; }

    // The unit-disc lens positions (lu, lv pairs) of pattern `pattern`'s S samples.
    const float* lens(int pattern) const { return &lens_[size_t(pattern) * size_t(S_) * 2]; }

    // The time permutation of pixel (x, y) in `frame`; for it, the time stratum of each sample,
    // the sample of each stratum (slice), and each stratum's time as a fraction of the exposure,
    // in [k / S, (k + 1) / S).
    int permutationOf(int x, int y, int frame) const { return permutationAt(permutationKeyOf(x, y), frame); }
    // The same in two steps, for a block that needs a pixel's permutation in many frames: the
    // pixel's key once, then one hash a frame.
    uint64_t permutationKeyOf(int x, int y) const;
    int permutationAt(uint64_t pixelKey, int frame) const;
    const uint16_t* stratumOfSample(int q) const { return &stratumOf_[size_t(q) * size_t(S_)]; }
    const uint16_t* sampleOfStratum(int q) const { return &sampleOf_[size_t(q) * size_t(S_)]; }
    const float* stratumTimes(int q) const { return &times_[size_t(q) * size_t(S_)]; }

    // The S samples of pixel (x, y) in `frame`: raster position and time (for tests and oracles;
    // an ImageBlock keeps them for its pixels).
    void pixelSamples(int x, int y, int frame, SamplePosition* out) const;

  private:
    SamplePattern pattern_;
    int S_ = 0, P_ = 0, Q_ = 0;
    // What patternOf and permutationOf hash from for every pixel, made once (each block makes a
    // pixel's pattern and, per frame with motion, its permutation).
    uint64_t patternKey_ = 0, permutationKey_ = 0;
    FastMod32 modP_, modQ_;
    std::vector<float> offsets_;       // P x S x 2
    std::vector<float> lens_;          // P x S x 2
    std::vector<uint16_t> stratumOf_;  // Q x S
    std::vector<uint16_t> sampleOf_;   // Q x S
    std::vector<float> times_;         // Q x S
};

// Kensler's correlated multi-jittered sample j of an m x n pattern number p: in stratum
// (j % m, j / m) of [0, 1)^2. Exposed for tests.
void correlatedMultiJitter(int j, int m, int n, uint32_t p, float* x, float* y);
// Shirley and Chiu's concentric map of [0, 1)^2 onto the unit disc. Exposed for tests.
void concentricDisc(float x, float y, float* u, float* v);

}  // namespace streyes
