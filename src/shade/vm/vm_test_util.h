// Test helpers for the Shading Language: a grid whose arrays the test owns, and shorthand to
// compile and run. (Tests only.)
#pragma once

#include <string>
#include <vector>

#include "shade/sl/compiler.h"
#include "shade/vm/shader_instance.h"
#include "shade/vm/vm.h"

namespace streyes::sl::test {

// A grid of nu x nv micropolygons (or n unshaped points) with owned structure-of-arrays values.
struct TestGrid {
    ShadingGrid grid;
    std::vector<std::vector<float>> store;

    explicit TestGrid(int n) { grid.n = n; }
    TestGrid(int nu, int nv) { grid.setShape(nu, nv); }
    int n() const { return grid.n; }

    // Per-point values from f(i) (a triple, or a float when comps == 1).
    template <class F>
    void setVarying(Global g, int comps, F f) {
        std::vector<float> a(size_t(grid.n) * size_t(comps));
        for (int i = 0; i < grid.n; ++i) {
            Vec3f v = f(i);
            for (int c = 0; c < comps; ++c) a[size_t(c) * size_t(grid.n) + size_t(i)] = v[c];
        }
        store.push_back(std::move(a));
        const float* p = store.back().data();
        const size_t n = size_t(grid.n);
        grid.set(g, ValueRef::soa(p, comps > 1 ? p + n : nullptr, comps > 2 ? p + 2 * n : nullptr));
    }
    void setFloat(Global g, float v) {
        store.push_back({v});
        grid.set(g, ValueRef::uniform(store.back().data(), 1));
    }
    void setVec(Global g, Vec3f v) {
        store.push_back({v.x, v.y, v.z});
        grid.set(g, ValueRef::uniform(store.back().data(), 3));
    }
};

inline ProgramPtr compile(const std::string& src) { return compileShader(src, "test.sl"); }

// The message of the InputError compiling `src` throws ("" when it compiles).
inline std::string compileError(const std::string& src) {
    try {
        compile(src);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

inline Vec3f at3(const ValueRef& v, int i) { return {v.at(0, i), v.at(1, i), v.at(2, i)}; }

// The path of a shipped shader.
inline std::string shaderPath(const std::string& name) {
    return std::string(STREYES_SOURCE_DIR) + "/shaders/" + name + ".sl";
}

}  // namespace streyes::sl::test
