// Blobby field plug-ins (scene/blobby_plugin.h): PRMan's form (opcode 1004, ImplicitFieldNew) and
// AIR's (opcode 9000, ImplicitBound/ImplicitValue), built by the suite (tests/data/plugins/):
// a plug-in sphere's silhouette is its level set's, a plug-in leaf blends with an ellipsoid as a
// second ellipsoid does, and a missing plug-in or entry point is reported at its line.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "streyes/rib.h"
#include "streyes/scene_access.h"
#include "test_util.h"

namespace streyes {
namespace {

constexpr double kPi = 3.14159265358979323846;
const double kLevelRadius = 0.5;  // where a lone (1 - r^2)^3 blob is 27/64, the level
const std::string kPluginDir = STREYES_PLUGIN_DIR;

std::string n(double v) { return std::to_string(v); }

std::string sphereMatrix(double R, double x, double y, double z) {
    return n(R) + " 0 0 0  0 " + n(R) + " 0 0  0 0 " + n(R) + " 0  " + n(x) + " " + n(y) + " " + n(z) + " 1";
}

std::string header(int w, int h) {
    return test::orthoHeader(w, h, "Option \"searchpath\" \"procedural\" [\"" + kPluginDir + ":&\"]\n");
}

TEST(BlobbyPlugin, PrmanSphereFieldHasTheLevelSetsSilhouette) {
    // test_implicit_sphere: (1 - r^2/R^2)^3 around (cx, cy, cz): the level 27/64 at R / 2.
    const double R = 60, r = R * kLevelRadius;
    const std::string rib = header(64, 64) + "Blobby 1 [1004 0 4 0 0 0] [32 32 100 " + n(R) +
                            "] [\"test_implicit_sphere\"]\nWorldEnd\n";
    const test::RenderResult result = test::renderRib(rib);
    EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
    EXPECT_NEAR(test::alphaSum(result), kPi * r * r, 0.01 * kPi * r * r);
    EXPECT_NEAR(result.z(0, 32, 32), 100 - r, 0.5);
}

TEST(BlobbyPlugin, AirSphereFieldIsPlacedByItsMatrix) {
    // test_dbo_sphere: the field 1 - |p| / R in its own space, the level 27/64 at |p| = 37/64 R;
    // the matrix scales that space by 2 and moves it to (32, 32, 100): a sphere of radius 37/32 R.
    const double R = 24, radius = R * 37.0 / 32.0;
    const std::string rib = header(64, 64) + "Blobby 1 [9000 4 0 0 1 16] [" + sphereMatrix(2, 32, 32, 100) + " " +
                            n(R) + "] [\"test_dbo_sphere\"]\nWorldEnd\n";
    const test::RenderResult result = test::renderRib(rib);
    EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
    EXPECT_NEAR(test::alphaSum(result), kPi * radius * radius, 0.01 * kPi * radius * radius);
    EXPECT_NEAR(result.z(0, 32, 32), 100 - radius, 0.5);
}

TEST(BlobbyPlugin, PluginLeafBlendsAsAnEllipsoidDoes) {
    // Two overlapping blobs, the second an ellipsoid or the plug-in's same field: one merged shape,
    // and the per-leaf colours blended by each leaf's field, the same either way.
    const double R = 30;
    const std::string first = sphereMatrix(R, 22, 32, 100);
    const std::string colours = " \"varying color Cs\" [1 0 0  0 0 1]\n";
    const std::string builtIn = header(64, 64) + "Surface \"matte\"\nLightSource \"ambientlight\" 1 \"intensity\" 1\n" +
                                "Blobby 2 [1001 0 1001 16 0 2 0 1] [" + first + " " + sphereMatrix(R, 42, 32, 100) +
                                "] [\"\"]" + colours + "WorldEnd\n";
    const std::string plugin = header(64, 64) + "Surface \"matte\"\nLightSource \"ambientlight\" 1 \"intensity\" 1\n" +
                               "Blobby 2 [1001 0 1004 0 4 16 0 0 0 2 0 1] [" + first + " 42 32 100 " + n(R) +
                               "] [\"test_implicit_sphere\"]" + colours + "WorldEnd\n";
    const test::RenderResult a = test::renderRib(builtIn), b = test::renderRib(plugin);
    const double lone = kPi * std::pow(R * kLevelRadius, 2);
    EXPECT_GT(test::alphaSum(a), 1.5 * lone);  // both blobs are drawn, merged
    EXPECT_NEAR(test::alphaSum(b), test::alphaSum(a), 1e-3 * test::alphaSum(a));
    // Pixels agree but for the plug-in's float arithmetic (a vertex moves by ~1e-6).
    EXPECT_LT(test::maxAbsDifference(a, b), 1e-3f);
    // Red on the left, blue on the right, a blend at the middle: the colours do vary.
    EXPECT_GT(b.channel(0, 14, 32, 0), 0.9f);
    EXPECT_GT(b.channel(0, 50, 32, 2), 0.9f);
    // The pixels either side of the midpoint (x = 32) mirror each other: red at 31 is blue at 32.
    EXPECT_NEAR(b.channel(0, 31, 32, 0), b.channel(0, 32, 32, 2), 0.01f);
    EXPECT_GT(b.channel(0, 32, 32, 0), 0.3f);
    EXPECT_GT(b.channel(0, 32, 32, 2), 0.3f);
}

TEST(BlobbyPlugin, MissingPluginWarnsAtItsLineAndTakesItsFieldAsZero) {
    const std::string blob = sphereMatrix(60, 32, 32, 100);
    const test::RenderResult alone =
        test::renderRib(header(64, 64) + "Blobby 1 [1001 0] [" + blob + "] [\"\"]\nWorldEnd\n");
    for (const std::string& code : {std::string("1001 0 1004 0 0 0 0 0 0 2 0 1"), std::string("1001 0 9000 2 0 0 0 2 0 1")}) {
        const std::string rib = header(64, 64) + "Blobby 2 [" + code + "] [" + blob + "] [\"no_such_field\"]\nWorldEnd\n";
        const test::RenderResult r = test::renderRib(rib);
        ASSERT_EQ(r.warnings.size(), 1u) << code;
        EXPECT_NE(r.warnings[0].find("test.rib:8"), std::string::npos) << r.warnings[0];
        EXPECT_NE(r.warnings[0].find("no field plug-in 'no_such_field'"), std::string::npos) << r.warnings[0];
        EXPECT_NE(r.warnings[0].find("searchpath"), std::string::npos) << r.warnings[0];
        EXPECT_TRUE(test::identicalPixels(r, alone)) << code;
        // Under --strict, an error.
        EXPECT_NE(test::ribError(rib, true).find("no field plug-in"), std::string::npos) << code;
    }
}

TEST(BlobbyPlugin, PluginWithoutItsEntryPointIsAnErrorAtItsLine) {
    const std::string m = sphereMatrix(1, 0, 0, 0);
    const std::string prman = test::ribError(header(8, 8) + "Blobby 1 [1004 0 0 0 0 0] [] [\"" + kPluginDir +
                                             "/test_plugin_no_symbols.so\"]\nWorldEnd\n");
    EXPECT_NE(prman.find("bad.rib:8"), std::string::npos) << prman;
    EXPECT_NE(prman.find("does not export ImplicitFieldNew"), std::string::npos) << prman;
    const std::string air = test::ribError(header(8, 8) + "Blobby 1 [9000 2 0 0] [" + m + "] [\"" + kPluginDir +
                                           "/test_implicit_sphere.so\"]\nWorldEnd\n");
    EXPECT_NE(air.find("bad.rib:8"), std::string::npos) << air;
    EXPECT_NE(air.find("does not export ImplicitValue ImplicitBound"), std::string::npos) << air;
    // And a 9000 instruction with a wrong operand count.
    const std::string count = test::ribError(header(8, 8) + "Blobby 1 [9000 3 0 0 0] [" + m +
                                             "] [\"test_dbo_sphere\"]\nWorldEnd\n");
    EXPECT_NE(count.find("9000) has 3 operands"), std::string::npos) << count;
}

TEST(BlobbyPlugin, SafeRefusesFieldPlugins) {
    // A plug-in runs code: --safe refuses it at the Blobby's line, as it does DynamicLoad's.
    const SceneAccess before = sceneAccess();
    SceneAccess safe = before;
    safe.programs = false;
    safe.safe = true;
    setSceneAccess(safe);
    const std::string e = test::ribError(header(8, 8) + "Blobby 1 [1004 0 4 0 0 0] [0 0 0 1] [\"test_implicit_sphere\"]\n"
                                         "WorldEnd\n");
    setSceneAccess(before);
    EXPECT_NE(e.find("bad.rib:8"), std::string::npos) << e;
    EXPECT_NE(e.find("refused by --safe"), std::string::npos) << e;
}

}  // namespace
}  // namespace streyes
