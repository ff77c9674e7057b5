// A Blobby's per-leaf primitive variables (RI Spec 3.2, 5.6): at a surface point, the leaves'
// values weighted by each leaf's field there over the sum of those fields, read by shaders as on
// any other primitive; PRMan's "vertex mpoint Pref" (a reference frame per leaf) gives the point
// carried from each leaf's blob space into its frame, blended the same way.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "shader_test_util.h"
#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

std::string n(double v) { return std::to_string(v); }

// The matrix of a sphere blob of radius R (its field's reach) centred at (x, y, z), and the same
// frame moved by (dx, dy, dz).
std::string sphereMatrix(double R, double x, double y, double z) {
    return n(R) + " 0 0 0  0 " + n(R) + " 0 0  0 0 " + n(R) + " 0  " + n(x) + " " + n(y) + " " + n(z) + " 1";
}

// Two equal blobs of reach R on the line y = 48, z = 100, their centres R apart (so their fields
// overlap and the surface bridges them), summed; placed under Translate 10 0 0 so that object
// space is not world space. Leaf A is centred at pixel column 66 (x = 66.5), B at 126 (x = 126.5),
// their midpoint at column 96 (x = 96.5).
constexpr double kR = 60, kAx = 66.5, kBx = 126.5, kY = 48, kZ = 100, kShift = 10;

std::string twoBlobs(const std::string& vars, const std::string& surface = "") {
    return "TransformBegin\nTranslate " + n(kShift) + " 0 0\n" + surface + "Blobby 2 [1001 0 1001 16 0 2 0 1] [" +
           sphereMatrix(kR, kAx - kShift, kY, kZ) + "  " + sphereMatrix(kR, kBx - kShift, kY, kZ) + "] [\"\"]\n" +
           vars + "\nTransformEnd\n";
}

// The reference frames: A's blob moved by (1, 0, 0), B's by (0, 0, 1): the point carried through
// a leaf's frame is P plus that offset.
const std::string kFrames = "\"vertex mpoint Pref\" [" + sphereMatrix(kR, kAx - kShift + 1, kY, kZ) + "  " +
                            sphereMatrix(kR, kBx - kShift, kY, kZ + 1) + "]";

double falloff(double d2) {
    const double r2 = d2 / (kR * kR);
    return r2 < 1 ? std::pow(1 - r2, 3) : 0;
}

// Leaf A's share of the blend at object-space point p: fA / (fA + fB).
double shareOfA(const Vec3d& p) {
    const double ay = p.y - kY, az = p.z - kZ;
    const double fa = falloff(std::pow(p.x - (kAx - kShift), 2) + ay * ay + az * az);
    const double fb = falloff(std::pow(p.x - (kBx - kShift), 2) + ay * ay + az * az);
    return fa / (fa + fb);
}

TEST(BlobbyVars, EachVertexGetsTheFieldWeightedBlend) {
    Log log;
    const Scene scene = parseRibString(
        "WorldBegin\nAttribute \"streyes\" \"float blobbyresolution\" [90]\n" + twoBlobs("\"vertex color tint\" [1 0 0  0 0 1] \"varying float amount\" [1 0] "
                                  "\"vertex point Pfixed\" [1 2 3  -1 0 5] " + kFrames) + "WorldEnd\n",
        "v.rib", log);
    EXPECT_TRUE(log.warnings().empty()) << log.warnings().front();
    ASSERT_EQ(scene.polygonMeshes.size(), 1u);
    const PolygonMeshDesc& mesh = scene.polygonMeshes[0];
    const std::vector<Vec3d>& P = mesh.P[0];
    ASSERT_GT(P.size(), 1000u);
    const Param* tint = mesh.primvars.find("tint");
    const Param* amount = mesh.primvars.find("amount");
    const Param* fixed = mesh.primvars.find("Pfixed");
    const Param* pref = mesh.primvars.find("Pref");
    ASSERT_TRUE(tint && amount && fixed && pref);
    EXPECT_EQ(tint->cls, ParamClass::Vertex);
    EXPECT_EQ(pref->type, ParamType::Point);
    ASSERT_EQ(tint->nums.size(), 3 * P.size());
    ASSERT_EQ(amount->nums.size(), P.size());
    ASSERT_EQ(pref->nums.size(), 3 * P.size());
    size_t mixed = 0;  // vertices where both leaves weigh
    for (size_t i = 0; i < P.size(); ++i) {
        const double a = shareOfA(P[i]), b = 1 - a;
        if (a > 0.01 && b > 0.01) ++mixed;
        ASSERT_NEAR(tint->nums[3 * i], a, 1e-9) << i;
        ASSERT_NEAR(tint->nums[3 * i + 1], 0, 1e-12) << i;
        ASSERT_NEAR(tint->nums[3 * i + 2], b, 1e-9) << i;
        ASSERT_NEAR(amount->nums[i], a, 1e-9) << i;
        const Vec3d f = Vec3d(1, 2, 3) * a + Vec3d(-1, 0, 5) * b;
        ASSERT_NEAR(fixed->nums[3 * i], f.x, 1e-9) << i;
        ASSERT_NEAR(fixed->nums[3 * i + 2], f.z, 1e-9) << i;
        // Pref: P carried through each leaf's frame, P + (1, 0, 0) by A and P + (0, 0, 1) by B.
        ASSERT_NEAR(pref->nums[3 * i] - P[i].x, a, 1e-9) << i;
        ASSERT_NEAR(pref->nums[3 * i + 1] - P[i].y, 0, 1e-9) << i;
        ASSERT_NEAR(pref->nums[3 * i + 2] - P[i].z, b, 1e-9) << i;
    }
    EXPECT_GT(mixed, 100u);
}

// A shader that shows one variable as its colour (green when none is bound: no variable is ever
// green). Declared where the blobby is (after its Translate), so "shader" space is its object space.
const char* kShowVars = R"(
surface showvars(varying color tint = color(0, 1, 0); varying float amount = -1;
                 varying point Pfixed = point(0, 1, 0); varying point Pref = point(0, 1, 0);
                 uniform float mode = 0) {
    Oi = 1;
    if (mode == 0) Ci = tint;
    else if (mode == 1) Ci = color(amount, 0, 1 - amount);
    else if (mode == 2) {
        point q = transform("shader", Pfixed);
        Ci = color(xcomp(q), ycomp(q), zcomp(q));
    } else {
        vector d = transform("shader", Pref) - transform("shader", P);
        Ci = color(xcomp(d), ycomp(d), zcomp(d));
    }
}
)";

TEST(BlobbyVars, ShadersReadTheBlend) {
    test::ShaderDir shaders;
    shaders.add("showvars", kShowVars);
    // Each mode shows red (1, 0, 0) where leaf A alone reaches and blue (0, 0, 1) where B does:
    // the per-leaf values are red and blue, the points (1, 0, 0) and (0, 0, 1) in object space
    // (so transforming them back to object space must undo the Translate), and Pref minus P is
    // A's or B's frame offset.
    const std::string vars[] = {
        "\"vertex color tint\" [1 0 0  0 0 1]",
        "\"vertex float amount\" [1 0]",
        "\"vertex point Pfixed\" [1 0 0  0 0 1]",
        kFrames,
    };
    for (int mode = 0; mode < 4; ++mode) {
        const std::string rib = shaders.option() + test::orthographicView(192, 96, "") + "WorldBegin\n" +
                                twoBlobs(vars[mode], "Surface \"showvars\" \"mode\" [" + std::to_string(mode) + "]\n") +
                                "WorldEnd\n";
        const test::RenderResult r = test::renderRib(rib);
        for (int row : {47, 48}) {
            // At A's and B's centres, the mesh's vertices within a cell (2 pixels) of the pixel are
            // at least R - 2.5 = 57.5 from the other leaf: its field there is at most
            // (1 - (57.5/60)^2)^3 = 5.5e-4 against a sum of 27/64 on the surface, a share of at most 1.3e-3.
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(r.channel(0, 66, row, c), c == 0 ? 1 : 0, 2e-3) << mode << " A " << c;
                EXPECT_NEAR(r.channel(0, 126, row, c), c == 2 ? 1 : 0, 2e-3) << mode << " B " << c;
            }
            // The midpoint: equal fields, the mean. Its samples lie within half a pixel of it, where
            // the share changes at |d/dx (fA / (fA + fB))| = 3 (1 - r^2)^2 (2 dx / R^2) / (27/64) with
            // dx = R/2 and r^2 = 0.405 on the surface (each field 27/128): 0.042 a pixel, so at most
            // 0.021 either way.
            EXPECT_NEAR(r.channel(0, 96, row, 0), 0.5, 0.025) << mode;
            // Green is 0 and red + blue is 1 but for float rounding of camera-space coordinates
            // near 100 (Pref - P: a unit in the last place is 7.6e-6 there).
            EXPECT_NEAR(r.channel(0, 96, row, 1), 0.0, 1e-4) << mode;
            EXPECT_NEAR(r.channel(0, 96, row, 2), 0.5, 0.025) << mode;
            EXPECT_NEAR(r.channel(0, 96, row, 0) + r.channel(0, 96, row, 2), 1.0, 1e-4) << mode;
            EXPECT_EQ(r.alpha(0, 96, row), 1.0f) << mode;
        }
    }
}

// Without "s", "t" or "st", s and t are the object-space x and y of the point (as the RI Spec sets
// them on polygons, and as Aqsis gives them on its Blobby's polygons), not each triangle's own
// (u, v): a pattern in s (Aqsis's texture.rib, "stripes") runs across the blobby, not per triangle.
TEST(BlobbyVars, SAndTAreObjectXAndY) {
    for (const char* surface : {"Surface \"showst\"\n", "Surface \"plastic\"\n"}) {
        Log log;
        const Scene scene = parseRibString("WorldBegin\nAttribute \"streyes\" \"float blobbyresolution\" [40]\n" +
                                               twoBlobs("", surface) + "WorldEnd\n",
                                           "st.rib", log);
        ASSERT_EQ(scene.polygonMeshes.size(), 1u);
        const PolygonMeshDesc& mesh = scene.polygonMeshes[0];
        const std::vector<Vec3d>& P = mesh.P[0];
        const Param* s = mesh.primvars.find("s");
        const Param* t = mesh.primvars.find("t");
        if (std::string(surface).find("plastic") != std::string::npos) {
            // The built-in surfaces read neither: none is added (the built-in shading still serves).
            EXPECT_TRUE(s == nullptr && t == nullptr && mesh.primvars.params.empty());
            continue;
        }
        ASSERT_TRUE(s && t);
        EXPECT_EQ(s->cls, ParamClass::Vertex);
        ASSERT_EQ(s->nums.size(), P.size());
        ASSERT_EQ(t->nums.size(), P.size());
        for (size_t i = 0; i < P.size(); ++i) {
            ASSERT_EQ(s->nums[i], P[i].x) << i;
            ASSERT_EQ(t->nums[i], P[i].y) << i;
        }
    }
    // Given per leaf, "st" is blended as any variable is, and nothing replaces it.
    Log log;
    const Scene scene = parseRibString("WorldBegin\n" +
                                           twoBlobs("\"varying float[2] st\" [1 2  3 4]", "Surface \"showst\"\n") +
                                           "WorldEnd\n",
                                       "st.rib", log);
    ASSERT_EQ(scene.polygonMeshes.size(), 1u);
    EXPECT_TRUE(scene.polygonMeshes[0].primvars.find("st") != nullptr);
    EXPECT_TRUE(scene.polygonMeshes[0].primvars.find("s") == nullptr);

    // Rendered: the shader sees s = x - 10 (object space is under Translate 10 0 0) and t = y.
    test::ShaderDir shaders;
    shaders.add("showst", "surface showst() { Oi = 1; Ci = color(s, t, 0) * 0.01; }");
    const std::string rib = shaders.option() + test::orthographicView(192, 96, "") + "WorldBegin\n" +
                            twoBlobs("", "Surface \"showst\"\n") + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    for (int column : {50, 66, 96, 126, 140})
        for (int row : {40, 47, 55}) {
            // A pixel's 2 x 2 jittered samples keep their mean within half a pixel of its centre.
            EXPECT_NEAR(r.channel(0, column, row, 0), (column + 0.5 - kShift) * 0.01, 0.005) << column << " " << row;
            EXPECT_NEAR(r.channel(0, column, row, 1), (96 - row - 0.5) * 0.01, 0.005) << column << " " << row;
            EXPECT_EQ(r.alpha(0, column, row), 1.0f) << column << " " << row;
        }
}

// A colour declared inline without a class ("color Cs") is uniform (RI Spec 3.2, RiDeclare: a
// declaration without a class is uniform), and a Blobby has one uniform value: every blob and
// bridge takes it. Aqsis's check.rib gives its Blobbies so; Aqsis 1.8.4 colours only the first
// leaf's triangles with it and the rest black (its CqBlobby's class counts are marked "to do"):
// docs/results/aqsis-corpus.md.
TEST(BlobbyVars, AColourDeclaredWithoutAClassIsUniformOverEveryBlob) {
    const std::string rib = test::orthographicView(192, 96, "") + "WorldBegin\n" +
                            twoBlobs("\"color Cs\" [0.1 0.9 0.2]", "Surface \"constant\"\n") + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    const float want[3] = {0.1f, 0.9f, 0.2f};
    for (int column : {66, 96, 126})
        for (int row : {40, 48, 55}) {
            // Equal to float rounding of the pixel filter's weights.
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.channel(0, column, row, c), want[c], 1e-6) << column << " " << row << " " << c;
            EXPECT_NEAR(r.alpha(0, column, row), 1.0f, 1e-6) << column << " " << row;
        }
}

TEST(BlobbyVars, WrongValueCountNamesFileAndLine) {
    const std::string head = "WorldBegin Attribute \"streyes\" \"float blobbyresolution\" [8]\n";
    const std::string blob = "Blobby 2 [1001 0 1001 16 0 2 0 1] [" + sphereMatrix(1, 0, 0, 0) + " " +
                             sphereMatrix(1, 1, 0, 0) + "] [\"\"]";
    struct Case {
        std::string vars, message;
    };
    const Case cases[] = {
        {"\"vertex color tint\" [1 0 0]", "parameter 'tint' has 3 numbers, expected 6 (2 vertex colors"},
        {"\"varying float amount\" [1 0 0]", "parameter 'amount' has 3 numbers, expected 2"},
        {"\"vertex mpoint Pref\" [" + sphereMatrix(1, 0, 0, 0) + "]", "parameter 'Pref' has 16 numbers, expected 32"},
    };
    for (const Case& c : cases) {
        const std::string error = test::ribError(head + blob + "\n" + c.vars + "\nWorldEnd\n");
        EXPECT_NE(error.find("bad.rib:3"), std::string::npos) << error;
        EXPECT_NE(error.find(c.message), std::string::npos) << error;
    }
}

}  // namespace
}  // namespace streyes
