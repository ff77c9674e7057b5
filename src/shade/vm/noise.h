// Noise for the Shading Language: gradient (Perlin-style) noise in 1 to 4 dimensions, its
// periodic form, and cell noise. Deterministic (a fixed integer hash, no tables built at run
// time), continuous, and in [0, 1] as RenderMan's noise() is (0.5 on every lattice point).
#pragma once

#include <cstdint>

namespace streyes::sl {

// Gradient noise at p (dims floats) in [0, 1]; `period` (dims ints, or null) makes it repeat
// with those periods (each at least 1). `seed` gives independent channels (color noise).
float gradientNoise(int dims, const float* p, const int* period = nullptr, uint32_t seed = 0);
// A value in [0, 1) constant over each unit cell (floor of every coordinate).
float cellNoise(int dims, const float* p, uint32_t seed = 0);
// A 32-bit integer hash of up to 5 ints.
uint32_t hashInts(const int32_t* v, int count, uint32_t seed);

}  // namespace streyes::sl
