// Area lights (AreaLightSource): the light shader run at points of the geometry that follows it,
// against the closed form of a small Lambertian emitter; soft shadows; bad and unusable shapes.
#include <gtest/gtest.h>

#include <cmath>

#include "test_util.h"

namespace streyes {
namespace {

// A floor (z = 0 plane seen from above, orthographic, one unit a pixel: 64 x 64) under `light`,
// shaded matte with Kd 1, no ambient.
std::string floorUnder(const std::string& light, const std::string& extra = "") {
    return "Format 64 64 1\nProjection \"orthographic\"\nScreenWindow 0 64 0 64\nPixelFilter \"box\" 1 1\n"
           "PixelSamples 2 2\nWorldBegin\n" +
           light + extra +
           "AttributeBegin\nSurface \"matte\" \"Ka\" [0] \"Kd\" [1]\nColor [1 1 1]\n"
           "Patch \"bilinear\" \"P\" [0 0 10  64 0 10  0 64 10  64 64 10]\nAttributeEnd\nWorldEnd\n";
}

// A small square area light (side s) centred over (cx, cy) at camera depth z (the floor is at 10),
// facing the floor, drawn invisible (its own surface clear).
std::string squareLight(double cx, double cy, double z, double s, const std::string& params) {
    auto n = [](double v) { return std::to_string(v); };
    return "AttributeBegin\nOpacity [0 0 0]\nSurface \"constant\"\nAreaLightSource \"arealight\" 7 " + params + "\n" +
           "Patch \"bilinear\" \"P\" [" + n(cx - s / 2) + " " + n(cy - s / 2) + " " + n(z) + "  " + n(cx + s / 2) + " " +
           n(cy - s / 2) + " " + n(z) + "  " + n(cx - s / 2) + " " + n(cy + s / 2) + " " + n(z) + "  " + n(cx + s / 2) +
           " " + n(cy + s / 2) + " " + n(z) + "]\nAttributeEnd\nIlluminate 7 1\n";  // lights are attributes: on again
}

// A light of side 0.02 at height h over the floor is a point emitter with a Lambertian cosine:
// E = I cos(theta_light) cos(theta_surface) / d^2 = I h^2 / d^4 at horizontal distance x.
TEST(AreaLight, ASmallSquareLightGivesTheLambertianEmitterClosedForm) {
    // High enough that the peak is flat over a pixel (a pixel is the mean over its samples).
    const double h = 16, I = 400;
    const test::RenderResult r = test::renderRib(floorUnder(squareLight(32, 32, 10 - h, 0.02, "\"intensity\" [400]")));
    for (int x : {32, 40, 52, 63}) {
        const int y = 31;  // raster row 31: scene y 32 to 33
        const double dx = x + 0.5 - 32, dy = 64 - (y + 0.5) - 32;
        const double d2 = dx * dx + dy * dy + h * h;
        const double want = I * h * h / (d2 * d2);
        EXPECT_NEAR(r.channel(0, x, y, 0), want, 0.01 * want) << x;
    }
    EXPECT_EQ(r.stats.counters.shadowRays, 0u);
}

// A large light over a blocker casts a soft shadow: between full shadow and full light a wide band
// of floor pixels, where a point light at its centre leaves a hard edge of about one pixel.
TEST(AreaLight, ALargeLightCastsASoftShadow) {
    const std::string blocker =
        "AttributeBegin\nSurface \"constant\"\nColor [0 0 0]\nOpacity [0 0 0]\n"  // invisible from the camera,
        "Patch \"bilinear\" \"P\" [24 24 7  40 24 7  24 40 7  40 40 7]\nAttributeEnd\n";  // but casts shadows
    const std::string area = squareLight(32, 32, 2, 16, "\"intensity\" [3000] \"string shadowname\" [\"raytrace\"]");
    const std::string point = "LightSource \"pointlight\" 1 \"from\" [32 32 2] \"intensity\" [3000] \"string shadowname\" [\"raytrace\"]\n";
    // Along the row through the centre: pixels the blocker darkens to between 10% and 90% of their
    // unshadowed value.
    auto penumbra = [](const test::RenderResult& shadowed, const test::RenderResult& open) {
        int n = 0;
        for (int x = 0; x < 64; ++x) {
            const float ratio = shadowed.channel(0, x, 32, 0) / open.channel(0, x, 32, 0);
            n += ratio > 0.1f && ratio < 0.9f;
        }
        return n;
    };
    const test::RenderResult areaShadowed = test::renderRib(floorUnder(area, blocker));
    const test::RenderResult areaOpen = test::renderRib(floorUnder(area));
    const test::RenderResult pointShadowed = test::renderRib(floorUnder(point, blocker));
    const test::RenderResult pointOpen = test::renderRib(floorUnder(point));
    EXPECT_GT(areaShadowed.stats.counters.shadowRays + areaShadowed.stats.counters.shadowVertexRays, 0u);
    EXPECT_LE(penumbra(pointShadowed, pointOpen), 4);
    EXPECT_GE(penumbra(areaShadowed, areaOpen), 10);
    // Under the blocker's middle the light is mostly hidden; at the image's edge not at all.
    EXPECT_LT(areaShadowed.channel(0, 32, 32, 0), 0.5f * areaOpen.channel(0, 32, 32, 0));
    EXPECT_FLOAT_EQ(areaShadowed.channel(0, 1, 32, 0), areaOpen.channel(0, 1, 32, 0));
    // The ray tracer shades the same light the same way.
    const test::RenderResult traced = test::renderRib(floorUnder(area, blocker), test::optionsFor(Algorithm::Raytrace));
    EXPECT_LT(test::meanAbsDifference(areaShadowed, traced), 0.02f * areaOpen.channel(0, 32, 32, 0));
}

TEST(AreaLight, WhatCannotShapeALightSaysSo) {
    // A subdivision mesh does not shape the light (warned once, drawn); an area light with no shape
    // lights nothing, and says so.
    const test::RenderResult r = test::renderRib(floorUnder(
        "AttributeBegin\nAreaLightSource \"arealight\" 1 \"intensity\" [100]\n"
        "SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"interpolateboundary\"] [0 0] [] [] \"P\" [20 20 5  40 20 5  40 40 5  20 40 5]\n"
        "AttributeEnd\n"));
    int shape = 0, nothing = 0;
    for (const std::string& w : r.warnings) {
        shape += w.find("SubdivisionMesh does not shape an area light") != std::string::npos;
        nothing += w.find("has no shape") != std::string::npos;
    }
    EXPECT_EQ(shape, 1);
    EXPECT_EQ(nothing, 1);
    EXPECT_EQ(r.channel(0, 2, 2, 0), 0.0f);  // the floor: lit by nothing
    // Outside the world an area light is skipped with a warning, as the peers do (an error until
    // issue 46), and an error under --strict.
    EXPECT_EQ(test::ribError("WorldBegin\nWorldEnd\nAreaLightSource \"arealight\" 1\n"), "");
    EXPECT_NE(test::ribError("WorldBegin\nWorldEnd\nAreaLightSource \"arealight\" 1\n", true).find("after WorldEnd"),
              std::string::npos);
    EXPECT_NE(test::ribError("AreaLightSource \"arealight\" 1\nWorldBegin\nWorldEnd\n", true).find("before WorldBegin"),
              std::string::npos);
}

}  // namespace
}  // namespace streyes
