// Message passing in a render: a light reading its surface's parameter, a surface reading a
// light's output variable, a displacement and an atmosphere reading the surface's, each through
// the renderer's own order of shaders (displacement, surface with its lights, atmosphere).
#include <gtest/gtest.h>


#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

std::string view(const test::ShaderDir& d) {
    return "Format 8 8 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 8\nPixelFilter \"box\" 1 1\n"
           "PixelSamples 2 2\n" +
           d.option();
}

test::ShaderDir messageShaders() {
    test::ShaderDir d;
    // The light shines the surface's Kd and tells it, through an output, what it found.
    d.add("reader", "light reader(output varying float found = -1) {\n"
                    "  float k = 0;\n  found = surface(\"Kd\", k);\n"
                    "  illuminate(P) Cl = k;\n}\n");
    d.add("tinted", "surface tinted(float Kd = 0.5; output varying float mark = 0) {\n"
                    "  float found = -1, lift = -1;\n"
                    "  displacement(\"lift\", lift);\n"
                    "  mark = 0.125;\n  Ci = 0;\n"
                    "  illuminance(P) { Ci += Cl; lightsource(\"found\", found); }\n"
                    "  Ci = color(comp(Ci, 0), found, lift);\n  Oi = 1;\n}\n");
    d.add("lifter", "displacement lifter(output varying float lift = 0) {\n"
                    "  float kd = 0;\n  surface(\"Kd\", kd);\n  lift = kd / 2;\n}\n");
    d.add("marker", "volume marker() {\n  float m = -1;\n  surface(\"mark\", m);\n  Ci += m;\n}\n");
    return d;
}

TEST(MessageRender, LightSurfaceDisplacementAndAtmosphereReadEachOther) {
    const test::ShaderDir d = messageShaders();
    const std::string rib = view(d) + "WorldBegin\nLightSource \"reader\" 1\n" +
                            "Displacement \"lifter\"\nAtmosphere \"marker\"\n"
                            "Surface \"tinted\" \"float Kd\" [0.75]\n" +
                            test::square(0, 8, 0, 8, 10) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    for (int py = 0; py < 8; ++py)
        for (int px = 0; px < 8; ++px) {
            EXPECT_FLOAT_EQ(r.channel(0, px, py, 0), 0.75f + 0.125f) << px << " " << py;  // Kd, then the mark
            EXPECT_FLOAT_EQ(r.channel(0, px, py, 1), 1.0f + 0.125f) << px << " " << py;   // the light found Kd
            EXPECT_FLOAT_EQ(r.channel(0, px, py, 2), 0.375f + 0.125f) << px << " " << py; // the displacement's Kd / 2
        }
}

TEST(MessageRender, WithoutTheOtherShadersTheVariablesKeepTheirValues) {
    const test::ShaderDir d = messageShaders();
    // No displacement, no atmosphere; the light still finds Kd (the default).
    const std::string rib = view(d) + "WorldBegin\nLightSource \"reader\" 1\nSurface \"tinted\"\n" +
                            test::square(0, 8, 0, 8, 10) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_FLOAT_EQ(r.channel(0, 3, 3, 0), 0.5f);
    EXPECT_FLOAT_EQ(r.channel(0, 3, 3, 1), 1.0f);
    EXPECT_FLOAT_EQ(r.channel(0, 3, 3, 2), -1.0f);  // lift left at -1: no displacement
}

}  // namespace
}  // namespace streyes
