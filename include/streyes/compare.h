// Image comparison: the error of an image B against a reference A, measured the same way for
// every speed figure (`streyes compare`, tools/speed-vs-error, tools/bench).
//
// Errors are kept as sums over pixels, so per-frame figures pool exactly into an overall figure
// for a whole animation. Non-finite values are counted, not averaged: OIIO's own compare passes
// images full of NaN. In Z, +inf is the background ("no surface", what streyes writes where
// nothing is hit); NaN and -inf in Z are errors.
#pragma once

#include <cstdint>
#include <string>

#include "streyes/image_io.h"

namespace streyes {

struct CompareOptions {
    // A pixel is "over threshold" when any of its R G B A differs by more than this.
    double threshold = 0.01;
    // Two surface depths disagree when |za - zb| > zTolerance * max(|za|, |zb|).
    double zTolerance = 1e-3;
    // Resample B bilinearly to A's size before comparing (R G B A only: Z is then not compared).
    // This is how a preview rendered at a lower --res is measured at the reference's size.
    bool resize = false;
};

// Values in one image that are not numbers a pixel may hold. +inf Z is not counted.
struct NonFiniteCounts {
    uint64_t colorNaN = 0, colorInf = 0;  // in R G B A
    uint64_t zNaN = 0, zNegInf = 0;
    uint64_t total() const { return colorNaN + colorInf + zNaN + zNegInf; }
    NonFiniteCounts& operator+=(const NonFiniteCounts& o);
};

// The error of B against A over one or more images of equal size.
struct ImageErrors {
    uint64_t pixels = 0;         // pixels whose R G B (A) are finite in both images
    uint64_t pixelsSkipped = 0;  // pixels left out because a colour value is not finite in A or B
    double sumSqRGB = 0, sumAbsRGB = 0, maxAbsRGB = 0;
    double sumSqA = 0, maxAbsA = 0;
    uint64_t pixelsDiffering = 0;     // any of R G B A differs at all
    uint64_t pixelsOverThreshold = 0; // any of R G B A differs by more than CompareOptions::threshold
    bool hasAlpha = false;
    bool zCompared = false;
    uint64_t zCoverageMismatch = 0;   // a surface (finite Z) in one image, background (+inf) in the other
    uint64_t zDepthMismatch = 0;      // surfaces in both, depths beyond CompareOptions::zTolerance
    double zMaxRelDiff = 0;           // largest relative depth difference where both have a surface
    NonFiniteCounts nonFiniteA, nonFiniteB;

    ImageErrors& operator+=(const ImageErrors& o);  // pools frames: the sums add up exactly

    double rmseRGB() const;     // sqrt of the mean squared difference over R, G and B
    double rmseA() const;       // the same for A (0 without alpha)
    double meanAbsRGB() const;  // mean absolute difference over R, G and B
    double psnr() const;        // dB, 10 log10(1 / MSE of RGB) with peak 1; +inf when identical
    double shareDiffering() const;
    double shareOverThreshold() const;
    bool hasNonFinite() const { return nonFiniteA.total() + nonFiniteB.total() > 0; }
};

// B against A. The images must have the same channel names (in any order) including R, G and B,
// and the same size unless options.resize; otherwise InputError naming both, never a number.
// `nameA` and `nameB` are used in those messages.
ImageErrors compareImages(const ImageData& a, const ImageData& b, const CompareOptions& options,
                          const std::string& nameA = "A", const std::string& nameB = "B");

// Bilinear resample of an image's pixels to width x height (pixel centres map onto each other).
ImageData resampleImage(const ImageData& image, int width, int height);

}  // namespace streyes
