// indirectdiffuse()'s "environmentmap": a ray that hits nothing brings the map's colour in its
// direction (in "environmentspace" when given, else current space), and ray-traced occlusion()'s
// "environmentcolor" output (the map its unoccluded rays see), against closed forms. The
// maps are analytic (a texture source of the test's own), so the answers are the integrals of
// the cosine-weighted hemisphere over them: a constant c gives c, a cap of half-angle a about
// the normal sin^2 a.
//
// The camera is orthographic along +z, one unit a pixel; the floor faces +z (away from the eye)
// for its rays, as in shader_rays_test.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "shade/vm/texture_source.h"
#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

constexpr float kCapCos = 0.5f;  // the cap's half-angle: 60 degrees

// "constant.env": (0.2, 0.5, 0.9) everywhere. "cap.env": 1 within 60 degrees of +z, else 0.
// "upper.env": 1 where z > 0, else 0.25. Other names cannot be read.
class AnalyticSkies final : public sl::TextureSource {
  public:
    bool texture(const std::string&, const sl::TextureOptions&, const sl::TextureQuery&, float* const*) override {
        return false;
    }
    bool shadow(const std::string&, const sl::TextureOptions&, const sl::DirectionQuery&, float* const*) override {
        return false;
    }
    bool environment(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q,
                     float* const* out) override {
        if (name != "constant.env" && name != "cap.env" && name != "upper.env") return false;
        for (int i = 0; i < q.n; ++i) {
            if (q.active && !q.active[i]) continue;
            const double x = q.R[0][i], y = q.R[1][i], z = q.R[2][i];
            const double cz = z / std::sqrt(x * x + y * y + z * z);
            float c[3] = {0.2f, 0.5f, 0.9f};
            if (name == "cap.env") c[0] = c[1] = c[2] = cz > kCapCos ? 1.0f : 0.0f;
            if (name == "upper.env") c[0] = c[1] = c[2] = cz > 0 ? 1.0f : 0.25f;
            for (int k = 0; k < o.channels; ++k) out[k][i] = c[o.firstChannel + k];
        }
        return true;
    }
};

RenderOptions withSkies() {
    RenderOptions o;
    o.textureSource = [](const std::vector<std::string>&, Log&) { return std::make_shared<AnalyticSkies>(); };
    return o;
}

constexpr int kN = 8;

// A white floor lit by indirectdiffuse() with `options` (after the sample count).
test::RenderResult litFloor(const std::string& options, const std::string& extra = "") {
    test::ShaderDir d;
    d.add("gi", "surface gi() {\n  Ci = Cs * indirectdiffuse(P, normal(0, 0, 1), 256" + options + "); Oi = 1;\n}\n");
    return test::renderRib(test::orthographicView(kN, kN, d.option()) + "WorldBegin\n" + extra + "Surface \"gi\"\n" +
                               test::square(0, kN, 0, kN, 100) + "WorldEnd\n",
                           withSkies());
}

TEST(EnvironmentRays, AConstantEnvironmentGivesItsColour) {
    const test::RenderResult r = litFloor(", \"environmentmap\", \"constant.env\"");
    const float c[3] = {0.2f, 0.5f, 0.9f};
    for (int py = 0; py < kN; ++py)
        for (int px = 0; px < kN; ++px)
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.channel(0, px, py, k), c[k], 1e-5f) << px << " " << py;
    // Without the map, or with one that cannot be read, the misses are black.
    for (const char* o : {"", ", \"environmentmap\", \"nosuch.env\""}) {
        const test::RenderResult dark = litFloor(o);
        for (int py = 0; py < kN; ++py)
            for (int px = 0; px < kN; ++px) EXPECT_EQ(dark.channel(0, px, py, 0), 0.0f) << o;
    }
}

// A cap of half-angle 60 degrees about the normal: sin^2 60 = 3/4 of the cosine-weighted
// hemisphere (a uniform weighting would give 1 - cos 60 = 1/2). The mean over the floor within
// 1%; each pixel within four standard errors of 256 independent rays.
TEST(EnvironmentRays, ACapAboutTheNormalGivesSinSquaredOfItsAngle) {
    const test::RenderResult r = litFloor(", \"environmentmap\", \"cap.env\"");
    const double want = 1 - double(kCapCos) * kCapCos;
    const double se = std::sqrt(want * (1 - want) / 256);
    double sum = 0;
    for (int py = 0; py < kN; ++py)
        for (int px = 0; px < kN; ++px) {
            EXPECT_NEAR(r.channel(0, px, py, 0), want, 4 * se) << px << " " << py;
            sum += r.channel(0, px, py, 0);
        }
    EXPECT_NEAR(sum / (kN * kN), want, 0.01 * want);
}

// Hits and misses together: a white wall (constant) over half the hemisphere, the constant map
// over the other half: 1/2 + c/2 within the noise of 256 stratified rays.
TEST(EnvironmentRays, HitsAreShadedAndMissesBringTheMap) {
    const double L = 1000;
    const std::string wall = "AttributeBegin\nSurface \"constant\"\nPatch \"bilinear\" \"P\" [4.5 -1000 0 4.5 1000 0 4.5 -1000 " +
                             std::to_string(L) + " 4.5 1000 " + std::to_string(L) + "]\nAttributeEnd\n";
    const test::RenderResult r = litFloor(", \"environmentmap\", \"constant.env\", \"bias\", 0.001", wall);
    const float c[3] = {0.2f, 0.5f, 0.9f};
    for (int py = 0; py < kN; ++py)
        for (int px = 0; px < kN; ++px)
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(r.channel(0, px, py, k), 0.5f + 0.5f * c[k], 4 * 0.5f / 16) << px << " " << py;
}

// indirectdiffuse()'s "occlusion" output: the share of its rays that hit something, written by
// the same call: 1/2 under the wall over half the hemisphere (within the noise of 256 stratified
// rays, as above), 0 under the open sky, whatever the map.
TEST(EnvironmentRays, TheOcclusionOutputIsTheShareOfRaysThatHit) {
    const std::string wall = "AttributeBegin\nSurface \"constant\"\nPatch \"bilinear\" \"P\" [4.5 -1000 0 4.5 1000 0 4.5 -1000 1000 4.5 1000 1000]\nAttributeEnd\n";
    auto render = [](const std::string& extra) {
        test::ShaderDir d;
        d.add("gio", "surface gio() {\n  float o = -1;\n"
                     "  color c = indirectdiffuse(P, normal(0, 0, 1), 256, \"environmentmap\", \"constant.env\", \"bias\", 0.001, "
                     "\"occlusion\", o);\n  Ci = color(o, comp(c, 2), 0); Oi = 1;\n}\n");
        return test::renderRib(test::orthographicView(kN, kN, d.option()) + "WorldBegin\n" + extra + "Surface \"gio\"\n" +
                                   test::square(0, kN, 0, kN, 100) + "WorldEnd\n",
                               withSkies());
    };
    const test::RenderResult walled = render(wall), open = render("");
    for (int py = 0; py < kN; ++py)
        for (int px = 0; px < kN; ++px) {
            EXPECT_NEAR(walled.channel(0, px, py, 0), 0.5f, 4 * 0.5f / 16) << px << " " << py;
            // The colour is what it was without the output: the map's blue where rays miss.
            EXPECT_NEAR(walled.channel(0, px, py, 1), 0.5f + 0.5f * 0.9f, 4 * 0.5f / 16) << px << " " << py;
            EXPECT_EQ(open.channel(0, px, py, 0), 0.0f) << px << " " << py;
            EXPECT_NEAR(open.channel(0, px, py, 1), 0.9f, 1e-5f) << px << " " << py;
        }
}

// "environmentspace" names the map's space: a coordinate system turned half a turn about x
// sees the floor's hemisphere (current +z) as its -z, where "upper.env" is 0.25; without it
// the map is read in current space, where the hemisphere is its upper half.
TEST(EnvironmentRays, TheEnvironmentSpaceTurnsTheDirections) {
    const std::string sky = "AttributeBegin\nRotate 180 1 0 0\nCoordinateSystem \"sky\"\nAttributeEnd\n";
    const test::RenderResult turned = litFloor(", \"environmentmap\", \"upper.env\", \"environmentspace\", \"sky\"", sky);
    const test::RenderResult plain = litFloor(", \"environmentmap\", \"upper.env\"", sky);
    for (int py = 0; py < kN; ++py)
        for (int px = 0; px < kN; ++px) {
            EXPECT_NEAR(turned.channel(0, px, py, 0), 0.25f, 1e-5f) << px << " " << py;
            EXPECT_NEAR(plain.channel(0, px, py, 0), 1.0f, 1e-5f) << px << " " << py;
        }
}

// Ray-traced occlusion()'s "environmentcolor": the map in the directions of the rays that hit
// nothing, over all the rays. Under the open sky of a constant map, the map itself (the rays'
// sum is exact: within 1e-6); in "environmentspace"; black without a map (the variable's -1 does
// not survive the call).
test::RenderResult occludedFloor(const std::string& options, const std::string& extra = "") {
    test::ShaderDir d;
    d.add("aoe", "surface aoe() {\n  color e = -1;\n"
                 "  float o = occlusion(P, normal(0, 0, 1), 256, \"bias\", 0.001" + options +
                     ", \"environmentcolor\", e);\n"
                 "  Ci = e; Oi = 1;\n}\n");
    return test::renderRib(test::orthographicView(kN, kN, d.option()) + "WorldBegin\n" + extra + "Surface \"aoe\"\n" +
                               test::square(0, kN, 0, kN, 100) + "WorldEnd\n",
                           withSkies());
}

TEST(EnvironmentRays, OcclusionsEnvironmentColourUnderTheOpenSkyIsTheMap) {
    const float c[3] = {0.2f, 0.5f, 0.9f};
    const std::string sky = "AttributeBegin\nRotate 180 1 0 0\nCoordinateSystem \"sky\"\nAttributeEnd\n";
    const test::RenderResult constant = occludedFloor(", \"environmentmap\", \"constant.env\"");
    const test::RenderResult turned = occludedFloor(", \"environmentmap\", \"upper.env\", \"environmentspace\", \"sky\"", sky);
    const test::RenderResult none = occludedFloor("");
    for (int py = 0; py < kN; ++py)
        for (int px = 0; px < kN; ++px)
            for (int k = 0; k < 3; ++k) {
                EXPECT_NEAR(constant.channel(0, px, py, k), c[k], 1e-6f) << px << " " << py;
                EXPECT_NEAR(turned.channel(0, px, py, k), 0.25f, 1e-6f) << px << " " << py;
                EXPECT_EQ(none.channel(0, px, py, k), 0.0f) << px << " " << py;
            }
}

// Under a half-open box (a roof 16 over the floor and two walls; open at two sides) the same
// call's occlusion o and colour e: e = c (1 - o) at every pixel within rounding, for a constant
// map c, and the box covers most of the sky (a dropped face or a colour from hit rays would show).
TEST(EnvironmentRays, OcclusionsEnvironmentColourIsTheMapTimesTheOpenShareOfTheSameRays) {
    constexpr int W = 16;
    const double f = 100, roof = 116, x0 = -0.05, x1 = W + 0.05;
    auto wall = [&](double x) {
        return "Patch \"bilinear\" \"P\" [" + std::to_string(x) + " 0 " + std::to_string(f) + " " + std::to_string(x) + " " +
               std::to_string(W) + " " + std::to_string(f) + " " + std::to_string(x) + " 0 " + std::to_string(roof) + " " +
               std::to_string(x) + " " + std::to_string(W) + " " + std::to_string(roof) + "]\n";
    };
    const std::string box = "AttributeBegin\nSurface \"constant\"\n" + test::square(x0, x1, 0, W, roof) + wall(x0) + wall(x1) +
                            "AttributeEnd\n";
    test::ShaderDir d;
    d.add("aoe", "surface aoe() {\n  color e = -1;\n"
                 "  float o = occlusion(P, normal(0, 0, 1), 256, \"bias\", 0.001, \"environmentmap\", \"constant.env\", "
                 "\"environmentcolor\", e);\n"
                 "  Ci = color(o, comp(e, 0) - 0.2 * (1 - o), comp(e, 2) - 0.9 * (1 - o)); Oi = 1;\n}\n");
    const test::RenderResult r = test::renderRib(
        test::orthographicView(W, W, d.option()) + "WorldBegin\n" + box + "Surface \"aoe\"\n" + test::square(0, W, 0, W, f) + "WorldEnd\n",
        withSkies());
    double sum = 0;
    int partly = 0;
    for (int py = 0; py < W; ++py)
        for (int px = 0; px < W; ++px) {
            const float o = r.channel(0, px, py, 0);
            sum += o;
            partly += o > 0 && o < 1;
            EXPECT_NEAR(r.channel(0, px, py, 1), 0.0f, 1e-6f) << px << " " << py;
            EXPECT_NEAR(r.channel(0, px, py, 2), 0.0f, 1e-6f) << px << " " << py;
        }
    EXPECT_GT(sum / (W * W), 0.5);
    EXPECT_EQ(partly, W * W);  // every pixel sees some of the sky and some of the box
}

// A square moving over the floor's sky, frame by frame, with the colour output in use: each
// frame's is its own and the same whatever the block renders it.
TEST(EnvironmentRays, OcclusionsEnvironmentColourIsTheSameWhateverTheBlock) {
    test::ShaderDir d;
    d.add("aoe", "surface aoe() {\n  color e = 0;\n"
                 "  float o = occlusion(P, normal(0, 0, 1), 32, \"environmentmap\", \"cap.env\", \"environmentcolor\", e);\n"
                 "  Ci = e; Oi = 1;\n}\n");
    const std::string rib = test::orthographicView(32, 8, d.option() + "Hider \"hidden\" \"jitter\" [0]\nPixelSamples 1 1\n") +
                            "Shutter 0 0\nFrameBegin 0\nWorldBegin\nAttributeBegin\nSurface \"constant\"\n"
                            "MotionBegin [0 3]\nTranslate 0 0 0\nTranslate 24 0 0\nMotionEnd\n" +
                            test::square(-4, 4, 0, 8, 104) + "AttributeEnd\nSurface \"aoe\"\n" + test::square(0, 32, 0, 8, 100) +
                            "WorldEnd\nFrameEnd\n";
    RenderOptions o = withSkies();
    o.hasFrames = true;
    o.hasShot = true;
    o.shotFirst = 0;
    o.shotLast = 3;
    const test::ShotAndFrame r = test::renderShotAndFrame(rib, o, 0, 3, 2);
    EXPECT_TRUE(r.samePixels(2)) << "frame 2 alone differs from frame 2 of the shot";
    // Under the square (x in [-4, 4] + 8 t) the cap is hidden: frame 0 has it over pixel 2, frame 3 over 26.
    EXPECT_LT(r.shot.channel(0, 2, 4, 0), r.shot.channel(3, 2, 4, 0) - 0.2f);
    EXPECT_LT(r.shot.channel(3, 26, 4, 0), r.shot.channel(0, 26, 4, 0) - 0.2f);
}

}  // namespace
}  // namespace streyes
