#include "streyes/quantize.h"

#include <algorithm>
#include <cmath>

namespace streyes {

const char* Quantize::storage() const {
    if (floats() || min < 0 || max > 65535) return "float";
    return max <= 255 ? "uint8" : "uint16";
}

double Quantize::storageMax() const {
    const std::string s = storage();
    return s == "uint8" ? 255 : s == "uint16" ? 65535 : 1;
}

double Quantize::random(int x, int y, int frame) {
    // A 64-bit mix (splitmix64's finaliser) of the pixel and frame; the top 53 bits as [0, 1).
    uint64_t h = uint64_t(uint32_t(x)) * 0x9E3779B97F4A7C15ull ^ uint64_t(uint32_t(y)) * 0xC2B2AE3D27D4EB4Full ^
                 uint64_t(uint32_t(frame)) * 0x165667B19E3779F9ull;
    h ^= h >> 30;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 27;
    h *= 0x94D049BB133111EBull;
    h ^= h >> 31;
    return double(h >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

double Quantize::apply(double v, int x, int y, int frame) const {
    if (floats()) return v;
    if (std::isnan(v)) v = 0;
    const double q = std::round(zero + v * (one - zero) + (dither != 0 ? dither * random(x, y, frame) : 0.0));
    return std::clamp(q, min, max);
}

}  // namespace streyes
