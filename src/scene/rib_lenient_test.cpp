// What the RIB reader forgives as PRMan and Aqsis do (a warning naming file:line, the rest read),
// what --strict (Log::setStrict) makes of the same input, the Option and Attribute values it keeps
// for shaders and other passes, empty primitives, attributes inside object definitions, level of
// detail and Geometry "teapot" as the scene holds them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "streyes/rib.h"

namespace streyes {
namespace {

const char* kUnitPatch = "Patch \"bilinear\" \"P\" [0 0 0  1 0 0  0 1 0  1 1 0]\n";

Scene parse(const std::string& text, Log& log) { return parseRibString(text, "test.rib", log); }

// The InputError message of parsing `text` under --strict, or "" when it reads.
std::string strictError(const std::string& text) {
    Log log;
    log.setQuiet(true);
    log.setStrict(true);
    try {
        parseRibString(text, "strict.rib", log);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// ---- What the peers warn about: warned once, skipped; errors under --strict ------------------------
// These four were errors before (rib_parser_test.cpp's RibErrors cases "option in world",
// "geometry before world", "geometry after world" and "misspelled request"): PRMan and Aqsis warn
// and render, so streyes does too; --strict keeps them errors.
TEST(RibLenient, RequestsInTheWrongBlockAreSkippedWithAWarning) {
    const std::string patch = kUnitPatch;
    struct Case {
        const char* what;
        std::string text;
        const char* warning;
        size_t patches;
    };
    const std::vector<Case> cases = {
        {"an Imager inside the world (11 Aqsis scenes)",
         "\nWorldBegin\nImager \"background\" \"color bgcolor\" [1 0 0]\n" + patch + "WorldEnd\n",
         "test.rib:3: warning: Imager is an option: it belongs before WorldBegin (line 2); ignored here", 1},
        {"an option inside the world", "WorldBegin\n\nFormat 10 10 1\n" + patch + "WorldEnd\n",
         "test.rib:3: warning: Format is an option", 1},
        {"geometry before the world", "\n\n" + patch + "WorldBegin\n" + patch + "WorldEnd\n",
         "test.rib:3: warning: Patch belongs between WorldBegin and WorldEnd: ignored before WorldBegin", 1},
        {"geometry after the world", "WorldBegin\nWorldEnd\n" + patch,
         "test.rib:3: warning: Patch belongs between WorldBegin and WorldEnd: ignored after WorldEnd", 0},
        {"an unknown request, with its arguments", "WorldBegin\n\nShaderGroupBegin \"plastic\" \"a\" \"Kd\" 1\n" + patch + "WorldEnd\n",
         "test.rib:3: warning: unknown request 'ShaderGroupBegin' ignored", 1},
        {"a request misspelled in case", "WorldBegin\n\ntranslate 1 0 0\n" + patch + "WorldEnd\n",
         "did you mean 'Translate'", 1},
    };
    for (const Case& c : cases) {
        Log log;
        log.setQuiet(true);
        const Scene scene = parse(c.text, log);
        EXPECT_EQ(scene.patches.size(), c.patches) << c.what;
        EXPECT_TRUE(scene.settings.imager.name.empty()) << c.what;
        EXPECT_EQ(scene.camera.xres, 640) << c.what;  // Format in the world left no mark
        const std::vector<std::string> w = log.warnings();
        ASSERT_EQ(w.size(), 1u) << c.what;
        EXPECT_NE(w[0].find(c.warning), std::string::npos) << c.what << ": " << w[0] << " (expected " << c.warning << ")";
        // --strict: the same warning is an error at the same line.
        const std::string e = strictError(c.text);
        EXPECT_NE(e.find("strict.rib:3: "), std::string::npos) << c.what << ": " << e;
        EXPECT_NE(e.find("(an error under --strict)"), std::string::npos) << c.what << ": " << e;
    }
    // The translate misspelled moved nothing: the patch is where it was.
    Log log;
    log.setQuiet(true);
    const Scene scene = parse("WorldBegin\ntranslate 5 0 0\n" + patch + "WorldEnd\n", log);
    ASSERT_EQ(scene.patches.size(), 1u);
    EXPECT_EQ(scene.patches[0].objectToWorld.keys()[0], Matrix4::identity());
}

TEST(RibLenient, EachKindIsSaidOnce) {
    Log log;
    log.setQuiet(true);
    parse("WorldBegin\nFoo 1\nFoo 2\nBar\nImager \"x\"\nImager \"y\"\nWorldEnd\n", log);
    const std::vector<std::string> w = log.warnings();
    ASSERT_EQ(w.size(), 3u);
    EXPECT_NE(w[0].find("test.rib:2: warning: unknown request 'Foo'"), std::string::npos) << w[0];
    EXPECT_NE(w[1].find("test.rib:4: warning: unknown request 'Bar'"), std::string::npos) << w[1];
    EXPECT_NE(w[2].find("test.rib:5: warning: Imager is an option"), std::string::npos) << w[2];
}

TEST(RibLenient, MalformedInputStaysAnError) {
    // Leniency is for what the peers skip, not for what cannot be read.
    Log log;
    for (const char* bad : {"WorldBegin\nTranslate 1 nan 0\nWorldEnd\n", "WorldBegin\nColor 1 0\nWorldEnd\n",
                            "WorldBegin\nPatch \"bilinear\" \"P\" [0 0 0 1 0 0 0 1 0]\nWorldEnd\n",
                            "WorldBegin\nAttribute \"user\" \"float x\" \"a\"\nWorldEnd\n",
                            "Option\nWorldBegin\nWorldEnd\n", "WorldBegin\nDetailRange 5 1 2 3\nWorldEnd\n",
                            "WorldBegin\nAttributeEnd\nWorldEnd\n"}) {
        EXPECT_THROW(parse(bad, log), InputError) << bad;
        EXPECT_NE(strictError(bad), "") << bad;
    }
}

// ---- Options and attributes: never an error for want of a declaration ----------------------------
TEST(RibOptionsKept, EveryValueIsKeptAndTuningOptionsAreSilent) {
    Log log;
    const Scene scene = parse(
        "Option \"limits\" \"texturememory\" 8192 \"eyesplits\" 5 \"othreshold\" [0.99 0.99 0.99]\n"
        "Option \"limits\" \"bucketsize\" [32 32] \"gridsize\" 128\n"
        "Option \"user\" \"string pass\" \"bake\" \"float weight\" [0.25]\n"
        "Option \"user\" \"passnumber\" 3\n"
        "Option \"trace\" \"int maxdepth\" [4]\n"
        "Option \"statistics\" \"endofframe\" [3]\n"
        "Option \"render\" \"bucketorder\" \"horizontal\"\n"
        "Option \"shadow\" \"bias\" [0.3]\n"
        "WorldBegin\nWorldEnd\n",
        log);
    EXPECT_TRUE(log.warnings().empty()) << log.warnings()[0];
    const ParamList& o = scene.settings.options;
    EXPECT_EQ(o.getFloat("limits:texturememory", 0), 8192);
    EXPECT_EQ(o.getFloat("limits:eyesplits", 0), 5);
    ASSERT_NE(o.find("limits:othreshold"), nullptr);
    EXPECT_EQ(o.find("limits:othreshold")->nums.size(), 3u);
    EXPECT_FALSE(o.find("limits:othreshold")->declared);  // typed by its value
    EXPECT_EQ(o.getString("user:pass", ""), "bake");
    EXPECT_EQ(o.getFloat("user:weight", 0), 0.25);
    EXPECT_EQ(o.getFloat("user:passnumber", 0), 3);
    EXPECT_EQ(o.find("trace:maxdepth")->type, ParamType::Integer);
    EXPECT_EQ(o.getFloat("shadow:bias", 0), 0.3);
    EXPECT_EQ(o.getString("render:bucketorder", ""), "horizontal");
    // The limits streyes reads still act.
    EXPECT_EQ(scene.settings.bucketSize, 32);
    EXPECT_EQ(scene.settings.gridSize, 128);
}

TEST(RibOptionsKept, AnOptionThatChangesAnotherRenderersPictureWarns) {
    Log log;
    const Scene scene = parse("Option \"photon\" \"emit\" 100000\nOption \"photon\" \"emit\" 2\nWorldBegin\nWorldEnd\n", log);
    const std::vector<std::string> w = log.warnings();
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("test.rib:1: warning: Option \"photon\" is not read by streyes: ignored"), std::string::npos) << w[0];
    EXPECT_EQ(scene.settings.options.getFloat("photon:emit", 0), 2);  // kept all the same, the later value
    EXPECT_NE(strictError("Option \"photon\" \"emit\" 1\nWorldBegin\nWorldEnd\n").find("strict.rib:1: "), std::string::npos);
}

TEST(RibAttributesKept, EveryCategoryIsKeptAndOnlyWhatChangesThePictureWarns) {
    Log log;
    const Scene scene = parse(
        "WorldBegin\n"
        "Attribute \"visibility\" \"integer camera\" [1] \"integer trace\" [1] \"string transmission\" [\"Os\"]\n"
        "Attribute \"visibility\" \"diffuse\" 1 \"specular\" 1\n"
        "Attribute \"trace\" \"integer displacements\" [1] \"bias\" 0.01\n"
        "Attribute \"render\" \"integer truedisplacement\" [0]\n"
        "Attribute \"dice\" \"int rasterorient\" [0]\n"
        "Attribute \"cull\" \"int hidden\" 0 \"int backfacing\" 0\n"
        "Attribute \"displacementbound\" \"sphere\" [0.5]\n"
        "Attribute \"identifier\" \"name\" [\"teapot\"]\n"
        "Attribute \"user\" \"weight\" 2\n" +
            std::string(kUnitPatch) +
            "Attribute \"visibility\" \"integer camera\" [0]\n"
            "Attribute \"visibility\" \"string transmission\" [\"transparent\"]\n"
            "Attribute \"sss\" \"string groupname\" \"skin\"\n" +
            kUnitPatch + "WorldEnd\n",
        log);
    ASSERT_EQ(scene.patches.size(), 2u);
    const ParamList& a = scene.patches[0].attributes->user;
    EXPECT_EQ(a.getFloat("visibility:trace", 0), 1);
    EXPECT_EQ(a.getString("visibility:transmission", ""), "Os");
    EXPECT_EQ(a.getFloat("trace:bias", 0), 0.01);
    EXPECT_EQ(a.getFloat("dice:rasterorient", 1), 0);
    EXPECT_EQ(a.getString("identifier:name", ""), "teapot");
    EXPECT_EQ(a.getFloat("user:weight", 0), 2);
    EXPECT_EQ(scene.patches[0].attributes->displacementBound, 0.5);
    EXPECT_EQ(scene.patches[1].attributes->user.getFloat("visibility:camera", 1), 0);
    const std::vector<std::string> w = log.warnings();
    ASSERT_EQ(w.size(), 3u) << (w.empty() ? "" : w[0]);
    EXPECT_NE(w[0].find("test.rib:12: warning: Attribute \"visibility\" \"camera\" 0 is not supported"), std::string::npos)
        << w[0];
    EXPECT_NE(w[1].find("test.rib:13: warning: Attribute \"visibility\" \"transmission\""), std::string::npos) << w[1];
    EXPECT_NE(w[2].find("test.rib:14: warning: Attribute \"sss\" is not read by streyes"), std::string::npos) << w[2];
}

// ---- Empty primitives: nothing, with one warning ---------------------------------------------------
TEST(RibEmptyPrimitives, AreNothingWithOneWarning) {
    const std::vector<std::pair<const char*, const char*>> cases = {
        {"PointsPolygons", "PointsPolygons [] [] \"P\" []"},
        {"PointsGeneralPolygons", "PointsGeneralPolygons [] [] [] \"P\" []"},
        {"SubdivisionMesh", "SubdivisionMesh \"catmull-clark\" [] [] \"P\" []"},
        {"Points", "Points \"P\" []"},
        {"Curves", "Curves \"linear\" [] \"nonperiodic\" \"P\" []"},
    };
    for (const auto& [request, text] : cases) {
        Log log;
        const Scene scene = parse(std::string("WorldBegin\n") + text + "\n" + text + "\n" + kUnitPatch + "WorldEnd\n", log);
        EXPECT_EQ(scene.patches.size(), 1u) << request;
        EXPECT_TRUE(scene.polygonMeshes.empty() && scene.subdivisionMeshes.empty() && scene.points.empty() &&
                    scene.curves.empty())
            << request;
        const std::vector<std::string> w = log.warnings();
        ASSERT_EQ(w.size(), 1u) << request;
        EXPECT_NE(w[0].find("test.rib:2: warning: " + std::string(request) + " has no"), std::string::npos)
            << request << ": " << w[0];
        EXPECT_NE(strictError(std::string("WorldBegin\n") + text + "\nWorldEnd\n").find("strict.rib:2: "), std::string::npos)
            << request;
    }
}


// ---- Geometry "teapot" ---------------------------------------------------------------------------
// A point of a bicubic Bezier patch (rows of constant v, u fastest).
Vec3d bezierPoint(const std::vector<Vec3d>& P, double u, double v) {
    auto b = [](double t, int i) {
        const double s = 1 - t;
        return i == 0 ? s * s * s : i == 1 ? 3 * t * s * s : i == 2 ? 3 * t * t * s : t * t * t;
    };
    Vec3d p{0, 0, 0};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) p = p + P[size_t(j * 4 + i)] * (b(u, i) * b(v, j));
    return p;
}

// A patch's side k (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0) at parameter s along it.
Vec3d sidePoint(const std::vector<Vec3d>& P, int k, double s) {
    switch (k) {
    case 0: return bezierPoint(P, s, 0);
    case 1: return bezierPoint(P, 1, s);
    case 2: return bezierPoint(P, s, 1);
    default: return bezierPoint(P, 0, s);
    }
}

TEST(RibTeapot, ThirtyTwoBezierPatchesThatJoinWithoutCracks) {
    Log log;
    const Scene scene =
        parse("WorldBegin\nBasis \"b-spline\" 1 \"b-spline\" 1\nColor 1 0 0\nGeometry \"teapot\"\nWorldEnd\n", log);
    EXPECT_TRUE(log.warnings().empty());
    ASSERT_EQ(scene.patchMeshes.size(), 32u);
    const BasisDesc bezier;
    Bounds3d box;
    for (const PatchMeshDesc& p : scene.patchMeshes) {
        EXPECT_TRUE(p.bicubic && p.nu == 4 && p.nv == 4);
        EXPECT_EQ(p.uBasis.m, bezier.m);  // Bezier, whatever Basis is in force
        EXPECT_EQ(p.attributes->color, Color(1, 0, 0));
        for (const Vec3d& q : p.P[0]) box.extend(q);
    }
    // Newell's teapot: bottom at z = 0, lid at 3.15, spout to x = 3.525, handle to x = -3, 2 wide.
    EXPECT_EQ(box.lo.z, 0);
    EXPECT_EQ(box.hi.z, 3.15);
    EXPECT_EQ(box.hi.x, 3.525);
    EXPECT_EQ(box.lo.x, -3);
    EXPECT_EQ(box.hi.y, 2);
    // Where two patches' sides meet at both ends, they are one curve: the surface has no crack.
    // Counted by part: the body is 3 rings of 4 patches (12 seams around, 8 between rings) on the
    // bottom's 4 patches (4 seams to the body, 4 around); the lid 2 rings of 4 (8 around, 4
    // between); the handle and the spout each 2 lengths of 2 halves (4 seams along, 2 across).
    const size_t expectedJoins = (12 + 8) + (4 + 4) + (8 + 4) + (4 + 2) + (4 + 2);
    // The other sides that meet at both ends are the two halves of the handle's and the spout's
    // cross-sections (their ends, and where their two lengths meet), mirror images across y = 0
    // that close the tube between them: 3 sections of the handle's and 3 of the spout's, each
    // seen by both lengths' patches where two lengths meet (2 x 2 pairs) or once at an end.
    const size_t expectedSections = 2 * (1 + 4 + 1);
    size_t joins = 0, sections = 0, degenerate = 0;
    double worst = 0, worstSection = 0;
    for (size_t a = 0; a < 32; ++a)
        for (int ka = 0; ka < 4; ++ka) {
            const std::vector<Vec3d>& A = scene.patchMeshes[a].P[0];
            const Vec3d a0 = sidePoint(A, ka, 0), a1 = sidePoint(A, ka, 1);
            if (length(a1 - a0) < 1e-9 && length(sidePoint(A, ka, 0.5) - a0) < 1e-9) {
                ++degenerate;  // a side shrunk to a point (the lid's knob, the bottom's centre)
                continue;
            }
            for (size_t b = a + 1; b < 32; ++b)
                for (int kb = 0; kb < 4; ++kb) {
                    const std::vector<Vec3d>& B = scene.patchMeshes[b].P[0];
                    const Vec3d b0 = sidePoint(B, kb, 0), b1 = sidePoint(B, kb, 1);
                    const bool same = length(a0 - b0) < 1e-9 && length(a1 - b1) < 1e-9;
                    const bool reversed = length(a0 - b1) < 1e-9 && length(a1 - b0) < 1e-9;
                    if (!same && !reversed) continue;
                    double apart = 0, mirrored = 0;
                    for (int i = 1; i < 16; ++i) {
                        const double s = i / 16.0;
                        const Vec3d p = sidePoint(A, ka, s), q = sidePoint(B, kb, same ? s : 1 - s);
                        apart = std::max(apart, length(p - q));
                        mirrored = std::max(mirrored, length(p - Vec3d(q.x, -q.y, q.z)));
                    }
                    if (apart < 1e-3) {
                        ++joins;
                        worst = std::max(worst, apart);
                    } else {
                        ++sections;
                        worstSection = std::max(worstSection, mirrored);
                    }
                }
        }
    EXPECT_EQ(joins, expectedJoins);
    EXPECT_LT(worst, 1e-9);  // the data's shared points are equal, so the curves are identical
    EXPECT_EQ(sections, expectedSections);
    EXPECT_LT(worstSection, 1e-9);
    EXPECT_EQ(degenerate, 4u + 4u);  // the knob's 4 patches and the bottom's 4 meet in a point each
}

TEST(RibTeapot, OtherGeometryTypesWarnOnce) {
    Log log;
    const Scene scene = parse("WorldBegin\nGeometry \"bunny\"\nGeometry \"bunny\"\nWorldEnd\n", log);
    EXPECT_TRUE(scene.patchMeshes.empty());
    ASSERT_EQ(log.warnings().size(), 1u);
    EXPECT_NE(log.warnings()[0].find("test.rib:2: warning: Geometry \"bunny\" is not supported"), std::string::npos);
}

// ---- Attributes inside an object's definition ----------------------------------------------------
TEST(RibObjects, AttributesSetInsideADefinitionApplyOverTheInstances) {
    Log log;
    const Scene scene = parse(
        "WorldBegin\nSurface \"constant\"\n"
        "ObjectBegin 1\nAttributeBegin\nColor [0.1 0.5 0.5]\nOpacity 0.8 0.8 0.8\n" + std::string(kUnitPatch) +
            "AttributeEnd\n" + kUnitPatch + "ObjectEnd\n"
            "AttributeBegin\nColor 1 0 0\nShadingRate 4\nObjectInstance 1\nAttributeEnd\n"
            "AttributeBegin\nColor 0 1 0\nObjectInstance 1\nAttributeEnd\nWorldEnd\n",
        log);
    ASSERT_EQ(scene.procedurals.size(), 2u);
    const ProceduralDesc& red = scene.procedurals[0];
    const ProceduralDesc& green = scene.procedurals[1];
    ASSERT_EQ(red.object->patches.size(), 2u);
    // The first square's state was set inside the definition: each instance has its own copy of
    // it, the object's Color and Opacity over the instance's (whose ShadingRate it keeps); the
    // second square set nothing, so it takes the instance's attributes as they are.
    ASSERT_EQ(red.objectAttributes.size(), 1u);
    EXPECT_EQ(red.objectAttributes[0].first, red.object->patches[0].attributes);
    const Attributes& mixed = *red.objectAttributes[0].second;
    EXPECT_EQ(mixed.color, Color(0.1f, 0.5f, 0.5f));
    EXPECT_EQ(mixed.opacity, Color(0.8f, 0.8f, 0.8f));
    EXPECT_EQ(mixed.shadingRate, 4);
    EXPECT_EQ(mixed.surface.name, "constant");
    EXPECT_EQ(green.objectAttributes.at(0).second->shadingRate, 1);
    EXPECT_EQ(red.attributes->color, Color(1, 0, 0));
    EXPECT_EQ(green.attributes->color, Color(0, 1, 0));
}

// ---- Level of detail -----------------------------------------------------------------------------
TEST(RibDetail, DetailAndRangesAreKeptWithTheAttributes) {
    Log log;
    const Scene scene = parse(
        "RelativeDetail 0.5\nWorldBegin\nAttributeBegin\nTranslate 0 0 5\nDetail [-1 1 -2 2 -3 3]\n"
        "DetailRange [0 0 10 20]\n" + std::string(kUnitPatch) + "DetailRange [10 20 1e38 1e38]\n" + kUnitPatch +
            "AttributeEnd\n" + kUnitPatch + "WorldEnd\n",
        log);
    EXPECT_TRUE(log.warnings().empty());
    EXPECT_EQ(scene.settings.relativeDetail, 0.5);
    ASSERT_EQ(scene.patches.size(), 3u);
    const LevelOfDetail* far = scene.patches[0].attributes->detail.get();
    const LevelOfDetail* near = scene.patches[1].attributes->detail.get();
    ASSERT_TRUE(far && near);
    EXPECT_TRUE(far->hasBound);
    EXPECT_EQ(far->bound.lo, Vec3d(-1, -2, -3));
    EXPECT_EQ(far->bound.hi, Vec3d(1, 2, 3));
    EXPECT_EQ(far->boundToWorld.keys()[0].point({0, 0, 0}), Vec3d(0, 0, 5));
    EXPECT_EQ(far->range, (std::array<double, 4>{0, 0, 10, 20}));
    EXPECT_EQ(near->range[0], 10);
    EXPECT_TRUE(std::isinf(near->range[3]));  // 1e38 is RI_INFINITY
    EXPECT_EQ(scene.patches[2].attributes->detail, nullptr);  // AttributeEnd ends it
}

}  // namespace
}  // namespace streyes
