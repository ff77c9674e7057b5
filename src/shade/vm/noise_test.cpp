// Noise: deterministic, in [0, 1], continuous, periodic where asked, and cell noise constant
// over cells.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "shade/vm/noise.h"
#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

TEST(VmNoise, InRangeAndSpread) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> d(-100, 100);
    for (int dims = 1; dims <= 4; ++dims) {
        float lo = 1, hi = 0;
        double sum = 0;
        const int count = 100000;
        for (int k = 0; k < count; ++k) {
            float p[4] = {d(rng), d(rng), d(rng), d(rng)};
            float v = gradientNoise(dims, p);
            ASSERT_GE(v, 0.0f);
            ASSERT_LE(v, 1.0f);
            lo = std::min(lo, v);
            hi = std::max(hi, v);
            sum += v;
        }
        EXPECT_NEAR(sum / count, 0.5, 0.01) << dims;
        EXPECT_LT(lo, 0.15f) << dims;  // it uses its range
        EXPECT_GT(hi, 0.85f) << dims;
    }
}

TEST(VmNoise, DeterministicAndHalfOnTheLattice) {
    float p[3] = {1.25f, -7.5f, 3.75f};
    EXPECT_EQ(gradientNoise(3, p), gradientNoise(3, p));
    float q[3] = {4, -2, 9};
    EXPECT_FLOAT_EQ(gradientNoise(3, q), 0.5f);
    EXPECT_NE(gradientNoise(3, p, nullptr, 1), gradientNoise(3, p, nullptr, 2));  // channels differ
    // Values are fixed by the code, not by a run-time table: this one never changes.
    float r[2] = {0.3f, 0.7f};
    EXPECT_EQ(gradientNoise(2, r), gradientNoise(2, r));
}

TEST(VmNoise, Continuous) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> d(-50, 50);
    const float h = 1e-3f;
    for (int dims = 1; dims <= 4; ++dims) {
        float worst = 0;
        for (int k = 0; k < 20000; ++k) {
            float p[4] = {d(rng), d(rng), d(rng), d(rng)}, q[4];
            for (int c = 0; c < 4; ++c) q[c] = p[c] + h;
            worst = std::max(worst, std::fabs(gradientNoise(dims, p) - gradientNoise(dims, q)));
        }
        EXPECT_LT(worst, 0.01f) << dims;  // a gradient bounded by ~5 per unit
    }
}

TEST(VmNoise, PeriodicAndCellNoise) {
    int period[3] = {3, 5, 7};
    for (float x = 0.1f; x < 4; x += 0.37f) {
        float p[3] = {x, 2 * x, 0.5f}, q[3] = {x + 3, 2 * x + 10, 0.5f - 7};
        EXPECT_NEAR(gradientNoise(3, p, period), gradientNoise(3, q, period), 1e-5f);
    }
    float a[2] = {2.1f, 5.9f}, b[2] = {2.8f, 5.05f}, c[2] = {3.1f, 5.5f};
    EXPECT_EQ(cellNoise(2, a), cellNoise(2, b));
    EXPECT_NE(cellNoise(2, a), cellNoise(2, c));
    EXPECT_GE(cellNoise(2, a), 0.0f);
    EXPECT_LT(cellNoise(2, a), 1.0f);
    float nan[1] = {std::nanf("")};
    EXPECT_FLOAT_EQ(gradientNoise(1, nan), 0.5f);  // no undefined conversion of NaN
}

TEST(VmNoise, ShadingLanguageForms) {
    const char* src = R"(
        surface s(output varying float f = 0; output varying color c = 0; output varying point p = 0;
                  output varying float pn = 0; output varying float pn2 = 0; output varying float cn = 0;
                  output varying float r1 = 0; output varying float r2 = 0) {
            f = noise(P);
            c = color noise(P, 1.5);
            p = point noise(u * 10);
            pn = pnoise(u * 10, 4);
            pn2 = pnoise(u * 10 + 4, 4);
            cn = cellnoise(u * 10);
            r1 = random();
            r2 = random();
            Ci = 0;
        })";
    test::TestGrid g(50);
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{0.37f * float(i), 1.1f, -2.3f}; });
    g.setVarying(Global::u, 1, [](int i) { return Vec3f{float(i) / 49.0f, 0, 0}; });
    ShaderInstance inst(test::compile(src));
    ShadingVM vm;
    vm.run(inst, g.grid);
    ValueRef f = vm.output("f"), c = vm.output("c"), p = vm.output("p"), pn = vm.output("pn"), pn2 = vm.output("pn2");
    ValueRef r1 = vm.output("r1"), r2 = vm.output("r2");
    int differ = 0;
    for (int i = 0; i < 50; ++i) {
        float q[3] = {0.37f * float(i), 1.1f, -2.3f};
        EXPECT_EQ(f.at(0, i), gradientNoise(3, q));
        EXPECT_NE(c.at(0, i), c.at(1, i));
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(c.at(k, i), 0.0f);
            EXPECT_LE(p.at(k, i), 1.0f);
        }
        EXPECT_NEAR(pn.at(0, i), pn2.at(0, i), 1e-5f);
        EXPECT_GE(r1.at(0, i), 0.0f);
        EXPECT_LT(r1.at(0, i), 1.0f);
        differ += r1.at(0, i) != r2.at(0, i);
    }
    EXPECT_EQ(differ, 50);
    // The same grid again: the same random numbers (reproducible renders).
    std::vector<float> before;
    for (int i = 0; i < 50; ++i) before.push_back(r1.at(0, i));
    vm.run(inst, g.grid);
    for (int i = 0; i < 50; ++i) EXPECT_EQ(vm.output("r1").at(0, i), before[size_t(i)]);
}

// pnoise and noise in a shader give gradientNoise's values at each point, with varying and
// uniform periods and coordinates, in 1 to 4 dimensions (the interpreter hands the kernel runs of
// 64 points: a grid of 150 ends in a partial run).
TEST(VmNoise, ShaderNoiseIsGradientNoiseAtEachPoint) {
    const char* src = R"(
        surface s(output varying float a = 0; output varying float b = 0; output varying float c = 0;
                  output varying float d = 0; output varying float e = 0) {
            a = pnoise(P, point(2 + floor(u * 4), 3, 5));
            b = pnoise(u * 10, 1.5 + v, 3, 2 + floor(u * 3));
            c = noise(point(1.5, 2.5, u * 7));
            d = noise(P, v * 3);
            e = pnoise(point(1.5, 2.5, u * 7), 0.5, point(4, 4, 4), 6);
            Ci = 0;
        })";
    const int n = 150;
    test::TestGrid g(n);
    auto pAt = [](int i) { return Vec3f{0.37f * float(i) - 20, 1.1f + 0.05f * float(i), -2.3f}; };
    g.setVarying(Global::P, 3, pAt);
    g.setVarying(Global::u, 1, [](int i) { return Vec3f{float(i) / (n - 1), 0, 0}; });
    g.setVarying(Global::v, 1, [](int i) { return Vec3f{float(i % 17) / 16.0f, 0, 0}; });
    ShaderInstance inst(test::compile(src));
    ShadingVM vm;
    vm.run(inst, g.grid);
    for (int i = 0; i < n; ++i) {
        const float u = float(i) / (n - 1), v = float(i % 17) / 16.0f;
        const Vec3f P = pAt(i);
        const float pa[3] = {P.x, P.y, P.z}, pb[2] = {u * 10, 1.5f + v}, pc[3] = {1.5f, 2.5f, u * 7},
                    pd[4] = {P.x, P.y, P.z, v * 3}, pe[4] = {1.5f, 2.5f, u * 7, 0.5f};
        const int perA[3] = {2 + int(std::floor(u * 4)), 3, 5}, perB[2] = {3, 2 + int(std::floor(u * 3))},
                  perE[4] = {4, 4, 4, 6};
        EXPECT_EQ(vm.output("a").at(0, i), gradientNoise(3, pa, perA)) << i;
        EXPECT_EQ(vm.output("b").at(0, i), gradientNoise(2, pb, perB)) << i;
        EXPECT_EQ(vm.output("c").at(0, i), gradientNoise(3, pc)) << i;
        EXPECT_EQ(vm.output("d").at(0, i), gradientNoise(4, pd)) << i;
        EXPECT_EQ(vm.output("e").at(0, i), gradientNoise(4, pe, perE)) << i;
    }
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The SIMD kernels of every instruction set this CPU runs give gradientNoise's values bit for
// bit: in 1 to 4 dimensions, periodic or not, every channel seed, on lattice points and cell
// edges, at negative coordinates, NaN and infinities, far out where the lattice wraps (the kernel
// leaves those vectors to the scalar code), and for counts that leave a partial last vector.
TEST(VmNoise, KernelsGiveTheScalarNoiseBitForBit) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> near(-40, 40);
    std::uniform_int_distribution<int> per(1, 9);
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 3.0f, 1e-30f, -1e-30f, 0.99999994f, -0.99999994f,
                              1073741823.0f, -1073741824.0f, 2e9f, -3e12f, 1e38f, inf, -inf, nan};
    const auto kernels = noiseKernelsOfEveryTarget();
    ASSERT_GE(kernels.size(), 2u);  // at least a SIMD target and Highway's scalar one
    const uint32_t seeds[] = {0u, 0x68e31da4u, 0xb5297a4du};
    int farPoints = 0;
    for (int dims = 1; dims <= 4; ++dims)
        for (int periodic = 0; periodic < 2; ++periodic)
            for (const size_t n : {size_t(1), size_t(7), size_t(16), size_t(37), size_t(300)}) {
                std::vector<float> coords[4];
                std::vector<int32_t> periods[4];
                for (int k = 0; k < dims; ++k)
                    for (size_t i = 0; i < n; ++i) {
                        const int kind = int(rng() % 8);
                        float v = near(rng);
                        if (kind == 0) v = std::round(v);                                  // a lattice point
                        if (kind == 1) v = specials[rng() % (sizeof specials / sizeof *specials)];
                        coords[k].push_back(v);
                        periods[k].push_back(rng() % 5 == 0 ? 0 : per(rng));  // 0: below 1, taken as 1
                    }
                // Far points put their whole vector on the scalar path: keep most vectors near.
                for (int k = 0; k < dims; ++k)
                    for (size_t i = 0; i < n; ++i)
                        if (std::isfinite(coords[k][i]) && std::fabs(coords[k][i]) >= 1073741824.0f) {
                            if (i % 32 != 0) coords[k][i] = near(rng);
                            else ++farPoints;
                        }
                const float* p[4];
                const int32_t* pp[4];
                for (int k = 0; k < dims; ++k) p[k] = coords[k].data(), pp[k] = periods[k].data();
                for (const uint32_t seed : seeds) {
                    std::vector<float> want(n), got(n);
                    noisePointsScalar()(dims, p, periodic ? pp : nullptr, n, seed, want.data());
                    for (size_t i = 0; i < n; ++i) {  // the scalar reference is gradientNoise itself
                        float q[4];
                        int qp[4];
                        for (int k = 0; k < dims; ++k) q[k] = coords[k][i], qp[k] = periods[k][i];
                        ASSERT_TRUE(sameBits(want[i], gradientNoise(dims, q, periodic ? qp : nullptr, seed)));
                    }
                    for (const auto& [target, kernel] : kernels) {
                        kernel(dims, p, periodic ? pp : nullptr, n, seed, got.data());
                        for (size_t i = 0; i < n; ++i)
                            ASSERT_TRUE(sameBits(got[i], want[i]))
                                << target << " dims " << dims << " periodic " << periodic << " n " << n << " point " << i
                                << ": " << got[i] << " against " << want[i];
                    }
                }
            }
    EXPECT_GT(farPoints, 0);  // the scalar path for far vectors was taken
}

}  // namespace
}  // namespace streyes::sl
