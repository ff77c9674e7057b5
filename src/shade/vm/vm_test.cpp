// The interpreter: varying control flow under masks against a scalar reference, uniform values
// computed once, sanitised results, user functions, arrays, output parameters, spaces.
#include <gtest/gtest.h>

#include <cmath>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

// Runs surface `src` over n points with u = i / (n - 1) (s and t too) and returns Ci's red.
std::vector<float> runRed(const std::string& src, int n, ShadingVM* vmOut = nullptr) {
    TestGrid g(n);
    g.setVarying(Global::u, 1, [&](int i) { return Vec3f{float(i) / float(n - 1), 0, 0}; });
    g.setVarying(Global::s, 1, [&](int i) { return Vec3f{float(i) / float(n - 1), 0, 0}; });
    g.setVarying(Global::t, 1, [&](int i) { return Vec3f{float(i % 7) / 7.0f, 0, 0}; });
    g.setVarying(Global::P, 3, [&](int i) { return Vec3f{float(i), 1, 2}; });
    ShaderInstance inst(test::compile(src));
    ShadingVM local;
    ShadingVM& vm = vmOut ? *vmOut : local;
    vm.run(inst, g.grid);
    ValueRef ci = vm.result(Global::Ci);
    std::vector<float> out;
    for (int i = 0; i < n; ++i) out.push_back(ci.at(0, i));
    return out;
}

// A loop whose trip count differs per point, with continue, break and nested ifs, gives each
// point what a scalar C++ loop gives it.
TEST(VmControl, VaryingLoopsMatchAScalarReference) {
    const char* src = R"(
        surface s() {
            float k = floor(u * 20);   // 0 .. 20
            float sum = 0, i;
            for (i = 0; i < k; i += 1) {
                if (mod(i, 3) == 1) continue;
                sum += i;
                if (sum > 60) { sum += 1000; break; }
                else if (i > 15) sum -= .5;
            }
            Ci = sum;
        })";
    const int n = 64;
    std::vector<float> got = runRed(src, n);
    for (int p = 0; p < n; ++p) {
        float k = std::floor(float(p) / float(n - 1) * 20), sum = 0;
        for (float i = 0; i < k; i += 1) {
            if (std::fmod(i, 3.0f) == 1) continue;
            sum += i;
            if (sum > 60) {
                sum += 1000;
                break;
            } else if (i > 15) {
                sum -= .5f;
            }
        }
        EXPECT_FLOAT_EQ(got[size_t(p)], sum) << "point " << p;
    }
}

TEST(VmControl, WhileLoopAndNestedLoopsWithLevels) {
    const char* src = R"(
        surface s() {
            float x = u * 10, steps = 0;
            while (x > 1) { x = x / 2; steps += 1; }
            float found = -1, a, b;
            for (a = 0; a < 4; a += 1) {
                for (b = 0; b < 4; b += 1) {
                    if (a * 4 + b >= u * 15) { found = a * 10 + b; break 2; }
                }
            }
            Ci = steps * 1000 + found;
        })";
    const int n = 32;
    std::vector<float> got = runRed(src, n);
    for (int p = 0; p < n; ++p) {
        float u = float(p) / float(n - 1), x = u * 10, steps = 0, found = -1;
        while (x > 1) {
            x /= 2;
            steps += 1;
        }
        for (int a = 0; a < 4 && found < 0; ++a)
            for (int b = 0; b < 4; ++b)
                if (float(a * 4 + b) >= u * 15) {
                    found = float(a * 10 + b);
                    break;
                }
        EXPECT_FLOAT_EQ(got[size_t(p)], steps * 1000 + found) << p;
    }
}

TEST(VmControl, ReturnUnderAVaryingConditionInAFunctionAndTheShader) {
    const char* src = R"(
        float f(float x) {
            if (x < .3) return 1;
            if (x < .6) return 2;
            return 3;
        }
        surface s() {
            Ci = f(u);
            if (u > .9) return;
            Ci += 10;
        })";
    const int n = 21;
    std::vector<float> got = runRed(src, n);
    for (int p = 0; p < n; ++p) {
        float u = float(p) / float(n - 1);
        float e = u < .3f ? 1 : u < .6f ? 2 : 3;
        if (!(u > .9f)) e += 10;
        EXPECT_FLOAT_EQ(got[size_t(p)], e) << p;
    }
}

TEST(VmControl, UniformConditionsAreJumps) {
    ProgramPtr p = test::compile("surface s(float k = 1) { if (k > 0) Ci = 1; else Ci = 2; }");
    for (const Instr& in : p->code) EXPECT_STRNE(opName(in.fn), "maskIf");
    std::vector<float> r = runRed("surface s(float k = 1) { if (k > 0) Ci = 1; else Ci = 2; }", 4);
    EXPECT_EQ(r[0], 1.0f);
}

TEST(VmControl, TernaryAndLogic) {
    std::vector<float> r = runRed("surface s() { Ci = (u > .5 && !(u > .8)) || u == 0 ? 1 : 0; }", 11);
    for (int p = 0; p < 11; ++p) {
        float u = float(p) / 10;
        EXPECT_EQ(r[size_t(p)], ((u > .5f && !(u > .8f)) || u == 0) ? 1.0f : 0.0f) << p;
    }
}

// A uniform computation runs once per grid, however many points; a varying one n times.
TEST(VmUniform, UniformValuesAreComputedOnce) {
    const char* uniformSrc = R"(
        surface s(float Kd = 2) {
            float x = 0, i;
            for (i = 0; i < 50; i += 1) x += sin(i * Kd);
            Ci = x;
        })";
    const char* varyingSrc = R"(
        surface s(float Kd = 2) {
            float x = 0, i;
            for (i = 0; i < 50; i += 1) x += sin(i * Kd * u);
            Ci = x;
        })";
    const int n = 1000;
    ShadingVM a, b;
    runRed(uniformSrc, n, &a);
    runRed(varyingSrc, n, &b);
    // The uniform loop: ~6 instructions x 50 iterations, each on one value; only the final
    // store into Ci (and the globals' handling) is n wide.
    EXPECT_GT(a.stats().instructions, 250u);
    EXPECT_LT(a.stats().laneOps, a.stats().instructions + 3u * n);
    // The varying one does the sine n times each iteration.
    EXPECT_GT(b.stats().laneOps, 50u * n);
    // And the variable that only ever held uniform values was kept uniform.
    ProgramPtr p = test::compile(uniformSrc);
    for (const Register& r : p->regs) {
        if (r.name == "x" || r.name == "i") {
            EXPECT_EQ(r.detail, Detail::Uniform) << r.name;
        }
    }
    ProgramPtr q = test::compile(varyingSrc);
    for (const Register& r : q->regs) {
        if (r.name == "x") {
            EXPECT_EQ(r.detail, Detail::Varying);
        }
    }
}

// x/0, sqrt and log of negatives, pow out of its domain: 0, counted; no NaN or infinity out.
TEST(VmSanitise, DivisionByZeroAndDomainErrorsGiveZeroAndAreCounted) {
    ShadingVM vm;
    std::vector<float> r = runRed("surface s() { Ci = color(1 / (u - u), sqrt(-1 - u), log(-u)); }", 8, &vm);
    for (float v : r) EXPECT_EQ(v, 0.0f);
    ValueRef ci = vm.result(Global::Ci);
    for (int i = 0; i < 8; ++i) {
        EXPECT_EQ(ci.at(1, i), 0.0f);
        EXPECT_EQ(ci.at(2, i), 0.0f);
    }
    EXPECT_EQ(vm.stats().sanitised, 8u * 3u);
    // Only points that run count; overflow (exp) is caught on the way out.
    ShadingVM vm2;
    runRed("surface s() { Ci = 0; if (u > .5) Ci = 1 / (u - u); Ci += exp(1000 * u); }", 11, &vm2);
    EXPECT_EQ(vm2.stats().sanitised, 5u + 3u * 10u);  // 5 divisions (u > .5), infinity in 10 points' 3 channels
    ValueRef c2 = vm2.result(Global::Ci);
    for (int i = 0; i < 11; ++i) EXPECT_TRUE(std::isfinite(c2.at(0, i)));
    // A uniform division by zero counts once.
    ShadingVM vm3;
    runRed("surface s(float z = 0) { Ci = 1 / z; }", 50, &vm3);
    EXPECT_EQ(vm3.stats().sanitised, 1u);
}

TEST(VmFunctions, UserFunctionsArraysAndOutputParameters) {
    const char* src = R"(
        float sq(float x) { return x * x; }
        void split(float v; output float lo; output float hi) {
            lo = floor(v);
            hi = v - lo;
        }
        color pick(float k; color table[3]) { return table[k]; }
        surface s(float weights[3] = {1, 10, 100}; color table[3] = {color(1,0,0), color(0,1,0), color(0,0,1)}) {
            float lo, hi;
            split(u * 3, lo, hi);
            float w = weights[min(lo, 2)];
            float acc[4];
            acc[0] = w; acc[1] = sq(hi); acc[2] = acc[0] + acc[1]; acc[3] = 0;
            Ci = acc[2] + pick(min(lo, 2), table);
        })";
    const int n = 13;
    TestGrid g(n);
    g.setVarying(Global::u, 1, [&](int i) { return Vec3f{float(i) / float(n - 1), 0, 0}; });
    ShaderInstance inst(test::compile(src));
    ShadingVM vm;
    vm.run(inst, g.grid);
    ValueRef ci = vm.result(Global::Ci);
    const float w[3] = {1, 10, 100};
    for (int p = 0; p < n; ++p) {
        float v = float(p) / float(n - 1) * 3, lo = std::floor(v), hi = v - lo;
        int k = int(std::min(lo, 2.0f));
        float base = w[k] + hi * hi;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(ci.at(c, p), base + (c == k ? 1.0f : 0.0f), 1e-5f) << p << " " << c;
    }
}

TEST(VmFunctions, ShaderOutputParametersAndInstanceValues) {
    const char* src = R"(
        surface s(float Ks = .5; color tint = 1; output varying float coverage = 0; output float count = 0) {
            coverage = u * Ks;
            count = 3;
            Ci = tint;
        })";
    TestGrid g(4);
    g.setVarying(Global::u, 1, [](int i) { return Vec3f{float(i), 0, 0}; });
    ShaderInstance inst(test::compile(src));
    inst.setDeclared("float Ks", {2});
    inst.set("tint", BaseType::Color, {0.1f, 0.2f, 0.3f});
    ShadingVM vm;
    vm.run(inst, g.grid);
    ValueRef cov = vm.output("coverage"), count = vm.output("count");
    ASSERT_TRUE(cov.valid());
    for (int i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(cov.at(0, i), float(i) * 2);
    EXPECT_FLOAT_EQ(count.at(0, 0), 3);
    EXPECT_FLOAT_EQ(vm.result(Global::Ci).at(2, 3), 0.3f);
    EXPECT_FALSE(vm.output("Ks").valid());  // not an output
    // Wrong type, wrong count, unknown name: errors at the caller's location.
    SourceLoc loc{std::make_shared<const std::string>("scene.rib"), 12};
    try {
        inst.set("Ks", BaseType::Color, {1, 1, 1}, loc);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("scene.rib:12: ", 0), 0u) << e.what();
        EXPECT_NE(std::string(e.what()).find("is uniform float, not color"), std::string::npos) << e.what();
    }
    EXPECT_THROW(inst.set("tint", BaseType::Color, {1, 1}, loc), InputError);
    EXPECT_THROW(inst.setDeclared("float Kx", {1}, loc), InputError);
    EXPECT_THROW(inst.setStrings("tint", {"a"}, loc), InputError);
}

TEST(VmFunctions, PrimitiveVariablesBindParameters) {
    const char* src = "surface s(varying float ramp = 0; color base = 1) { Ci = base * ramp; }";
    TestGrid g(3);
    std::vector<float> ramp{0.5f, 1.0f, 1.5f};
    Vec3f base{0.2f, 0.4f, 0.6f};
    std::vector<Primvar> pv(2);
    pv[0].name = "ramp";
    pv[0].type = BaseType::Float;
    pv[0].value = ValueRef::soa(ramp.data());
    pv[1].name = "base";
    pv[1].type = BaseType::Color;
    pv[1].value = ValueRef::uniform(base);
    g.grid.primvars = &pv;
    ShaderInstance inst(test::compile(src));
    ShadingVM vm;
    vm.run(inst, g.grid);
    EXPECT_FLOAT_EQ(vm.result(Global::Ci).at(1, 2), 0.4f * 1.5f);
    // A varying value for a uniform parameter is an error at the primitive variable.
    pv[1].value = ValueRef::aos(&base);
    pv[1].loc = {std::make_shared<const std::string>("scene.rib"), 7};
    EXPECT_THROW(vm.run(inst, g.grid), InputError);
}

// A point moved to "world" and back is itself; named spaces come from the grid.
TEST(VmSpaces, TransformFromANamedSpaceThroughAMatrix) {
    // transform(from, m, p) (RI Spec 3.2, 15.2): p taken from `from` to current space, then
    // through m; as the two steps written out, for points, vectors and normals, and a varying m.
    const char* src = R"(
        surface s(output varying point a = 0; output varying point b = 0; output varying vector va = 0;
                  output varying vector vb = 0; output varying normal na = 0; output varying normal nb = 0;
                  output varying point ca = 0; output varying point cb = 0) {
            matrix m = translate(scale(matrix 1, point(1, 2, 3)), vector(s, 1, -2));
            point p = point(1, s, 2);
            a = transform("world", m, p);
            b = transform(m, transform("world", "current", p));
            va = vtransform("world", m, vector p);
            vb = vtransform(m, vtransform("world", "current", vector p));
            na = ntransform("world", m, normal p);
            nb = ntransform(m, ntransform("world", "current", normal p));
            ca = transform("current", m, p);
            cb = transform(m, p);
            Ci = 0;
        })";
    TestGrid g(5);
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{float(i), 2, -1}; });
    g.grid.setSpace(Space::World, Matrix4::scale({2, 2, 2}) * Matrix4::rotate(90, {1, 0, 0}) * Matrix4::translate({1, 2, 3}));
    ShaderInstance inst(test::compile(src));
    ShadingVM vm;
    vm.run(inst, g.grid);
    for (const char* pair : {"ab", "v", "n", "c"}) {
        const std::string x = pair[0] == 'a' ? "a" : std::string(1, pair[0]) + "a";
        const std::string y = pair[0] == 'a' ? "b" : std::string(1, pair[0]) + "b";
        for (int i = 0; i < g.n(); ++i) {
            const Vec3f u = test::at3(vm.output(x), i), v = test::at3(vm.output(y), i);
            EXPECT_NEAR(u.x, v.x, 1e-4f) << x << " " << i;
            EXPECT_NEAR(u.y, v.y, 1e-4f) << x << " " << i;
            EXPECT_NEAR(u.z, v.z, 1e-4f) << x << " " << i;
        }
    }
    // Not the matrix alone: world space is not current here.
    EXPECT_GT(std::abs(test::at3(vm.output("a"), 1).x - test::at3(vm.output("cb"), 1).x), 0.1f);
}

TEST(VmSpaces, TransformsToNamedSpacesAndBack) {
    const char* src = R"(
        surface s(output varying point w = 0; output varying point back = 0; output varying vector nw = 0;
                  output uniform float det = 0; output varying point viaMatrix = 0) {
            w = transform("world", P);
            back = transform("world", "current", w);
            nw = ntransform("world", normal(0, 0, 1));
            matrix m = matrix "world" 1;   // world to current
            det = determinant(m);
            viaMatrix = transform(m, w);   // world coordinates through world-to-current: P again
            Ci = 0;
        })";
    TestGrid g(5);
    g.setVarying(Global::P, 3, [](int i) { return Vec3f{float(i), 2, -1}; });
    // world to camera: scale by 2, then rotate 90 degrees about x, then translate.
    Matrix4 worldToCamera = Matrix4::scale({2, 2, 2}) * Matrix4::rotate(90, {1, 0, 0}) * Matrix4::translate({1, 2, 3});
    g.grid.setSpace(Space::World, worldToCamera);
    ShaderInstance inst(test::compile(src));
    ShadingVM vm;
    vm.run(inst, g.grid);
    Matrix4 cameraToWorld;
    ASSERT_TRUE(invert(worldToCamera, &cameraToWorld));
    ValueRef w = vm.output("w"), back = vm.output("back"), via = vm.output("viaMatrix");
    for (int i = 0; i < 5; ++i) {
        Vec3d expect = cameraToWorld.point({double(i), 2, -1});
        EXPECT_NEAR(w.at(0, i), expect.x, 1e-5);
        EXPECT_NEAR(w.at(1, i), expect.y, 1e-5);
        EXPECT_NEAR(w.at(2, i), expect.z, 1e-5);
        EXPECT_NEAR(back.at(0, i), float(i), 1e-5);
        EXPECT_NEAR(back.at(1, i), 2, 1e-5);
        EXPECT_NEAR(back.at(2, i), -1, 1e-5);
        EXPECT_NEAR(via.at(0, i), float(i), 1e-5);
    }
    EXPECT_NEAR(vm.output("det").at(0, 0), 8.0f, 1e-4f);
    // Normals go by the inverse transpose: camera to world scales by 1/2, so a normal doubles;
    // and it stays perpendicular to the plane's vectors moved to world space.
    ValueRef nw = vm.output("nw");
    Vec3f nwv = test::at3(nw, 0);
    EXPECT_NEAR(length(nwv), 2.0f, 1e-5f);
    Vec3f tx(cameraToWorld.vector({1, 0, 0})), ty(cameraToWorld.vector({0, 1, 0}));
    EXPECT_NEAR(dot(nwv, tx), 0.0f, 1e-5f);
    EXPECT_NEAR(dot(nwv, ty), 0.0f, 1e-5f);
    EXPECT_EQ(vm.stats().unknownSpaces, 0u);
    // An unknown space is the identity, counted.
    ShadingVM vm2;
    ShaderInstance bad(test::compile("surface s() { Ci = color(transform(\"nowhere\", P)); }"));
    vm2.run(bad, g.grid);
    EXPECT_EQ(vm2.stats().unknownSpaces, 1u);
    EXPECT_FLOAT_EQ(vm2.result(Global::Ci).at(0, 3), 3.0f);
}

TEST(VmSpaces, ConstructorsWithSpacesAndColourSpaces) {
    const char* src = R"(
        surface s(output color hsv = 0; output color back = 0; output point shaderOrigin = 0;
                  output color viaHsl = 0; output color viaXyz = 0; output color viaYiq = 0) {
            hsv = ctransform("hsv", color(1, 0.5, 0));
            back = color "hsv" (hsv[0] * 0 + comp(hsv, 0), comp(hsv, 1), comp(hsv, 2));
            shaderOrigin = point "shader" (0, 0, 0);
            viaHsl = ctransform("hsl", "rgb", ctransform("hsl", color(.2, .4, .6)));
            viaXyz = ctransform("xyz", "rgb", ctransform("xyz", color(.2, .4, .6)));
            viaYiq = ctransform("yiq", "rgb", ctransform("yiq", color(.2, .4, .6)));
            Ci = 0;
        })";
    EXPECT_NE(test::compileError(src), "");  // hsv[0]: a color is not an array
    const char* ok = R"(
        surface s(output color hsv = 0; output color back = 0; output point shaderOrigin = 0;
                  output color viaHsl = 0; output color viaXyz = 0; output color viaYiq = 0) {
            hsv = ctransform("hsv", color(1, 0.5, 0));
            back = color "hsv" (comp(hsv, 0), comp(hsv, 1), comp(hsv, 2));
            shaderOrigin = point "shader" (0, 0, 0);
            viaHsl = ctransform("hsl", "rgb", ctransform("hsl", color(.2, .4, .6)));
            viaXyz = ctransform("xyz", "rgb", ctransform("xyz", color(.2, .4, .6)));
            viaYiq = ctransform("yiq", "rgb", ctransform("yiq", color(.2, .4, .6)));
            Ci = 0;
        })";
    TestGrid g(1);
    g.grid.setSpace(Space::Shader, Matrix4::translate({5, 6, 7}));
    ShaderInstance inst(test::compile(ok));
    ShadingVM vm;
    vm.run(inst, g.grid);
    ValueRef hsv = vm.output("hsv");
    EXPECT_NEAR(hsv.at(0, 0), 30.0f / 360.0f, 1e-6f);  // orange: hue 30 degrees
    EXPECT_NEAR(hsv.at(1, 0), 1.0f, 1e-6f);
    EXPECT_NEAR(hsv.at(2, 0), 1.0f, 1e-6f);
    ValueRef back = vm.output("back");
    EXPECT_NEAR(back.at(0, 0), 1.0f, 1e-6f);
    EXPECT_NEAR(back.at(1, 0), 0.5f, 1e-6f);
    EXPECT_NEAR(back.at(2, 0), 0.0f, 1e-6f);
    EXPECT_NEAR(vm.output("shaderOrigin").at(1, 0), 6.0f, 1e-6f);
    for (const char* name : {"viaHsl", "viaXyz", "viaYiq"}) {
        ValueRef c = vm.output(name);
        EXPECT_NEAR(c.at(0, 0), 0.2f, 1e-4f) << name;
        EXPECT_NEAR(c.at(1, 0), 0.4f, 1e-4f) << name;
        EXPECT_NEAR(c.at(2, 0), 0.6f, 1e-4f) << name;
    }
}

TEST(VmMath, StandardFunctions) {
    const char* src = R"(
        surface s(output float v[12] = {0,0,0,0,0,0,0,0,0,0,0,0}) {
            v[0] = mix(2, 4, .25);
            v[1] = smoothstep(0, 2, 1);
            v[2] = clamp(5, 0, 3);
            v[3] = step(1, .5) + step(1, 1);
            v[4] = mod(-1, 3);
            v[5] = spline(.5, 0, 1, 2, 3);            // catmull-rom through 1 and 2: 1.5
            v[6] = spline("linear", .25, 0, 10, 20, 30, 40);
            v[7] = max(1, 5, 3) + min(4, 2, 6);
            v[8] = length(vector(3, 4, 0)) + distance(point(1, 1, 1), point(1, 1, 3));
            v[9] = ptlined(point(0, 0, 0), point(2, 0, 0), point(1, 3, 0));
            v[10] = xcomp(rotate(point(1, 0, 0), PI / 2, point(0, 0, 0), point(0, 0, 1)));
            v[11] = PI;
            Ci = 0;
        })";
    TestGrid g(1);
    ShaderInstance inst(test::compile(src));
    ShadingVM vm;
    vm.run(inst, g.grid);
    const float want[12] = {2.5f, 0.5f, 3, 1, 2, 1.5f, 15, 7, 7, 3, 0, 3.14159265f};
    for (int k = 0; k < 12; ++k) EXPECT_NEAR(vm.param("v", k).at(0, 0), want[k], 1e-5f) << k;
}

TEST(VmStrings, PrintfFormatConcatMatch) {
    const char* src = R"(
        surface s(string name = "bark"; output string joined = ""; output float matched = 0) {
            joined = concat(name, "-", format("%d:%.2f", 7, 0.5));
            matched = match("^ba", name) + 2 * match("x", name);
            if (u > .5) printf("u %.1f %c\n", u, color(1, 0, 0));
            printf("once %s\n", name);
            Ci = 0;
        })";
    TestGrid g(3);
    g.setVarying(Global::u, 1, [](int i) { return Vec3f{float(i) * 0.5f, 0, 0}; });
    ShaderInstance inst(test::compile(src));
    ShadingVM vm;
    std::string printed;
    vm.setPrintSink([&](const std::string& s) { printed += s; });
    vm.run(inst, g.grid);
    EXPECT_EQ(vm.paramStrings("joined")[0], "bark-7:0.50");
    EXPECT_EQ(vm.output("matched").at(0, 0), 1.0f);
    EXPECT_EQ(printed, "u 1.0 1 0 0\nonce bark\n");
}

TEST(VmFunctions, ArrayLengthAndUnsizedArraysTakingTheirValuesLength) {
    ProgramPtr prog = test::compile(R"(
        surface s(float weights[] = {1, 2, 3, 4}; output uniform float n = 0; output uniform float sum = 0;
                  output uniform float m = 0) {
            color ramp[] = {color 0, color 1, color 2};
            float fixed[5];
            uniform float i;
            for (i = 0; i < arraylength(weights); i += 1) sum += weights[i];
            n = arraylength(weights);
            m = arraylength(ramp) * 10 + arraylength(fixed);
            Ci = 0;
        })");
    ShaderInstance inst(prog);
    ShadingVM vm;
    TestGrid g(3);
    vm.run(inst, g.grid);
    EXPECT_EQ(vm.output("n").at(0, 0), 4.0f);
    EXPECT_EQ(vm.output("sum").at(0, 0), 10.0f);
    EXPECT_EQ(vm.output("m").at(0, 0), 35.0f);
    // A value bound to the unsized parameter (4 floats, its length) is summed.
    ShaderInstance bound(prog);
    bound.set("weights", BaseType::Float, {0.5f, 0.25f, 2, 8});
    vm.run(bound, g.grid);
    EXPECT_EQ(vm.output("sum").at(0, 0), 10.75f);
    // Errors at the call. (`float a[];` and `string a[];` are empty resizable arrays,
    // resizable_arrays_test.cpp.)
    EXPECT_EQ(test::compileError("surface s() { string a[]; Ci = 0; }"), "");
    EXPECT_NE(test::compileError("surface s() { float a = 1; Ci = arraylength(a); }").find("arraylength of a float, not an array"),
              std::string::npos);
}

}  // namespace
}  // namespace streyes::sl
