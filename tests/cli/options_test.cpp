// What a user gives a render from outside the scene, as RenderMan renderers take it: search paths
// from the environment (STREYES_SHADERPATH, STREYES_TEXTUREPATH, STREYES_PROCEDURALPATH, after the
// scene's own) and RIB requests from the command line (--option, read before the scene as defaults
// it may override).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::runStreyesWith;
using test::writeFile;

// An 8 x 8 orthographic view of a square covering it, with `surface` (and `options` first).
std::string scene(const std::string& surface, const std::string& options = "") {
    return options + "Format 8 8 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 8\nPixelFilter \"box\" 1 1\n"
                     "WorldBegin\n" + surface + "\nPatch \"bilinear\" \"P\" [0 0 5  8 0 5  0 8 5  8 8 5]\nWorldEnd\n";
}

// The red of the centre pixel of the frame the render wrote.
float red(const std::string& exr) { return readImage(exr).at(4, 4, 0); }

// A shader that paints `r`.
void paintShader(const std::string& dir, const std::string& name, float r) {
    fs::create_directories(dir);
    writeFile(dir, name + ".sl", "surface " + name + "() { Oi = 1; Ci = color(" + std::to_string(r) + ", 0, 0); }\n");
}

CliRun render(const std::string& dir, const std::string& args, const std::string& environment = "") {
    return runStreyesWith("cd '" + dir + "' && " + (environment.empty() ? "" : "env " + environment + " "),
                          "render " + args);  // not --quiet: it silences warnings
}

TEST(Environment, ShadersAreFoundAlongStreyesShaderpathAfterTheScenesOwnPath) {
    const test::TempDir dir("env-shaders");
    const std::string d = dir.path();
    paintShader(d + "/studio", "paint", 0.25f);
    writeFile(d, "scene.rib", scene("Surface \"paint\""));
    CliRun r = render(d, "scene.rib -o out.exr");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("surface shader \"paint\" not found"), std::string::npos) << r.output;
    r = render(d, "scene.rib -o out.exr", "STREYES_SHADERPATH=/nonexistent:" + d + "/studio");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(r.output.find("not found"), std::string::npos) << r.output;
    EXPECT_FLOAT_EQ(red(d + "/out.exr"), 0.25f);
    // The scene's own path first: its folder (by default), or Option "searchpath" "shader".
    paintShader(d, "paint", 0.5f);
    r = render(d, "scene.rib -o out.exr", "STREYES_SHADERPATH=" + d + "/studio");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_FLOAT_EQ(red(d + "/out.exr"), 0.5f);
    fs::remove(d + "/paint.sl");
    paintShader(d + "/show", "paint", 0.75f);
    writeFile(d, "scene.rib", scene("Surface \"paint\"", "Option \"searchpath\" \"shader\" [\"show:@\"]\n"));
    r = render(d, "scene.rib -o out.exr", "STREYES_SHADERPATH=" + d + "/studio");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_FLOAT_EQ(red(d + "/out.exr"), 0.75f);
    // A shipped shader ('@' in the scene's path) still wins over the environment's of the same name.
    paintShader(d + "/studio", "constant", 0.125f);
    writeFile(d, "scene.rib", scene("Color [1 0 0]\nSurface \"constant\""));
    r = render(d, "scene.rib -o out.exr", "STREYES_SHADERPATH=" + d + "/studio");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_FLOAT_EQ(red(d + "/out.exr"), 1.0f);
}

void writeMap(const std::string& path, float value) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << path;
    OIIO::ImageSpec spec(4, 4, 3, OIIO::TypeDesc::FLOAT);
    std::vector<float> px(4 * 4 * 3, value);
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data())) << out->geterror();
    ASSERT_TRUE(out->close());
}

TEST(Environment, MapsAreFoundAlongStreyesTexturepathAfterTheScenesOwnPath) {
    const test::TempDir dir("env-maps");
    const std::string d = dir.path();
    fs::create_directories(d + "/maps");
    writeMap(d + "/maps/wood.exr", 0.5f);
    writeFile(d, "tex.sl", "surface tex() { Oi = 1; Ci = color texture(\"wood.exr\", s, t, \"fill\", 0.25); }\n");
    writeFile(d, "scene.rib", scene("Surface \"tex\""));
    CliRun r = render(d, "scene.rib -o out.exr");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("texture(\"wood.exr\")"), std::string::npos) << r.output;
    EXPECT_FLOAT_EQ(red(d + "/out.exr"), 0.25f);
    r = render(d, "scene.rib -o out.exr", "STREYES_TEXTUREPATH=" + d + "/maps");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NEAR(red(d + "/out.exr"), 0.5f, 1e-6f);
    // The scene's own first: beside the scene (by default).
    writeMap(d + "/wood.exr", 0.75f);
    r = render(d, "scene.rib -o out.exr", "STREYES_TEXTUREPATH=" + d + "/maps");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NEAR(red(d + "/out.exr"), 0.75f, 1e-6f);
}

TEST(Environment, PlugInsAreFoundAlongStreyesProceduralpathAfterTheScenesOwnPath) {
    const test::TempDir dir("env-plugins");
    const std::string d = dir.path();
    writeFile(d, "scene.rib",
              "Format 32 32 1\nProjection \"orthographic\"\nScreenWindow 0 32 0 32\nPixelFilter \"box\" 1 1\n"
              "WorldBegin\nSurface \"constant\"\n"
              "Procedural \"DynamicLoad\" [\"menger\" \"level=1 x=2 y=2 z=1 size=27\"] [2 29 2 29 1 28]\nWorldEnd\n");
    CliRun r = render(d, "scene.rib -o out.exr");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("scene.rib:7: error: DynamicLoad: no plug-in 'menger'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("STREYES_PROCEDURALPATH"), std::string::npos) << r.output;
    r = render(d, "scene.rib -o out.exr", "STREYES_PROCEDURALPATH=/nonexistent:" STREYES_PLUGIN_DIR);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const ImageData img = readImage(d + "/out.exr");
    double covered = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) covered += img.at(x, y, img.channelIndex("A"));
    EXPECT_NEAR(covered, 27.0 * 27.0 * 8.0 / 9.0, 1e-2);
}

TEST(Option, RequestsBeforeTheSceneAreDefaultsItMayOverride) {
    const test::TempDir dir("option");
    const std::string d = dir.path();
    // A scene without a Format takes --option's; one with its own keeps it.
    writeFile(d, "noformat.rib",
              "Projection \"orthographic\"\nScreenWindow 0 8 0 8\nWorldBegin\nSurface \"constant\"\n"
              "Patch \"bilinear\" \"P\" [0 0 5  8 0 5  0 8 5  8 8 5]\nWorldEnd\n");
    writeFile(d, "format.rib", scene("Surface \"constant\""));
    CliRun r = render(d, "noformat.rib -o a.exr --option 'Format 16 12 1'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(readImage(d + "/a.exr").width, 16);
    EXPECT_EQ(readImage(d + "/a.exr").height, 12);
    r = render(d, "format.rib -o b.exr --option 'Format 16 12 1'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(readImage(d + "/b.exr").width, 8);
    // Any number, in order: a shader folder and an option the scene does not give.
    paintShader(d + "/studio", "paint", 0.25f);
    writeFile(d, "paint.rib", scene("Surface \"paint\""));
    r = render(d, "paint.rib -o c.exr --option 'Option \"searchpath\" \"shader\" [\"/nonexistent:@\"]' "
                  "--option 'Option \"searchpath\" \"shader\" [\"" + d + "/studio:&\"]'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_FLOAT_EQ(red(d + "/c.exr"), 0.25f);
    // Every frame file of a pattern reads them.
    for (int f = 1; f <= 2; ++f)
        writeFile(d, "shot.000" + std::to_string(f) + ".rib",
                  "Projection \"orthographic\"\nScreenWindow 0 8 0 8\nWorldBegin\nSurface \"constant\"\n"
                  "Patch \"bilinear\" \"P\" [0 0 5  8 0 5  0 8 5  8 8 5]\nWorldEnd\n");
    r = render(d, "'shot.####.rib' -o 'p.####.exr' --option 'Format 16 12 1'");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(readImage(d + "/p.0002.exr").width, 16);
}

TEST(Option, ABadOneIsAnErrorNamingIt) {
    const test::TempDir dir("option");
    const std::string d = dir.path();
    writeFile(d, "scene.rib", scene("Surface \"constant\""));
    CliRun r = render(d, "scene.rib -o a.exr --option 'Format 16 12 1' --option 'Fromat 16 12 1'");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--option 2:1: error: unknown request 'Fromat'"), std::string::npos) << r.output;
    r = render(d, "scene.rib -o a.exr --option 'WorldBegin'");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--option 1 ('WorldBegin'): give options and other requests of the kind a scene gives "
                            "before WorldBegin"),
              std::string::npos)
        << r.output;
    r = render(d, "scene.rib -o a.exr --option 'AttributeBegin'");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_FALSE(fs::exists(d + "/a.exr"));
    r = render(d, "scene.rib -o a.exr --option");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--option"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace streyes
