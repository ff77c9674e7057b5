// Hash-based random numbers. Every random choice is a pure function of (seed, pixel, frame,
// index), never of the order work is done in, so that images do not depend on threads or buckets.
#pragma once

#include <cstdint>

namespace streyes {

// splitmix64's finaliser: a good 64-bit mix.
inline uint64_t mix64(uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}

inline uint64_t hashCombine(uint64_t h, uint64_t v) { return mix64(h ^ (v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2))); }

// a % d for 32-bit a by a multiplication (Lemire, Kaser and Kurz, "Faster remainder by direct
// computation", 2019): exact for every a and every d > 0, and several times cheaper than the
// division where the same d serves many a (a pattern table's count, per pixel and frame).
class FastMod32 {
  public:
    FastMod32() = default;
    explicit FastMod32(uint32_t d) : m_(UINT64_MAX / d + 1), d_(d) {}
    uint32_t operator()(uint32_t a) const {
        return uint32_t((static_cast<unsigned __int128>(m_ * a) * d_) >> 64);
    }

  private:
    uint64_t m_ = 0;
    uint32_t d_ = 1;
};

// Largest float below 1: jittered values stay inside their stratum.
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

// A small counter-based stream: the n-th value is mix64(key + n * golden ratio).
class HashRng {
  public:
    explicit HashRng(uint64_t key) : state_(key) {}
    uint32_t nextU32() {
        state_ += 0x9e3779b97f4a7c15ULL;
        return uint32_t(mix64(state_) >> 32);
    }
    float nextFloat() {  // [0, 1)
        float f = float(nextU32() >> 8) * 0x1p-24f;
        return f < kOneMinusEpsilon ? f : kOneMinusEpsilon;
    }
    // Uniform integer in [0, n) (n small; the bias of the multiply-shift is below 2^-24 here).
    uint32_t nextBelow(uint32_t n) { return uint32_t((uint64_t(nextU32()) * n) >> 32); }

  private:
    uint64_t state_;
};

}  // namespace streyes
