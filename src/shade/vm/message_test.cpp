// Message passing: surface(), displacement(), atmosphere(), incident() and opposite() read
// another shader's parameters as the renderer runs them over one grid (displacement, surface
// with its lights, atmosphere); a name that is missing, or a variable of another type, gives 0
// and leaves the variable alone.
#include <gtest/gtest.h>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

TestGrid grid() {
    TestGrid g(3, 3);  // 16 points, s = u across
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{float(i), 0, 5}; });
    g.setVec(Global::N, {0, 0, -1});
    return g;
}

float sAt(const TestGrid& g, int i) { return float(i % (g.grid.nu + 1)) / float(g.grid.nu); }

// The grid's shaders as GridShader runs them: peers named, then each run in turn.
struct Chain {
    std::unique_ptr<ShaderInstance> displacement, surface, atmosphere;
    void peers(ShadingVM& vm) const {
        PeerShaders p;
        p[size_t(Peer::Surface)].shader = surface.get();
        p[size_t(Peer::Displacement)].shader = displacement.get();
        p[size_t(Peer::Atmosphere)].shader = atmosphere.get();
        p[size_t(Peer::Incident)].shader = atmosphere.get();
        vm.setPeers(p);
    }
};

TEST(VmMessage, ALightReadsTheSurfacesParameters) {
    // The light's colour is the surface's Kd (an instance value) times its varying output `mark`
    // as the surface has set it when its illuminance loop runs the light.
    ProgramPtr light = test::compile(R"(
        light l(output varying float missing = 0; output varying float found = 0; output varying float flag = 0) {
            float kd = -1, mark = -1, none = 7;
            color wrong = 3;
            found = surface("Kd", kd) + surface("mark", mark);
            missing = surface("nothing", none) + surface("Kd", wrong);  /* absent; a colour is not a float */
            flag = none + comp(wrong, 0);   /* 7 + 3: both left alone */
            illuminate(P) Cl = kd * mark;
        })");
    ProgramPtr surf = test::compile(R"(
        surface s(float Kd = 0.5; output varying float mark = 0; output varying float found = 0;
                  output varying float flag = 0) {
            mark = 1 + s;
            Ci = 0;
            illuminance(P) { Ci += Cl; lightsource("found", found); lightsource("flag", flag); }
        })");
    ShaderInstance li(light);
    Chain c;
    c.surface = std::make_unique<ShaderInstance>(surf);
    c.surface->set("Kd", BaseType::Float, {0.25f});
    TestGrid g = grid();
    ShadingVM vm;
    c.peers(vm);
    vm.run(*c.surface, g.grid, {LightRef(&li, Matrix4())});
    for (int i = 0; i < g.n(); ++i) EXPECT_FLOAT_EQ(vm.result(Global::Ci).at(0, i), 0.25f * (1 + sAt(g, i))) << i;
    EXPECT_EQ(vm.output("found").at(0, 0), 2.0f);
    EXPECT_EQ(vm.output("flag").at(0, 0), 10.0f);
}

TEST(VmMessage, WithoutPeersEveryCallGivesZero) {
    ProgramPtr surf = test::compile(R"(
        surface s(output float got = 0) {
            float x = 4;
            got = surface("got", x) + displacement("a", x) + atmosphere("b", x) + incident("c", x) + opposite("d", x);
            Ci = x;
        })");
    ShaderInstance s(surf);
    TestGrid g = grid();
    ShadingVM vm;
    vm.run(s, g.grid);
    EXPECT_EQ(vm.output("got").at(0, 0), 0.0f);
    EXPECT_EQ(vm.result(Global::Ci).at(0, 3), 4.0f);
}

TEST(VmMessage, DisplacementSurfaceAndAtmosphereReadEachOther) {
    Chain c;
    // The displacement runs first: the surface it asks about has not run, so it reads the bound value.
    c.displacement = std::make_unique<ShaderInstance>(test::compile(R"(
        displacement d(float amp = 2; output varying float bump = 0) {
            float kd = 0;
            surface("Kd", kd);
            bump = kd * (1 + s);
            P += bump * N;
        })"));
    c.surface = std::make_unique<ShaderInstance>(test::compile(R"(
        surface s(float Kd = 0.5; string label = "none"; output varying color shade = 0) {
            float b = -1, amp = -1, dens = -1, inc = -1, opp = 9;
            string name = "";
            displacement("bump", b);
            displacement("amp", amp);
            atmosphere("density", dens);   /* not run yet: its instance value */
            incident("density", inc);      /* the atmosphere, for rays from the eye */
            opposite("density", opp);      /* no interior: left alone */
            surface("label", name);        /* its own string parameter */
            shade = color(b, amp + dens, inc + opp) + (name == "marble" ? 100 : 0);
            Ci = shade;
        })"));
    c.surface->set("Kd", BaseType::Float, {0.75f});
    c.surface->setStrings("label", {"marble"});
    c.atmosphere = std::make_unique<ShaderInstance>(test::compile(R"(
        volume fog(float density = 1) {
            color sh = -1;
            uniform float kd = -1;
            surface("shade", sh);
            surface("Kd", kd);
            Ci = sh + kd;
        })"));
    c.atmosphere->set("density", BaseType::Float, {0.125f});
    TestGrid g = grid();
    ShadingVM vm;
    c.peers(vm);
    vm.run(*c.displacement, g.grid);
    for (int i = 0; i < g.n(); ++i) EXPECT_FLOAT_EQ(vm.result(Global::P).at(2, i), 5 - 0.75f * (1 + sAt(g, i))) << i;
    vm.run(*c.surface, g.grid);
    for (int i = 0; i < g.n(); ++i) {
        const Vec3f ci = test::at3(vm.result(Global::Ci), i);
        EXPECT_FLOAT_EQ(ci.x, 100 + 0.75f * (1 + sAt(g, i))) << i;
        EXPECT_FLOAT_EQ(ci.y, 100 + 2 + 0.125f) << i;
        EXPECT_FLOAT_EQ(ci.z, 100 + 0.125f + 9) << i;
    }
    vm.run(*c.atmosphere, g.grid);
    for (int i = 0; i < g.n(); ++i)
        EXPECT_FLOAT_EQ(vm.result(Global::Ci).at(0, i), 100 + 0.75f * (1 + sAt(g, i)) + 0.75f) << i;

    // A new grid: nothing is read from the last one's runs (the surface's `shade` is bound anew, 0).
    c.peers(vm);
    vm.run(*c.atmosphere, g.grid);
    EXPECT_FLOAT_EQ(vm.result(Global::Ci).at(0, 5), 0.75f);
}

TEST(VmMessage, BadCallsAreCompileErrorsAtTheirPlace) {
    const std::string head = "surface s() {\n  float x = 0;\n";
    EXPECT_NE(test::compileError(head + "  surface(1, x);\n}\n").find("test.sl:3:"), std::string::npos);
    EXPECT_NE(test::compileError(head + "  displacement(\"Kd\");\n}\n").find("takes (string name, output variable)"),
              std::string::npos);
    EXPECT_NE(test::compileError(head + "  atmosphere(\"Kd\", x + 1);\n}\n").find("test.sl:3:"), std::string::npos);
    const std::string bad = test::compileError(head + "  incident(\"surface:Ci\", x);\n}\n");
    EXPECT_NE(bad.find("test.sl:3:12"), std::string::npos) << bad;
    EXPECT_NE(bad.find("a parameter name is an identifier"), std::string::npos) << bad;
    EXPECT_EQ(test::compileError(head + "  string n = \"Kd\";\n  opposite(n, x);\n}\n"), "");
}

TEST(VmMessage, ShaderNameOfATypeNamesTheGridsShaderOfThatType) {
    // shadername(type): the primitive's shader of that type, "" when it has none; the running
    // shader's own type names itself.
    Chain c;
    c.displacement = std::make_unique<ShaderInstance>(test::compile(R"(
        displacement bumpy(output uniform float ok = 0) {
            ok = (shadername("surface") == "marble" ? 1 : 0) + (shadername("displacement") == "bumpy" ? 2 : 0) +
                 (shadername("atmosphere") == "" ? 4 : 0) + (shadername("imager") == "" ? 8 : 0);
        })"));
    c.surface = std::make_unique<ShaderInstance>(test::compile(R"(
        surface marble(output uniform float ok = 0) {
            string which = "displacement";
            ok = (shadername(which) == "bumpy" ? 1 : 0) + (shadername("surface") == "marble" ? 2 : 0) +
                 (shadername() == "marble" ? 4 : 0) + (shadername("lightsource") == "" ? 8 : 0);
            Ci = 0;
        })"));
    TestGrid g = grid();
    ShadingVM vm;
    c.peers(vm);
    vm.run(*c.displacement, g.grid);
    EXPECT_EQ(vm.output("ok").at(0, 0), 15.0f);
    vm.run(*c.surface, g.grid);
    EXPECT_EQ(vm.output("ok").at(0, 0), 15.0f);
    // Without peers, another type's name is "" (and its own type still names the surface).
    ShadingVM alone;
    alone.run(*c.surface, g.grid);
    EXPECT_EQ(alone.output("ok").at(0, 0), 2.0f + 4.0f + 8.0f);
}

}  // namespace
}  // namespace streyes::sl
