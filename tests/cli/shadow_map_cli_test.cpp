// Shadow maps through the streyes command: depth frames, MakeShadow and pictures reading the maps
// (streyes/passes.h, shade/shadow_map.h), against ray-traced shadows and analytic answers; bad maps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "cli_run.h"
#include "streyes/image_io.h"
#include "test_util.h"

namespace streyes {
namespace {

namespace fs = std::filesystem;
using test::readFile;
using test::runStreyesWith;
using test::writeFile;

constexpr double kPi = 3.14159265358979323846;

struct V {
    double x, y, z;
};
V sub(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V unit(V a) {
    const double l = std::sqrt(dot(a, a));
    return {a.x / l, a.y / l, a.z / l};
}

// RIB's Transform for a camera at `eye` looking at `target`, `up` up (world -> camera, row vectors).
std::string lookAt(V eye, V target, V up = {0, 1, 0}) {
    const V z = unit(sub(target, eye));
    const V x = unit(cross(up, z));
    const V y = cross(z, x);
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "Transform [%.17g %.17g %.17g 0 %.17g %.17g %.17g 0 %.17g %.17g %.17g 0 %.17g %.17g %.17g 1]\n", x.x,
                  y.x, z.x, x.y, y.y, z.y, x.z, y.z, z.z, -dot(eye, x), -dot(eye, y), -dot(eye, z));
    return buf;
}

std::string runIn(const std::string& dir, const std::string& args) {
    const test::CliRun r = runStreyesWith("cd " + dir + " && ", "render " + args);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return r.output;
}

// The light, the sphere and the plane: a spot light at (5, 3, 0) aimed at a unit sphere at the
// origin over the plane y = -1.5. The picture looks straight down (orthographic) at the part of the
// plane x in [-7.2, -1.2], where the shadow lies and the sphere does not.
const V kLight{5, 3, 0};

std::string world(const std::string& shadowname, const std::string& extra = "") {
    return "WorldBegin\n"
           "LightSource \"shadowspot\" 1 \"intensity\" [100] \"from\" [5 3 0] \"to\" [0 0 0] \"coneangle\" [0.6] "
           "\"conedeltaangle\" [0.05] \"shadowname\" [\"" +
           shadowname + "\"]" + extra +
           "\n"
           "Surface \"matte\"\n"
           "Sphere 1 -1 1 360\n"
           "Patch \"bilinear\" \"P\" [-12 -1.5 -12  12 -1.5 -12  -12 -1.5 12  12 -1.5 12]\n"
           "WorldEnd\n";
}

std::string depthFrame(int n, const std::string& map, const std::string& hider = "") {
    return "FrameBegin " + std::to_string(n) + "\nDisplay \"" + map +
           "\" \"zfile\" \"z\"\nFormat 512 512 1\nPixelSamples 2 2\n" + hider +
           "Projection \"perspective\" \"fov\" [40]\n" + lookAt(kLight, {0, 0, 0}) + world("") + "FrameEnd\n";
}

std::string pictureFrame(int n, const std::string& shadowname, const std::string& out, const std::string& extra = "") {
    return "FrameBegin " + std::to_string(n) + "\nDisplay \"" + out +
           "\" \"file\" \"rgba\"\nFormat 256 256 1\nPixelSamples 4 4\nProjection \"orthographic\"\n"
           "ScreenWindow -3 3 -3 3\n" +
           lookAt({-4.2, 10, 0}, {-4.2, 0, 0}, {0, 0, 1}) + world(shadowname, extra) + "FrameEnd\n";
}

// The area of the plane in shadow in a picture: each pixel's share of light missing against the
// unshadowed picture, times the pixel's area (by default 6 x 6 units over 256 x 256 pixels).
double shadowArea(const ImageData& shadowed, const ImageData& lit, double pixel = (6.0 / 256) * (6.0 / 256)) {
    double area = 0;
    for (int y = 0; y < lit.height; ++y)
        for (int x = 0; x < lit.width; ++x) {
            const float l = lit.at(x, y, 0), s = shadowed.at(x, y, 0);
            EXPECT_TRUE(std::isfinite(s)) << x << " " << y;
            if (l > 1e-3f) area += pixel * std::clamp(1.0 - double(s) / double(l), 0.0, 1.0);
        }
    return area;
}

// The same for the scene itself: points of the plane in view whose segment to the light meets
// the sphere, on a fine grid.
double analyticShadowArea() {
    const double d = 0.005, yp = -1.5;
    double area = 0;
    for (double x = -7.2 + d / 2; x < -1.2; x += d)
        for (double z = -3 + d / 2; z < 3; z += d) {
            const V p{x, yp, z}, dir = sub(kLight, p);
            const double a = dot(dir, dir), b = 2 * dot(p, dir), c = dot(p, p) - 1;
            const double disc = b * b - 4 * a * c;
            if (disc <= 0) continue;
            const double t = (-b - std::sqrt(disc)) / (2 * a);
            if (t > 0 && t < 1) area += d * d;
        }
    return area;
}

// A depth frame, MakeShadow, the picture reading the map (as exporters write them), against the
// same picture with ray-traced shadows: the areas in shadow agree within 3%, and with the scene's.
TEST(ShadowMapCli, ASpheresShadowFromAShadowSpotMapMatchesTheRayTracedOne) {
    test::TempDir tmp("shadowmap");
    writeFile(tmp.path(), "map.rib", depthFrame(1, "sphere.z") + "MakeShadow \"sphere.z\" \"sphere.shd\"\n" +
                                         pictureFrame(1, "sphere.shd", "map.exr"));
    writeFile(tmp.path(), "traced.rib", pictureFrame(1, "raytrace", "traced.exr"));
    writeFile(tmp.path(), "lit.rib", pictureFrame(1, "", "lit.exr"));
    const std::string out = runIn(tmp.path(), "map.rib");
    EXPECT_EQ(out.find("warning"), std::string::npos) << out;
    runIn(tmp.path(), "traced.rib -q");
    runIn(tmp.path(), "lit.rib -q");
    ASSERT_TRUE(fs::exists(tmp.path() + "/sphere.z"));
    ASSERT_TRUE(fs::exists(tmp.path() + "/sphere.shd"));
    const ImageData lit = readImage(tmp.path() + "/lit.exr");
    const double map = shadowArea(readImage(tmp.path() + "/map.exr"), lit);
    const double traced = shadowArea(readImage(tmp.path() + "/traced.exr"), lit);
    const double exact = analyticShadowArea();
    EXPECT_GT(exact, 10.0);
    EXPECT_NEAR(traced, exact, 0.03 * exact);
    EXPECT_NEAR(map, traced, 0.03 * traced) << "map " << map << " traced " << traced << " exact " << exact;
    std::fprintf(stderr, "shadow area: map %.4f, ray traced %.4f, the scene's %.4f\n", map, traced, exact);
}

// A plane tilted 80 degrees from the light (its normal 80 degrees from the direction to the light),
// its depth map made with the default depthfilter (the nearest of 4 jittered samples a pixel) and
// read at the default bias: it does not shadow itself anywhere. The lit picture, with and without
// the map, is the same.
TEST(ShadowMapCli, APlaneTiltedEightyDegreesFromTheLightHasNoAcneAtTheDefaultBias) {
    test::TempDir tmp("shadowmap-acne");
    const double t = 80 * kPi / 180;
    // The plane through (0, 0, 0) with normal (sin t, cos t, 0); the light straight above at y = 6.
    const V u{std::cos(t), -std::sin(t), 0};
    char plane[512];
    std::snprintf(plane, sizeof plane,
                  "Patch \"bilinear\" \"P\" [%.9g %.9g -1.5  %.9g %.9g -1.5  %.9g %.9g 1.5  %.9g %.9g 1.5]\n",
                  -1.5 * u.x, -1.5 * u.y, 1.5 * u.x, 1.5 * u.y, -1.5 * u.x, -1.5 * u.y, 1.5 * u.x, 1.5 * u.y);
    auto scene = [&](const std::string& shadowname) {
        return "WorldBegin\nLightSource \"shadowspot\" 1 \"intensity\" [40] \"from\" [0 6 0] \"to\" [0 0 0] "
               "\"coneangle\" [0.5] \"shadowname\" [\"" +
               shadowname + "\"]\nSurface \"matte\"\n" + std::string(plane) + "WorldEnd\n";
    };
    const std::string depth = "FrameBegin 1\nDisplay \"plane.z\" \"zfile\" \"z\"\nFormat 256 256 1\nPixelSamples 2 2\n"
                              "Projection \"perspective\" \"fov\" [40]\n" +
                              lookAt({0, 6, 0}, {0, 0, 0}, {0, 0, 1}) + scene("") + "FrameEnd\n";
    auto picture = [&](const std::string& shadowname, const std::string& out) {
        return "FrameBegin 1\nDisplay \"" + out +
               "\" \"file\" \"rgba\"\nFormat 200 200 1\nPixelSamples 2 2\n"
               "Projection \"perspective\" \"fov\" [30]\n" +
               lookAt({2, 5, 3}, {0, 0, 0}) + scene(shadowname) + "FrameEnd\n";
    };
    writeFile(tmp.path(), "map.rib",
              depth + "MakeShadow \"plane.z\" \"plane.shd\"\n" + picture("plane.shd", "map.exr"));
    writeFile(tmp.path(), "lit.rib", picture("", "lit.exr"));
    runIn(tmp.path(), "map.rib -q");
    runIn(tmp.path(), "lit.rib -q");
    const ImageData map = readImage(tmp.path() + "/map.exr"), lit = readImage(tmp.path() + "/lit.exr");
    int covered = 0, acne = 0;
    for (int y = 0; y < lit.height; ++y)
        for (int x = 0; x < lit.width; ++x) {
            if (lit.at(x, y, 3) < 1) continue;  // the plane's inside only
            ++covered;
            acne += map.at(x, y, 0) < lit.at(x, y, 0) * (1 - 1e-4f);
        }
    EXPECT_GT(covered, 4000);
    EXPECT_EQ(acne, 0);
}

// The shadow lights a point light and a distant light have: shadowpoint reading six 90-degree
// maps from the light (one a world axis), shadowdistant an orthographic map. A sphere over a floor,
// the floor's area in shadow against the ray-traced pointlight's and distantlight's, within 3%.
TEST(ShadowMapCli, ShadowPointsSixMapsAndShadowDistantsMapMatchRayTracedShadows) {
    test::TempDir tmp("shadowmap-point");
    // A light at (0.8, 2.2, 0.4) over a unit sphere at the origin and the floor y = -1.5; the floor
    // seen from straight above.
    const V light{0.8, 2.2, 0.4};
    auto scene = [&](const std::string& lightSource) {
        return "WorldBegin\n" + lightSource +
               "\nSurface \"matte\"\nSphere 1 -1 1 360\n"
               "Patch \"bilinear\" \"P\" [-12 -1.5 -12  12 -1.5 -12  -12 -1.5 12  12 -1.5 12]\nWorldEnd\n";
    };
    auto picture = [&](const std::string& lightSource, const std::string& out) {
        return "FrameBegin 1\nDisplay \"" + out +
               "\" \"file\" \"rgba\"\nFormat 300 300 1\nPixelSamples 3 3\nProjection \"orthographic\"\n"
               "ScreenWindow -5 5 -5 5\n" +
               lookAt({0, 10, 0}, {0, 0, 0}, {0, 0, 1}) + scene(lightSource) + "FrameEnd\n";
    };
    const std::string point = "LightSource \"pointlight\" 1 \"intensity\" [30] \"from\" [0.8 2.2 0.4]";
    // Six faces: +x -x +y -y +z -z, each a 90-degree view from the light.
    const V axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const char* names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    std::string faces, sfs;
    for (int k = 0; k < 6; ++k) {
        const V a = axes[k], up = std::fabs(a.y) > 0.5 ? V{0, 0, 1} : V{0, 1, 0};
        faces +=
            "FrameBegin 1\nDisplay \"" + std::string(names[k]) +
            ".shd\" \"shadow\" \"z\"\nFormat 256 256 1\nPixelSamples 2 2\nProjection \"perspective\" \"fov\" [90]\n" +
            lookAt(light, {light.x + a.x, light.y + a.y, light.z + a.z}, up) + scene("") + "FrameEnd\n";
        sfs += std::string(" \"sf") + names[k] + "\" [\"" + names[k] + ".shd\"]";
    }
    writeFile(
        tmp.path(), "point.rib",
        faces + picture("LightSource \"shadowpoint\" 1 \"intensity\" [30] \"from\" [0.8 2.2 0.4]" + sfs, "point.exr"));
    writeFile(tmp.path(), "point-traced.rib", picture(point + " \"shadowname\" [\"raytrace\"]", "point-traced.exr"));
    writeFile(tmp.path(), "point-lit.rib", picture(point, "point-lit.exr"));
    // The distant light: from (3, 4, 1) towards the origin, its map an orthographic view along it
    // over the sphere (what lies outside the map is lit: nothing there casts a shadow).
    const std::string distant = "LightSource \"distantlight\" 1 \"intensity\" [1] \"from\" [3 4 1] \"to\" [0 0 0]";
    writeFile(tmp.path(), "distant.rib",
              "FrameBegin 1\nDisplay \"sun.z\" \"zfile\" \"z\"\nFormat 512 512 1\nPixelSamples 2 2\n"
              "Projection \"orthographic\"\nScreenWindow -3 3 -3 3\n" +
                  lookAt({9, 12, 3}, {0, 0, 0}) + scene("") + "FrameEnd\nMakeShadow \"sun.z\" \"sun.shd\"\n" +
                  picture("LightSource \"shadowdistant\" 1 \"intensity\" [1] \"from\" [3 4 1] \"to\" [0 0 0] "
                          "\"shadowname\" [\"sun.shd\"]",
                          "distant.exr"));
    writeFile(tmp.path(), "distant-traced.rib",
              picture(distant + " \"shadowname\" [\"raytrace\"]", "distant-traced.exr"));
    writeFile(tmp.path(), "distant-lit.rib", picture(distant, "distant-lit.exr"));
    for (const char* rib : {"point.rib", "point-traced.rib", "point-lit.rib", "distant.rib", "distant-traced.rib",
                            "distant-lit.rib"}) {
        const std::string out = runIn(tmp.path(), std::string(rib));
        EXPECT_EQ(out.find("warning"), std::string::npos) << rib << ": " << out;
    }
    // Areas in the picture's units (10 x 10 over 300 x 300 pixels).
    auto area = [&](const std::string& shadowed, const std::string& lit) {
        return shadowArea(readImage(tmp.path() + "/" + shadowed), readImage(tmp.path() + "/" + lit),
                          (10.0 / 300) * (10.0 / 300));
    };
    for (const std::string light : {"point", "distant"}) {
        const double map = area(light + ".exr", light + "-lit.exr");
        const double traced = area(light + "-traced.exr", light + "-lit.exr");
        EXPECT_GT(traced, 1.0) << light;
        EXPECT_NEAR(map, traced, 0.03 * traced) << light << ": map " << map << " traced " << traced;
        std::fprintf(stderr, "%s shadow area: map %.4f, ray traced %.4f\n", light.c_str(), map, traced);
    }
}

}  // namespace
}  // namespace streyes
