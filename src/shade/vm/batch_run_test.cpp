// Several small grids shaded in one run (ShadingGrid::parts, GridShader::shadeSlots): every
// point's values, derivatives included, must be those of its grid shaded alone, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "shade/vm/batch_safety.h"
#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

struct Shape {
    int nu, nv;
    int points() const { return (nu + 1) * (nv + 1); }
};
// Grids of other shapes, one with a single row and one with a single column of micropolygons.
const Shape kShapes[] = {{1, 1}, {3, 2}, {2, 4}, {5, 1}, {1, 3}, {4, 4}};

// Point i of grid g: a curved, tilted sheet (its derivatives change from point to point, so a
// difference across two grids' border is not the one within either), with s, t over it.
Vec3f position(int g, int nu, int i) {
    const float u = float(i % (nu + 1)), v = float(i / (nu + 1));
    return {0.3f * u + 0.05f * float(g), 0.2f * v - 0.1f * u * u, 4.0f + 0.7f * float(g) + 0.04f * u * v + 0.02f * v * v};
}
Vec3f normalAt(int g, int i) { return {0.1f * float(g), 0.05f * float(i % 4), -1}; }
float sAt(int g, int nu, int i) { return 0.1f * float(g) + 0.13f * float(i % (nu + 1)) + 0.01f * float(i * i % 7); }
float tAt(int g, int nu, int i) { return 0.07f * float(i / (nu + 1)) * (1 + 0.1f * float(g)); }

void setInputs(TestGrid& tg, const std::vector<std::pair<int, int>>& who, const std::vector<int>& nus) {
    auto grid = [&](int i) { return who[size_t(i)].first; };
    auto local = [&](int i) { return who[size_t(i)].second; };
    tg.setVarying(Global::P, 3, [&](int i) { return position(grid(i), nus[size_t(grid(i))], local(i)); });
    tg.setVarying(Global::N, 3, [&](int i) { return normalAt(grid(i), local(i)); });
    tg.setVarying(Global::s, 1, [&](int i) { return Vec3f{sAt(grid(i), nus[size_t(grid(i))], local(i)), 0, 0}; });
    tg.setVarying(Global::t, 1, [&](int i) { return Vec3f{tAt(grid(i), nus[size_t(grid(i))], local(i)), 0, 0}; });
    tg.setVec(Global::Cs, {0.8f, 0.6f, 0.4f});
    tg.setFloat(Global::du, 0.25f);
    tg.setFloat(Global::dv, 0.5f);
}

// Grid g alone.
TestGrid alone(int g) {
    const Shape sh = kShapes[g];
    TestGrid out(sh.nu, sh.nv);
    const int grid = g;
    out.setVarying(Global::P, 3, [&](int i) { return position(grid, sh.nu, i); });
    out.setVarying(Global::N, 3, [&](int i) { return normalAt(grid, i); });
    out.setVarying(Global::s, 1, [&](int i) { return Vec3f{sAt(grid, sh.nu, i), 0, 0}; });
    out.setVarying(Global::t, 1, [&](int i) { return Vec3f{tAt(grid, sh.nu, i), 0, 0}; });
    out.setVec(Global::Cs, {0.8f, 0.6f, 0.4f});
    out.setFloat(Global::du, 0.25f);
    out.setFloat(Global::dv, 0.5f);
    return out;
}

// Every grid of kShapes one after another; `parts` gets their shapes.
TestGrid together(std::vector<ShadingGridPart>& parts) {
    std::vector<std::pair<int, int>> who;
    std::vector<int> nus;
    parts.clear();
    for (int g = 0; g < int(std::size(kShapes)); ++g) {
        parts.push_back({int(who.size()), kShapes[g].nu, kShapes[g].nv});
        for (int i = 0; i < kShapes[g].points(); ++i) who.push_back({g, i});
        nus.push_back(kShapes[g].nu);
    }
    TestGrid tg(int(who.size()));
    setInputs(tg, who, nus);
    tg.grid.parts = parts.data();
    tg.grid.partCount = int(parts.size());
    return tg;
}

const char* kDerivatives = R"(
surface derivs(output varying normal cn = 0; output varying float dus = 0; output varying vector dvp = 0;
               output varying float ar = 0; output varying float fs = 0; output varying float dst = 0;
               output varying vector dup = 0)
{
    cn = calculatenormal(P);
    dus = Du(s);
    dvp = Dv(P);
    dup = Du(P);
    ar = area(P);
    fs = filterstep(0.3, s * t * 7);
    dst = Deriv(s * s, t + s);
    Ci = color(cn) * 0.5 + color(dus, ar, fs);
    Oi = color(1, fs, 1);
}
)";

const char* const kOutputs[] = {"cn", "dus", "dvp", "ar", "fs", "dst", "dup"};

// Values of `name` (output or Ci/Oi) of the VM's last run: components one after another.
std::vector<float> valuesOf(const ShadingVM& vm, const std::string& name, int n) {
    const ValueRef v = name == "Ci" ? vm.result(Global::Ci) : name == "Oi" ? vm.result(Global::Oi) : vm.output(name);
    EXPECT_TRUE(v.valid()) << name;
    std::vector<float> out;
    for (int c = 0; c < 3 && v.valid(); ++c) {
        if (!v.comp[c]) break;
        for (int i = 0; i < n; ++i) out.push_back(v.at(c, i));
    }
    return out;
}

// The batched run's values of `name` for grid g, components one after another.
std::vector<float> partOf(const std::vector<float>& all, int total, const ShadingGridPart& p, int n) {
    std::vector<float> out;
    const int comps = int(all.size()) / total;
    for (int c = 0; c < comps; ++c)
        for (int i = 0; i < n; ++i) out.push_back(all[size_t(c * total + p.offset + i)]);
    return out;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

TEST(VmBatchRun, DerivativesOfEachGridAreItsOwnBitForBit) {
    ShaderInstance surface(test::compile(kDerivatives));
    ASSERT_TRUE(batchProgramSafe(surface.program()));
    std::vector<ShadingGridPart> parts;
    TestGrid batch = together(parts);
    ShadingVM vm;
    vm.run(surface, batch.grid);
    const int total = batch.n();
    std::vector<std::string> names(std::begin(kOutputs), std::end(kOutputs));
    names.push_back("Ci");
    names.push_back("Oi");
    std::vector<std::vector<float>> batched;
    for (const std::string& name : names) batched.push_back(valuesOf(vm, name, total));
    for (int g = 0; g < int(std::size(kShapes)); ++g) {
        TestGrid one = alone(g);
        ShadingVM fresh;
        fresh.run(surface, one.grid);
        for (size_t k = 0; k < names.size(); ++k) {
            SCOPED_TRACE("grid " + std::to_string(g) + " " + names[k]);
            const std::vector<float> want = valuesOf(fresh, names[k], one.n());
            EXPECT_TRUE(sameBits(partOf(batched[k], total, parts[size_t(g)], one.n()), want));
        }
    }
    // The derivatives are not trivial at the grids' edges: the same points as one row of
    // micropolygons (no parts) difference across the borders and give other values there.
    TestGrid row = together(parts);
    row.grid.parts = nullptr;
    row.grid.partCount = 0;
    row.grid.nu = total - 1;
    row.grid.nv = 0;
    ShadingVM naive;
    naive.run(surface, row.grid);
    EXPECT_FALSE(sameBits(valuesOf(naive, "dus", total), batched[1]));
    EXPECT_FALSE(sameBits(valuesOf(naive, "dup", total), batched[6]));
}

// The forest's surfaces under its lights and a point light (which is run over the batch's points,
// not kept): Ci and Oi of each grid as shaded alone. The lights' place and spaces are the same for
// every grid of a batch (the batch's key), as here.
TEST(VmBatchRun, ShippedSurfacesUnderLightsGiveEachGridItsOwnColour) {
    ShaderInstance amb{compileShaderFile(test::shaderPath("ambientlight"))};
    ShaderInstance sun{compileShaderFile(test::shaderPath("distantlight"))};
    ShaderInstance bulb{compileShaderFile(test::shaderPath("pointlight"))};
    sun.set("from", BaseType::Point, {-4, 5, 3});
    bulb.set("intensity", BaseType::Float, {3});
    const std::vector<LightRef> lights{{&amb, Matrix4()}, {&sun, Matrix4::rotate(30, {0, 1, 0})},
                                       {&bulb, Matrix4::translate({1, 2, -1})}};
    for (const char* l : {"ambientlight", "distantlight", "pointlight"}) {
        ShaderInstance li(compileShaderFile(test::shaderPath(l)));
        EXPECT_TRUE(batchProgramSafe(li.program())) << l;
    }
    for (const char* name : {"matte", "plastic", "leaf", "bark"}) {
        SCOPED_TRACE(name);
        ShaderInstance surface(compileShaderFile(test::shaderPath(name)));
        ASSERT_TRUE(batchProgramSafe(surface.program()));
        std::vector<ShadingGridPart> parts;
        TestGrid batch = together(parts);
        ShadingVM vm;
        vm.run(surface, batch.grid, lights);
        const std::vector<float> ci = valuesOf(vm, "Ci", batch.n()), oi = valuesOf(vm, "Oi", batch.n());
        for (int g = 0; g < int(std::size(kShapes)); ++g) {
            TestGrid one = alone(g);
            ShadingVM fresh;
            fresh.run(surface, one.grid, lights);
            EXPECT_TRUE(sameBits(partOf(ci, batch.n(), parts[size_t(g)], one.n()), valuesOf(fresh, "Ci", one.n()))) << g;
            EXPECT_TRUE(sameBits(partOf(oi, batch.n(), parts[size_t(g)], one.n()), valuesOf(fresh, "Oi", one.n()))) << g;
        }
    }
}

// What may not be batched: derivatives where some points may not run (refused before the run),
// and operations that read the point's index or the grid's seed or hand the points to something
// outside as a set (refused when they run: the caller then shades each grid alone).
TEST(VmBatchRun, ProgramsThatReadMoreThanTheirPointAreNotBatched) {
    auto program = [](const std::string& body) {
        return test::compile("surface s(float k = 1; string map = \"\";) { float x = s; " + body + " }");
    };
    auto safe = [&](const std::string& body) { return batchProgramSafe(*program(body)); };
    EXPECT_TRUE(safe("Ci = color(Du(x), 0, 0); if (x > 0.5) Ci = 1;"));
    EXPECT_FALSE(safe("if (x > 0.5) Ci = color(Du(x), 0, 0);"));
    EXPECT_FALSE(safe("if (x > 0.5) Ci = 1; Ci += color(area(P));"));  // after a varying if
    EXPECT_FALSE(safe("illuminance(P) { Ci += color(Du(x)); }"));
    EXPECT_TRUE(safe("Ci = color(noise(P)) + color(cellnoise(P * k)) + diffuse(normalize(N));"));
    std::vector<ShadingGridPart> parts;
    TestGrid batch = together(parts);
    auto refused = [&](const std::string& body) {
        ShaderInstance surface(program(body));
        ShadingVM vm;
        try {
            vm.run(surface, batch.grid);
        } catch (const BatchRefused&) {
            return true;
        }
        return false;
    };
    for (const char* body : {"Ci = color(random());", "Ci = color(texture(\"a.tx\", s, t));",
                             "Ci = color(shadow(\"a.shd\", P));", "Ci = color(occlusion(P, N, 4));",
                             "printf(\"%f\\n\", x);", "float y = 0; if (surface(\"Kd\", y) != 0) Ci = y;"}) {
        SCOPED_TRACE(body);
        EXPECT_TRUE(safe(body));
        EXPECT_TRUE(refused(body));
    }
    // Not reached, not refused: a shadow map that is not given (the shipped lights' form).
    EXPECT_FALSE(refused("Ci = 1; if (map != \"\") Ci = color(shadow(map, P));"));
    EXPECT_FALSE(refused("Ci = color(noise(P)) + diffuse(normalize(N));"));
}

}  // namespace
}  // namespace streyes::sl
