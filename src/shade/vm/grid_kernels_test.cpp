// The grid kernels (grid_kernels.h) of every instruction set this CPU runs give the plain C++
// reference's results bit for bit, kernel by kernel and for whole shaders run by the VM: the
// shipped ones and shaders with divergent control flow, uniform and varying operands mixed,
// values that are sanitised, and array indices out of range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "shade/vm/grid_kernels.h"
#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using namespace test;

// Bit for bit, but a NaN matches any NaN: IEEE 754 leaves the sign and payload of a NaN an
// operation makes unspecified, and targets differ (clang's EMU128 negates a NaN where the reference
// keeps its sign). No NaN reaches a pixel: shader outputs are sanitised (ShadingVM counts them).
bool sameBits(float a, float b) { return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0; }

// Random floats with the awkward ones mixed in: zeros of both signs, NaN, infinities, tiny.
std::vector<float> awkward(std::mt19937& rng, size_t n) {
    std::uniform_real_distribution<float> near(-3, 3);
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, inf, -inf, nan, 1e-30f, 1e-45f, 3e38f, -3e38f};
    std::vector<float> v(n);
    for (float& f : v) f = rng() % 6 == 0 ? specials[rng() % (sizeof specials / sizeof *specials)] : near(rng);
    return v;
}

struct Triple {
    std::vector<float> c[3];
    const float* in[3];
    float* out[3];
    Triple(std::mt19937& rng, size_t n) {
        for (auto& v : c) v = awkward(rng, n);
        for (int k = 0; k < 3; ++k) in[k] = out[k] = c[k].data();
    }
    explicit Triple(size_t n) {
        for (auto& v : c) v.assign(n, 0.0f);
        for (int k = 0; k < 3; ++k) in[k] = out[k] = c[k].data();
    }
};

void expectSame(const std::vector<float>& got, const std::vector<float>& want, const std::string& what) {
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < got.size(); ++i)
        ASSERT_TRUE(sameBits(got[i], want[i])) << what << " point " << i << ": " << got[i] << " against " << want[i];
}

TEST(GridKernels, EveryTargetMatchesTheReferenceBitForBit) {
    const auto targets = gridKernelsOfEveryTarget();
    ASSERT_GE(targets.size(), 2u);  // at least a SIMD target and Highway's scalar one
    const GridKernels& ref = gridKernelsScalar();
    std::mt19937 rng(47);
    const float cosHalf = std::cos(3.14159265358979323846f / 2);
    for (const size_t n : {size_t(1), size_t(7), size_t(16), size_t(37), size_t(289)})
        for (int flags = 0; flags < 4; ++flags) {
            const bool av = flags & 1, bv = flags & 2;
            Triple a(rng, n), b(rng, n), c(rng, n), light(rng, n), cl(rng, n), unit(rng, n);
            std::vector<uint8_t> lit(n);
            for (auto& l : lit) l = uint8_t(rng() % 3 != 0);
            const LightLanes lanes{{light.in[0], light.in[1], light.in[2]}, {cl.in[0], cl.in[1], cl.in[2]}, lit.data()};
            std::vector<float> t = awkward(rng, n), aos = awkward(rng, 3 * n);
            for (const GridKernels* k : targets) {
                const std::string name = k->target;
                Triple want(n), got(n);
                ref.normalize(n, a.in, av, want.out);
                k->normalize(n, a.in, av, got.out);
                for (int q = 0; q < 3; ++q) expectSame(got.c[q], want.c[q], name + " normalize");
                ref.faceforward(n, a.in, av, b.in, bv, c.in, !av, want.out);
                k->faceforward(n, a.in, av, b.in, bv, c.in, !av, got.out);
                for (int q = 0; q < 3; ++q) expectSame(got.c[q], want.c[q], name + " faceforward");
                ref.dot(n, a.in, av, b.in, bv, want.out[0]);
                k->dot(n, a.in, av, b.in, bv, got.out[0]);
                expectSame(got.c[0], want.c[0], name + " dot");
                ref.divide(n, a.in[0], av, b.in[1], bv, want.out[0]);
                k->divide(n, a.in[0], av, b.in[1], bv, got.out[0]);
                expectSame(got.c[0], want.c[0], name + " divide");
                using Binary = void (*)(size_t, const float*, bool, const float*, bool, float*);
                const std::pair<const char*, Binary GridKernels::*> binaries[] = {
                    {"add", &GridKernels::add}, {"sub", &GridKernels::sub}, {"mul", &GridKernels::mul},
                    {"min", &GridKernels::min}, {"max", &GridKernels::max}, {"mod", &GridKernels::mod}};
                for (const auto& [what, op] : binaries) {
                    (ref.*op)(n, a.in[0], av, b.in[1], bv, want.out[0]);
                    (k->*op)(n, a.in[0], av, b.in[1], bv, got.out[0]);
                    expectSame(got.c[0], want.c[0], name + " " + what);
                }
                ref.mix(n, a.in[0], av, b.in[1], bv, c.in[2], !av, want.out[0]);
                k->mix(n, a.in[0], av, b.in[1], bv, c.in[2], !av, got.out[0]);
                expectSame(got.c[0], want.c[0], name + " mix");
                ref.smoothstep(n, a.in[0], av, b.in[1], bv, c.in[2], !bv, want.out[0]);
                k->smoothstep(n, a.in[0], av, b.in[1], bv, c.in[2], !bv, got.out[0]);
                expectSame(got.c[0], want.c[0], name + " smoothstep");
                ref.filterstep(n, a.in[0], av, b.in[1], bv, c.in[0], c.in[1], 1.5f, want.out[0]);
                k->filterstep(n, a.in[0], av, b.in[1], bv, c.in[0], c.in[1], 1.5f, got.out[0]);
                expectSame(got.c[0], want.c[0], name + " filterstep");
                // Accumulating kernels: from the same start.
                Triple accWant(rng, n);
                Triple accGot = accWant;
                for (int q = 0; q < 3; ++q) accGot.in[q] = accGot.out[q] = accGot.c[q].data();
                ref.diffuseLight(n, lanes, cosHalf, unit.in, a.in, av, accWant.out);
                k->diffuseLight(n, lanes, cosHalf, unit.in, a.in, av, accGot.out);
                ref.addLight(n, cl.in, true, t.data(), accWant.out);
                k->addLight(n, cl.in, true, t.data(), accGot.out);
                for (int q = 0; q < 3; ++q) expectSame(accGot.c[q], accWant.c[q], name + " diffuseLight, addLight");
                ref.specularBase(n, lanes, cosHalf, unit.in, a.in, av, b.in, bv, want.out[1]);
                k->specularBase(n, lanes, cosHalf, unit.in, a.in, av, b.in, bv, got.out[1]);
                expectSame(got.c[1], want.c[1], name + " specularBase");
                ref.deinterleave3(n, aos.data(), want.out);
                k->deinterleave3(n, aos.data(), got.out);
                for (int q = 0; q < 3; ++q) expectSame(got.c[q], want.c[q], name + " deinterleave3");
            }
        }
}

// A uniform light's lanes (one Ln, Cl and lit for every point: a point-free light kept uniform)
// give, on every target, the results of the same values broadcast to every point, bit for bit.
TEST(GridKernels, UniformLightLanesMatchTheBroadcastOnes) {
    const float cosHalf = std::cos(3.14159265358979323846f / 2);
    std::mt19937 rng(4747);
    for (const size_t n : {size_t(1), size_t(9), size_t(16), size_t(45), size_t(289)})
        for (int flags = 0; flags < 8; ++flags) {
            const bool nv = flags & 1, vv = flags & 2;
            const uint8_t lit = (flags & 4) ? 0 : 1;
            Triple N(rng, n), V(rng, n), unit(n), ln(n), cl(n);
            // Finite values: a light's Ln is normalised and its Cl sanitised.
            std::uniform_real_distribution<float> near(-2, 2);
            const float one[6] = {near(rng), near(rng), near(rng), std::fabs(near(rng)), std::fabs(near(rng)), 0.5f};
            const float len = std::sqrt(one[0] * one[0] + one[1] * one[1] + one[2] * one[2]);
            const float lnOne[3] = {one[0] / len, one[1] / len, one[2] / len}, clOne[3] = {one[3], one[4], one[5]};
            for (int c = 0; c < 3; ++c) {
                ln.c[c].assign(n, lnOne[c]);
                cl.c[c].assign(n, clOne[c]);
            }
            gridKernelsScalar().normalize(n, N.in, nv, unit.out);
            std::vector<uint8_t> litAll(n, lit);
            const LightLanes broadcast{{ln.in[0], ln.in[1], ln.in[2]}, {cl.in[0], cl.in[1], cl.in[2]}, litAll.data()};
            const float* const lnp[3] = {&lnOne[0], &lnOne[1], &lnOne[2]};
            const float* const clp[3] = {&clOne[0], &clOne[1], &clOne[2]};
            const LightLanes uniform{{lnp[0], lnp[1], lnp[2]}, {clp[0], clp[1], clp[2]}, &lit, false};
            const std::vector<float> t = awkward(rng, n);
            for (const GridKernels* k : gridKernelsOfEveryTarget()) {
                const std::string name = std::string(k->target) + " n=" + std::to_string(n) + " flags=" + std::to_string(flags);
                Triple want(rng, n);
                Triple got = want;
                for (int q = 0; q < 3; ++q) got.in[q] = got.out[q] = got.c[q].data();
                k->diffuseLight(n, broadcast, cosHalf, unit.in, N.in, nv, want.out);
                k->diffuseLight(n, uniform, cosHalf, unit.in, N.in, nv, got.out);
                k->addLight(n, cl.in, true, t.data(), want.out);
                k->addLight(n, clp, false, t.data(), got.out);
                for (int q = 0; q < 3; ++q) expectSame(got.c[q], want.c[q], name + " diffuseLight, addLight");
                std::vector<float> baseWant(n), baseGot(n);
                k->specularBase(n, broadcast, cosHalf, unit.in, N.in, nv, V.in, vv, baseWant.data());
                k->specularBase(n, uniform, cosHalf, unit.in, N.in, nv, V.in, vv, baseGot.data());
                expectSame(baseGot, baseWant, name + " specularBase");
                // Not blind: the light reaches some points when lit (varying N random about the
                // sphere; one uniform N may face away).
                if (lit && nv && n >= 16) {
                    size_t reached = 0;
                    for (float b : baseGot) reached += b >= 0;
                    EXPECT_GT(reached, 0u) << name;
                }
            }
        }
}

// The reference's map operations are the interpreter's scalar ones, NaN and infinity included:
// std::min/std::max keep a when b is NaN, smoothstep's edges are tested before the cubic.
TEST(GridKernels, MapOperationsFollowTheScalarRules) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const float a[] = {1.0f, nan, 2.0f, -inf, 0.25f, 3.0f, -0.0f, 5.0f, 0.5f, 0.5f, 7.0f, nan, 1.0f, 2.0f, 0.0f, 4.0f, 9.0f};
    const float b[] = {nan, 1.0f, 3.0f, 1.0f, 0.75f, -1.0f, 0.0f, inf, 0.5f, nan, 1.0f, nan, 2.0f, 2.0f, 1.0f, 0.0f, -9.0f};
    const size_t n = sizeof a / sizeof *a;
    for (const GridKernels* k : gridKernelsOfEveryTarget()) {
        const std::string name = k->target;
        std::vector<float> lo(n), hi(n), sum(n), prod(n), mixed(n), smooth(n);
        k->min(n, a, true, b, true, lo.data());
        k->max(n, a, true, b, true, hi.data());
        k->add(n, a, true, b, true, sum.data());
        k->mul(n, a, true, b, true, prod.data());
        const float half = 0.5f;
        k->mix(n, a, true, b, true, &half, false, mixed.data());
        const float e0 = 0.0f, e1 = 4.0f;
        k->smoothstep(n, &e0, false, &e1, false, a, true, smooth.data());
        std::vector<float> rem(n), fstep(n);
        k->mod(n, a, true, b, true, rem.data());
        k->filterstep(n, b, true, a, true, a, b, 1.0f, fstep.data());
        for (size_t i = 0; i < n; ++i) {
            const std::string at = name + " point " + std::to_string(i);
            EXPECT_TRUE(sameBits(lo[i], std::min(a[i], b[i]))) << at << " min " << lo[i];
            EXPECT_TRUE(sameBits(hi[i], std::max(a[i], b[i]))) << at << " max " << hi[i];
            EXPECT_TRUE(sameBits(sum[i], a[i] + b[i])) << at << " add " << sum[i];
            EXPECT_TRUE(sameBits(prod[i], a[i] * b[i])) << at << " mul " << prod[i];
            EXPECT_TRUE(sameBits(mixed[i], a[i] * (1.0f - half) + b[i] * half)) << at << " mix " << mixed[i];
            float want = a[i] <= e0 ? 0.0f : a[i] >= e1 ? 1.0f : 0.0f;
            if (!(a[i] <= e0) && !(a[i] >= e1)) {
                const float t = (a[i] - e0) / (e1 - e0);
                want = t * t * (3.0f - 2.0f * t);
            }
            EXPECT_TRUE(sameBits(smooth[i], want)) << at << " smoothstep " << smooth[i];
            const float r = b[i] == 0.0f ? 0.0f : a[i] - b[i] * std::floor(a[i] / b[i]);
            EXPECT_TRUE(sameBits(rem[i], r)) << at << " mod " << rem[i];
            const float w = std::fabs(a[i]) + std::fabs(b[i]), lo = a[i] - 0.5f * w, hi = a[i] + 0.5f * w;
            const float f = hi > lo ? std::min(1.0f, std::max(0.0f, (hi - b[i]) / (hi - lo))) : (a[i] < b[i] ? 0.0f : 1.0f);
            EXPECT_TRUE(sameBits(fstep[i], f)) << at << " filterstep " << fstep[i];
        }
        EXPECT_EQ(lo[0], 1.0f) << name;  // std::min(1, NaN) is 1
        EXPECT_TRUE(std::isnan(lo[1])) << name;  // std::min(NaN, 1) is NaN
        EXPECT_TRUE(std::isnan(smooth[1])) << name;
        EXPECT_EQ(smooth[3], 0.0f) << name;
        EXPECT_EQ(smooth[10], 1.0f) << name;
        EXPECT_EQ(smooth[12], 0.15625f) << name;  // t = 1/4: 1/16 * 5/2
        EXPECT_EQ(rem[14], 0.0f) << name;         // mod(0, 1)
        EXPECT_EQ(rem[15], 0.0f) << name;         // mod(4, 0): 0, not NaN
        EXPECT_EQ(rem[2], 2.0f) << name;          // mod(2, 3)
        EXPECT_EQ(fstep[8], 0.5f) << name;        // s = edge = .5, w = 1: halfway
    }
}

// ---- Whole shaders -------------------------------------------------------------------------

// Shaders that use the kernels' operations the way shader libraries do, with divergent control
// flow (if and while under varying conditions), uniform operands beside varying ones, results
// that are sanitised (x / 0) and array indices out of range (clamped).
const char* const kShaders[] = {
    R"(surface divergent(float Kd = .8; float k = 3;) {
        normal Nf = faceforward(normalize(N), I);
        float d = Nf . normalize(-I);
        color c = 0;
        if (d > .5) c = Kd * diffuse(Nf);
        else c = color(1, 0, 0) / (d - .25);
        float i = 0;
        while (i < s * 10) { c += .01 * specular(Nf, -normalize(I), .2); i += 1; }
        uniform float u = k / 2;
        Ci = c * u + d / s;
        Oi = 1;
    })",
    R"(surface arrays(float a[3] = {1, 2, 3};) {
        float idx = floor(s * 6) - 1;
        float v = a[idx];
        vector V = normalize(vector(v, t, 1)) / (t - .5);
        Ci = color(V . normalize(N), v, comp(diffuse(normalize(N)), 1));
        if (s > .5) { Ci /= (s - .75); }
        Oi = 1;
    })",
    R"(surface mapops(float lo = .2; float hi = .7;) {
        float a = smoothstep(lo, hi, s);
        float b = smoothstep(t, hi, s);
        color c = mix(color(s, t, 1), Cs, a);
        c = mix(c, color(1, 0, 0), t);
        float m = max(s - .5, min(t, a)) * pow(s - .5, 1.5);
        float r = mod(s * 3 - 1, t) + mod(s, t - t) + filterstep(.5, s * t) + filterstep(lo, t, "width", 2);
        Ci = c * m + b - a * color(.1, .2, .3) + max(lo, .5) - min(hi, 1) + r;
        Oi = 1;
    })",
};

struct Scene {
    TestGrid g{16, 16};
    ShaderInstance amb{compileShaderFile(shaderPath("ambientlight"))}, sun{compileShaderFile(shaderPath("distantlight"))},
        bulb{compileShaderFile(shaderPath("pointlight"))};
    std::vector<LightRef> lights;
    std::vector<Vec3f> P;  // bound as the renderer binds it: triples x y z x y z
    Vec3f eye{0, 0, 0};
    Scene() {
        for (int i = 0; i < g.n(); ++i) {
            const float u = float(i % 17) / 16, v = float(i / 17) / 16;
            P.push_back({std::sin(u * 1.2f) * 3, std::sin(v * 1.2f) * 3, 8 - std::cos(u) * std::cos(v) * 3});
        }
        g.grid.set(Global::P, ValueRef::aos(P.data()));
        g.grid.set(Global::I, ValueRef::aos(P.data()));
        g.grid.set(Global::E, ValueRef::uniform(eye));
        g.setVarying(Global::N, 3, [](int i) { return Vec3f{std::sin(i * .3f), std::cos(i * .7f), -1.0f + (i % 5) * .4f}; });
        g.setVarying(Global::Cs, 3, [](int i) { return Vec3f{.8f, .5f + .001f * i, .3f}; });
        bulb.set("intensity", BaseType::Float, {30});
        sun.set("from", BaseType::Point, {1, 2, -1});
        lights = {{&amb, Matrix4()}, {&sun, Matrix4()}, {&bulb, Matrix4::translate({-3, 4, 0})}};
    }
};

// Every component of every point of Ci and Oi.
std::vector<float> results(ShadingVM& vm) {
    std::vector<float> out;
    for (Global gl : {Global::Ci, Global::Oi}) {
        ValueRef v = vm.result(gl);
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < 289; ++i) out.push_back(v.at(c, i));
    }
    return out;
}

TEST(GridKernels, ShadersGiveThePlainPathsGridsBitForBit) {
    Scene scene;
    std::vector<ProgramPtr> programs;
    for (const char* name : {"matte", "plastic", "bark", "leaf", "ground", "sky", "metal", "shinymetal", "paintedplastic"})
        programs.push_back(compileShaderFile(shaderPath(name)));
    for (const char* src : kShaders) programs.push_back(compile(src));
    const auto targets = gridKernelsOfEveryTarget();
    for (const ProgramPtr& p : programs) {
        ShaderInstance inst(p);
        ShadingVM plain;
        plain.setKernels(gridKernelsScalar());
        plain.run(inst, scene.g.grid, scene.lights);
        const std::vector<float> want = results(plain);
        for (const GridKernels* k : targets) {
            ShadingVM vm;
            vm.setKernels(*k);
            vm.run(inst, scene.g.grid, scene.lights);
            expectSame(results(vm), want, p->name + " on " + k->target);
            EXPECT_EQ(vm.stats().sanitised, plain.stats().sanitised) << p->name;
            EXPECT_EQ(vm.stats().indicesClamped, plain.stats().indicesClamped) << p->name;
        }
        if (p->name == "divergent") {
            EXPECT_GT(plain.stats().sanitised, 0u);  // x / 0 met
        }
        if (p->name == "mapops") {
            EXPECT_GT(plain.stats().sanitised, 0u);  // pow of a negative met
        }
        if (p->name == "arrays") {
            EXPECT_GT(plain.stats().indicesClamped, 0u);
        }
    }
}

}  // namespace
}  // namespace streyes::sl
