// What SceneShaders::bind and makeMaterial say a material reads of the view (Material::viewUse).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "shade/scene_shaders.h"
#include "streyes/rib.h"

namespace streyes {
namespace {

// The view use of the first sphere's material in `world` (a RIB world body) under `options`.
ViewUse viewUseOf(const std::string& world, const std::string& options = "") {
    Log log;
    const std::string rib = "Display \"t.exr\" \"file\" \"rgba\"\nFormat 16 16 1\nProjection \"perspective\"\n" +
                            options + "WorldBegin\n" + world + "\nWorldEnd\n";
    Scene scene = parseRibString(rib, "view_use.rib", log);
    EXPECT_EQ(scene.quadrics.size(), 1u);
    if (scene.quadrics.empty()) return ViewUse::Reads;
    const Attributes& a = *scene.quadrics[0].attributes;
    SceneShaders shaders(scene, log);
    Material m = makeMaterial(a);
    shaders.bind(m, a);
    return m.viewUse;
}

const char* const kStillLights =
    "LightSource \"ambientlight\" 1 \"intensity\" 0.2\n"
    "LightSource \"distantlight\" 2 \"from\" [0 1 0] \"to\" [0 0 0]\n"
    "LightSource \"pointlight\" 3 \"from\" [1 2 3]\n";

TEST(MaterialViewUse, BuiltInSurfacesUnderLightsStillInWorld) {
    const std::string lights = kStillLights;
    EXPECT_EQ(viewUseOf(lights + "Surface \"constant\"\nSphere 1 -1 1 360"), ViewUse::None);
    // matte reads the view only through faceforward(N, I).
    EXPECT_EQ(viewUseOf(lights + "Surface \"matte\"\nSphere 1 -1 1 360"), ViewUse::FacingOnly);
    // plastic's highlight reads I; defaultsurface's brightness is (N.I)^2.
    EXPECT_EQ(viewUseOf(lights + "Surface \"plastic\"\nSphere 1 -1 1 360"), ViewUse::Reads);
    EXPECT_EQ(viewUseOf(lights + "Sphere 1 -1 1 360"), ViewUse::Reads);
}

TEST(MaterialViewUse, ALightMovingInWorldOrWithTheCameraReadsTheView) {
    const std::string moving = "MotionBegin [0 1]\nTranslate 0 0 0\nTranslate 1 0 0\nMotionEnd\n"
                               "LightSource \"pointlight\" 1 \"from\" [1 2 3]\n";
    EXPECT_EQ(viewUseOf("AttributeBegin\n" + moving + "AttributeEnd\nIlluminate 1 1\nSurface \"matte\"\nSphere 1 -1 1 360"),
              ViewUse::Reads);
    // The constant surface reads no light.
    EXPECT_EQ(viewUseOf("AttributeBegin\n" + moving + "AttributeEnd\nIlluminate 1 1\nSurface \"constant\"\nSphere 1 -1 1 360"),
              ViewUse::None);
    // A light declared before WorldBegin is placed in camera space: under a moving camera it
    // moves in world.
    const std::string cameraLight = "LightSource \"pointlight\" 1 \"from\" [0 0 0]\n"
                                    "MotionBegin [0 1]\nTranslate 0 0 5\nTranslate 1 0 5\nMotionEnd\n";
    EXPECT_EQ(viewUseOf("Illuminate 1 1\nSurface \"matte\"\nSphere 1 -1 1 360", cameraLight), ViewUse::Reads);
    // The same light with the camera still is still in world.
    EXPECT_EQ(viewUseOf("Illuminate 1 1\nSurface \"matte\"\nSphere 1 -1 1 360",
                        "LightSource \"pointlight\" 1 \"from\" [0 0 0]\nTranslate 0 0 5\n"),
              ViewUse::FacingOnly);
}

TEST(MaterialViewUse, ShadersAsTheCompilerClassesThemWithTheirLights) {
    const std::string lights = kStillLights;
    // The shipped matte run as a shader (a primitive variable keeps it from the built-in).
    const std::string matteShader = "Surface \"matte\" \"Kd\" 0.5\nSphere 1 -1 1 360 \"constant float Kd\" [0.5]";
    EXPECT_EQ(viewUseOf(lights + matteShader), ViewUse::FacingOnly);
    EXPECT_EQ(viewUseOf(lights + "Surface \"plastic\" \"Kd\" 0.5\nSphere 1 -1 1 360 \"constant float Kd\" [0.5]"),
              ViewUse::Reads);
    EXPECT_EQ(viewUseOf(lights + "Surface \"ground\"\nSphere 1 -1 1 360"), ViewUse::FacingOnly);
    EXPECT_EQ(viewUseOf(lights + "Surface \"sky\"\nSphere 1 -1 1 360"), ViewUse::Reads);
    // A displacement and an atmosphere count with the surface.
    EXPECT_EQ(viewUseOf(lights + "Surface \"constant\"\nDisplacement \"bumpy\"\nSphere 1 -1 1 360"), ViewUse::None);
    EXPECT_EQ(viewUseOf(lights + "Surface \"constant\"\nAtmosphere \"fog\"\nSphere 1 -1 1 360"), ViewUse::Reads);
    EXPECT_EQ(viewUseOf(lights + "Surface \"constant\"\nSphere 1 -1 1 360", "Option \"shading\" \"builtin\" \"off\"\n"),
              ViewUse::None);
    // A light's shader: a spotlight still in world, then moving with its own transform.
    const std::string spot = "LightSource \"spotlight\" 1 \"from\" [0 2 0] \"to\" [0 0 0]\n";
    EXPECT_EQ(viewUseOf(spot + matteShader), ViewUse::FacingOnly);
    EXPECT_EQ(viewUseOf("AttributeBegin\nMotionBegin [0 1]\nTranslate 0 0 0\nTranslate 0 1 0\nMotionEnd\n" + spot +
                        "AttributeEnd\nIlluminate 1 1\n" + matteShader),
              ViewUse::Reads);
    // A surface that reads no light does not care how they move.
    EXPECT_EQ(viewUseOf("AttributeBegin\nMotionBegin [0 1]\nTranslate 0 0 0\nTranslate 0 1 0\nMotionEnd\n" + spot +
                        "AttributeEnd\nIlluminate 1 1\nSurface \"constant\"\nSphere 1 -1 1 360 \"constant float Kd\" [0.5]"),
              ViewUse::None);
    // The surface's own "shader" space moving in world.
    EXPECT_EQ(viewUseOf(lights + "MotionBegin [0 1]\nTranslate 0 0 0\nTranslate 0 1 0\nMotionEnd\nSurface \"ground\"\n"
                                 "Identity\nSphere 1 -1 1 360"),
              ViewUse::Reads);
}

TEST(MaterialViewUse, ACameraThatScalesOrShearsReadsTheView) {
    const std::string lights = kStillLights;
    const std::string matteShader = "Surface \"matte\" \"Kd\" 0.5\nSphere 1 -1 1 360 \"constant float Kd\" [0.5]";
    const std::string pan = "MotionBegin [0 1]\nRotate 0 0 1 0\nRotate 10 0 1 0\nMotionEnd\nTranslate 0 0 5\n";
    const std::string zoomByScale = "MotionBegin [0 1]\nScale 1 1 1\nScale 1.2 1.2 1.2\nMotionEnd\nTranslate 0 0 5\n";
    const std::string mirrored = "Scale 1 1 -1\nMotionBegin [0 1]\nTranslate 0 0 5\nTranslate 1 0 5\nMotionEnd\n";
    EXPECT_EQ(viewUseOf(lights + matteShader, pan), ViewUse::FacingOnly);
    EXPECT_EQ(viewUseOf(lights + matteShader, mirrored), ViewUse::FacingOnly);
    EXPECT_EQ(viewUseOf(lights + matteShader, zoomByScale), ViewUse::Reads);
    EXPECT_EQ(viewUseOf(lights + "Surface \"matte\"\nSphere 1 -1 1 360", zoomByScale), ViewUse::Reads);
    // The built-in constant reads nothing of the view, whatever the camera.
    EXPECT_EQ(viewUseOf(lights + "Surface \"constant\"\nSphere 1 -1 1 360", zoomByScale), ViewUse::None);
}

// A layered displacement: the widest of its layers; a connection that carries a predefined
// variable of the view (I) into a layer's parameter, which the analysis takes as given, reads it.
TEST(MaterialViewUse, ALayeredDisplacementCombinesItsLayersAndItsConnections) {
    const std::string dir = ::testing::TempDir() + "/view_use_layers";
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/pushdir.sl") << "displacement pushdir(varying vector dir = 0) { P += 0.01 * dir; N = calculatenormal(P); }\n";
    const std::string path = "Option \"searchpath\" \"shader\" \"" + dir + ":@\"\n";
    const std::string lights = kStillLights, layers = "Surface \"constant\"\n"
                                                      "ShaderLayer \"displacement\" \"bumpy\" \"one\"\n"
                                                      "ShaderLayer \"displacement\" \"pushdir\" \"two\"\n";
    EXPECT_EQ(viewUseOf(lights + layers + "Sphere 1 -1 1 360", path), ViewUse::None);
    EXPECT_EQ(viewUseOf(lights + layers + "ConnectShaderLayers \"displacement\" \"one\" \"I\" \"two\" \"dir\"\n"
                                          "Sphere 1 -1 1 360",
                        path),
              ViewUse::Reads);
    // A layered surface (sky reads the view) over a matte one: the widest.
    EXPECT_EQ(viewUseOf(lights + "ShaderLayer \"surface\" \"sky\" \"one\"\nShaderLayer \"surface\" \"matte\" \"two\"\n"
                                 "Sphere 1 -1 1 360"),
              ViewUse::Reads);
}

}  // namespace
}  // namespace streyes
