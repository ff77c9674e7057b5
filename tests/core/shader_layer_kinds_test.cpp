// ShaderLayer / ConnectShaderLayers for displacements and imagers (shade/layer_network.h): a
// displacement's layers run in order, each from the P and N the one before left; an imager's over
// the image, each from the Ci, Oi and alpha the one before left. Closed forms: layers that move
// a and b along N are one shader moving a + b; a connection carries the value computed; the ray
// tracer and a frame alone see the layered displacement as a block of frames does.
#include <gtest/gtest.h>

#include <cmath>

#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

// Moves every point `a` along its normal; `next` is twice `a` (for a connection).
const char* kAlong =
    "displacement along(float a = 0; output uniform float next = 0) {\n"
    "  P += a * normalize(N);\n  N = calculatenormal(P);\n  next = 2 * a;\n}\n";
// Moves every point towards the camera by d + k * time (a displacement that changes per frame).
// Moves every point `a` along its normal and leaves N: the next layer starts from the same N.
const char* kPush = "displacement push(float a = 0) { P += a * normalize(N); }\n";
const char* kLiftLayer =
    "displacement liftlayer(float d = 0, k = 0) { P += vector(0, 0, -(d + k * time)); N = calculatenormal(P); }\n";

test::ShaderDir displacementShaders() {
    test::ShaderDir d{"layerkinds"};
    d.add("along", kAlong);
    d.add("push", kPush);
    d.add("liftlayer", kLiftLayer);
    return d;
}

// A 32 x 32 frame of the plane [0, 32]^2 at depth 10 (camera facing), displaced by `displacement`.
std::string planeScene(const test::ShaderDir& d, const std::string& displacement) {
    return test::orthographicView(32, 32, d.option()) + "WorldBegin\nSurface \"constant\"\n" +
           "Attribute \"displacementbound\" \"sphere\" [8]\n" + displacement + test::square(0, 32, 0, 32, 10) +
           "WorldEnd\n";
}

// A cylinder of radius 10 and height 40 about the vertical through the middle of a 64 x 64
// frame, 50 away, displaced by `displacement` (a cylinder has no pole where N is 0).
std::string cylinderScene(const test::ShaderDir& d, const std::string& displacement) {
    return test::orthographicView(64, 64, d.option()) + "WorldBegin\nSurface \"constant\"\n" +
           "Attribute \"displacementbound\" \"sphere\" [8]\n" + displacement +
           "Translate 32 32 50\nRotate 90 1 0 0\nCylinder 10 -20 20 360\nWorldEnd\n";
}

TEST(ShaderLayerKinds, TwoDisplacementLayersAlongNAreOneShaderMovingTheSum) {
    const test::ShaderDir d = displacementShaders();
    const std::string layers = "ShaderLayer \"displacement\" \"along\" \"first\" \"float a\" [2]\n"
                               "ShaderLayer \"displacement\" \"along\" \"second\" \"float a\" [4]\n";
    const std::string one = "Displacement \"along\" \"float a\" [6]\n";
    // A plane: N is exactly (0, 0, +-1), so the sums are exact and the renders bit-identical; the
    // plane moves 6 along z.
    const test::RenderResult plane2 = test::renderRib(planeScene(d, layers));
    const test::RenderResult plane1 = test::renderRib(planeScene(d, one));
    EXPECT_TRUE(plane2.warnings.empty()) << plane2.warnings.front();
    EXPECT_TRUE(test::identicalPixels(plane2, plane1));
    EXPECT_EQ(std::fabs(plane2.z(0, 16, 16) - 10.0f), 6.0f);
    // A cylinder of radius 10 grown to 16 by layers that keep N (push: calculatenormal's N at a
    // grid's edge is a chord's, so layers that recompute it move the next layer's points along
    // another direction than one shader does): the one-shader render within float rounding, its
    // outline the rectangle 32 x 40 (the diced chords lie inside the circle: 1.7% less measured),
    // its nearest line 16 in front of its axis (within the chords' sagitta).
    const test::RenderResult cylinder2 = test::renderRib(
        cylinderScene(d, "ShaderLayer \"displacement\" \"push\" \"first\" \"float a\" [2]\n"
                         "ShaderLayer \"displacement\" \"push\" \"second\" \"float a\" [4]\n"));
    const test::RenderResult cylinder1 = test::renderRib(cylinderScene(d, "Displacement \"push\" \"float a\" [6]\n"));
    EXPECT_TRUE(cylinder2.warnings.empty()) << cylinder2.warnings.front();
    EXPECT_LE(test::maxAbsDifference(cylinder2, cylinder1), 1e-6f);
    EXPECT_NEAR(test::alphaSum(cylinder2), 32 * 40, 0.025 * 32 * 40);
    EXPECT_NEAR(cylinder2.z(0, 32, 32), 50 - 16, 0.05);
}

TEST(ShaderLayerKinds, AConnectionBetweenDisplacementLayersCarriesTheValueComputed) {
    const test::ShaderDir d = displacementShaders();
    // The first layer moves 2 and passes next = 4 to the second's a: 6 in all.
    const std::string layers = "ShaderLayer \"displacement\" \"along\" \"first\" \"float a\" [2]\n"
                               "ShaderLayer \"displacement\" \"along\" \"second\"\n"
                               "ConnectShaderLayers \"displacement\" \"first\" \"next\" \"second\" \"a\"\n";
    const test::RenderResult r = test::renderRib(planeScene(d, layers));
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    EXPECT_TRUE(test::identicalPixels(r, test::renderRib(planeScene(d, "Displacement \"along\" \"float a\" [6]\n"))));
    EXPECT_EQ(std::fabs(r.z(0, 16, 16) - 10.0f), 6.0f);
    // Unconnected, the second layer keeps a = 0: the plane moves 2.
    const std::string unconnected = "ShaderLayer \"displacement\" \"along\" \"first\" \"float a\" [2]\n"
                                    "ShaderLayer \"displacement\" \"along\" \"second\"\n";
    EXPECT_EQ(std::fabs(test::renderRib(planeScene(d, unconnected)).z(0, 16, 16) - 10.0f), 2.0f);
}

TEST(ShaderLayerKinds, AMissingDisplacementLayerIsWarnedAboutOnceAndLeftOut) {
    const test::ShaderDir d = displacementShaders();
    const std::string layers = "ShaderLayer \"displacement\" \"along\" \"first\" \"float a\" [2]\n"
                               "ShaderLayer \"displacement\" \"nosuchlayer\" \"second\"\n"
                               "ConnectShaderLayers \"displacement\" \"first\" \"next\" \"second\" \"a\"\n";
    const test::RenderResult r = test::renderRib(planeScene(d, layers));
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("nosuchlayer"), std::string::npos) << r.warnings[0];
    EXPECT_TRUE(test::identicalPixels(r, test::renderRib(planeScene(d, "Displacement \"along\" \"float a\" [2]\n"))));
    // A Displacement request replaces the layers.
    const test::RenderResult replaced =
        test::renderRib(planeScene(d, "ShaderLayer \"displacement\" \"along\" \"first\" \"float a\" [2]\n"
                                      "Displacement \"along\" \"float a\" [5]\n"));
    EXPECT_EQ(std::fabs(replaced.z(0, 16, 16) - 10.0f), 5.0f);
}

// A last layer that does not name what the layers carry (P, N; Oi) takes it from the layer
// before: not from the grid's input.
TEST(ShaderLayerKinds, ALastLayerThatDoesNotNameACarriedVariableKeepsTheOneBefore) {
    test::ShaderDir d = displacementShaders();
    d.add("idle", "displacement idle(output varying float seen = 0) { seen = 1; }\n");
    d.add("halfopaque", "surface halfopaque() { Ci = 0.25; Oi = 0.5; }\n");
    d.add("tint", "surface tint() { Ci = color(1, 0, 0); }\n");
    const test::RenderResult r = test::renderRib(planeScene(d, "ShaderLayer \"displacement\" \"along\" \"first\" \"float a\" [2]\n"
                                                               "ShaderLayer \"displacement\" \"idle\" \"second\"\n"));
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    EXPECT_EQ(std::fabs(r.z(0, 16, 16) - 10.0f), 2.0f);
    const test::RenderResult s = test::renderRib(test::orthographicView(8, 8, d.option()) + "WorldBegin\n" +
                                                 "ShaderLayer \"surface\" \"halfopaque\" \"first\"\n"
                                                 "ShaderLayer \"surface\" \"tint\" \"second\"\n" +
                                                 test::square(0, 8, 0, 8, 10) + "WorldEnd\n");
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_EQ(s.alpha(0, 4, 4), 0.5f);
}

// The roof of tests/core/displaced_trace_test.cpp lifted by two layers, 2 and 2 * time: the ray
// tracer's hits lie on it (110 - 2 - 2 f in frame f), and frame 2 alone is frame 2 of the shot.
TEST(ShaderLayerKinds, ALayeredDisplacementIsTracedAndAFrameAloneIsTheFrameInABlock) {
    test::ShaderDir d = displacementShaders();
    d.add("probe", "surface probe() {\n  point hp = 0;\n  float hits = 0, height = 0;\n"
                   "  gather(\"\", P, vector(0, 0, 1), 0, 1, \"surface:P\", hp, \"bias\", 0.001) {\n"
                   "    hits += 1;\n    height += zcomp(hp);\n  }\n"
                   "  Ci = color(height / max(hits, 1), hits, 0);\n  Oi = 1;\n}\n");
    const std::string rib = test::orthographicView(8, 8, d.option()) + "WorldBegin\nAttributeBegin\n" +
                            "Surface \"constant\"\nAttribute \"displacementbound\" \"sphere\" [12]\n" +
                            "ShaderLayer \"displacement\" \"liftlayer\" \"still\" \"float d\" [2]\n" +
                            "ShaderLayer \"displacement\" \"liftlayer\" \"moving\" \"float k\" [2]\n" +
                            test::square(-12, 20, -12, 20, 110) + "AttributeEnd\nSurface \"probe\"\n" +
                            test::square(0, 8, 0, 8, 100) + "WorldEnd\n";
    RenderOptions o;
    o.hasFrames = true;
    o.hasShot = true;
    o.shotFirst = 0;
    o.shotLast = 3;
    for (Algorithm a : {Algorithm::Spacetime, Algorithm::Frames}) {
        SCOPED_TRACE(test::testName(a));
        o.algorithm = a;
        const test::ShotAndFrame r = test::renderShotAndFrame(rib, o, 0, 3, 2);
        EXPECT_TRUE(r.shot.warnings.empty()) << r.shot.warnings.front();
        EXPECT_TRUE(r.samePixels(2)) << "frame 2 alone differs from frame 2 of the shot";
        for (int f = 0; f <= 3; ++f) {
            EXPECT_EQ(r.shot.channel(f, 4, 4, 1), 1.0f) << "frame " << f;  // the ray hit the roof
            EXPECT_NEAR(r.shot.channel(f, 4, 4, 0), 110 - 2 - 2 * f, 1e-3) << "frame " << f;
        }
    }
}

// Two imager layers: Ci halved, then `amount` added (0.25, or connected from the first layer).
test::ShaderDir imagerShaders() {
    test::ShaderDir d{"imagerlayers"};
    d.add("halve", "imager halve(output uniform float lift = 0.125) { Ci *= 0.5; }\n");
    d.add("addto", "imager addto(uniform float amount = 0) { Ci += amount; }\n");
    return d;
}

// An 8 x 8 frame whose left half is a constant surface of colour (0.5, 0.25, 1).
test::RenderResult imagerRender(const test::ShaderDir& d, const std::string& imager) {
    return test::renderRib(test::orthographicView(8, 8, d.option() + imager) +
                           "WorldBegin\nSurface \"constant\"\nColor [0.5 0.25 1]\n" + test::square(0, 4, 0, 8, 10) +
                           "WorldEnd\n");
}

TEST(ShaderLayerKinds, ImagerLayersRunInOrderOverTheImage) {
    const test::ShaderDir d = imagerShaders();
    const test::RenderResult r = imagerRender(d, "ShaderLayer \"imager\" \"halve\" \"scale\"\n"
                                                 "ShaderLayer \"imager\" \"addto\" \"offset\" \"float amount\" [0.25]\n");
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    for (int py = 0; py < 8; ++py)
        for (int px = 0; px < 8; ++px) {
            const bool covered = px < 4;
            const float c[3] = {0.5f, 0.25f, 1.0f};
            for (int k = 0; k < 3; ++k)
                EXPECT_EQ(r.channel(0, px, py, k), covered ? c[k] * 0.5f + 0.25f : 0.25f) << px << " " << py << " " << k;
            EXPECT_EQ(r.alpha(0, px, py), covered ? 1.0f : 0.0f) << px << " " << py;  // carried through both
        }
    // Connected: the first layer's lift (0.125) is the second's amount.
    const test::RenderResult c = imagerRender(d, "ShaderLayer \"imager\" \"halve\" \"scale\"\n"
                                                 "ShaderLayer \"imager\" \"addto\" \"offset\"\n"
                                                 "ConnectShaderLayers \"imager\" \"scale\" \"lift\" \"offset\" \"amount\"\n");
    EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
    EXPECT_EQ(c.channel(0, 1, 1, 0), 0.25f + 0.125f);
    EXPECT_EQ(c.channel(0, 6, 1, 0), 0.125f);
}

TEST(ShaderLayerKinds, AMissingImagerLayerIsWarnedAboutOnceAndLeftOut) {
    const test::ShaderDir d = imagerShaders();
    const test::RenderResult r = imagerRender(d, "ShaderLayer \"imager\" \"nosuchimager\" \"scale\"\n"
                                                 "ShaderLayer \"imager\" \"addto\" \"offset\" \"float amount\" [0.25]\n");
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("nosuchimager"), std::string::npos) << r.warnings[0];
    EXPECT_EQ(r.channel(0, 1, 1, 0), 0.5f + 0.25f);
    EXPECT_EQ(r.channel(0, 6, 1, 0), 0.25f);
    // Inside the world an imager layer is an option in the wrong place: warned and ignored.
    const test::RenderResult late = test::renderRib(
        test::orthographicView(8, 8, d.option()) + "WorldBegin\nSurface \"constant\"\n" +
        "ShaderLayer \"imager\" \"halve\" \"scale\"\n" + test::square(0, 4, 0, 8, 10) + "WorldEnd\n");
    ASSERT_EQ(late.warnings.size(), 1u);
    EXPECT_NE(late.warnings[0].find("belongs before WorldBegin"), std::string::npos) << late.warnings[0];
    EXPECT_EQ(late.channel(0, 1, 1, 0), 1.0f);
}

}  // namespace
}  // namespace streyes
