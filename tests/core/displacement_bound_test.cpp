// Attribute "displacementbound" "coordinatesystem": the bound's radius is measured in the space
// named there, "shader" (the displacement's CTM), "object" (the primitive's), "world", "camera",
// "current", PRMan's "null" (the CTM at the Attribute) or a CoordinateSystem's. A displacement
// of 16 pixels with a bound of 2.25 given in a space scaled by 8 draws the whole displaced plane;
// the same bound in an unscaled space is too small (at most 3 x 2.25 = 6.75 pixels: the bound's
// stretch is the Frobenius norm, up to sqrt(3) a transform) and loses the buckets right of x = 40
// (which shows the test can fail).
#include <gtest/gtest.h>

#include <cstdio>

#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

const char* kShiftX = "displacement shiftx(float dx = 0) { P += vector(dx, 0, 0); N = calculatenormal(P); }\n";

// The plane [0, 32] x [0, 64] at depth 10 moved 16 pixels right: its pixels are x in [16, 48).
// `before` comes before the Displacement, `between` between it and the plane (as transforms).
test::RenderResult shifted(const test::ShaderDir& d, const std::string& bound, const std::string& before,
                           const std::string& between, const std::string& plane = test::square(0, 32, 0, 64, 10)) {
    const std::string rib = test::orthographicView(64, 64, d.option()) + "WorldBegin\nSurface \"constant\"\n" +
                            "TransformBegin\n" + before + "Attribute \"displacementbound\" \"sphere\" [2.25] " +
                            bound + "\nDisplacement \"shiftx\" \"dx\" 16\nTransformEnd\n" + between + plane +
                            "WorldEnd\n";
    RenderOptions o;
    o.bucketSize = 8;  // buckets right of x = 40 see the plane only through its bound
    return test::renderRib(rib, o);
}

// A number as the bound's warning writes it (3 significant digits).
std::string boundText(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

// Whether the displaced plane is drawn whole, and nothing else.
bool whole(const test::RenderResult& r) {
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            if (r.alpha(0, x, y) != (x >= 16 && x < 48 ? 1.0f : 0.0f)) return false;
    return true;
}

TEST(DisplacementBound, TheRadiusIsMeasuredInTheSpaceNamed) {
    test::ShaderDir d;
    d.add("shiftx", kShiftX);
    const std::string scale = "Scale 8 8 8\n";
    struct Case {
        std::string what, bound, before, between;
        bool whole;
    };
    const std::string plane = test::square(0, 32, 0, 64, 10);
    const std::vector<Case> cases = {
        // The displacement's shader space is scaled by 8: 2.25 there is 18 pixels.
        {"shader", "\"coordinatesystem\" [\"shader\"]", scale, "", true},
        {"world", "\"coordinatesystem\" [\"world\"]", scale, "", false},
        {"camera", "\"coordinatesystem\" [\"camera\"]", scale, "", false},
        {"current", "\"coordinatesystem\" [\"current\"]", scale, "", false},
        // Object space is the primitive's: unscaled here, though the shader's is.
        {"object, shader scaled", "\"coordinatesystem\" [\"object\"]", scale, "", false},
        {"object by default, shader scaled", "", scale, "", false},
        // ... and scaled here, though the shader's is not.
        {"object, primitive scaled", "\"coordinatesystem\" [\"object\"]", "", scale, true},
        // A name CoordinateSystem gave under the scale, and PRMan's "null" (the CTM at the Attribute).
        {"named", "\"coordinatesystem\" [\"big\"]", "", "", true},
        {"null", "\"coordinatesystem\" [\"null\"]", scale, "", true},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        const std::string named = "TransformBegin\nScale 8 8 8\nCoordinateSystem \"big\"\nTransformEnd\n";
        // The primitive scaled by 8: the same plane is the square an eighth its size.
        const bool primitiveScaled = !c.between.empty();
        const test::RenderResult r = shifted(d, c.bound, named + c.before, c.between,
                                             primitiveScaled ? test::square(0, 4, 0, 8, 1.25) : plane);
        EXPECT_EQ(whole(r), c.whole);
        // A bound too small is said (DisplacementBoundIsExceeded..., below): once, at the request.
        ASSERT_EQ(r.warnings.size(), c.whole ? 0u : 1u) << (r.warnings.empty() ? "" : r.warnings.front());
        if (!c.whole) {
            EXPECT_NE(r.warnings[0].find("moved points up to 16 (camera space)"), std::string::npos) << r.warnings[0];
        }
    }
}

TEST(DisplacementBound, AnotherRenderersSpaceIsWarnedAboutOnceAndTakenAsObjectSpace) {
    test::ShaderDir d;
    d.add("shiftx", kShiftX);
    // "eye" is in neither PRMan's list nor Aqsis's (which takes a name it does not know as camera
    // space, silently).
    const test::RenderResult r = shifted(d, "\"coordinatesystem\" [\"eye\"]", "", "Scale 8 8 8\n",
                                         test::square(0, 4, 0, 8, 1.25));
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("coordinatesystem \"eye\""), std::string::npos) << r.warnings[0];
    EXPECT_TRUE(whole(r));  // object space: the primitive's scale of 8
}

// "surface" (Aqsis's repel.rib) is the surface shader's space, the CTM at Surface, as "shader" is
// the displacement's: scaled by 8 there, 2.25 covers the 16-pixel move though neither the
// displacement's space nor the primitive's is scaled; unscaled there, it does not, though the
// displacement's space is scaled. No warning that the name is unknown.
TEST(DisplacementBound, SurfaceIsTheSurfaceShadersSpace) {
    test::ShaderDir d;
    d.add("shiftx", kShiftX);
    const std::string bound = "\"coordinatesystem\" [\"surface\"]";
    const test::RenderResult scaled =
        shifted(d, bound, "TransformBegin\nScale 8 8 8\nSurface \"constant\"\nTransformEnd\n", "");
    EXPECT_TRUE(whole(scaled));
    EXPECT_TRUE(scaled.warnings.empty()) << scaled.warnings.front();
    const test::RenderResult unscaled = shifted(d, bound, "Scale 8 8 8\n", "");  // the Surface before it
    EXPECT_FALSE(whole(unscaled));
    ASSERT_EQ(unscaled.warnings.size(), 1u);
    EXPECT_NE(unscaled.warnings[0].find("in \"surface\" space"), std::string::npos) << unscaled.warnings[0];
}

// The image's spaces under an orthographic projection: a bound measured across the image, one
// unit of "screen" a unit of camera space, of "NDC" the screen window's larger side, of "raster"
// a pixel's larger side. A 64 x 64 image of the screen window [0, 128]^2: a pixel is 2 units, NDC
// 128. The plane moves 16 units (8 pixels): a bound just short of it is exceeded, and the warning
// gives its size in camera space, the closed form; one just over it draws the plane whole.
TEST(DisplacementBound, ImageSpacesMeasureTheBoundAcrossAnOrthographicImage) {
    test::ShaderDir d;
    d.add("shiftx", kShiftX);
    auto render = [&](const std::string& space, double r, const std::string& view, const RenderOptions& o) {
        const std::string rib = view + d.option() + "WorldBegin\nSurface \"constant\"\n" +
                                "Attribute \"displacementbound\" \"sphere\" [" + boundText(r) +
                                "] \"coordinatesystem\" [\"" + space + "\"]\nDisplacement \"shiftx\" \"dx\" 16\n" +
                                test::square(0, 64, 0, 128, 10) + "WorldEnd\n";
        return test::renderRib(rib, o);
    };
    const std::string view = "Format 64 64 1\nProjection \"orthographic\"\nScreenWindow 0 128 0 128\n"
                             "PixelFilter \"box\" 1 1\nPixelSamples 2 2\n";
    RenderOptions o;
    o.bucketSize = 8;
    struct Case {
        std::string space;
        double under, camera, over;  // a bound short of the move, it in camera space, one past it
    };
    for (const Case& c : {Case{"screen", 15, 15, 17}, Case{"NDC", 0.1, 12.8, 0.13}, Case{"raster", 7, 14, 9}}) {
        SCOPED_TRACE(c.space);
        const test::RenderResult short_ = render(c.space, c.under, view, o);
        ASSERT_EQ(short_.warnings.size(), 1u);
        EXPECT_NE(short_.warnings[0].find("moved points up to 16 (camera space) but its bound is " + boundText(c.under) +
                                          " (Attribute \"displacementbound\" \"sphere\" in \"" + c.space + "\" space; " +
                                          boundText(c.camera) + " in camera space)"),
                  std::string::npos)
            << short_.warnings[0];
        // The bound to give is named in camera space: an image space's size is the projection's.
        EXPECT_NE(short_.warnings[0].find("raise it to at least Attribute \"displacementbound\" \"sphere\" [16.2] "
                                          "\"coordinatesystem\" [\"camera\"]"),
                  std::string::npos)
            << short_.warnings[0];
        const test::RenderResult enough = render(c.space, c.over, view, o);
        EXPECT_TRUE(enough.warnings.empty()) << enough.warnings.front();
        // The plane's pixels x in [8, 40) once moved, whole.
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) ASSERT_EQ(enough.alpha(0, x, y), x >= 8 && x < 40 ? 1.0f : 0.0f) << x << " " << y;
    }
    // The render's resolution, not Format's, makes a pixel: at 32 x 32 a pixel is 4 units.
    RenderOptions half = o;
    half.xres = half.yres = 32;
    EXPECT_TRUE(render("raster", 7, view, half).warnings.empty());
    // Without a ScreenWindow, RenderMan's default: the shorter side spans [-1, 1], here 4 x 2 at
    // 64 x 32 pixels: NDC's unit 4, a pixel 1/16.
    const std::string wide = "Format 64 32 1\nProjection \"orthographic\"\nPixelSamples 2 2\n";
    for (const Case& c : {Case{"NDC", 2, 8, 0}, Case{"raster", 100, 6.25, 0}}) {
        const test::RenderResult r = render(c.space, c.under, wide, o);
        ASSERT_EQ(r.warnings.size(), 1u) << c.space;
        EXPECT_NE(r.warnings[0].find("in \"" + c.space + "\" space; " + boundText(c.camera) + " in camera space)"),
                  std::string::npos)
            << r.warnings[0];
    }
}

// Under a perspective projection a length in the image's spaces grows with depth: such a bound is
// warned about once (file:line) and taken in object space, as an unknown name is.
TEST(DisplacementBound, ImageSpacesUnderAPerspectiveProjectionAreWarnedAboutAndTakenAsObjectSpace) {
    for (const char* space : {"screen", "NDC", "raster"}) {
        const std::string rib = std::string("Format 16 16 1\nProjection \"perspective\" \"fov\" [40]\nWorldBegin\n") +
                                "Attribute \"displacementbound\" \"sphere\" [1] \"coordinatesystem\" [\"" + space +
                                "\"]\nAttribute \"displacementbound\" \"sphere\" [1] \"coordinatesystem\" [\"" +
                                space + "\"]\nTranslate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\n";
        const test::RenderResult r = test::renderRib(rib);
        ASSERT_EQ(r.warnings.size(), 1u) << space;
        EXPECT_NE(r.warnings[0].find("test.rib:4: "), std::string::npos) << r.warnings[0];
        EXPECT_NE(r.warnings[0].find("under a perspective projection has no single size in camera space"),
                  std::string::npos)
            << r.warnings[0];
        EXPECT_NE(test::ribError(rib, true).find("perspective projection"), std::string::npos) << space;  // --strict
    }
    // Given before the Projection request (the reader did not know it yet): the render says so
    // once, at the Displacement request, and takes the bound in object space.
    test::ShaderDir d;
    d.add("shiftx", kShiftX);
    const std::string early = "Attribute \"displacementbound\" \"sphere\" [1] \"coordinatesystem\" [\"raster\"]\n"
                              "Format 16 16 1\nProjection \"perspective\" \"fov\" [40]\n" +
                              d.option() + "WorldBegin\nDisplacement \"shiftx\" \"dx\" 0.5\n"
                              "Translate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\n";
    const test::RenderResult r = test::renderRib(early);
    ASSERT_EQ(r.warnings.size(), 1u) << r.warnings.front();
    EXPECT_NE(r.warnings[0].find("test.rib:6: "), std::string::npos) << r.warnings[0];  // the Displacement
    EXPECT_NE(r.warnings[0].find("coordinatesystem \"raster\" under a perspective projection"), std::string::npos)
        << r.warnings[0];
    // Under --strict, an error at the same line, as the reader's.
    try {
        test::renderRib(early, RenderOptions{}, true);
        ADD_FAILURE() << "--strict rendered";
    } catch (const InputError& e) {
        const std::string strict = e.what();
        EXPECT_NE(strict.find("test.rib:6: "), std::string::npos) << strict;
        EXPECT_NE(strict.find("under a perspective projection"), std::string::npos) << strict;
    }
}

// A displacement that moves points farther than its bound may lose pieces (the case above): the
// render says so once per Displacement request, at its line, with the bound, the largest move
// and the bound to give; a displacement within its bound says nothing.
TEST(DisplacementBound, DisplacementBoundIsExceededWarnsOnceAtTheRequest) {
    test::ShaderDir d;
    d.add("shiftx", kShiftX);
    auto render = [&](double dx) {
        // Two planes (many grids each) under one Displacement request, the bound 1 in camera space
        // (a pixel: the view maps a unit to a pixel).
        const std::string rib = test::orthographicView(64, 64, d.option()) + "WorldBegin\nSurface \"constant\"\n" +
                                "Attribute \"displacementbound\" \"sphere\" [1] \"coordinatesystem\" [\"camera\"]\n" +
                                "Displacement \"shiftx\" \"dx\" " + std::to_string(dx) + "\n" +
                                test::square(0, 30, 0, 64, 10) + test::square(32, 62, 0, 64, 10) + "WorldEnd\n";
        RenderOptions o;
        o.bucketSize = 8;
        return test::renderRib(rib, o);
    };
    const test::RenderResult over = render(2);
    ASSERT_EQ(over.warnings.size(), 1u);
    const std::string& w = over.warnings[0];
    EXPECT_NE(w.find("test.rib:10: "), std::string::npos) << w;  // the Displacement request's line
    EXPECT_NE(w.find("Displacement \"shiftx\" moved points up to 2 (camera space) but its bound is 1 "
                     "(Attribute \"displacementbound\" \"sphere\" in \"camera\" space; 1 in camera space): parts "
                     "of the surface moved past the bound may be missing from the picture; raise it to at least "
                     "Attribute \"displacementbound\" \"sphere\" [2.02] \"coordinatesystem\" [\"camera\"]"),
              std::string::npos)
        << w;
    const test::RenderResult within = render(0.75);
    EXPECT_TRUE(within.warnings.empty()) << within.warnings.front();
    // Exactly at the bound: no warning either (float rounding of the points is not a move).
    EXPECT_TRUE(render(1).warnings.empty()) << render(1).warnings.front();
}

}  // namespace
}  // namespace streyes
