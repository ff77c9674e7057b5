// What SceneShaders::bind and makeMaterial say a material reads of the view (Material::viewUse).
#include <gtest/gtest.h>

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
    // plastic's highlight reads I; defaultsurface's brightness is |N.I|.
    EXPECT_EQ(viewUseOf(lights + "Surface \"plastic\"\nSphere 1 -1 1 360"), ViewUse::Reads);
    EXPECT_EQ(viewUseOf(lights + "Sphere 1 -1 1 360"), ViewUse::Reads);
}

TEST(MaterialViewUse, ALightMovingInWorldOrWithTheCameraReadsTheView) {
    const std::string moving = "MotionBegin [0 1]\nTranslate 0 0 0\nTranslate 1 0 0\nMotionEnd\n"
                               "LightSource \"pointlight\" 1 \"from\" [1 2 3]\n";
    EXPECT_EQ(viewUseOf("AttributeBegin\n" + moving + "AttributeEnd\nSurface \"matte\"\nSphere 1 -1 1 360"),
              ViewUse::Reads);
    // The constant surface reads no light.
    EXPECT_EQ(viewUseOf("AttributeBegin\n" + moving + "AttributeEnd\nSurface \"constant\"\nSphere 1 -1 1 360"),
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

TEST(MaterialViewUse, ShadersAreAssumedToReadTheView) {
    const std::string lights = kStillLights;
    // A Shading Language surface (the shipped matte, run as a shader because it has a primitive
    // variable), a displacement and an atmosphere each read the view until analysed.
    EXPECT_EQ(viewUseOf(lights + "Surface \"matte\" \"Kd\" 0.5\nSphere 1 -1 1 360 \"constant float Kd\" [0.5]"),
              ViewUse::Reads);
    EXPECT_EQ(viewUseOf(lights + "Surface \"constant\"\nDisplacement \"bumpy\"\nSphere 1 -1 1 360"),
              ViewUse::Reads);
    EXPECT_EQ(viewUseOf(lights + "Surface \"constant\"\nAtmosphere \"fog\"\nSphere 1 -1 1 360"), ViewUse::Reads);
    EXPECT_EQ(viewUseOf(lights + "Surface \"constant\"\nSphere 1 -1 1 360", "Option \"shading\" \"builtin\" \"off\"\n"),
              ViewUse::Reads);
}

}  // namespace
}  // namespace streyes
