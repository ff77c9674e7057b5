// CoordinateSystem, ScopedCoordinateSystem and CoordSysTransform: geometry placed through a named
// system lands where its transform says (covered pixels against the closed form), camera-relative
// names given before WorldBegin, a scoped name forgotten at the end of its block, and shaders'
// transform("name", ...) reading the named spaces.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "test_util.h"

namespace streyes {
namespace {

// The covered pixels of frame 0 (alpha 1), as a count and their bounding box [x0, x1) x [y0, y1).
struct Covered {
    int count = 0, x0 = 1 << 20, y0 = 1 << 20, x1 = -1, y1 = -1;
};
Covered covered(const test::RenderResult& r) {
    Covered c;
    const FrameImage& f = r.frame(0);
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x)
            if (r.alpha(0, x, y) == 1.0f) {
                ++c.count;
                c.x0 = std::min(c.x0, x), c.y0 = std::min(c.y0, y), c.x1 = std::max(c.x1, x + 1), c.y1 = std::max(c.y1, y + 1);
            } else {
                EXPECT_EQ(r.alpha(0, x, y), 0.0f) << "pixel (" << x << ", " << y << ") half covered";
            }
    return c;
}

void expectSquareAt(const test::RenderResult& r, int x0, int y0, int side, const std::string& what) {
    const Covered c = covered(r);
    EXPECT_EQ(c.count, side * side) << what;
    EXPECT_EQ(c.x0, x0) << what;
    EXPECT_EQ(c.y0, y0) << what;
    EXPECT_EQ(c.x1, x0 + side) << what;
    EXPECT_EQ(c.y1, y0 + side) << what;
}

// Scene units are pixels (raster y = 32 - y). "spot" is Translate 20 4 0 then Rotate 90 about z:
// the square [0, 8] x [-8, 0] of it is the world's [20, 28] x [4, 12], raster rows 20..27.
TEST(CoordinateSystems, GeometryLandsWhereTheNamedTransformSays) {
    const std::string rib = test::orthoHeader(32, 32) +
                            "AttributeBegin\nTranslate 20 4 0\nRotate 90 0 0 1\nCoordinateSystem \"spot\"\nAttributeEnd\n"
                            "Translate 100 100 0\nScale 3 3 3\nCoordSysTransform \"spot\"\n" +
                            test::square(0, 8, -8, 0, 5) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    expectSquareAt(r, 20, 20, 8, "through \"spot\"");
}

// Before WorldBegin the CTM is camera-relative: "three" is 3 pixels right in camera space, while
// the camera moves the world 5 right. "camera" inside the world is camera space itself.
TEST(CoordinateSystems, CameraRelativeNamesAndCameraSpace) {
    const std::string header = test::orthoHeader(32, 32, "Translate 3 0 0\nCoordinateSystem \"three\"\nTranslate 2 0 0\n");
    const test::RenderResult three =
        test::renderRib(header + "CoordSysTransform \"three\"\n" + test::square(0, 8, 0, 8, 5) + "WorldEnd\n");
    expectSquareAt(three, 3, 24, 8, "\"three\"");
    const test::RenderResult world = test::renderRib(header + test::square(0, 8, 0, 8, 5) + "WorldEnd\n");
    expectSquareAt(world, 5, 24, 8, "the world");
    const test::RenderResult camera =
        test::renderRib(header + "Translate 7 0 0\nCoordSysTransform \"camera\"\n" + test::square(0, 8, 0, 8, 5) + "WorldEnd\n");
    expectSquareAt(camera, 0, 24, 8, "\"camera\"");
    const test::RenderResult backToWorld = test::renderRib(header + "Translate 7 0 0\nCoordSysTransform \"world\"\n" +
                                                           test::square(0, 8, 0, 8, 5) + "WorldEnd\n");
    expectSquareAt(backToWorld, 5, 24, 8, "\"world\"");
}

// A scoped name is gone after its block (a warning names it; the CTM is unchanged); one defined
// again inside a block by ScopedCoordinateSystem comes back to its outer meaning.
TEST(CoordinateSystems, ScopedNamesEndWithTheirBlock) {
    const std::string gone = test::orthoHeader(32, 32) +
                             "AttributeBegin\nTranslate 20 0 0\nScopedCoordinateSystem \"tmp\"\nAttributeEnd\n"
                             "CoordSysTransform \"tmp\"\n" + test::square(0, 8, 0, 8, 5) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(gone);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("no coordinate system 'tmp'"), std::string::npos) << r.warnings[0];
    expectSquareAt(r, 0, 24, 8, "unknown name: the CTM unchanged");
    EXPECT_NE(test::ribError(gone, true).find("tmp"), std::string::npos);  // --strict: an error
    const std::string back = test::orthoHeader(32, 32) +
                             "AttributeBegin\nTranslate 10 0 0\nCoordinateSystem \"a\"\nAttributeEnd\n"
                             "TransformBegin\nTranslate 20 0 0\nScopedCoordinateSystem \"a\"\nTransformEnd\n"
                             "CoordSysTransform \"a\"\n" + test::square(0, 8, 0, 8, 5) + "WorldEnd\n";
    expectSquareAt(test::renderRib(back), 10, 24, 8, "the outer \"a\"");
}

// transform("spot", p) of a world point gives it in "spot" coordinates: world (1, 2, 3) is
// Rotate(-90) of (1, 2, 3) - (20, 4, 0) = (-2, 19, 3).
TEST(CoordinateSystems, ShadersTransformToNamedSpaces) {
    const test::TempDir dir("coordsys-shaders");
    std::ofstream(dir.path() + "/probe.sl") << "surface probe() {\n"
                                               "  point q = transform(\"spot\", point \"world\" (1, 2, 3));\n"
                                               "  point back = transform(\"spot\", \"world\", q);\n"
                                               "  Ci = color(xcomp(q), ycomp(q), zcomp(q)) + color(xcomp(back) - 1, 0, 0); Oi = 1;\n"
                                               "}\n";
    const std::string rib = "Option \"searchpath\" \"shader\" \"" + dir.path() + ":@\"\n" +
                            "Format 8 8 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 8\nPixelFilter \"box\" 1 1\n"
                            "Translate 1 0 0\nWorldBegin\n"
                            "AttributeBegin\nTranslate 20 4 0\nRotate 90 0 0 1\nCoordinateSystem \"spot\"\nAttributeEnd\n"
                            "Surface \"probe\"\n" + test::square(-1, 7, 0, 8, 5) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    EXPECT_NEAR(r.channel(0, 4, 4, 0), -2.0f, 1e-4f);
    EXPECT_NEAR(r.channel(0, 4, 4, 1), 19.0f, 1e-4f);
    EXPECT_NEAR(r.channel(0, 4, 4, 2), 3.0f, 1e-4f);
}

}  // namespace
}  // namespace streyes
