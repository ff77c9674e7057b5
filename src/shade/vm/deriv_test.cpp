// Derivatives on the grid: P = (u^2, v, 0) has finite differences we can write down.
#include <gtest/gtest.h>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

TEST(VmDeriv, DuDvAreaNormalAndDerivOnAKnownGrid) {
    const int nu = 8, nv = 4;
    TestGrid g(nu, nv);
    g.setVarying(Global::P, 3, [&](int k) {
        float u = float(k % (nu + 1)) / float(nu), v = float(k / (nu + 1)) / float(nv);
        return Vec3f{u * u, v, 0};
    });
    const char* src = R"(
        surface s(output varying vector dPu = 0; output varying vector dPv = 0; output varying float a = 0;
                  output varying normal nn = 0; output varying float d = 0; output varying float du0 = 1;
                  output varying float uu = 0) {
            dPu = Du(P);
            dPv = Dv(P);
            a = area(P);
            nn = calculatenormal(P);
            d = Deriv(u * u, u);
            du0 = Du(Ka());   // a uniform value's derivative
            uu = u;
            Ci = 0;
        }
        float Ka() { return 3; })";
    ShaderInstance inst(test::compile(src));
    ShadingVM vm;
    vm.run(inst, g.grid);
    ValueRef dPu = vm.output("dPu"), dPv = vm.output("dPv"), a = vm.output("a"), nn = vm.output("nn"), d = vm.output("d");
    const float du = 1.0f / nu, dv = 1.0f / nv;
    for (int k = 0; k < g.n(); ++k) {
        const int i = k % (nu + 1);
        const float u = float(i) / float(nu);
        // Central differences of u^2 are exact (2u); the edges are one-sided.
        float expectDu = i == 0 ? du : i == nu ? 2 - du : 2 * u;
        EXPECT_NEAR(dPu.at(0, k), expectDu, 1e-5f) << k;
        EXPECT_NEAR(dPu.at(1, k), 0.0f, 1e-6f);
        EXPECT_NEAR(dPv.at(0, k), 0.0f, 1e-6f);
        EXPECT_NEAR(dPv.at(1, k), 1.0f, 1e-5f);
        EXPECT_NEAR(a.at(0, k), expectDu * du * dv, 1e-6f);
        EXPECT_NEAR(nn.at(2, k), expectDu, 1e-5f);  // (Du(P) x Dv(P)).z = expectDu * 1
        EXPECT_NEAR(nn.at(0, k), 0.0f, 1e-6f);
        EXPECT_NEAR(d.at(0, k), i == 0 || i == nu ? expectDu : 2 * u, 1e-4f) << k;  // Du(u*u)/Du(u); Dv(u) = 0 adds 0
    }
    EXPECT_EQ(vm.output("du0").at(0, 5), 0.0f);
    EXPECT_EQ(vm.stats().sanitised, 0u);
    // Reversed orientation flips calculatenormal.
    g.grid.flipNormals = true;
    vm.run(inst, g.grid);
    EXPECT_NEAR(vm.output("nn").at(2, 3), -2.0f * 3 / nu, 1e-5f);
}

TEST(VmDeriv, NoShapeNoDerivatives) {
    TestGrid g(5);  // points from a ray tracer, say: no grid
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{float(i * i), 0, 0}; });
    ShaderInstance inst(test::compile("surface s(output varying vector d = 1) { d = Du(P); Ci = 0; }"));
    ShadingVM vm;
    vm.run(inst, g.grid);
    for (int i = 0; i < 5; ++i) EXPECT_EQ(vm.output("d").at(0, i), 0.0f);
}

TEST(VmDeriv, FilterstepAntialiasesAnEdge) {
    const int nu = 10;
    TestGrid g(nu, 1);
    g.setVarying(Global::s, 1, [&](int k) { return Vec3f{float(k % (nu + 1)) / float(nu), 0, 0}; });
    ShaderInstance inst(test::compile("surface s(output varying float f = 0) { f = filterstep(.52, s); Ci = 0; }"));
    ShadingVM vm;
    vm.run(inst, g.grid);
    ValueRef f = vm.output("f");
    // s steps by 0.1: the point at .5 covers [.45, .55], of which (.55 - .52) / .1 is past the edge.
    EXPECT_NEAR(f.at(0, 5), 0.3f, 1e-5f);
    EXPECT_EQ(f.at(0, 2), 0.0f);
    EXPECT_EQ(f.at(0, 8), 1.0f);
}

}  // namespace
}  // namespace streyes::sl
