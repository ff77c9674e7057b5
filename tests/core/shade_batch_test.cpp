// Small grids of one material shaded together in one interpreter run (GridShader::shadeSlots,
// BucketWorker::batchKeys / batchGrid): the pixels must be those of one run a grid, bit for bit,
// whatever the algorithm and the thread count, and the grids must share runs.
#include <gtest/gtest.h>

#include <cmath>

#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

// A field of small leaves (a few micropolygons each: the forest's case) swaying with `keys`
// motion keys (2: a grid diced over its span; 3 or more: a keyed body, diced at each key), under
// an ambient, a distant and a point light. Half the leaves wear the shipped leaf shader
// (filterstep, cellnoise, a see-through cut-out), half one reading derivatives at every point
// (calculatenormal, Du, Dv, area), whose values at a grid's border are the ones a difference
// across two grids would change.
std::string leafField(const test::ShaderDir& shaders, int keys) {
    std::string rib = shaders.option() + "Option \"streyes\" \"int frames\" [0 4]\nFormat 96 64 1\n"
                      "Projection \"perspective\" \"fov\" 40\nPixelSamples 2 2\nShutter 0 0.5\nTranslate 0 0 9\nWorldBegin\n"
                      "LightSource \"ambientlight\" 1 \"intensity\" 0.3\n"
                      "LightSource \"distantlight\" 2 \"from\" [-1 1 -2] \"to\" [0 0 0]\n"
                      "LightSource \"pointlight\" 3 \"from\" [1 2 -3] \"intensity\" 6\n";
    std::string times;
    for (int k = 0; k < keys; ++k) times += std::to_string(4.0 * k / (keys - 1)) + (k + 1 < keys ? " " : "");
    // Two materials (an attribute block each), the leaves within one differing by their transform.
    for (const char* surface : {"leaf", "slopes"}) {
        rib += std::string("AttributeBegin\nSurface \"") + surface + "\"\nColor [0.5 0.7 0.4]\n";
        for (int leaf = 0; leaf < 24; ++leaf) {
            const int col = leaf % 6, row = leaf / 6 + (surface[0] == 's' ? 4 : 0);
            rib += "TransformBegin\nTranslate " + std::to_string(-3 + col) + " " + std::to_string(-3.5 + row) + " " +
                   std::to_string(0.1 * (leaf % 5)) + "\nMotionBegin [" + times + "]\n";
            for (int k = 0; k < keys; ++k) rib += "Rotate " + std::to_string(20 * std::sin(0.9 * k + leaf)) + " 0.3 0.2 1\n";
            rib += "MotionEnd\nPatch \"bilinear\" \"P\" [-0.4 -0.3 0  0.4 -0.3 0.1  -0.4 0.3 0.2  0.4 0.3 0]\nTransformEnd\n";
        }
        rib += "AttributeEnd\n";
    }
    return rib + "WorldEnd\n";
}

const char* kSlopes = R"(surface slopes() {
    normal n = normalize(calculatenormal(P));
    float a = area(P);
    Ci = Cs * color(0.5 + 0.5 * abs(xcomp(n)), 0.5 + 0.5 * abs(ycomp(n)), 0.5) * diffuse(faceforward(n, I)) + color(abs(Du(s)), abs(Dv(t)), 10 * sqrt(a));
    Oi = 1;
})";

TEST(ShadeBatching, SmallGridsShareRunsAndGiveTheSamePixels) {
    test::ShaderDir shaders;
    shaders.add("slopes", kSlopes);
    std::ofstream(shaders.dir.path() + "/leaf.sl") << std::ifstream(test::sourcePath("shaders/leaf.sl")).rdbuf();
    for (int keys : {2, 3, 5}) {
        const std::string rib = leafField(shaders, keys);
        for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Spacetime}) {
            for (int threads : {1, 2}) {
                SCOPED_TRACE(std::to_string(keys) + " keys, " + algorithmName(a) + ", threads " + std::to_string(threads));
                RenderOptions on = test::optionsFor(a), off = on;
                on.threads = off.threads = threads;
                off.shadeBatching = false;
                const test::RenderResult batched = test::renderRib(rib, on), alone = test::renderRib(rib, off);
                EXPECT_TRUE(test::identicalPixels(batched, alone));
                EXPECT_GT(test::alphaSum(alone, 2), 500.0);  // the leaves are there
                const RenderCounters &b = batched.stats.counters, &o = alone.stats.counters;
                EXPECT_EQ(o.shadingBatchRuns, 0u);
                EXPECT_EQ(o.shadingBatchedGrids, 0u);
                // Every shaded point is shaded once either way; grids share runs, two or more to a run on average.
                EXPECT_EQ(b.pointsShadedSurface, o.pointsShadedSurface);
                EXPECT_GT(b.shadingBatchRuns, 0u);
                EXPECT_GE(b.shadingBatchedGrids, 2 * b.shadingBatchRuns);
            }
        }
    }
}

// Grids diced at other rates (other du and dv) share a run: du and dv are bound point by point,
// each grid's own. Six still patches of other sizes in one bucket under one material: one run
// of all six, and the pixels of one run a grid, with a shader whose colour reads du and dv
// themselves and through Du, Dv, area and calculatenormal (the first grid's du for all would
// change them).
const char* kRates = R"(surface rates() {
    normal n = normalize(calculatenormal(P));
    Ci = color(40 * du, 40 * dv, 0.5 + 0.5 * zcomp(n)) + color(abs(Du(s)) * 0.01, abs(Dv(t)) * 0.01, area(P) * 0.02);
    Oi = color(1 - 0.1 * du, 1 - 0.1 * dv, 1);
})";

TEST(ShadeBatching, GridsOfOtherRatesShareARun) {
    test::ShaderDir shaders;
    shaders.add("rates", kRates);
    std::string scene = "Surface \"rates\"\nColor [0.5 0.7 0.4]\n";
    for (int g = 0; g < 6; ++g) {
        const float x0 = 1 + 7.5f * float(g), w = 2 + float(g), h = 1 + 0.5f * float(g);
        const std::string x = std::to_string(x0), x1 = std::to_string(x0 + w), y1 = std::to_string(2 + h);
        scene += "Patch \"bilinear\" \"P\" [" + x + " 2 1  " + x1 + " 2 1  " + x + " " + y1 + " 1  " + x1 + " " + y1 + " 1]\n";
    }
    const std::string rib = shaders.option() + test::orthographicView(48, 12, "WorldBegin\n" + scene + "WorldEnd\n");
    RenderOptions on = test::optionsFor(Algorithm::Spacetime), off = on;
    on.threads = off.threads = 1;
    off.shadeBatching = false;
    const test::RenderResult batched = test::renderRib(rib, on), alone = test::renderRib(rib, off);
    EXPECT_TRUE(test::identicalPixels(batched, alone));
    EXPECT_GT(test::alphaSum(alone), 50.0);  // the patches are there (69.5 pixels)
    EXPECT_EQ(batched.stats.counters.shadingBatchRuns, 1u);
    EXPECT_EQ(batched.stats.counters.shadingBatchedGrids, 6u);
    EXPECT_EQ(batched.stats.counters.pointsShadedSurface, alone.stats.counters.pointsShadedSurface);
}

// Slots at other times share a run where the runs see the same spaces (a still camera, lights
// and shader space; only the patches move): the moving patches' two slots (shutter open and
// close) in one run, the pixels those of one run a grid. A shader that reads `time` is run
// once a time.
TEST(ShadeBatching, SlotsAtOtherTimesShareARunUnlessTheShaderReadsTime) {
    test::ShaderDir shaders;
    shaders.add("rates", kRates);
    shaders.add("clock", R"(surface clock() {
    normal n = normalize(calculatenormal(P));
    Ci = color(time, 40 * du, 0.5 + 0.5 * zcomp(n)) + color(0, 0, area(P) * 0.02);
    Oi = 1;
})");
    for (const char* surface : {"rates", "clock"}) {
        SCOPED_TRACE(surface);
        std::string scene = "LightSource \"distantlight\" 1 \"from\" [0 0 -1] \"to\" [0 0 0]\n";
        scene += std::string("Surface \"") + surface + "\"\nColor [0.5 0.7 0.4]\n";
        for (int g = 0; g < 6; ++g) {
            const float x0 = 1 + 7.5f * float(g), w = 2 + float(g), h = 1 + 0.5f * float(g);
            const std::string x = std::to_string(x0), x1 = std::to_string(x0 + w), y1 = std::to_string(2 + h);
            scene += "MotionBegin [0 1]\nTranslate 0 0 0\nTranslate 0.4 " + std::to_string(0.3 * g) +
                     " 0\nMotionEnd\nPatch \"bilinear\" \"P\" [" + x + " 2 1  " + x1 + " 2 1  " + x + " " + y1 + " 1  " + x1 + " " +
                     y1 + " 1]\nIdentity\n";
        }
        const std::string rib =
            shaders.option() + test::orthographicView(48, 12, "Shutter 0 1\nWorldBegin\n" + scene + "WorldEnd\n");
        RenderOptions on = test::optionsFor(Algorithm::Spacetime), off = on;
        on.threads = off.threads = 1;
        off.shadeBatching = false;
        const test::RenderResult batched = test::renderRib(rib, on), alone = test::renderRib(rib, off);
        EXPECT_TRUE(test::identicalPixels(batched, alone));
        EXPECT_GT(test::alphaSum(alone), 50.0);
        const bool readsTime = surface[0] == 'c';
        EXPECT_EQ(batched.stats.counters.shadingBatchRuns, readsTime ? 2u : 1u);
        EXPECT_EQ(batched.stats.counters.shadingBatchedGrids, 12u);  // six grids, two slots each
    }
}

// With a tolerance, occlusion culling is not exact and a batch sampled later could move what is
// culled: nothing is batched then.
TEST(ShadeBatching, NotWithAnOcclusionTolerance) {
    test::ShaderDir shaders;
    shaders.add("slopes", kSlopes);
    std::ofstream(shaders.dir.path() + "/leaf.sl") << std::ifstream(test::sourcePath("shaders/leaf.sl")).rdbuf();
    RenderOptions o = test::optionsFor(Algorithm::SpacetimeOcclusion);
    o.tolerance = 0.01;
    EXPECT_EQ(test::renderRib(leafField(shaders, 3), o).stats.counters.shadingBatchRuns, 0u);
}

}  // namespace
}  // namespace streyes
