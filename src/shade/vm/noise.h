// Noise for the Shading Language: gradient (Perlin-style) noise in 1 to 4 dimensions, its
// periodic form, and cell noise. Deterministic (a fixed integer hash, no tables built at run
// time), continuous, and in [0, 1] as RenderMan's noise() is (0.5 on every lattice point).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace streyes::sl {

// Gradient noise at p (dims floats) in [0, 1]; `period` (dims ints, or null) makes it repeat
// with those periods (each at least 1). `seed` gives independent channels (color noise).
float gradientNoise(int dims, const float* p, const int* period = nullptr, uint32_t seed = 0);
// gradientNoise at n points at once, bit for bit: coordinate k of point i is p[k][i] (dims arrays
// of n floats), its period period[k][i] (null: none), out[i] its noise. Runs the widest SIMD
// kernel the CPU has (noise_kernels.cpp; Highway, capped as the sample kernels are: capSimd in
// raster/sample_kernels.h, which caps every Highway kernel chosen after it).
void gradientNoisePoints(int dims, const float* const* p, const int32_t* const* period, size_t n, uint32_t seed,
                         float* out);
// The kernels behind it, for tests and benchmarks: the one this CPU runs, the scalar reference
// (gradientNoise point by point), and every instruction set's that this CPU runs.
using NoisePointsFn = void (*)(int dims, const float* const* p, const int32_t* const* period, size_t n, uint32_t seed,
                               float* out);
NoisePointsFn noisePointsKernel();
NoisePointsFn noisePointsScalar();
std::vector<std::pair<std::string, NoisePointsFn>> noiseKernelsOfEveryTarget();
// A value in [0, 1) constant over each unit cell (floor of every coordinate).
float cellNoise(int dims, const float* p, uint32_t seed = 0);
// A 32-bit integer hash of up to 5 ints.
uint32_t hashInts(const int32_t* v, int count, uint32_t seed);

}  // namespace streyes::sl
