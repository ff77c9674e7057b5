// The work the Shading Language fuzzers do with one input, shared by the libFuzzer targets
// (sl_fuzz.cpp: the compiler; vm_fuzz.cpp: the compiler and the grid interpreter) and the
// regression test that replays what they once found (tests/core/fuzz_regression_test.cpp).
//
// The input is shader source. It must compile or end in an InputError naming file:line:column;
// when it compiles, runFuzzedShader runs it over a 4 x 4 grid (25 points) of a surface lit by a
// point light and a distant light, with every global a shader may read set, so that whatever the
// compiler accepts also goes through the interpreter. Anything else (another exception, a crash, a
// sanitizer report, a hang) is a bug. A shader may loop forever, as in any renderer: the
// interpreter is given an instruction budget here, and running out of it is bad input.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "shade/sl/compiler.h"
#include "shade/vm/shader_instance.h"
#include "shade/vm/vm.h"

namespace streyes::fuzz {

enum class ShaderOutcome { Compiled, Ran, BadInput };

inline ShaderOutcome compileFuzzedShader(std::string_view text) {
    try {
        sl::compileShader(std::string(text), "fuzz.sl");
        return ShaderOutcome::Compiled;
    } catch (const InputError&) {
        return ShaderOutcome::BadInput;
    }
}

// Instructions a fuzzed shader may run over one grid: the shipped shaders run a few hundred to a
// few thousand; a loop of a million steps is a hang to a fuzzer.
constexpr uint64_t kFuzzInstructionBudget = 200000;

// A 4 x 4 grid of a wavy surface facing the eye, its arrays owned.
struct FuzzGrid {
    sl::ShadingGrid grid;
    std::vector<std::vector<float>> store;

    FuzzGrid() {
        grid.setShape(4, 4);
        const int n = grid.n;
        auto varying = [&](sl::Global g, int comps, auto f) {
            std::vector<float> a(size_t(n) * size_t(comps));
            for (int i = 0; i < n; ++i) {
                const std::array<float, 3> v = f(i % 5, i / 5);
                for (int c = 0; c < comps; ++c) a[size_t(c) * size_t(n) + size_t(i)] = v[size_t(c)];
            }
            store.push_back(std::move(a));
            const float* p = store.back().data();
            grid.set(g, sl::ValueRef::soa(p, comps > 1 ? p + n : nullptr, comps > 2 ? p + 2 * n : nullptr));
        };
        auto uniform = [&](sl::Global g, std::vector<float> v) {
            store.push_back(std::move(v));
            grid.set(g, sl::ValueRef::uniform(store.back().data(), int(store.back().size())));
        };
        using G = sl::Global;
        varying(G::P, 3, [](int u, int v) { return std::array<float, 3>{u * 0.25f, v * 0.25f, 5 + 0.1f * std::sin(float(u + v))}; });
        varying(G::N, 3, [](int u, int v) { return std::array<float, 3>{0.1f * float(u - 2), 0.1f * float(v - 2), -1}; });
        varying(G::Ng, 3, [](int, int) { return std::array<float, 3>{0, 0, -1}; });
        varying(G::I, 3, [](int u, int v) { return std::array<float, 3>{u * 0.25f, v * 0.25f, 5}; });
        varying(G::s, 1, [](int u, int) { return std::array<float, 3>{u / 4.0f, 0, 0}; });
        varying(G::t, 1, [](int, int v) { return std::array<float, 3>{v / 4.0f, 0, 0}; });
        varying(G::u, 1, [](int u, int) { return std::array<float, 3>{u / 4.0f, 0, 0}; });
        varying(G::v, 1, [](int, int v) { return std::array<float, 3>{v / 4.0f, 0, 0}; });
        varying(G::dPdu, 3, [](int, int) { return std::array<float, 3>{1, 0, 0}; });
        varying(G::dPdv, 3, [](int, int) { return std::array<float, 3>{0, 1, 0}; });
        varying(G::Cs, 3, [](int u, int v) { return std::array<float, 3>{u / 4.0f, v / 4.0f, 0.5f}; });
        varying(G::Os, 3, [](int, int) { return std::array<float, 3>{1, 1, 1}; });
        uniform(G::du, {0.25f});
        uniform(G::dv, {0.25f});
        uniform(G::E, {0, 0, 0});
        uniform(G::time, {0});
        uniform(G::dtime, {1});
        uniform(G::dPdtime, {0, 0, 0});
        uniform(G::alpha, {1});
    }
};

inline ShaderOutcome runFuzzedShader(std::string_view text) {
    sl::ProgramPtr program;
    try {
        program = sl::compileShader(std::string(text), "fuzz.sl");
    } catch (const InputError&) {
        return ShaderOutcome::BadInput;
    }
    static const sl::ProgramPtr point = sl::compileShader(R"(
        light pointlight(float intensity = 1; color lightcolor = 1; point from = point "shader" (0, 0, 0)) {
            illuminate(from) Cl = intensity * lightcolor / (L . L);
        })", "pointlight.sl");
    static const sl::ProgramPtr distant = sl::compileShader(R"(
        light distantlight(float intensity = 1; point from = point "shader" (0, 0, 0); point to = point "shader" (0, 0, 1)) {
            solar(to - from, 0) Cl = intensity;
        })", "distantlight.sl");
    const sl::ShaderInstance pointLight(point), distantLight(distant), shader(program);
    Matrix4 lightSpace = Matrix4::translate({1, 2, 0});
    const std::vector<sl::LightRef> lights = {{&pointLight, lightSpace}, {&distantLight, Matrix4()}};
    const FuzzGrid g;
    sl::ShadingVM vm;
    vm.setInstructionBudget(kFuzzInstructionBudget);
    vm.setPrintSink([](const std::string&) {});
    try {
        vm.run(shader, g.grid, lights);
    } catch (const InputError&) {
        return ShaderOutcome::BadInput;
    }
    return ShaderOutcome::Ran;
}

}  // namespace streyes::fuzz
