// The backend's constant folding and dead-code removal (optimize.h) change no grid: every
// shipped shader and shaders written to exercise them (constant expressions, dead variables,
// divergent if and while, uniform beside varying, x / 0 and array indices out of range) give
// the plain program's Ci and Oi bit for bit, and the same counts, on the plain interpreter path
// and on the SIMD kernels.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "shade/sl/optimize.h"
#include "shade/vm/ops.h"
#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using namespace test;

const char* const kFolds = R"(surface folds(float Kd = 1;) {
    float unused = sin(s) * 3 + t;          /* dead: never read */
    vector alsoUnused = normalize(N) * 2;   /* dead */
    float k = (2 * 3 - 1) / 4.0;            /* 1.25 */
    color c = color(1, .5, .25) * (1 - .5) + (1 < 2) * .125;
    uniform float i;
    for (i = 0; i < 2 + 1; i += 1) c += k * .01;
    float j = 0;
    while (j < s * 7) { c += color(.01, 0, 0); j += 1; }   /* divergent loop */
    if (s > 1 / 2.0) Ci = c * Kd * diffuse(normalize(N));   /* divergent if */
    else Ci = c / (t - .5) + -(2 * .25);
    float arr[3] = {1 / 4.0, 2, 3};
    Ci += arr[floor(t * 5) - 1] * .1;                         /* out of range at both ends */
    Oi = 1;
})";

// Returns under varying conditions: the result is written by masked moves, which a dead-code
// pass must not take for whole writes.
const char* const kReturns = R"(
    float f(float x) {
        if (x < .3) return 1;
        if (x < .6) return 2;
        return 3;
    }
    surface returns() {
        Ci = f(s);
        if (t > .9) return;
        Ci += 10;
        Oi = 1;
    })";

const char* const kShipped[] = {"matte", "plastic", "bark", "leaf", "ground", "sky", "metal", "shinymetal",
                                "paintedplastic", "bumpy", "constant", "defaultsurface"};

struct Scene {
    TestGrid g{16, 16};
    ShaderInstance amb{compileShaderFile(shaderPath("ambientlight"))}, sun{compileShaderFile(shaderPath("distantlight"))},
        bulb{compileShaderFile(shaderPath("pointlight"))};
    std::vector<LightRef> lights;
    Scene() {
        g.setVarying(Global::P, 3, [](int i) { return Vec3f{(i % 17) * .2f - 1.6f, (i / 17) * .2f - 1.6f, 6.0f}; });
        g.setVarying(Global::N, 3, [](int i) { return Vec3f{std::sin(i * .3f), std::cos(i * .7f), -1.0f + (i % 5) * .4f}; });
        g.setVarying(Global::I, 3, [](int i) { return Vec3f{(i % 17) * .2f - 1.6f, (i / 17) * .2f - 1.6f, 6.0f}; });
        bulb.set("intensity", BaseType::Float, {30});
        lights = {{&amb, Matrix4()}, {&sun, Matrix4()}, {&bulb, Matrix4::translate({-3, 4, 0})}};
    }
};

struct GridRun {
    std::vector<float> values;
    ShadeStats stats;
};

GridRun run(const ProgramPtr& p, const Scene& scene, const GridKernels& kernels) {
    ShaderInstance inst(p);
    ShadingVM vm;
    vm.setKernels(kernels);
    vm.run(inst, scene.g.grid, scene.lights);
    GridRun r;
    for (Global gl : {Global::Ci, Global::Oi, Global::P, Global::N}) {
        ValueRef v = vm.result(gl);
        if (!v.valid()) {
            r.values.push_back(-1);  // not there: the same in both
            continue;
        }
        for (int c = 0; c < 3; ++c)
            for (int i = 0; i < scene.g.n(); ++i) r.values.push_back(v.at(c, i));
    }
    r.stats = vm.stats();
    return r;
}

void expectSameRun(const GridRun& got, const GridRun& want, const std::string& what) {
    ASSERT_EQ(got.values.size(), want.values.size());
    for (size_t i = 0; i < got.values.size(); ++i)
        ASSERT_EQ(std::memcmp(&got.values[i], &want.values[i], sizeof(float)), 0)
            << what << " value " << i << ": " << got.values[i] << " against " << want.values[i];
    EXPECT_EQ(got.stats.sanitised, want.stats.sanitised) << what;
    EXPECT_EQ(got.stats.indicesClamped, want.stats.indicesClamped) << what;
}

TEST(SlOptimize, FoldedAndPrunedProgramsGiveThePlainProgramsGridsBitForBit) {
    Scene scene;
    BackendOptions plain;
    plain.optimize = false;
    std::vector<std::pair<ProgramPtr, ProgramPtr>> programs;  // optimised, plain
    for (const char* name : kShipped)
        programs.emplace_back(compileShaderFile(shaderPath(name)), compileShaderFile(shaderPath(name), {}, plain));
    programs.emplace_back(compileShader(kFolds, "folds.sl"), compileShader(kFolds, "folds.sl", {}, plain));
    programs.emplace_back(compileShader(kReturns, "returns.sl"), compileShader(kReturns, "returns.sl", {}, plain));
    for (const auto& [opt, base] : programs) {
        EXPECT_LE(opt->code.size(), base->code.size()) << opt->name;
        const GridRun want = run(base, scene, gridKernelsScalar());  // the plain program, the plain path
        expectSameRun(run(opt, scene, gridKernelsScalar()), want, opt->name + " optimised, plain path");
        for (const GridKernels* k : gridKernelsOfEveryTarget())
            expectSameRun(run(opt, scene, *k), want, opt->name + " optimised on " + k->target);
        if (opt->name == "folds") {
            EXPECT_GT(want.stats.sanitised, 0u);       // c / (t - .5) at t = .5
            EXPECT_GT(want.stats.indicesClamped, 0u);  // arr[-1] and arr[4]
        }
    }
}

int countOps(const ShaderProgram& p, OpFn fn) {
    int k = 0;
    for (const Instr& in : p.code) k += in.fn == fn ? 1 : 0;
    return k;
}

// What the passes did to `folds`: every operation on constants alone is gone (the loop's bound
// 2 + 1, (2 * 3 - 1) / 4, the colour's products, 1 / 2, -(2 * .25), 1 / 4 in the array), so are
// the dead variables' computations (sin(s) * 3 + t, normalize(N) * 2); and a folded value is
// the VM's own: (2 * 3 - 1) / 4.0 is 1.25 exactly.
TEST(SlOptimize, FoldsConstantsAndDropsDeadVariables) {
    BackendOptions plain;
    plain.optimize = false;
    ProgramPtr opt = compileShader(kFolds, "folds.sl"), base = compileShader(kFolds, "folds.sl", {}, plain);
    EXPECT_EQ(countOps(*opt, ops::sin_), 0);
    EXPECT_EQ(countOps(*base, ops::sin_), 1);
    // normalize(N) stays once (diffuse's argument), the dead one is gone.
    EXPECT_EQ(countOps(*opt, ops::normalize), countOps(*base, ops::normalize) - 1);
    EXPECT_LE(countOps(*opt, ops::div), countOps(*base, ops::div) - 3);  // (..)/4, 1/2, 1/4 folded; c/(t-.5) stays
    EXPECT_LT(countOps(*opt, ops::mul), countOps(*base, ops::mul));
    bool found = false;
    for (const Register& r : opt->regs)
        if (r.constant >= 0 && !r.type.isString() && r.floats() == 1 && opt->constFloats[size_t(r.constant)] == 1.25f) found = true;
    EXPECT_TRUE(found);
    // Jumps still land: the optimised program runs the loops and branches to the same values
    // (checked bit for bit above); here, every jump target is inside the program.
    for (const Instr& in : opt->code)
        if (in.fn == ops::jmp || in.fn == ops::jmpIfNone) {
            EXPECT_GE(in.a[0], 0);
            EXPECT_LE(in.a[0], int(opt->code.size()));
        }
}

// A division by a constant zero is not folded: the VM still counts it when it runs.
TEST(SlOptimize, DivisionByAConstantZeroStaysToBeCounted) {
    ProgramPtr p = compileShader("surface z() { Ci = 1 / 0; }", "z.sl");
    EXPECT_EQ(countOps(*p, ops::div), 1);
    TestGrid g(4);
    ShaderInstance inst(p);
    ShadingVM vm;
    vm.run(inst, g.grid);
    EXPECT_EQ(vm.stats().sanitised, 1u);  // one uniform result
    EXPECT_EQ(vm.result(Global::Ci).at(0, 2), 0.0f);
}

}  // namespace
}  // namespace streyes::sl
