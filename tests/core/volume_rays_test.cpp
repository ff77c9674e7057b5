// Interior and Exterior volume shaders over the segments of shaders' rays (trace/shader_rays.h),
// against Beer's law: a volume that lets through exp(-k length(I)) of what comes from the far end
// of its segment gives exp(-k * chord) through a sphere it fills, exp(-k * distance) outside.
//
// The camera is orthographic along +z, one unit a pixel (raster x = x, raster y = H - y).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "test_util.h"

namespace streyes {
namespace {

struct ShaderDir {
    test::TempDir dir{"shaders"};
    void add(const std::string& name, const std::string& source) const {
        std::ofstream(dir.path() + "/" + name + ".sl") << source;
    }
    std::string option() const { return "Option \"searchpath\" \"shader\" \"" + dir.path() + ":@\"\n"; }
    std::string file(const std::string& name) const { return dir.path() + "/" + name + ".sl"; }
};

constexpr int kW = 32, kH = 32;

std::string view(const ShaderDir& d) {
    return "Format 32 32 1\nProjection \"orthographic\"\nScreenWindow 0 32 0 32\nPixelFilter \"box\" 1 1\n"
           "PixelSamples 2 2\n" + d.option();
}

void addShaders(const ShaderDir& d) {
    d.add("absorb", "volume absorb(float k = 1) { Ci *= exp(-k * length(I)); }\n");
    // Looks straight through itself, along the view.
    d.add("see", "surface see() { Ci = trace(P, normalize(I)); Oi = 1; }\n");
    d.add("through", "surface through() { Ci = transmission(P, P + vector(0, 0, 300)); Oi = 1; }\n");
}

// The mean over the pixel (4 x 4 points) of f(rho), rho the distance from (16, 16).
template <typename F>
double pixelMean(int px, int py, F f) {
    double sum = 0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const double x = px + (i + 0.5) / 4 - 16, y = kH - py - 1 + (j + 0.5) / 4 - 16;
            sum += f(std::sqrt(x * x + y * y));
        }
    return sum / 16;
}

constexpr double kR = 8, kK = 0.1;

// A sphere of radius 8 filled with an Interior absorbing k = 0.1, its surface seeing through
// itself with trace() onto a white plane: exp(-k 2 sqrt(r^2 - rho^2)), 0.2 through the centre.
TEST(VolumeRays, AnInteriorFogSeenThroughASphereWithTraceIsBeersLawOverTheChord) {
    ShaderDir d;
    addShaders(d);
    for (bool fog : {false, true}) {
        SCOPED_TRACE(fog ? "interior fog" : "none");
        const std::string rib = view(d) + "WorldBegin\nAttributeBegin\nSurface \"constant\"\n" +
                                test::square(-100, 200, -100, 200, 200) + "AttributeEnd\nAttributeBegin\n" +
                                (fog ? "Interior \"absorb\" \"k\" " + std::to_string(kK) + "\n" : "") +
                                "Surface \"see\"\nTranslate 16 16 100\nSphere 8 -8 8 360\nAttributeEnd\nWorldEnd\n";
        const test::RenderResult r = test::renderRib(rib);
        ASSERT_GT(r.stats.counters.shaderRays, 0u);
        int checked = 0;
        for (int py = 0; py < kH; ++py)
            for (int px = 0; px < kW; ++px) {
                const double rho = std::hypot(px + 0.5 - 16, kH - py - 0.5 - 16);
                if (rho > kR / 2) continue;  // the middle: the chord, not the faceted rim
                const double want = fog ? pixelMean(px, py, [](double q) { return std::exp(-kK * 2 * std::sqrt(kR * kR - q * q)); }) : 1.0;
                // Micropolygons a pixel across stand off the sphere by 1/64 of a pixel: 0.5% of
                // the chord's attenuation at most.
                EXPECT_NEAR(r.channel(0, px, py, 0), want, 0.01 * want) << px << " " << py;
                ++checked;
            }
        EXPECT_GT(checked, 40);
    }
}

// A white sphere of radius 40 whose nearest point is 10 beyond the floor, with an Exterior
// absorbing k: the floor sees it through exp(-k (10 + R - sqrt(R^2 - rho^2))).
TEST(VolumeRays, AnExteriorFogBeforeASphereIsBeersLawOverTheDistance) {
    ShaderDir d;
    addShaders(d);
    const double R = 40;
    const std::string rib = view(d) + "WorldBegin\nAttributeBegin\nSurface \"constant\"\nExterior \"absorb\" \"k\" " +
                            std::to_string(kK) + "\nTranslate 16 16 150\nSphere 40 -40 40 360\nAttributeEnd\n" +
                            "Surface \"see\"\n" + test::square(0, kW, 0, kH, 100) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            const double want = pixelMean(px, py, [&](double q) { return std::exp(-kK * (10 + R - std::sqrt(R * R - q * q))); });
            EXPECT_NEAR(r.channel(0, px, py, 0), want, 0.01 * want) << px << " " << py;
        }
}

// transmission() through a sphere of Opacity 0 filled with the Interior: Beer's law over the chord
// inside the sphere's disc, 1 outside it.
TEST(VolumeRays, TransmissionThroughAnInteriorIsBeersLawOverTheChord) {
    ShaderDir d;
    addShaders(d);
    const std::string rib = view(d) + "WorldBegin\nAttributeBegin\nOpacity [0 0 0]\nSurface \"constant\"\nInterior \"absorb\" \"k\" " +
                            std::to_string(kK) + "\nTranslate 16 16 150\nSphere 8 -8 8 360\nAttributeEnd\n" +
                            "Surface \"through\"\n" + test::square(0, kW, 0, kH, 100) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    int inside = 0;
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            const double rho = std::hypot(px + 0.5 - 16, kH - py - 0.5 - 16);
            if (rho > kR - 1.5 && rho < kR + 1.5) continue;  // the rim, where pixels are part in
            const double want = rho < kR ? pixelMean(px, py, [](double q) { return std::exp(-kK * 2 * std::sqrt(kR * kR - q * q)); }) : 1.0;
            EXPECT_NEAR(r.channel(0, px, py, 0), want, rho < kR / 2 ? 0.01 * want : 0.05 * want) << px << " " << py;
            inside += rho < kR;
        }
    EXPECT_GT(inside, 100);
}

// A volume shader that does not compile stops the render at its file:line:column.
TEST(VolumeRays, AnInteriorThatDoesNotCompileIsAnErrorAtItsPlace) {
    ShaderDir d;
    addShaders(d);
    d.add("broken", "volume broken() {\n  Ci *= undefinedThing;\n}\n");
    const std::string rib = view(d) + "WorldBegin\nInterior \"broken\"\nSurface \"see\"\n" + test::square(0, kW, 0, kH, 100) + "WorldEnd\n";
    const std::string e = test::ribError(rib);
    EXPECT_NE(e.find("broken.sl:2:"), std::string::npos) << e;
    EXPECT_NE(e.find("undefinedThing"), std::string::npos) << e;
}

}  // namespace
}  // namespace streyes
