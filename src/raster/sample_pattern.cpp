#include "raster/sample_pattern.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "util/sampling.h"

namespace streyes {

namespace {

// Kensler's hash-based permutation of [0, l): element i of permutation p. A bijection for any l
// (cycle walking within the next power of two).
uint32_t permute(uint32_t i, uint32_t l, uint32_t p) {
    uint32_t w = l - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    do {
        i ^= p;
        i *= 0xe170893d;
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i *= 0x0929eb3f;
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i *= 1 | p >> 27;
        i *= 0x6935fa69;
        i ^= (i & w) >> 11;
        i *= 0x74dcb303;
        i ^= (i & w) >> 2;
        i *= 0x9e501cc3;
        i ^= (i & w) >> 2;
        i *= 0xc860a3df;
        i &= w;
        i ^= i >> 5;
    } while (i >= l);
    return (i + p) % l;
}

// Kensler's hash to [0, 1).
float randfloat(uint32_t i, uint32_t p) {
    i ^= p;
    i ^= i >> 17;
    i ^= i >> 10;
    i *= 0xb36534e5;
    i ^= i >> 12;
    i ^= i >> 21;
    i *= 0x93fc4795;
    i ^= 0xdf6e307f;
    i ^= i >> 17;
    i *= 1 | p >> 18;
    return std::min(float(i) * 0x1p-32f, kOneMinusEpsilon);
}

// Table sizes: enough patterns and permutations that neighbouring pixels rarely share one, and
// no more than about a million entries however many samples a pixel has.
constexpr int kMaxPatterns = 64;
constexpr int kMaxPermutations = 64;
static_assert(kMaxPermutations < 255, "ImageBlock keeps a permutation in a byte, 255 for none yet");
constexpr size_t kMaxTableEntries = size_t(1) << 20;

}  // namespace

void correlatedMultiJitter(int j, int m, int n, uint32_t p, float* x, float* y) {
    const uint32_t s = uint32_t(j);
    const uint32_t sx = permute(s % uint32_t(m), uint32_t(m), p * 0xa511e9b3u);
    const uint32_t sy = permute(s / uint32_t(m), uint32_t(n), p * 0x63d83595u);
    const float jx = randfloat(s, p * 0xa399d265u), jy = randfloat(s, p * 0x711ad6a5u);
    *x = std::min((float(s % uint32_t(m)) + (float(sy) + jx) / float(n)) / float(m), kOneMinusEpsilon);
    *y = std::min((float(s / uint32_t(m)) + (float(sx) + jy) / float(m)) / float(n), kOneMinusEpsilon);
}

void concentricDisc(float x, float y, float* u, float* v) {
    const float a = 2 * x - 1, b = 2 * y - 1;
    if (a == 0 && b == 0) {
        *u = *v = 0;
        return;
    }
    constexpr float kQuarterPi = 0.785398163397448f;
    float r, phi;
    if (std::fabs(a) > std::fabs(b)) {
        r = a;
        phi = kQuarterPi * (b / a);
    } else {
        r = b;
        phi = 2 * kQuarterPi - kQuarterPi * (a / b);
    }
    *u = r * std::cos(phi);
    *v = r * std::sin(phi);
}

PatternTable::PatternTable(const SamplePattern& pattern) : pattern_(pattern) {
    S_ = pattern.count();
    P_ = int(std::clamp<size_t>(kMaxTableEntries / size_t(S_), 1, kMaxPatterns));
    Q_ = int(std::clamp<size_t>(kMaxTableEntries / size_t(S_), 1, kMaxPermutations));
    patternKey_ = mix64(pattern.seed);
    permutationKey_ = mix64(pattern.seed ^ 0x2545f4914f6cdd1dull);
    modP_ = FastMod32(uint32_t(P_));
    modQ_ = FastMod32(uint32_t(Q_));
    const uint64_t seed = mix64(pattern.seed);
    offsets_.resize(size_t(P_) * size_t(S_) * 2);
    for (int p = 0; p < P_; ++p) {
        const uint32_t id = uint32_t(hashCombine(seed, uint64_t(p)) >> 32);
        for (int j = 0; j < S_; ++j) {
            float* o = &offsets_[(size_t(p) * size_t(S_) + size_t(j)) * 2];
            if (pattern.jitter) {
                correlatedMultiJitter(j, pattern.sx, pattern.sy, id, &o[0], &o[1]);
            } else {
                o[0] = (float(j % pattern.sx) + 0.5f) / float(pattern.sx);
                o[1] = (float(j / pattern.sx) + 0.5f) / float(pattern.sy);
            }
        }
    }
    lens_.resize(offsets_.size());
    for (int p = 0; p < P_; ++p) {
        const uint32_t id = uint32_t(hashCombine(seed ^ 0x27d4eb2fu, uint64_t(p)) >> 32);
        for (int j = 0; j < S_; ++j) {
            const uint32_t stratum = permute(uint32_t(j), uint32_t(S_), id * 0x85ebca6bu);
            float x, y;
            correlatedMultiJitter(int(stratum), pattern.sx, pattern.sy, id, &x, &y);
            float* l = &lens_[(size_t(p) * size_t(S_) + size_t(j)) * 2];
            concentricDisc(x, y, &l[0], &l[1]);
        }
    }
    stratumOf_.resize(size_t(Q_) * size_t(S_));
    sampleOf_.resize(size_t(Q_) * size_t(S_));
    times_.resize(size_t(Q_) * size_t(S_));
    const float invS = 1.0f / float(S_);
    for (int q = 0; q < Q_; ++q) {
        const uint32_t id = uint32_t(hashCombine(seed ^ 0x5bd1e995u, uint64_t(q)) >> 32);
        for (int j = 0; j < S_; ++j) {
            const uint16_t k = uint16_t(permute(uint32_t(j), uint32_t(S_), id));
            stratumOf_[size_t(q) * size_t(S_) + size_t(j)] = k;
            sampleOf_[size_t(q) * size_t(S_) + k] = uint16_t(j);
        }
        for (int k = 0; k < S_; ++k)
            times_[size_t(q) * size_t(S_) + size_t(k)] =
                std::min((float(k) + (pattern.jitter ? randfloat(uint32_t(k), id * 0x68bc21ebu) : 0.5f)) * invS,
                         kOneMinusEpsilon);
    }
}

PatternTable::PatternTable(const SamplePattern& pattern, const std::vector<std::vector<float>>& stratumTimes,
                           const std::vector<float>& offsets)
    : PatternTable(pattern) {
    if (!offsets.empty()) {
        P_ = 1;
        modP_ = FastMod32(1);
        offsets_ = offsets;
    }
    Q_ = int(stratumTimes.size());
    if (Q_ >= 255) throw std::invalid_argument("a test pattern table holds at most 254 permutations");
    modQ_ = FastMod32(uint32_t(std::max(Q_, 1)));
    stratumOf_.resize(size_t(Q_) * size_t(S_));
    sampleOf_.resize(size_t(Q_) * size_t(S_));
    times_.resize(size_t(Q_) * size_t(S_));
    for (int q = 0; q < Q_; ++q)
        for (int k = 0; k < S_; ++k) {
            stratumOf_[size_t(q) * size_t(S_) + size_t(k)] = sampleOf_[size_t(q) * size_t(S_) + size_t(k)] = uint16_t(k);
            times_[size_t(q) * size_t(S_) + size_t(k)] = stratumTimes[size_t(q)][size_t(k)];
        }
}

void PatternTable::pixelSamples(int x, int y, int frame, SamplePosition* out) const {
    const float* o = offsets(patternOf(x, y));
    const int q = permutationOf(x, y, frame);
    for (int j = 0; j < S_; ++j)
        out[j] = {float(x) + o[2 * j], float(y) + o[2 * j + 1], stratumTimes(q)[stratumOfSample(q)[j]]};
}

int PatternTable::patternOf(int x, int y) const {
    const uint64_t h = hashCombine(hashCombine(patternKey_, uint64_t(uint32_t(x))), uint64_t(uint32_t(y)));
    return int(modP_(uint32_t(h >> 32)));
}

uint64_t PatternTable::permutationKeyOf(int x, int y) const {
    return hashCombine(hashCombine(permutationKey_, uint64_t(uint32_t(x))), uint64_t(uint32_t(y)));
}

int PatternTable::permutationAt(uint64_t pixelKey, int frame) const {
    return int(modQ_(uint32_t(hashCombine(pixelKey, uint64_t(uint32_t(frame))) >> 32)));
}

}  // namespace streyes
