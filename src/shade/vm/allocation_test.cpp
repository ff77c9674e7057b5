// Once warm, shading a grid allocates nothing: the VM keeps its registers, masks and light
// results between grids. Counted with a replacement of the global operator new that counts on
// the thread that asks (the rest of the test binary sees plain malloc and free).
#include <gtest/gtest.h>

#include <cstdlib>
#include <new>

#include "shade/vm/vm_test_util.h"

namespace {
thread_local bool counting = false;
thread_local size_t allocations = 0;
}  // namespace

void* operator new(std::size_t n) {
    if (counting) ++allocations;
    if (void* p = std::malloc(n ? n : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace streyes::sl {
namespace {

TEST(VmAllocation, NoneOnceWarm) {
    test::TestGrid g(16, 16);
    g.setVarying(Global::P, 3, [](int k) { return Vec3f{float(k % 17) * 0.1f, float(k / 17) * 0.1f, 5}; });
    g.setVarying(Global::N, 3, [](int k) { return Vec3f{0.01f * float(k % 17), 0, -1}; });
    ShaderInstance amb(compileShaderFile(test::shaderPath("ambientlight")));
    ShaderInstance sun(compileShaderFile(test::shaderPath("distantlight")));
    ShaderInstance spot(compileShaderFile(test::shaderPath("spotlight")));
    std::vector<LightRef> lights{{&amb, Matrix4()}, {&sun, Matrix4()}, {&spot, Matrix4::translate({0, 0, -1})}};
    for (const char* name : {"matte", "plastic", "ground", "bark", "leaf"}) {
        SCOPED_TRACE(name);
        ShaderInstance inst(compileShaderFile(test::shaderPath(name)));
        ShadingVM vm;
        vm.run(inst, g.grid, lights);  // warm up
        vm.run(inst, g.grid, lights);
        allocations = 0;
        counting = true;
        for (int k = 0; k < 10; ++k) vm.run(inst, g.grid, lights);
        counting = false;
        EXPECT_EQ(allocations, 0u);
        // Each light once per grid: the spotlight run, the ambient and the distant light's
        // results (the same at every point) run for the first grid and given again after.
        EXPECT_EQ(vm.stats().lightRuns, 12u + 2u);
        EXPECT_EQ(vm.stats().lightReuses, 11u * 2u);
    }
}

// Resizable arrays grow inside resize and push, by doubling; their storage is kept between
// grids, so once a shader has run at its largest nothing more is allocated.
TEST(VmAllocation, NoneOnceWarmWithResizableArrays) {
    test::TestGrid g(16, 16);
    ProgramPtr p = compileShader(
        "surface grow(float w[] = {1}; output varying float total = 0) {\n"
        "  float a[];\n"
        "  uniform float i;\n"
        "  for (i = 0; i < 100; i += 1) push(a, u + i);\n"
        "  color c[] = {1, 2};\n"
        "  resize(c, 50);\n"
        "  for (i = 0; i < arraylength(w); i += 1) total += w[i];\n"
        "  total += pop(a) + comp(c[1], 0) + arraylength(a);\n"
        "}\n",
        "grow.sl");
    ShaderInstance inst(p);
    std::vector<float> weights(64, 0.5f);
    inst.set("w", SlType(), weights, {});
    ShadingVM vm;
    vm.run(inst, g.grid);  // warm up
    allocations = 0;
    counting = true;
    for (int k = 0; k < 10; ++k) vm.run(inst, g.grid);
    counting = false;
    EXPECT_EQ(allocations, 0u);
    // 64 halves, the last pushed (u + 99), c[1]'s 2 and the 99 left.
    for (int i : {0, 100, 288}) {
        const float u = float(i % 17) / 16.0f;  // the grid's own parameterisation (no u given)
        EXPECT_FLOAT_EQ(vm.output("total").at(0, i), 32.0f + (u + 99.0f) + 2.0f + 99.0f) << i;
    }
}

}  // namespace
}  // namespace streyes::sl
