// Quantize (RI Spec 3.2): how a display's float values become the integers an 8- or 16-bit file
// holds: value = round(one * value + ditheramplitude * r), clamped to [min, max], r a uniform
// random number in [-1, 1) per pixel (the same for the pixel's channels). one = 0 writes floats.
// A display's "quantize" [zero one min max] (Aqsis's) maps 0 to zero: round(zero + value *
// (one - zero) + ...), so that a normal's -1..1 fills 0..255 with zero 128.
#pragma once

#include <cstdint>
#include <string>

namespace streyes {

struct Quantize {
    double one = 0, min = 0, max = 0, dither = 0;
    double zero = 0;
    bool floats() const { return one == 0; }
    // The file's storage: "float" (one = 0, or a range below 0 or above 65535), "uint8" (max <= 255)
    // or "uint16".
    const char* storage() const;
    // Largest value of the storage's unsigned integers (255 or 65535; 1 for floats).
    double storageMax() const;
    // The quantized value of channel value v at pixel (x, y) of `frame`: r is a hash of the three
    // (a pure function of them: the same frame gives the same file in any block of frames).
    double apply(double v, int x, int y, int frame) const;
    // The dither term's random number in [-1, 1).
    static double random(int x, int y, int frame);
};

// RenderMan's defaults: colour 8-bit with half an integer step of dither; depth as floats.
constexpr Quantize kColorQuantize{255, 0, 255, 0.5};
constexpr Quantize kDepthQuantize{0, 0, 0, 0};

}  // namespace streyes
