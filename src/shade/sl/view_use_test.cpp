// The compiler's view-use analysis (view_use.h): what a shader's results read of the view, rule
// by rule, and the classes of the shipped shaders.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "shade/sl/compiler.h"
#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

const char* name(ViewUse u) {
    switch (u) {
        case ViewUse::None: return "None";
        case ViewUse::FacingOnly: return "FacingOnly";
        case ViewUse::Reads: return "Reads";
    }
    return "?";
}

// The class of a shader's source, with why when it reads the view (for the failure message).
std::string classOf(const std::string& source) {
    ProgramPtr p = compileShader(source, "t.sl");
    return name(p->viewUse);
}

std::string shippedClass(const std::string& shader) {
    return name(compileShaderFile(test::shaderPath(shader))->viewUse);
}

std::string surface(const std::string& body, const std::string& functions = "") {
    return classOf(functions + "\nsurface t(float Kd = 1; color tint = 1;) {\n" + body + "\n}\n");
}

TEST(ViewUse, NoiseOfCurrentSpaceReadsTheViewAndOfShaderSpaceNot) {
    EXPECT_EQ(surface("Ci = noise(P);"), "Reads");
    EXPECT_EQ(surface("Ci = noise(transform(\"shader\", P));"), "None");
    EXPECT_EQ(surface("Ci = noise(transform(\"world\", P));"), "None");
    EXPECT_EQ(surface("Ci = noise(transform(\"object\", P) * 4);"), "None");
    // Through a space that follows the camera, or named only at run time.
    EXPECT_EQ(surface("Ci = noise(transform(\"raster\", P));"), "Reads");
    EXPECT_EQ(surface("Ci = noise(transform(\"NDC\", P));"), "Reads");
    EXPECT_EQ(surface("string sp = \"shader\"; Ci = noise(transform(sp, P));"), "Reads");
    // transform() of a normal into world space needs ntransform's rule: N is a vector.
    EXPECT_EQ(surface("Ci = color ntransform(\"world\", N);"), "None");
    EXPECT_EQ(surface("Ci = color vtransform(\"world\", P);"), "Reads");  // a point as a vector
    // A point fixed in current space is one that follows the camera; one from world space is not.
    EXPECT_EQ(surface("Ci = noise(transform(\"world\", point(0, 0, 1)));"), "Reads");
    EXPECT_EQ(surface("Ci = noise(transform(\"world\", point \"world\" (0, 0, 1)));"), "None");
    EXPECT_EQ(surface("Ci = noise(transform(\"world\", \"shader\", point(1, 2, 3)));"), "None");
}

TEST(ViewUse, ComponentsOfCurrentSpaceValuesReadTheView) {
    EXPECT_EQ(surface("Ci = xcomp(P);"), "Reads");
    EXPECT_EQ(surface("Ci = color(N);"), "Reads");
    EXPECT_EQ(surface("Ci = xcomp(transform(\"world\", P));"), "None");
    EXPECT_EQ(surface("point q = P; setxcomp(q, 0); Ci = noise(transform(\"world\", q));"), "Reads");
}

TEST(ViewUse, MetricRulesOfARigidCamera) {
    // Lengths and dot products of world-still vectors, distances between world-still points.
    EXPECT_EQ(surface("Ci = length(dPdu) * (normalize(N) . normalize(Ng));"), "None");
    EXPECT_EQ(surface("Ci = distance(P, point \"world\" (0, 1, 0));"), "None");
    EXPECT_EQ(surface("Ci = length(P - transform(\"shader\", \"current\", point(0, 0, 0)));"), "None");
    EXPECT_EQ(surface("Ci = area(P) + length(Du(P)) + length(Dv(P));"), "None");
    EXPECT_EQ(surface("Ci = length(dPdu ^ dPdv) + length(mix(N, Ng, .5));"), "None");
    // The distance from the eye, depth, and a point scaled about the eye do not.
    EXPECT_EQ(surface("Ci = length(P);"), "Reads");
    EXPECT_EQ(surface("Ci = depth(P);"), "Reads");
    EXPECT_EQ(surface("Ci = noise(transform(\"world\", 2 * P));"), "Reads");
    EXPECT_EQ(surface("Ci = noise(transform(\"world\", P + 1));"), "Reads");
    EXPECT_EQ(surface("Ci = normalize(P) . normalize(N);"), "Reads");
    EXPECT_EQ(surface("Ci = length(I);"), "Reads");
    EXPECT_EQ(surface("Ci = length(E - P);"), "Reads");
    EXPECT_EQ(surface("Ci = length(dPdtime);"), "Reads");
}

TEST(ViewUse, FacingOnlyThroughFaceforwardOrTheSignOfNDotI) {
    EXPECT_EQ(shippedClass("matte"), "FacingOnly");
    EXPECT_EQ(surface("normal Nf = faceforward(normalize(N), I); Ci = diffuse(Nf);"), "FacingOnly");
    EXPECT_EQ(surface("normal Nf = faceforward(N, I, Ng); Ci = diffuse(normalize(Nf));"), "FacingOnly");
    EXPECT_EQ(surface("if (N . I < 0) Ci = 1; else Ci = .5;"), "FacingOnly");
    EXPECT_EQ(surface("Ci = (-normalize(I) . Ng > 0) ? tint : 0;"), "FacingOnly");
    // Without faceforward, a Lambertian surface reads nothing of the view.
    EXPECT_EQ(surface("Ci = diffuse(normalize(N));"), "None");
    // N.I's value (not its sign), and faceforward of a vector that is not N, read it.
    EXPECT_EQ(surface("Ci = abs(N . I);"), "Reads");
    EXPECT_EQ(surface("if (N . I < .5) Ci = 1;"), "Reads");
    EXPECT_EQ(surface("Ci = diffuse(faceforward(normalize(N), I)) + specular(N, -I, .1);"), "Reads");
    // A highlight reads I.
    EXPECT_EQ(shippedClass("plastic"), "Reads");
    EXPECT_EQ(surface("Ci = color(reflect(I, N) . vector \"world\" (0, 1, 0));"), "Reads");
    // reflect of world-still vectors is one.
    EXPECT_EQ(surface("Ci = diffuse(reflect(dPdu, normalize(N)));"), "None");
}

TEST(ViewUse, ABranchOnAViewValueMakesWhatItAssignsReadTheView) {
    EXPECT_EQ(surface("color c = 0; if (zcomp(P) > 1) c = 1; Ci = c;"), "Reads");
    EXPECT_EQ(surface("Ci = zcomp(P) > 1 ? 1 : 0;"), "Reads");
    EXPECT_EQ(surface("color c = 0; if (zcomp(transform(\"world\", P)) > 1) c = 1; Ci = c;"), "None");
    // Assigned on both paths with the same class: a world-still point either way.
    EXPECT_EQ(surface("point q = P; if (s > .5) q = P + N; Ci = noise(transform(\"world\", q));"), "None");
    // A point on one path, a current-space constant on the other.
    EXPECT_EQ(surface("point q = 0; if (s > .5) q = P; Ci = noise(transform(\"world\", q));"), "Reads");
    // A value computed before the branch and not assigned under it keeps its class.
    EXPECT_EQ(surface("color c = tint; float z = zcomp(P); if (z > 1) z = 0; Ci = c;"), "None");
}

TEST(ViewUse, LoopsBreaksAndReturns) {
    EXPECT_EQ(surface("float i; color c = 0; for (i = 0; i < 4; i += 1) c += noise(transform(\"shader\", P) * i); Ci = c;"),
              "None");
    EXPECT_EQ(surface("float i; color c = 0; for (i = 0; i < zcomp(P); i += 1) c += 1; Ci = c;"), "Reads");
    // A break taken where the view decides ends the loop at a view-dependent count.
    EXPECT_EQ(surface("float i; color c = 0; for (i = 0; i < 4; i += 1) { c += 1; if (zcomp(P) > i) break; } Ci = c;"),
              "Reads");
    // A value carried around the loop: the second iteration sees what the first assigned.
    EXPECT_EQ(surface("float i; point q = transform(\"world\", P); point r = q; "
                      "for (i = 0; i < 3; i += 1) { r = q; q = P; } Ci = noise(r);"),
              "Reads");
    const std::string fns =
        "float early(float x) { if (x > 1) return 1; return 0; }\n"
        "float probe() { extern point P; if (zcomp(P) > 1) return 1; return 0; }\n";
    EXPECT_EQ(surface("Ci = early(s);", fns), "None");
    EXPECT_EQ(surface("Ci = early(zcomp(P));", fns), "Reads");
    EXPECT_EQ(surface("Ci = probe();", fns), "Reads");
}

TEST(ViewUse, UserFunctionsAsTheirBodiesSay) {
    const std::string fns =
        "point through(point p) { return p; }\n"
        "float height(point p) { return zcomp(p); }\n"
        "void toWorld(point p; output point w) { w = transform(\"world\", p); }\n"
        "void keep(point p; output point w) { w = p; }\n";
    EXPECT_EQ(surface("Ci = noise(transform(\"world\", through(P)));", fns), "None");
    EXPECT_EQ(surface("Ci = noise(through(P));", fns), "Reads");
    EXPECT_EQ(surface("Ci = height(P);", fns), "Reads");
    EXPECT_EQ(surface("Ci = height(transform(\"world\", P));", fns), "None");
    EXPECT_EQ(surface("point w; toWorld(P, w); Ci = noise(w);", fns), "None");
    EXPECT_EQ(surface("point w; keep(P, w); Ci = noise(w);", fns), "Reads");
    // A function writing a global the shader returns.
    EXPECT_EQ(surface("setci(); Oi = Os;", "void setci() { extern color Ci; extern vector I; Ci = length(I); }"),
              "Reads");
}

TEST(ViewUse, IlluminanceLightsAndOutputs) {
    EXPECT_EQ(surface("Ci = 0; illuminance(P, N, PI / 2) Ci += Cl * (normalize(L) . normalize(N));"), "None");
    EXPECT_EQ(surface("normal Nf = faceforward(normalize(N), I); Ci = 0;"
                      "illuminance(P, Nf, PI / 2) Ci += Cl * (normalize(L) . Nf);"),
              "FacingOnly");
    // The highlight by hand reads I; lights gathered about a point fixed to the camera too.
    EXPECT_EQ(surface("vector V = -normalize(I); Ci = 0;"
                      "illuminance(P, N, PI / 2) Ci += Cl * pow(max(0, normalize(normalize(L) + V) . normalize(N)), 20);"),
              "Reads");
    EXPECT_EQ(surface("Ci = 0; illuminance(point(0, 0, 0)) Ci += Cl;"), "Reads");
    // Lights: L from a point given in shader space; a cone about a world-still axis.
    EXPECT_EQ(classOf("light l(point from = point \"shader\" (0, 0, 0);) { illuminate(from) Cl = 1 / (L . L); }"), "None");
    EXPECT_EQ(classOf("light l(point from = (0, 0, 0);) { illuminate(from) Cl = 1 / (L . L); }"), "Reads");
    EXPECT_EQ(classOf("light l() { illuminate(point(0, 0, 0)) Cl = 1; }"), "Reads");
    // A vector parameter defaulting to zero is world-still either way; a zero point is the eye.
    EXPECT_EQ(classOf("displacement d(vector offset = (0, 0, 0);) { P += offset; }"), "None");
    EXPECT_EQ(classOf("displacement d(vector offset = vector (0, 0, .1);) { P += offset; }"), "Reads");
    EXPECT_EQ(classOf("surface t(point origin = (0, 0, 0);) { Ci = length(P - origin); }"), "Reads");
    EXPECT_EQ(classOf("surface t(point origin = point \"world\" (0, 0, 0);) { Ci = length(P - origin); }"), "None");
    EXPECT_EQ(classOf("light l() { Cl = length(Ps); }"), "Reads");
    // A displacement's P must stay a world-still point, its N a world-still vector.
    EXPECT_EQ(classOf("displacement d() { P += .1 * noise(transform(\"shader\", P)) * normalize(N); "
                      "N = calculatenormal(P); }"),
              "None");
    EXPECT_EQ(classOf("displacement d() { P += .1 * noise(P) * normalize(N); N = calculatenormal(P); }"), "Reads");
    EXPECT_EQ(classOf("displacement d() { P = transform(\"world\", P); }"), "Reads");
    // An output parameter (an AOV) is a result too.
    EXPECT_EQ(classOf("surface t(output varying float depthv = 0;) { depthv = length(I); Ci = Cs; }"), "Reads");
    EXPECT_EQ(classOf("volume v() { Ci = Ci * exp(-length(I)); }"), "Reads");
}

TEST(ViewUse, RaysMessagesRandomAndMapInformationReadTheView) {
    EXPECT_EQ(surface("Ci = trace(P, normalize(N));"), "Reads");
    EXPECT_EQ(surface("Ci = 1 - occlusion(P, normalize(N), 16);"), "Reads");
    // A map's information (a shadow map's matrix): maps may differ by frame.
    EXPECT_EQ(surface("matrix m = 0; textureinfo(\"sm.tex\", \"viewingmatrix\", m); Ci = comp(m, 0, 0);"), "Reads");
    // Options and attributes are the render's, the same in every frame.
    EXPECT_EQ(surface("float f[3]; option(\"Format\", f); Ci = f[0];"), "None");
    EXPECT_EQ(surface("float f = 0; lightsource(\"__k\", f); Ci = f;"), "Reads");
    EXPECT_EQ(surface("Ci = random();"), "Reads");
    EXPECT_EQ(surface("string id = \"\"; attribute(\"identifier:name\", id); Ci = tint;"), "None");
}

TEST(ViewUse, WhyNamesWhereTheViewIsRead) {
    ProgramPtr p = compileShader("surface t() {\n  Ci = Cs;\n  Ci *= noise(P);\n}\n", "why.sl");
    EXPECT_EQ(p->viewUse, ViewUse::Reads);
    EXPECT_NE(p->viewUseWhy.find("why.sl:3"), std::string::npos) << p->viewUseWhy;
    EXPECT_NE(p->viewUseWhy.find("noise"), std::string::npos) << p->viewUseWhy;
}

// Loops are analysed to a fixed point, each round of an outer loop analysing the inner ones again;
// once an inner loop's state is settled it takes one round, so deep nests stay cheap and exact.
TEST(ViewUse, NestedLoopsAreAnalysedInFull) {
    std::string still = "Ci += tint;", moving = "Ci += noise(q); q = P;", decls;
    for (int i = 0; i < 25; ++i) {
        const std::string v = "i" + std::to_string(i);
        decls += "float " + v + ";\n";
        still = "for (" + v + " = 0; " + v + " < 2; " + v + " += 1) { " + still + " }";
        moving = "for (" + v + " = 0; " + v + " < 2; " + v + " += 1) { " + moving + " }";
    }
    decls += "point q = transform(\"world\", P);\n";
    EXPECT_EQ(compileShader("surface t(color tint = 1;) {\n" + decls + still + "\n}\n", "still.sl")->viewUse,
              ViewUse::None);
    // The innermost body's second pass sees q = P (a current-space point) in noise().
    EXPECT_EQ(compileShader("surface t(color tint = 1;) {\n" + decls + moving + "\n}\n", "moving.sl")->viewUse,
              ViewUse::Reads);
}

TEST(ViewUse, TheShippedShaders) {
    const std::map<std::string, std::string> expected{
        {"ambientlight", "None"},   {"arealight", "None"},     {"background", "Reads"},     {"bark", "Reads"},
        {"bumpy", "None"},          {"constant", "None"},      {"defaultsurface", "Reads"}, {"depthcue", "Reads"},
        {"distantlight", "None"},   {"fog", "Reads"},          {"ground", "FacingOnly"},    {"leaf", "Reads"},
        {"matte", "FacingOnly"},    {"metal", "Reads"},        {"paintedplastic", "Reads"}, {"plastic", "Reads"},
        {"pointlight", "None"},     {"shadowdistant", "None"}, {"shadowpoint", "None"},     {"shadowspot", "None"},
        {"shinymetal", "Reads"},    {"sky", "Reads"},          {"spotlight", "None"},
        {"preethamsky", "Reads"},   {"sunlight", "None"},
    };
    size_t seen = 0;
    for (const auto& entry : std::filesystem::directory_iterator(std::string(STREYES_SOURCE_DIR) + "/shaders")) {
        if (entry.path().extension() != ".sl") continue;
        const std::string stem = entry.path().stem().string();
        SCOPED_TRACE(stem);
        auto it = expected.find(stem);
        ASSERT_NE(it, expected.end()) << "a shipped shader without an expected class: add it here";
        ProgramPtr p = compileShaderFile(entry.path().string());
        EXPECT_EQ(name(p->viewUse), it->second) << p->viewUseWhy;
        ++seen;
    }
    EXPECT_EQ(seen, expected.size());
}

}  // namespace
}  // namespace streyes::sl
