// ShaderLayer / ConnectShaderLayers: a surface made of layers run in order over the grid, a
// layer's output connected to a later layer's parameter or to a predefined variable, Ci and Oi
// carried from layer to layer; connections that cannot be made warned about (file:line) and left
// out, an error under --strict.
#include <gtest/gtest.h>

#include <fstream>

#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

// An 8 x 8 square filling the frame, u along x and v along y (up): with jitter 0 each pixel's
// samples are symmetric about its centre, so a colour linear in s and t averages to its value
// at the centre, s = (px + 0.5) / 8, t = 1 - (py + 0.5) / 8.
std::string view(const test::ShaderDir& d) {
    return "Format 8 8 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 8\nPixelFilter \"box\" 1 1\n"
           "PixelSamples 2 2\nHider \"hidden\" \"jitter\" [0]\n" +
           d.option();
}
const std::string kSquare = test::square(0, 8, 0, 8, 10);

test::ShaderDir layerShaders() {
    test::ShaderDir d{"layers"};
    // Layer 1: a gradient in an output, and Ci and Oi of its own.
    d.add("gradient", "surface gradient(float scale = 1; output varying color Cout = 0) {\n"
                      "  Cout = color(s * scale, t, 0.25);\n  Ci = 0.125;\n  Oi = 1;\n}\n");
    // Layer 2: its input scaled, plus the Ci the layer before left.
    d.add("mixer", "surface mixer(varying color Cin = color(1, 0, 1); float gain = 1) {\n"
                   "  Ci = Cin * gain + Ci;\n}\n");
    return d;
}

float s(int px) { return (float(px) + 0.5f) / 8; }
float t(int py) { return 1 - (float(py) + 0.5f) / 8; }

TEST(ShaderLayer, TheSecondLayerReadsTheFirstsOutputAndCi) {
    const test::ShaderDir d = layerShaders();
    const std::string rib = view(d) + "WorldBegin\n"
                            "ShaderLayer \"surface\" \"gradient\" \"base\" \"float scale\" [2]\n"
                            "ShaderLayer \"surface\" \"mixer\" \"top\" \"float gain\" [0.5]\n"
                            "ConnectShaderLayers \"surface\" \"base\" \"Cout\" \"top\" \"Cin\"\n" +
                            kSquare + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    for (int py = 0; py < 8; ++py)
        for (int px = 0; px < 8; ++px) {
            // Ci = Cout * gain + Ci of the first layer = (2s, t, 0.25) / 2 + 0.125.
            EXPECT_NEAR(r.channel(0, px, py, 0), s(px) + 0.125f, 1e-5) << px << " " << py;
            EXPECT_NEAR(r.channel(0, px, py, 1), 0.5f * t(py) + 0.125f, 1e-5) << px << " " << py;
            EXPECT_NEAR(r.channel(0, px, py, 2), 0.25f, 1e-5) << px << " " << py;
            EXPECT_FLOAT_EQ(r.alpha(0, px, py), 1.0f);  // Oi of the first layer, carried
        }
}

TEST(ShaderLayer, UnconnectedTheSecondLayerKeepsItsOwnValue) {
    const test::ShaderDir d = layerShaders();
    const std::string rib = view(d) + "WorldBegin\n"
                            "ShaderLayer \"surface\" \"gradient\" \"base\"\n"
                            "ShaderLayer \"surface\" \"mixer\" \"top\"\n" +
                            kSquare + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    // Cin's default (1, 0, 1) plus the first layer's Ci.
    EXPECT_NEAR(r.channel(0, 2, 5, 0), 1.125f, 1e-5);
    EXPECT_NEAR(r.channel(0, 2, 5, 1), 0.125f, 1e-5);
    EXPECT_NEAR(r.channel(0, 2, 5, 2), 1.125f, 1e-5);
}

TEST(ShaderLayer, AnOutputConnectedToCsColoursTheShippedConstant) {
    // As Aqsis's layered.rib connects a texture's output to matte's Cs.
    const test::ShaderDir d = layerShaders();
    const std::string rib = view(d) + "WorldBegin\nColor [0 1 0]\n"
                            "ShaderLayer \"surface\" \"gradient\" \"paint\"\n"
                            "ShaderLayer \"surface\" \"constant\" \"shade\"\n"
                            "ConnectShaderLayers \"surface\" \"paint\" \"Cout\" \"shade\" \"Cs\"\n" +
                            kSquare + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    for (int py = 0; py < 8; ++py)
        for (int px = 0; px < 8; ++px) {
            EXPECT_NEAR(r.channel(0, px, py, 0), s(px), 1e-5) << px << " " << py;
            EXPECT_NEAR(r.channel(0, px, py, 1), t(py), 1e-5) << px << " " << py;
            EXPECT_NEAR(r.channel(0, px, py, 2), 0.25f, 1e-5) << px << " " << py;
        }
}

TEST(ShaderLayer, ASurfaceRequestReplacesTheLayers) {
    const test::ShaderDir d = layerShaders();
    const std::string rib = view(d) + "WorldBegin\nColor [0.5 0.25 1]\n"
                            "ShaderLayer \"surface\" \"gradient\" \"base\"\n"
                            "ShaderLayer \"surface\" \"mixer\" \"top\"\n"
                            "Surface \"constant\"\n" +
                            kSquare + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_FLOAT_EQ(r.channel(0, 4, 4, 0), 0.5f);
    EXPECT_FLOAT_EQ(r.channel(0, 4, 4, 1), 0.25f);
    EXPECT_FLOAT_EQ(r.channel(0, 4, 4, 2), 1.0f);
}

TEST(ShaderLayer, ConnectionsThatCannotBeMadeAreWarnedAboutAndLeftOut) {
    const test::ShaderDir d = layerShaders();
    struct Case {
        std::string connect, warning;
    };
    const std::vector<Case> cases = {
        {"ConnectShaderLayers \"surface\" \"base\" \"Cout\" \"nosuch\" \"Cin\"",
         "layers.rib:11: warning: ConnectShaderLayers base.Cout -> nosuch.Cin: the surface has no layer named 'nosuch'"},
        {"ConnectShaderLayers \"surface\" \"top\" \"Ci\" \"base\" \"scale\"",
         "layers.rib:11: warning: ConnectShaderLayers top.Ci -> base.scale: layers run in the order they are declared"},
        {"ConnectShaderLayers \"surface\" \"base\" \"Cnone\" \"top\" \"Cin\"",
         "layers.rib:11: warning: ConnectShaderLayers base.Cnone -> top.Cin: shader \"gradient\""},
        {"ConnectShaderLayers \"surface\" \"base\" \"Cout\" \"top\" \"gain\"",
         "layers.rib:11: warning: ConnectShaderLayers base.Cout -> top.gain: Cout is a color, gain a float"},
        {"ConnectShaderLayers \"surface\" \"base\" \"t\" \"top\" \"gain\"",
         "layers.rib:11: warning: ConnectShaderLayers base.t -> top.gain: t varies over the surface"},
    };
    for (const Case& c : cases) {
        const std::string rib = view(d) + "WorldBegin\n"
                                "ShaderLayer \"surface\" \"gradient\" \"base\"\n"
                                "ShaderLayer \"surface\" \"mixer\" \"top\"\n" +
                                c.connect + "\n" + kSquare + "WorldEnd\n";
        // Written to a file so that warnings name it and its line.
        const test::TempDir dir("layers-rib");
        const std::string path = dir.path() + "/layers.rib";
        std::ofstream(path) << rib;
        const test::RenderResult r = test::renderFile(path);
        ASSERT_EQ(r.warnings.size(), 1u) << c.connect;
        EXPECT_NE(r.warnings[0].find(c.warning), std::string::npos) << r.warnings[0] << "\nexpected: " << c.warning;
        // Left out: the second layer keeps Cin's default (1, 0, 1) and gain 1.
        EXPECT_NEAR(r.channel(0, 3, 3, 0), 1.125f, 1e-5) << c.connect;
        EXPECT_NEAR(r.channel(0, 3, 3, 1), 0.125f, 1e-5) << c.connect;
        // --strict: an error.
        EXPECT_THROW(test::renderRib(rib, {}, true), InputError) << c.connect;
    }
}

}  // namespace
}  // namespace streyes
