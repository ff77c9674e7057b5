#include "shade/vm/noise.h"

#include <algorithm>
#include <cmath>

namespace streyes::sl {

uint32_t hashInts(const int32_t* v, int count, uint32_t seed) {
    // A murmur-style mix of each int, then a final avalanche: cheap and well spread.
    uint32_t h = 0x9e3779b9u ^ seed;
    for (int k = 0; k < count; ++k) {
        uint32_t x = uint32_t(v[k]) * 0xcc9e2d51u;
        x = (x << 15) | (x >> 17);
        x *= 0x1b873593u;
        h ^= x;
        h = (h << 13) | (h >> 19);
        h = h * 5u + 0xe6546b64u;
    }
    h ^= uint32_t(count);
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

namespace {

inline float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

// A gradient for a lattice point: components in [-1, 1] from the hash's bytes.
template <int D>
inline float gradDot(uint32_t h, const float* d) {
    float s = 0;
    for (int k = 0; k < D; ++k) {
        uint32_t bits = (h >> (8 * k)) & 0xffu;
        if (k == 3) bits = ((h >> 24) ^ (h << 3)) & 0xffu;
        s += (float(bits) * (2.0f / 255.0f) - 1.0f) * d[k];
    }
    return s;
}

// The lattice cell of a coordinate. Far out the lattice repeats (every 2^30), so that no float
// beyond int's range is ever converted to an int.
inline int32_t cellOf(float f) {
    if (std::fabs(f) < 1073741824.0f) return int32_t(f);
    return int32_t(std::fmod(double(f), 1073741824.0));
}

// Scale so that the signed noise fills about [-1, 1] (measured on many points).
constexpr float kScale[5] = {0, 1.9f, 1.5f, 1.3f, 1.15f};

template <int D>
float gradientNoiseD(const float* p, const int* period, uint32_t seed) {
    int32_t base[D];
    float frac[D], w[D];
    for (int k = 0; k < D; ++k) {
        const float pk = std::isfinite(p[k]) ? p[k] : 0.0f;
        const float f = std::floor(pk);
        base[k] = cellOf(f);
        frac[k] = pk - f;
        w[k] = fade(frac[k]);
    }
    float sum = 0;
    for (int corner = 0; corner < (1 << D); ++corner) {
        int32_t lattice[D];
        float d[D], weight = 1;
        for (int k = 0; k < D; ++k) {
            const int bit = (corner >> k) & 1;
            int32_t c = base[k] + bit;
            if (period) {
                const int per = std::max(1, period[k]);
                c %= per;
                if (c < 0) c += per;
            }
            lattice[k] = c;
            d[k] = frac[k] - float(bit);
            weight *= bit ? w[k] : 1.0f - w[k];
        }
        sum += weight * gradDot<D>(hashInts(lattice, D, seed), d);
    }
    const float n = 0.5f + 0.5f * kScale[D] * sum;
    return std::min(1.0f, std::max(0.0f, n));
}

}  // namespace

float gradientNoise(int dims, const float* p, const int* period, uint32_t seed) {
    switch (dims) {
        case 1: return gradientNoiseD<1>(p, period, seed);
        case 2: return gradientNoiseD<2>(p, period, seed);
        case 3: return gradientNoiseD<3>(p, period, seed);
        default: return gradientNoiseD<4>(p, period, seed);
    }
}

float cellNoise(int dims, const float* p, uint32_t seed) {
    int32_t cell[4];
    for (int k = 0; k < dims; ++k) cell[k] = cellOf(std::floor(std::isfinite(p[k]) ? p[k] : 0.0f));
    return float(hashInts(cell, dims, seed ^ 0x5bd1e995u) >> 8) * (1.0f / 16777216.0f);
}

}  // namespace streyes::sl
