// A shader's "shader" and "object" spaces as the RI Spec defines them (3.2, section 4.1): "shader"
// space is the coordinate system current where the shader was declared (Surface, Displacement,
// Atmosphere, LightSource); "object" space is that of the primitive being shaded, its CTM where it
// was given. A quad drawn after a Translate, Scale or Rotate that follows `Surface` reads both, as
// colours, against the closed form; a moving primitive's "object" space moves with it, and a frame
// alone equals the frame in a block. Aqsis 1.8.4 renders the same (checked by hand on its own RIB).
#include <gtest/gtest.h>

#include <string>

#include "shader_test_util.h"

namespace streyes {
namespace {

// An orthographic 16 x 16 view one unit a pixel, samples at the centres of 2 x 2 strata (jitter
// 0): a pixel's mean of a colour linear in position is its value at the pixel's centre.
std::string header(const test::ShaderDir& dir, const std::string& extra = "") {
    return test::orthoHeader(16, 16, "PixelSamples 2 2\nHider \"hidden\" \"jitter\" 0\n" + dir.option() + extra);
}

// A quad at z = 0 of its own space covering the view whatever transform places it.
const char* kQuad = "Polygon \"P\" [-100 -100 0  100 -100 0  100 100 0  -100 100 0]\n";

// A pixel's centre in camera space: x rightwards, y upwards (row 0 is the top).
double centreX(int x) { return x + 0.5; }
double centreY(int y) { return 16 - (y + 0.5); }

// Writes the point P in `space` as the colour (x, y, z) / 16.
void addSpaceShader(const test::ShaderDir& dir, const std::string& name, const std::string& space) {
    dir.add(name, "surface " + name + "() { point q = transform(\"" + space + "\", P) / 16; Oi = 1;\n"
                  "  Ci = color(xcomp(q), ycomp(q), zcomp(q)); }\n");
}

// Surface declared under Translate 0 0 5; the quad under a further Translate 3 2 1, Scale 2 0.5 1
// and Rotate 90 about z (which takes x to y and y to -x). A camera point (X, Y, 6) on the quad is
// in the surface's "shader" space (X, Y, 1), and in the quad's "object" space o with
// (-2 o.y, 0.5 o.x) + (3, 2) = (X, Y): o = (2 (Y - 2), (3 - X) / 2, 0).
TEST(ShaderSpaces, ObjectSpaceIsThePrimitivesAndShaderSpaceTheShaders) {
    const test::ShaderDir dir("shaderspaces");
    addSpaceShader(dir, "objectp", "object");
    addSpaceShader(dir, "shaderp", "shader");
    for (const Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
        for (const std::string space : {"object", "shader"}) {
            SCOPED_TRACE(std::string(algorithmName(a)) + " " + space);
            const std::string rib = header(dir) + "Translate 0 0 5\nSurface \"" + space + "p\"\n" +
                                    "Translate 3 2 1\nScale 2 0.5 1\nRotate 90 0 0 1\n" + kQuad + "WorldEnd\n";
            const test::RenderResult r = test::renderRib(rib, test::optionsFor(a));
            EXPECT_TRUE(r.warnings.empty()) << (r.warnings.empty() ? "" : r.warnings.front());
            for (int y : {0, 5, 11, 15})
                for (int x : {0, 4, 9, 15}) {
                    const double X = centreX(x), Y = centreY(y);
                    const double want[3] = {space == "object" ? 2 * (Y - 2) : X, space == "object" ? (3 - X) / 2 : Y,
                                            space == "object" ? 0.0 : 1.0};
                    for (int c = 0; c < 3; ++c)
                        EXPECT_NEAR(r.channel(0, x, y, c), want[c] / 16, 1e-4) << "pixel " << x << " " << y << " channel " << c;
                }
        }
    }
}

// The surface's other shaders see the same spaces: a displacement that moves P by its "object"
// x along the camera's z leaves a quad whose depth tells it (z = 6 + o.x / 16 with o as above; a
// pixel's depth is its nearest sample's, the one a quarter pixel lower in y).
TEST(ShaderSpaces, DisplacementReadsThePrimitivesObjectSpace) {
    const test::ShaderDir dir("shaderspacesdisp");
    dir.add("push", "displacement push() { point q = transform(\"object\", P); P += vector(0, 0, xcomp(q) / 16); }\n");
    const std::string rib = header(dir) +
                            "Translate 0 0 5\nDisplacement \"push\"\nAttribute \"displacementbound\" \"float sphere\" [2]\n"
                            "Translate 3 2 1\nScale 2 0.5 1\nRotate 90 0 0 1\n" + std::string(kQuad) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_TRUE(r.warnings.empty()) << (r.warnings.empty() ? "" : r.warnings.front());
    for (int y : {1, 8, 14})
        for (int x : {2, 7, 13}) {
            const double ox = 2 * (centreY(y) - 0.25 - 2);
            EXPECT_NEAR(r.z(0, x, y), 6 + ox / 16, 2e-3) << "pixel " << x << " " << y;
        }
}

// A quad moving 1 unit a frame in x (MotionBegin over the shot) under a surface declared before
// the motion: its "object" x at camera X in frame f is X - f, its "shader" x is X. With the
// surface declared after the motion, "shader" space moves too (X - f). An instant shutter, so
// that a pixel reads one time; frame 3 alone equals frame 3 of the block, bit for bit.
TEST(ShaderSpaces, AMovingPrimitivesObjectSpaceMovesWithIt) {
    const test::ShaderDir dir("shaderspacesmotion");
    dir.add("both", "surface both() { Oi = 1; Ci = color(xcomp(transform(\"object\", P)), "
                    "xcomp(transform(\"shader\", P)), 0) / 16; }\n");
    const std::string motion = "MotionBegin [0 7]\nTranslate 0 0 0\nTranslate 7 0 0\nMotionEnd\n";
    for (const bool surfaceAfter : {false, true}) {
        SCOPED_TRACE(surfaceAfter ? "Surface after the motion" : "Surface before the motion");
        const std::string rib = "Option \"streyes\" \"int frames\" [0 7]\nShutter 0 0\n" + header(dir) +
                                "Translate 0 0 5\n" + (surfaceAfter ? motion + "Surface \"both\"\n" : "Surface \"both\"\n" + motion) +
                                kQuad + "WorldEnd\n";
        for (const Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Raytrace}) {
            SCOPED_TRACE(algorithmName(a));
            const test::ShotAndFrame r = test::renderShotAndFrame(rib, test::optionsFor(a), 0, 7, 3);
            EXPECT_TRUE(r.samePixels(3));
            for (int f : {0, 3, 7})
                for (int x : {1, 6, 12}) {
                    const double X = centreX(x);
                    EXPECT_NEAR(r.shot.channel(f, x, 8, 0), (X - f) / 16, 1e-4) << "frame " << f << " pixel " << x;
                    EXPECT_NEAR(r.shot.channel(f, x, 8, 1), (surfaceAfter ? X - f : X) / 16, 1e-4)
                        << "frame " << f << " pixel " << x;
                }
        }
    }
}

// Primitives under one Surface each read their own "object" space (a material of its own per
// primitive when the shader names "object"), and all the surface's "shader" space.
TEST(ShaderSpaces, EachPrimitiveUnderOneSurfaceReadsItsOwnObjectSpace) {
    const test::ShaderDir dir("shaderspacesshare");
    addSpaceShader(dir, "objectp", "object");
    addSpaceShader(dir, "shaderp", "shader");
    for (const std::string space : {"object", "shader"}) {
        SCOPED_TRACE(space);
        std::string rib = header(dir) + "Translate 0 0 5\nSurface \"" + space + "p\"\n";
        // Four quads side by side, each under its own Translate: 4 x 16 pixels each.
        for (int i = 0; i < 4; ++i)
            rib += "TransformBegin\nTranslate " + std::to_string(4 * i) + " 0 0\n"
                   "Polygon \"P\" [0 0 0  4 0 0  4 16 0  0 16 0]\nTransformEnd\n";
        rib += "WorldEnd\n";
        const test::RenderResult r = test::renderRib(rib);
        for (int i = 0; i < 4; ++i) {
            const int x = 4 * i + 1;
            const double want = space == "object" ? centreX(x) - 4 * i : centreX(x);
            EXPECT_NEAR(r.channel(0, x, 7, 0), want / 16, 1e-4) << "quad " << i;
        }
    }
}

}  // namespace
}  // namespace streyes
