// Unit tests for the RIB lexer and parser: values land in the right Scene fields, transforms
// compose in RenderMan order, and malformed input is reported at the right file:line.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene/rib_lexer.h"
#include "scene/rib_parser.h"
#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

// A unit patch in the z = 0 plane, as RIB text.
const char* kUnitPatch = "Patch \"bilinear\" \"P\" [0 0 0  1 0 0  0 1 0  1 1 0]\n";

Scene parse(const std::string& text, Log& log) { return parseRibString(text, "test.rib", log); }

Scene parse(const std::string& text) {
    Log log;
    return parse(text, log);
}

// The message of the InputError that parsing `text` (named bad.rib) throws, or "" if none.
std::string errorOf(const std::string& text) { return test::ribError(text); }

void expectNear(Vec3d a, Vec3d b, double eps = 1e-12) {
    EXPECT_NEAR(a.x, b.x, eps);
    EXPECT_NEAR(a.y, b.y, eps);
    EXPECT_NEAR(a.z, b.z, eps);
}

// ---- Lexer ----------------------------------------------------------------------------------------
TEST(RibLexer, TokensNumbersStringsAndLines) {
    std::string text =
        "Translate -1 .5 +2e1 -3.25E-1 # a comment [ \"not a string\n"
        "\"a\\n\\t\\\\\\\"\\101z\" [ 7 ]\n"
        "\"two\nlines\" Next";
    RibLexer lexer(text, std::make_shared<const std::string>("t.rib"));
    RibToken t = lexer.next();
    EXPECT_EQ(t.kind, RibTokenKind::Request);
    EXPECT_EQ(t.text, "Translate");
    EXPECT_EQ(t.line, 1);
    for (double expected : {-1.0, 0.5, 20.0, -0.325}) {
        t = lexer.next();
        ASSERT_EQ(t.kind, RibTokenKind::Number);
        EXPECT_DOUBLE_EQ(t.number, expected);
        EXPECT_EQ(t.line, 1);
    }
    t = lexer.next();
    EXPECT_EQ(t.kind, RibTokenKind::String);
    EXPECT_EQ(t.text, "a\n\t\\\"Az");
    EXPECT_EQ(t.line, 2);
    EXPECT_EQ(lexer.peek().kind, RibTokenKind::ArrayBegin);
    EXPECT_EQ(lexer.next().kind, RibTokenKind::ArrayBegin);
    EXPECT_DOUBLE_EQ(lexer.next().number, 7);
    EXPECT_EQ(lexer.next().kind, RibTokenKind::ArrayEnd);
    t = lexer.next();
    EXPECT_EQ(t.text, "two\nlines");
    EXPECT_EQ(t.line, 3);
    t = lexer.next();
    EXPECT_EQ(t.text, "Next");
    EXPECT_EQ(t.line, 4);
    EXPECT_EQ(lexer.next().kind, RibTokenKind::End);
}

TEST(RibLexer, RejectsBadNumbersAndCharacters) {
    auto lexError = [](const std::string& text) -> std::string {
        RibLexer lexer(text, std::make_shared<const std::string>("lex.rib"));
        try {
            while (lexer.next().kind != RibTokenKind::End) {
            }
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(lexError("\n1e999").find("lex.rib:2: number '1e999' is too large"), std::string::npos);
    EXPECT_NE(lexError("-inf").find("NaN and infinity are not allowed"), std::string::npos);
    EXPECT_NE(lexError("NaN").find("NaN and infinity are not allowed"), std::string::npos);
    EXPECT_NE(lexError("1.2.3").find("malformed number '1.2.3'"), std::string::npos);
    EXPECT_NE(lexError("\n\n{").find("lex.rib:3: unexpected character '{'"), std::string::npos);
    EXPECT_NE(lexError("\"abc").find("unterminated string"), std::string::npos);
    EXPECT_EQ(lexError("1e-999 0.0 -0"), "");  // underflow is harmless
}

// ---- Options --------------------------------------------------------------------------------------
TEST(RibOptions, EveryOptionLandsInItsField) {
    Log log;
    Scene scene = parse(R"(
Format 320 240 1.5
Projection "perspective" "fov" 45
ScreenWindow -2 2 -1.5 1.5
FrameAspectRatio 1.25
Clipping 0.5 500
Shutter 0.25 0.75
PixelSamples 3 2.2
PixelFilter "catmullrom" 3 4
ShadingRate 0.5
Display "out.####.exr" "openexr" "rgbaz"
Display "+depth.exr" "openexr" "rgba"
Option "streyes" "int frames" [1 24]
WorldBegin
WorldEnd
)",
                        log);
    const CameraDesc& cam = scene.camera;
    EXPECT_EQ(cam.xres, 320);
    EXPECT_EQ(cam.yres, 240);
    EXPECT_DOUBLE_EQ(cam.pixelAspect, 1.5);
    EXPECT_EQ(cam.projection, ProjectionKind::Perspective);
    EXPECT_DOUBLE_EQ(cam.fov, 45);
    EXPECT_TRUE(cam.hasScreenWindow);
    EXPECT_DOUBLE_EQ(cam.screenWindow[0], -2);
    EXPECT_DOUBLE_EQ(cam.screenWindow[1], 2);
    EXPECT_DOUBLE_EQ(cam.screenWindow[2], -1.5);
    EXPECT_DOUBLE_EQ(cam.screenWindow[3], 1.5);
    EXPECT_DOUBLE_EQ(cam.frameAspect, 1.25);
    EXPECT_DOUBLE_EQ(cam.nearClip, 0.5);
    EXPECT_DOUBLE_EQ(cam.farClip, 500);
    const RenderSettings& s = scene.settings;
    EXPECT_DOUBLE_EQ(s.shutterOpen, 0.25);
    EXPECT_DOUBLE_EQ(s.shutterClose, 0.75);
    EXPECT_EQ(s.pixelSamplesX, 3);
    EXPECT_EQ(s.pixelSamplesY, 3);  // 2.2 rounds up
    EXPECT_EQ(s.filter.type, "catmull-rom");
    EXPECT_DOUBLE_EQ(s.filter.xwidth, 3);
    EXPECT_DOUBLE_EQ(s.filter.ywidth, 4);
    ASSERT_EQ(s.displays.size(), 2u);
    EXPECT_EQ(s.displays[0].name, "out.####.exr");
    EXPECT_EQ(s.displays[0].type, "openexr");
    EXPECT_EQ(s.displays[0].mode, "rgbaz");
    EXPECT_EQ(s.displays[0].loc.line, 11);
    EXPECT_EQ(s.displays[1].name, "depth.exr");  // '+' stripped
    EXPECT_EQ(s.displays[1].mode, "rgba");
    EXPECT_TRUE(s.hasFrames);
    EXPECT_EQ(s.firstFrame, 1);
    EXPECT_EQ(s.lastFrame, 24);
    EXPECT_EQ(scene.sourceName, "test.rib");
    EXPECT_TRUE(log.warnings().empty());
}

TEST(RibOptions, DefaultsAndVariants) {
    Scene scene = parse("WorldBegin\nWorldEnd\n");
    EXPECT_EQ(scene.camera.projection, ProjectionKind::Orthographic);
    EXPECT_EQ(scene.camera.xres, 640);
    EXPECT_EQ(scene.camera.yres, 480);
    EXPECT_DOUBLE_EQ(scene.camera.nearClip, 1e-4);
    EXPECT_DOUBLE_EQ(scene.camera.farClip, 1e30);
    EXPECT_EQ(scene.settings.pixelSamplesX, 2);
    EXPECT_EQ(scene.settings.filter.type, "gaussian");
    EXPECT_FALSE(scene.settings.hasFrames);
    EXPECT_TRUE(scene.patches.empty());

    // Predeclared "frames", "integer frames"; a second Display without '+' replaces the first.
    scene = parse(
        "Option \"streyes\" \"frames\" [3 5]\nDisplay \"a.exr\" \"file\" \"rgb\"\n"
        "Display \"b.exr\" \"file\" \"rgba\"\nWorldBegin\nWorldEnd\n");
    EXPECT_EQ(scene.settings.firstFrame, 3);
    EXPECT_EQ(scene.settings.lastFrame, 5);
    ASSERT_EQ(scene.settings.displays.size(), 1u);
    EXPECT_EQ(scene.settings.displays[0].name, "b.exr");
    scene = parse("Option \"streyes\" \"integer frames\" [-2 -2]\nWorldBegin\nWorldEnd\n");
    EXPECT_EQ(scene.settings.firstFrame, -2);

    // The RenderMan Interface's filters, and PRMan's "separable-" names for them.
    scene = parse("PixelFilter \"sinc\" 4 3\nWorldBegin\nWorldEnd\n");
    EXPECT_EQ(scene.settings.filter.type, "sinc");
    EXPECT_DOUBLE_EQ(scene.settings.filter.ywidth, 3);
    scene = parse("PixelFilter \"separable-catmull-rom\" 4 4\nWorldBegin\nWorldEnd\n");
    EXPECT_EQ(scene.settings.filter.type, "catmull-rom");
    for (const char* f : {"triangle", "mitchell", "disk", "blackman-harris"})
        EXPECT_EQ(parse(std::string("PixelFilter \"") + f + "\" 2 2\nWorldBegin\nWorldEnd\n").settings.filter.type, f);
    // PRMan's spelling without the hyphen, and its separable form.
    EXPECT_EQ(parse("PixelFilter \"separable-blackmanharris\" 3 3\nWorldBegin\nWorldEnd\n").settings.filter.type,
              "blackman-harris");

    // An unknown filter warns and keeps gaussian 2 2.
    Log log;
    scene = parse("PixelFilter \"box\" 1 1\nPixelFilter \"lanczos\" 4 4\nWorldBegin\nWorldEnd\n", log);
    EXPECT_EQ(scene.settings.filter.type, "gaussian");
    EXPECT_DOUBLE_EQ(scene.settings.filter.xwidth, 2);
    ASSERT_EQ(log.warnings().size(), 1u);
    EXPECT_NE(log.warnings()[0].find("test.rib:2"), std::string::npos);
}

TEST(RibOptions, DisplayModeErrorListsValidModes) {
    std::string e = errorOf("WorldBegin\nWorldEnd\n");  // control: fine
    EXPECT_EQ(e, "");
    e = errorOf("Format 10 10 1\n\nDisplay \"x.exr\" \"openexr\" \"rgbz\"\nWorldBegin\nWorldEnd\n");
    EXPECT_NE(e.find("bad.rib:3:"), std::string::npos) << e;
    EXPECT_NE(e.find("rgb, rgba, rgbaz, a, z, N, P"), std::string::npos) << e;
    // Output variables and lists of them are modes too (AovRender tests them rendered).
    EXPECT_EQ(errorOf("Display \"x.exr\" \"openexr\" \"z\"\nDisplay \"+y.exr\" \"openexr\" \"rgba,N,P,motion\"\n"
                      "WorldBegin\nWorldEnd\n"),
              "");
}

// ---- Transforms -----------------------------------------------------------------------------------
TEST(RibTransforms, TranslateThenScaleScalesFirst) {
    // Scale is written last, so it applies to the geometry first: (1,0,0) -> (2,0,0) -> (3,0,0).
    Scene scene = parse(std::string("WorldBegin\nTranslate 1 0 0\nScale 2 2 2\n") + kUnitPatch + "WorldEnd\n");
    ASSERT_EQ(scene.patches.size(), 1u);
    const Matrix4 m = scene.patches[0].objectToWorld.at(0);
    expectNear(m.point({1, 0, 0}), {3, 0, 0});
    expectNear(m.point({0, 1, 0}), {1, 2, 0});
    EXPECT_TRUE(scene.patches[0].objectToWorld.isStatic());
}

TEST(RibTransforms, Rotate90AboutZ) {
    Scene scene = parse(std::string("WorldBegin\nRotate 90 0 0 1\n") + kUnitPatch + "WorldEnd\n");
    const Matrix4 m = scene.patches[0].objectToWorld.at(0);
    expectNear(m.point({1, 0, 0}), {0, 1, 0});
    expectNear(m.point({0, 1, 0}), {-1, 0, 0});
}

TEST(RibTransforms, ConcatTransformAndTransform) {
    Scene scene = parse(std::string("WorldBegin\nTranslate 5 5 5\nTransform [1 0 0 0 0 1 0 0 0 0 1 0 1 2 3 1]\n"
                                    "ConcatTransform [2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1]\n") +
                        kUnitPatch + "Identity\n" + kUnitPatch + "WorldEnd\n");
    ASSERT_EQ(scene.patches.size(), 2u);
    expectNear(scene.patches[0].objectToWorld.at(0).point({1, 1, 1}), {3, 4, 5});  // Transform replaced Translate
    EXPECT_EQ(scene.patches[1].objectToWorld.at(0), Matrix4::identity());
}

TEST(RibTransforms, CameraTransformBecomesWorldToCamera) {
    Scene scene = parse(std::string("Projection \"perspective\" \"fov\" 40\nTranslate 0 0 5\nRotate 90 0 1 0\n"
                                    "WorldBegin\nTranslate 1 0 0\n") +
                        kUnitPatch + "WorldEnd\n");
    const Matrix4 w2c = scene.camera.worldToCamera.at(0);
    expectNear(w2c.point({0, 0, 0}), {0, 0, 5});
    expectNear(w2c.point({1, 0, 0}), {0, 0, 4});  // rotated onto -z, then moved 5 along z
    EXPECT_EQ(scene.camera.loc.line, 4);
    // The world starts from identity again.
    expectNear(scene.patches[0].objectToWorld.at(0).point({0, 0, 0}), {1, 0, 0});
}

TEST(RibTransforms, MotionBlockGivesKeysAtItsTimes) {
    Scene scene = parse(std::string("WorldBegin\nScale 2 2 2\nMotionBegin [0 1]\n"
                                    "Translate 0 0 0\nTranslate 1 0 0\nMotionEnd\n") +
                        kUnitPatch + "WorldEnd\n");
    const MotionTransform& o2w = scene.patches[0].objectToWorld;
    ASSERT_FALSE(o2w.isStatic());
    ASSERT_EQ(o2w.times(), (std::vector<double>{0, 1}));
    // The motion translate applies first, then the scale.
    EXPECT_EQ(o2w.keys()[0], Matrix4::scale({2, 2, 2}));
    EXPECT_EQ(o2w.keys()[1], Matrix4::translate({1, 0, 0}) * Matrix4::scale({2, 2, 2}));
    expectNear(o2w.at(1).point({1, 0, 0}), {4, 0, 0});
    expectNear(o2w.at(0.5).point({1, 0, 0}), {3, 0, 0});
    // The patch itself does not move: one key.
    EXPECT_EQ(scene.patches[0].P.size(), 1u);
}

TEST(RibTransforms, MovingCameraBeforeWorldBegin) {
    Scene scene = parse(
        "MotionBegin [10 12 14]\nTranslate 0 0 1\nTranslate 0 0 2\nTranslate 0 0 4\nMotionEnd\n"
        "WorldBegin\nWorldEnd\n");
    const MotionTransform& w2c = scene.camera.worldToCamera;
    ASSERT_EQ(w2c.times(), (std::vector<double>{10, 12, 14}));
    expectNear(w2c.at(12).point({0, 0, 0}), {0, 0, 2});
    expectNear(w2c.at(13).point({0, 0, 0}), {0, 0, 3});
    // Identical keys collapse to a static transform.
    scene = parse("MotionBegin [0 1]\nScale 1 2 3\nScale 1 2 3\nMotionEnd\nWorldBegin\nWorldEnd\n");
    EXPECT_TRUE(scene.camera.worldToCamera.isStatic());
}

// ---- Geometry -------------------------------------------------------------------------------------
TEST(RibGeometry, MovingPatchHasTwoKeys) {
    Scene scene = parse(
        "WorldBegin\nMotionBegin [0 0.5]\n"
        "Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n"
        "Patch \"bilinear\" \"P\" [0 0 1 1 0 1 0 1 1 1 1 1]\n"
        "MotionEnd\nWorldEnd\n");
    ASSERT_EQ(scene.patches.size(), 1u);
    const BilinearPatchDesc& p = scene.patches[0];
    EXPECT_EQ(p.times, (std::vector<double>{0, 0.5}));
    ASSERT_EQ(p.P.size(), 2u);
    expectNear(p.P[0][3], {1, 1, 0});
    expectNear(p.P[1][3], {1, 1, 1});
    EXPECT_EQ(p.loc.line, 3);
    EXPECT_TRUE(p.objectToWorld.isStatic());
}

TEST(RibGeometry, StaticPatchHasOneKeyAndSharedAttributes) {
    Scene scene = parse(std::string("WorldBegin\nColor 1 0 0\n") + kUnitPatch + kUnitPatch + "WorldEnd\n");
    ASSERT_EQ(scene.patches.size(), 2u);
    const BilinearPatchDesc& p = scene.patches[0];
    EXPECT_EQ(p.times, (std::vector<double>{0}));
    ASSERT_EQ(p.P.size(), 1u);
    expectNear(p.P[0][0], {0, 0, 0});
    expectNear(p.P[0][1], {1, 0, 0});
    expectNear(p.P[0][2], {0, 1, 0});
    expectNear(p.P[0][3], {1, 1, 0});
    EXPECT_FALSE(p.hasCs);
    EXPECT_EQ(p.attributes->color, Color(1, 0, 0));
    EXPECT_EQ(p.attributes.get(), scene.patches[1].attributes.get());  // nothing changed: shared
    EXPECT_EQ(p.loc.line, 3);
}

// Polygons are kept as written: vertices in order, Cs as given (bodies/polygons_test.cpp makes
// patches of them).
TEST(RibGeometry, PolygonsKeepTheirVerticesAndCs) {
    Scene scene = parse(
        "WorldBegin\n"
        "Polygon \"P\" [0 0 0  1 0 0  1 1 0  0 1 0] \"Cs\" [1 0 0  0 1 0  0 0 1  1 1 1]\n"
        + std::string(kUnitPatch) +
        "Polygon \"P\" [0 0 0  2 0 0  0 2 0] \"vertex color Cs\" [1 0 0  0 1 0  0 0 1]\n"
        "WorldEnd\n");
    ASSERT_EQ(scene.patches.size(), 1u);
    ASSERT_EQ(scene.polygonMeshes.size(), 2u);
    const PolygonMeshDesc& quad = scene.polygonMeshes[0];
    EXPECT_EQ(quad.request, "Polygon");
    EXPECT_EQ(quad.polygons, (std::vector<std::vector<std::vector<int>>>{{{0, 1, 2, 3}}}));
    ASSERT_EQ(quad.P.size(), 1u);
    ASSERT_EQ(quad.P[0].size(), 4u);
    expectNear(quad.P[0][2], {1, 1, 0});
    expectNear(quad.P[0][3], {0, 1, 0});
    EXPECT_EQ(quad.Cs.cls, ParamClass::Varying);
    ASSERT_EQ(quad.Cs.values.size(), 4u);
    EXPECT_EQ(quad.Cs.values[2], Color(0, 0, 1));
    EXPECT_EQ(quad.patchesBefore, 0u);
    EXPECT_EQ(quad.loc.line, 2);
    const PolygonMeshDesc& tri = scene.polygonMeshes[1];
    EXPECT_EQ(tri.polygons, (std::vector<std::vector<std::vector<int>>>{{{0, 1, 2}}}));
    expectNear(tri.P[0][2], {0, 2, 0});
    EXPECT_EQ(tri.Cs.cls, ParamClass::Vertex);
    EXPECT_EQ(tri.Cs.values.size(), 3u);
    EXPECT_EQ(tri.patchesBefore, 1u);  // after the patch: its id comes after the patch's
}

TEST(RibGeometry, CsVaryingPerCornerAndUniform) {
    Scene scene = parse(
        "WorldBegin\n"
        "Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0] \"Cs\" [1 0 0  0 1 0  0 0 1  0.5 0.5 0.5]\n"
        "Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0] \"uniform color Cs\" [0.25 0.5 0.75]\n"
        "WorldEnd\n");
    const BilinearPatchDesc& varying = scene.patches[0];
    ASSERT_TRUE(varying.hasCs);
    EXPECT_EQ(varying.Cs[0], Color(1, 0, 0));
    EXPECT_EQ(varying.Cs[1], Color(0, 1, 0));
    EXPECT_EQ(varying.Cs[2], Color(0, 0, 1));
    EXPECT_EQ(varying.Cs[3], Color(0.5f, 0.5f, 0.5f));
    const BilinearPatchDesc& uniform = scene.patches[1];
    for (const Color& c : uniform.Cs) EXPECT_EQ(c, Color(0.25f, 0.5f, 0.75f));
}

TEST(RibGeometry, PwDividesByW) {
    Scene scene = parse("WorldBegin\nPatch \"bilinear\" \"Pw\" [0 0 0 1  2 0 0 2  0 4 0 2  2 2 0 1]\nWorldEnd\n");
    expectNear(scene.patches[0].P[0][1], {1, 0, 0});
    expectNear(scene.patches[0].P[0][2], {0, 2, 0});
    expectNear(scene.patches[0].P[0][3], {2, 2, 0});
}

TEST(RibGeometry, UnsupportedGeometryIsSkippedWithOneWarning) {
    Log log;
    Scene scene = parse(
        "WorldBegin\nVolume \"box\" [0 1 0 1 0 1] [2 2 2]\n"
        "Volume \"box\" [0 1 0 1 0 1] [2 2 2]\n"
        "HierarchicalSubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [] [0 0] [] [] [] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]\n"
        "WorldEnd\n",
        log);
    EXPECT_TRUE(scene.patches.empty());
    EXPECT_TRUE(scene.patchMeshes.empty());
    EXPECT_TRUE(scene.polygonMeshes.empty());
    std::vector<std::string> w = log.warnings();
    ASSERT_EQ(w.size(), 2u);
    EXPECT_NE(w[0].find("test.rib:2: warning: unsupported request 'Volume'"), std::string::npos) << w[0];
    EXPECT_NE(w[1].find("test.rib:4: warning: unsupported request 'HierarchicalSubdivisionMesh'"), std::string::npos)
        << w[1];
}

// ---- Declarations ---------------------------------------------------------------------------------
TEST(RibDeclarations, InlineAndDeclare) {
    Log log;
    Scene scene = parse(
        "Declare \"gain\" \"uniform float\"\n"
        "Declare \"tints\" \"constant color[2]\"\n"
        "WorldBegin\n"
        "Attribute \"user\" \"gain\" 2.5 \"tints\" [1 0 0 0 1 0] \"uniform string label\" \"hello\"\n"
        "Attribute \"identifier\" \"name\" [\"wall\"]\n"
        "Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0] \"varying float[2] uv\" [0 0 1 0 0 1 1 1]\n"
        "WorldEnd\n",
        log);
    const ParamList& user = scene.patches[0].attributes->user;
    EXPECT_DOUBLE_EQ(user.getFloat("user:gain", 0), 2.5);
    const Param* tints = user.find("user:tints");
    ASSERT_NE(tints, nullptr);
    EXPECT_EQ(tints->type, ParamType::Color);
    EXPECT_EQ(tints->cls, ParamClass::Constant);
    EXPECT_EQ(tints->arraySize, 2);
    EXPECT_EQ(tints->componentsPerItem(), 6);
    EXPECT_EQ(tints->nums.size(), 6u);
    EXPECT_EQ(user.getString("user:label", ""), "hello");
    EXPECT_EQ(user.getString("identifier:name", ""), "wall");
    EXPECT_EQ(user.find("identifier:name")->loc.line, 5);
    // The unused "uv" is accepted (4 varying float[2] items) with a warning.
    ASSERT_EQ(log.warnings().size(), 1u);
    EXPECT_NE(log.warnings()[0].find("'uv'"), std::string::npos);
}

TEST(RibDeclarations, ParseDeclarationText) {
    RibParamDecl d;
    std::string name;
    EXPECT_EQ(parseRibDeclaration("varying float[2] st", true, &d, &name), "");
    EXPECT_EQ(d.cls, ParamClass::Varying);
    EXPECT_EQ(d.type, ParamType::Float);
    EXPECT_EQ(d.arraySize, 2);
    EXPECT_EQ(name, "st");
    EXPECT_EQ(parseRibDeclaration("int frames", true, &d, &name), "");
    EXPECT_EQ(d.cls, ParamClass::Uniform);  // class defaults to uniform
    EXPECT_EQ(d.type, ParamType::Integer);
    EXPECT_EQ(parseRibDeclaration("vertex hpoint [ 3 ]", false, &d, &name), "");
    EXPECT_EQ(d.type, ParamType::HPoint);
    EXPECT_EQ(d.arraySize, 3);
    EXPECT_NE(parseRibDeclaration("uniform flaot Kd", true, &d, &name).find("unknown type 'flaot'"),
              std::string::npos);
    EXPECT_NE(parseRibDeclaration("float", true, &d, &name), "");       // no name
    EXPECT_NE(parseRibDeclaration("float[0] x", true, &d, &name), "");  // bad size
}

TEST(RibDeclarations, ParamListReaders) {
    ParamList list;
    Param kd;
    kd.name = "Kd";
    kd.nums = {0.5};
    Param color;
    color.name = "c";
    color.type = ParamType::Color;
    color.nums = {1, 2, 3};
    Param hp;
    hp.name = "h";
    hp.type = ParamType::HPoint;
    hp.nums = {2, 4, 6, 2};
    list.params = {kd, color, hp};
    EXPECT_DOUBLE_EQ(list.getFloat("Kd", 0), 0.5);
    EXPECT_DOUBLE_EQ(list.getFloat("missing", 7), 7);
    EXPECT_EQ(list.getColor("c", {}), Color(1, 2, 3));
    expectNear(list.getPoint("h", {}), {1, 2, 3});
    EXPECT_THROW(list.getFloat("c", 0), InputError);
    EXPECT_THROW(list.getString("Kd", ""), InputError);
    EXPECT_THROW(list.getColor("Kd", {}), InputError);
}

// ---- Attributes and lights ------------------------------------------------------------------------
TEST(RibAttributes, BlocksRestoreColorAndTransform) {
    Scene scene =
        parse(std::string("WorldBegin\nColor 0 0 1\nTranslate 0 0 1\n"
                          "AttributeBegin\nColor 1 0 0\nTranslate 5 0 0\nSurface \"matte\" \"Kd\" 0.3\n") +
              kUnitPatch + "AttributeEnd\n" + kUnitPatch +
              "TransformBegin\nTranslate 0 7 0\nColor 0 1 0\nTransformEnd\n" + kUnitPatch + "WorldEnd\n");
    ASSERT_EQ(scene.patches.size(), 3u);
    const BilinearPatchDesc& inner = scene.patches[0];
    EXPECT_EQ(inner.attributes->color, Color(1, 0, 0));
    EXPECT_EQ(inner.attributes->surface.name, "matte");
    EXPECT_DOUBLE_EQ(inner.attributes->surface.params.getFloat("Kd", 1), 0.3);
    expectNear(inner.objectToWorld.at(0).point({0, 0, 0}), {5, 0, 1});
    const BilinearPatchDesc& after = scene.patches[1];
    EXPECT_EQ(after.attributes->color, Color(0, 0, 1));
    EXPECT_EQ(after.attributes->surface.name, "defaultsurface");
    expectNear(after.objectToWorld.at(0).point({0, 0, 0}), {0, 0, 1});
    // TransformEnd restores the transform but not the colour.
    const BilinearPatchDesc& afterTransformBlock = scene.patches[2];
    EXPECT_EQ(afterTransformBlock.attributes->color, Color(0, 1, 0));
    expectNear(afterTransformBlock.objectToWorld.at(0).point({0, 0, 0}), {0, 0, 1});
    // Copy-on-write: the earlier patches keep the state they were given.
    EXPECT_EQ(scene.patches[1].attributes->color, Color(0, 0, 1));
}

TEST(RibAttributes, ShadersAndOpacity) {
    Log log;
    Scene scene =
        parse(std::string("WorldBegin\nOpacity 0.5 1 1\nShadingRate 4\n"
                          "Surface \"plastic\" \"Ks\" 0.7 \"roughness\" 0.2 \"specularcolor\" [1 0.5 0]\n") +
                  kUnitPatch + "Surface \"wood\" \"grain\" 3\n" + kUnitPatch + "WorldEnd\n",
              log);
    const Attributes& a = *scene.patches[0].attributes;
    EXPECT_EQ(a.opacity, Color(0.5f, 1, 1));
    EXPECT_DOUBLE_EQ(a.shadingRate, 4);
    EXPECT_EQ(a.surface.name, "plastic");
    EXPECT_DOUBLE_EQ(a.surface.params.getFloat("Ks", 0), 0.7);
    EXPECT_EQ(a.surface.params.getColor("specularcolor", {}), Color(1, 0.5f, 0));
    // Any other name is a Shading Language shader, found and checked when the render binds it;
    // a parameter without a declaration takes the shader's type then.
    const ShaderDesc& wood = scene.patches[1].attributes->surface;
    EXPECT_EQ(wood.name, "wood");
    ASSERT_NE(wood.params.find("grain"), nullptr);
    EXPECT_FALSE(wood.params.find("grain")->declared);
    EXPECT_EQ(wood.params.find("grain")->nums, std::vector<double>{3});
    // Opacity is transparency now: no warning.
    EXPECT_EQ(log.warnings(), std::vector<std::string>{});
}

TEST(RibAttributes, LightsAttachToTheirAttributeScope) {
    Scene scene =
        parse(std::string("WorldBegin\n"
                          "LightSource \"ambientlight\" 1 \"intensity\" 0.2\n"
                          "AttributeBegin\n"
                          "Translate 0 3 0\n"
                          "LightSource \"pointlight\" \"key\" \"from\" [1 2 3] \"lightcolor\" [1 0.5 0]\n") +
              kUnitPatch + "Illuminate 1 0\n" + kUnitPatch + "AttributeEnd\n" + kUnitPatch +
              "Illuminate \"key\" 1\n" + kUnitPatch + "WorldEnd\n");
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].type, "ambientlight");
    EXPECT_DOUBLE_EQ(scene.lights[0].params.getFloat("intensity", 1), 0.2);
    EXPECT_EQ(scene.lights[1].type, "pointlight");
    expectNear(scene.lights[1].params.getPoint("from", {}), {1, 2, 3});
    expectNear(scene.lights[1].lightToWorld.at(0).point({1, 2, 3}), {1, 5, 3});
    EXPECT_EQ(scene.lights[1].loc.line, 5);
    ASSERT_EQ(scene.patches.size(), 4u);
    EXPECT_EQ(scene.patches[0].attributes->lights, (std::vector<int>{0, 1}));
    EXPECT_EQ(scene.patches[1].attributes->lights, (std::vector<int>{1}));     // ambient turned off
    EXPECT_EQ(scene.patches[2].attributes->lights, (std::vector<int>{0}));     // back outside the block
    EXPECT_EQ(scene.patches[3].attributes->lights, (std::vector<int>{0, 1}));  // turned on by handle
}

TEST(RibAttributes, LightShadowsAttributeMarksTheLightsDeclaredUnderIt) {
    Scene scene = parse("WorldBegin\n"
                        "LightSource \"distantlight\" 1\n"
                        "AttributeBegin\n"
                        "  Attribute \"light\" \"shadows\" \"on\"\n"
                        "  LightSource \"distantlight\" 2\n"
                        "  LightSource \"pointlight\" 3\n"
                        "  Attribute \"light\" \"string shadows\" [\"off\"]\n"
                        "  LightSource \"pointlight\" 4\n"
                        "AttributeEnd\n"
                        "LightSource \"pointlight\" 5\n"
                        "WorldEnd\n");
    ASSERT_EQ(scene.lights.size(), 5u);
    const bool expected[5] = {false, true, true, false, false};  // AttributeEnd restores "off"
    for (size_t i = 0; i < 5; ++i) EXPECT_EQ(scene.lights[i].castsShadows, expected[i]) << "light " << i + 1;
}

TEST(RibErrors, LightShadowsMustBeOnOrOff) {
    std::string e = errorOf("WorldBegin\n\nAttribute \"light\" \"shadows\" \"yes\"\nWorldEnd\n");
    EXPECT_NE(e.find("bad.rib:3: "), std::string::npos) << e;
    EXPECT_NE(e.find("expected \"on\" or \"off\", not \"yes\""), std::string::npos) << e;
}

// ---- Reuse: parsing more input into the same scene ------------------------------------------------
TEST(RibParserReuse, SecondStringContinuesWithCurrentState) {
    Scene scene;
    Log log;
    RibParser parser(scene, log);
    parser.parseString("WorldBegin\nColor 1 0 0\nTranslate 2 0 0\n", "main.rib");
    EXPECT_TRUE(parser.inWorld());
    parser.parseString(std::string("Scale 3 3 3\n") + kUnitPatch, "archive.rib");
    parser.parseString("WorldEnd\n", "main.rib");
    parser.finish();
    ASSERT_EQ(scene.patches.size(), 1u);
    EXPECT_EQ(*scene.patches[0].loc.file, "archive.rib");
    EXPECT_EQ(scene.patches[0].loc.line, 2);
    EXPECT_EQ(scene.patches[0].attributes->color, Color(1, 0, 0));
    expectNear(scene.patches[0].objectToWorld.at(0).point({1, 0, 0}), {5, 0, 0});
}

TEST(RibParserReuse, MissingFileIsAnInputErrorWithoutLine) {
    Log log;
    try {
        parseRibFile("/nonexistent/x.rib", log);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "cannot open scene '/nonexistent/x.rib': No such file or directory");
    }
}

// ---- Errors and warnings name file:line -----------------------------------------------------------
struct BadCase {
    const char* what;
    std::string text;
    const char* mentions;  // part of the message
};

TEST(RibErrors, MalformedInputNamesTheLine) {
    const std::string patch12 = "Patch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0]";
    const std::vector<BadCase> cases = {
        {"unknown parameter", "WorldBegin\n\n" + patch12 + " \"foo\" 1\nWorldEnd\n",
         "parameter 'foo' is not declared"},
        {"P count", "WorldBegin\n\nPatch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0 1 1]\nWorldEnd\n",
         "'P' has 11 numbers, expected 12"},
        {"Cs count", "WorldBegin\n\n" + patch12 + " \"Cs\" [1 0 0 0 1 0]\nWorldEnd\n",
         "'Cs' has 6 numbers, expected 12"},
        {"unterminated string", "WorldBegin\n\nSurface \"matte\nWorldEnd\n", "unterminated string"},
        {"unterminated array", "WorldBegin\n\nPatch \"bilinear\" \"P\" [0 0 0\n 1 0 0", "unterminated array"},
        {"request inside array", "WorldBegin\n\nPatch \"bilinear\" \"P\" [0 0 0\nWorldEnd\n",
         "unterminated array"},
        {"NaN", "WorldBegin\n\nTranslate nan 0 0\nWorldEnd\n", "NaN and infinity"},
        {"overflow", "WorldBegin\n\nTranslate 1e999 0 0\nWorldEnd\n", "overflows to infinity"},
        {"missing WorldEnd", "WorldBegin\n\n" + patch12 + "\n", "missing WorldEnd"},
        {"unbalanced AttributeEnd", "WorldBegin\n\nAttributeEnd\nWorldEnd\n", "AttributeEnd without"},
        {"unclosed AttributeBegin", "WorldBegin\n\nAttributeBegin\nWorldEnd\n", "AttributeBegin is never closed"},
        {"unclosed TransformBegin at EOF", "WorldBegin\nWorldEnd\nTransformBegin\n",
         "TransformBegin is never closed"},
        {"mismatched block end", "WorldBegin\nAttributeBegin\nTransformEnd\nWorldEnd\n", "does not match"},
        {"unbalanced MotionBegin", "WorldBegin\n\nMotionBegin [0 1]\nTranslate 1 0 0\nTranslate 2 0 0\n",
         "MotionBegin is never closed"},
        {"MotionEnd alone", "WorldBegin\n\nMotionEnd\nWorldEnd\n", "MotionEnd without MotionBegin"},
        {"nested MotionBegin", "WorldBegin\nMotionBegin [0 1]\nMotionBegin [0 1]\n", "nested MotionBegin"},
        {"too many motion requests",
         "WorldBegin\nMotionBegin [0 1]\nTranslate 1 0 0 Translate 2 0 0 Translate 3 0 0\n",
         "give one request per time"},
        {"too few motion requests", "WorldBegin\nMotionBegin [0 1] Translate 1 0 0\nMotionEnd\nWorldEnd\n",
         "gives 2 times, but the block holds 1 request"},
        {"mixed motion requests", "WorldBegin\nMotionBegin [0 1] Translate 1 0 0\nScale 2 2 2\n",
         "must be the same"},
        {"motion times", "WorldBegin\n\nMotionBegin [1 1]\n", "increase strictly"},
        {"not allowed in motion", "WorldBegin\nMotionBegin [0 1]\nColor 1 0 0\n", "cannot appear inside a motion"},
        {"wrong argument type", "WorldBegin\n\nTranslate \"a\" 1 2\nWorldEnd\n", "got the string \"a\""},
        {"too few arguments", "WorldBegin\n\nTranslate 1 2\nWorldEnd\n", "expected 3 numbers"},
        {"extra argument", "WorldBegin\n\nColor 1 0 0 1\nWorldEnd\n", "unexpected extra argument"},
        {"unexpected character", "WorldBegin\n\n@\nWorldEnd\n", "unexpected character '@'"},
        {"singular transform", "WorldBegin\n\nScale 1 0 1\nWorldEnd\n", "singular"},
        {"zero Format", "\n\nFormat 0 480 1\nWorldBegin\nWorldEnd\n", "xres must be between 1 and 65536"},
        {"huge Format", "\n\nFormat 640 70000 1\nWorldBegin\nWorldEnd\n", "yres must be between 1 and 65536"},
        {"bad Clipping", "\n\nClipping 10 1\nWorldBegin\nWorldEnd\n", "far must be greater than near"},
        {"bad Shutter", "\n\nShutter 1 0\nWorldBegin\nWorldEnd\n", "close must not come before open"},
        {"huge PixelSamples", "\n\nPixelSamples 100 1\nWorldBegin\nWorldEnd\n", "at most 64"},
        {"huge PixelFilter", "\n\nPixelFilter \"box\" 1 1666666666666\nWorldBegin\nWorldEnd\n", "at most 32 pixels"},
        {"bad Projection", "\n\nProjection \"fisheye\"\nWorldBegin\nWorldEnd\n",
         "\"perspective\" or \"orthographic\""},
        {"frames reversed", "\n\nOption \"streyes\" \"int frames\" [5 1]\nWorldBegin\nWorldEnd\n", "comes after"},
        {"polygon too small", "WorldBegin\n\nPolygon \"P\" [0 0 0 1 0 0]\nWorldEnd\n", "at least 3 vertices"},
        {"bad inline declaration", "WorldBegin\n\n" + patch12 + " \"uniform flaot g\" 1\nWorldEnd\n",
         "unknown type 'flaot'"},
        {"string for a float", "WorldBegin\n\nSurface \"matte\" \"Kd\" \"high\"\nWorldEnd\n",
         "declared uniform float"},
        {"wrong shape for a shader parameter", "WorldBegin\n\nSurface \"matte\" \"Kd\" [1 2]\nWorldEnd\n",
         "must be one float"},
        {"unknown light handle", "WorldBegin\n\nIlluminate 7 1\nWorldEnd\n", "no light has the handle '7'"},
        {"no WorldBegin", "Format 10 10 1\n\nDisplay \"a.exr\" \"file\" \"rgb\"\n", "no WorldBegin"},
        {"Pz", "WorldBegin\n\nPatch \"bilinear\" \"Pz\" [0 0 0 0]\nWorldEnd\n", "\"Pz\" is not supported"},
    };
    for (const BadCase& c : cases) {
        std::string e = errorOf(c.text);
        EXPECT_NE(e.find("bad.rib:3: "), std::string::npos) << c.what << ": " << e;
        EXPECT_NE(e.find(c.mentions), std::string::npos) << c.what << ": " << e;
    }
    // What PRMan and Aqsis warn about and render without (issue 46: these were errors here until
    // then) is a warning (rib_lenient_test.cpp), and an error naming the line under --strict.
    const std::vector<BadCase> peersWarn = {
        {"option in world", "WorldBegin\n\nFormat 10 10 1\nWorldEnd\n", "Format is an option: it belongs before WorldBegin"},
        {"geometry before world", "\n\n" + patch12 + "\nWorldBegin\nWorldEnd\n", "ignored before WorldBegin"},
        {"geometry after world", "WorldBegin\nWorldEnd\n" + patch12 + "\n", "ignored after WorldEnd"},
        {"misspelled request", "WorldBegin\n\nworldend\nWorldEnd\n", "did you mean 'WorldEnd'"},
    };
    for (const BadCase& c : peersWarn) {
        EXPECT_EQ(errorOf(c.text), "") << c.what;
        std::string e = test::ribError(c.text, true);
        EXPECT_NE(e.find("bad.rib:3: "), std::string::npos) << c.what << ": " << e;
        EXPECT_NE(e.find(c.mentions), std::string::npos) << c.what << ": " << e;
    }
}

TEST(RibErrors, UnsupportedRequestWarnsOnceAndParses) {
    // PixelVariance only tunes another renderer's sampling: accepted silently (it warned before).
    Log log;
    Scene scene = parse(std::string("Format 8 8 1\nColorSamples [1 0 0 0 1 0 0 0 1] [1 0 0 0 1 0 0 0 1]\n"
                                    "ColorSamples [1 0 0 0 1 0 0 0 1] [1 0 0 0 1 0 0 0 1]\n"
                                    "WorldBegin\nPixelVariance 0.01\nMatte 0\nMatte 1\n") +
                            kUnitPatch + "WorldEnd\n",
                        log);
    EXPECT_EQ(scene.patches.size(), 1u);
    std::vector<std::string> w = log.warnings();
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0], "test.rib:2: warning: unsupported request 'ColorSamples' ignored");
    // Matte 0 and Matte 1 are read silently: the patch after them is a holdout.
    const Param* matte = scene.patches[0].attributes->user.find("streyes:matte");
    ASSERT_NE(matte, nullptr);
    EXPECT_EQ(matte->nums, std::vector<double>{1});
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// CropWindow: the whole frame is silent, a smaller window warns (it is not cut out yet), a window
// outside [0, 1] or empty is an error at its line.
TEST(RibErrors, CropWindowIsReadSilentlyBadFails) {
    {
        Log log;
        parse(std::string("CropWindow 0 1 0 1\nWorldBegin\n") + kUnitPatch + "WorldEnd\n", log);
        EXPECT_TRUE(log.warnings().empty());
    }
    {
        // Kept among the options (what option("CropWindow") and the renderer read).
        Log log;
        const Scene scene = parse(std::string("CropWindow 0.25 0.75 0 1\nWorldBegin\n") + kUnitPatch + "WorldEnd\n", log);
        EXPECT_TRUE(log.warnings().empty());
        const Param* crop = scene.settings.options.find("CropWindow");
        ASSERT_NE(crop, nullptr);
        EXPECT_EQ(crop->nums, (std::vector<double>{0.25, 0.75, 0, 1}));
    }
    for (const char* bad : {"CropWindow 0 1.5 0 1\n", "CropWindow 0.5 0.5 0 1\n", "CropWindow 0 1 0\n"}) {
        Log log;
        try {
            parse(std::string("Format 8 8 1\n") + bad + "WorldBegin\n" + kUnitPatch + "WorldEnd\n", log);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("test.rib:2"), std::string::npos) << e.what();
        }
    }
}

}  // namespace
}  // namespace streyes
