// The ray tracer sees displaced surfaces as the rasterizer draws them (trace/tessellate.h): a
// plane displaced by a constant is hit, occludes and shadows at its displaced place; a bump's
// traced shadow is the rasterizer's silhouette of it seen from the light; a displacement that
// changes with time gives each frame its own traced surface, whatever the frame block.
//
// Cameras are orthographic along +z, one unit a pixel (raster x = x, raster y = H - y).
#include <gtest/gtest.h>

#include <cmath>

#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

// Moves every point d towards the camera (-z in camera space), d = k * time + c.
const char* kLift = "displacement lift(float d = 0, k = 0) { P += vector(0, 0, -(d + k * time)); N = calculatenormal(P); }\n";

// The floor's rays go up (+z) over the hemisphere: red, the mean height of the hits (0 when
// none); green, occlusion() within maxdist `m`.
const char* kProbe = R"(
surface probe(float m = 10) {
    point hp = 0;
    float hits = 0, height = 0;
    gather("", P, vector(0, 0, 1), PI / 2, 64, "surface:P", hp, "bias", 0.001) {
        hits += 1;
        height += zcomp(hp);
    }
    Ci = color(height / max(hits, 1), occlusion(P, normal(0, 0, 1), 1024, "maxdist", m, "bias", 0.001), 0);
    Oi = 1;
}
)";

// A roof 10 behind the floor (depth 110) displaced by lift; the floor [0, 8]^2 at 100. Rays
// that reach the roof within maxdist 10 go at most 8 sideways: the roof reaches beyond them.
std::string roofScene(const test::ShaderDir& d, const std::string& lift) {
    return test::orthographicView(8, 8, d.option()) + "WorldBegin\nAttributeBegin\nSurface \"constant\"\n" +
           "Attribute \"displacementbound\" \"sphere\" [8]\nDisplacement \"lift\" " + lift + "\n" +
           test::square(-12, 20, -12, 20, 110) + "AttributeEnd\nSurface \"probe\"\n" + test::square(0, 8, 0, 8, 100) +
           "WorldEnd\n";
}

// Rays from the floor meet a roof at height h above it within maxdist m with the cosine-weighted
// share of directions whose cosine exceeds h/m: 1 - (h/m)^2.
TEST(DisplacedTrace, APlaneDisplacedByAConstantIsHitAndOccludesAtItsDisplacedHeight) {
    test::ShaderDir d;
    d.add("lift", kLift);
    d.add("probe", kProbe);
    for (double lift : {0.0, 4.0}) {
        SCOPED_TRACE("lift " + std::to_string(lift));
        const test::RenderResult r = test::renderRib(roofScene(d, "\"d\" " + std::to_string(lift)));
        ASSERT_GT(r.stats.counters.shaderRays, 0u);
        const double h = 10 - lift, want = 1 - (h / 10) * (h / 10);
        double mean = 0;
        for (int py = 0; py < 8; ++py)
            for (int px = 0; px < 8; ++px) {
                // Every hit lies on the displaced plane: exact but for float rounding at depth ~100.
                EXPECT_NEAR(r.channel(0, px, py, 0), 110 - lift, 1e-3) << px << " " << py;
                mean += r.channel(0, px, py, 1);
            }
        // 1024 stratified rays a point: the mean over 64 pixels within 0.01.
        EXPECT_NEAR(mean / 64, want, 0.01);
    }
}

// A displaced roof too large to dice for the ray tracer (2e5 pixels across) is traced as the
// exact patch, undisplaced, with one warning: not left out.
TEST(DisplacedTrace, ASurfaceTooLargeToDiceIsTracedUndisplacedWithAWarning) {
    test::ShaderDir d;
    d.add("lift", kLift);
    d.add("probe", kProbe);
    std::string rib = roofScene(d, "\"d\" 4");
    const std::string small = test::square(-12, 20, -12, 20, 110), huge = test::square(-1e5, 1e5, -1e5, 1e5, 110);
    rib.replace(rib.find(small), small.size(), huge);
    const test::RenderResult r = test::renderRib(rib);
    EXPECT_NEAR(r.channel(0, 4, 4, 0), 110, 1e-3);
    int said = 0;
    for (const std::string& w : r.warnings) said += w.find("it is traced undisplaced") != std::string::npos;
    EXPECT_EQ(said, 1);
}

// Frame f lifts the roof by 2 f: each frame's hits at 110 - 2 f, and a frame's pixels are the
// same rendered alone, in one block, or in blocks of one frame.
TEST(DisplacedTrace, ADisplacementThatChangesPerFrameIsTracedPerFrameWhateverTheBlock) {
    test::ShaderDir d;
    d.add("lift", kLift);
    d.add("probe", kProbe);
    const std::string rib = roofScene(d, "\"k\" 2");
    RenderOptions o;
    o.hasFrames = true;
    o.hasShot = true;
    o.shotFirst = 0;
    o.shotLast = 3;
    for (Algorithm a : {Algorithm::Spacetime, Algorithm::Frames, Algorithm::Raytrace}) {
        SCOPED_TRACE(test::testName(a));
        o.algorithm = a;
        o.firstFrame = o.lastFrame = 0;
        o.hasFrames = true;
        const test::ShotAndFrame r = test::renderShotAndFrame(rib, o, 0, 3, 2);
        EXPECT_TRUE(r.samePixels(2)) << "frame 2 alone differs from frame 2 of the shot";
        for (int f = 0; f <= 3; ++f) EXPECT_NEAR(r.shot.channel(f, 4, 4, 0), 110 - 2 * f, 1e-3) << "frame " << f;
        o.firstFrame = 0, o.lastFrame = 3, o.maxFrameBlock = 1;
        const test::RenderResult apart = test::renderRib(rib, o);
        o.maxFrameBlock = 64;
        EXPECT_TRUE(test::identicalPixels(r.shot, apart)) << "blocks of one frame differ from one block";
    }
}

// Shadows tested per sample, as the ray tracer tests them (the rasterizer's default tests still
// occluders at a still floor's vertices: tests/core/still_shadow_test.cpp).
const char* kPerSampleShadows = "Option \"trace\" \"string shadowtest\" [\"sample\"]\n";

// A distant light along (0, -1, 1) casts the shadow of a plane displaced towards the camera by
// d, whose edge at (y = 26, depth 90) would fall on the floor (depth 100) at y = 16, above the
// picture: displaced, at y = 16 - d. The floor's rows below it are lit, those above dark.
TEST(DisplacedTrace, APlaneDisplacedByAConstantCastsItsShadowFromItsDisplacedPlace) {
    test::ShaderDir d;
    d.add("lift", kLift);
    for (double lift : {0.0, 6.0}) {
        SCOPED_TRACE("lift " + std::to_string(lift));
        // Per sample: the edge's place exact per pixel row (at the shading rate, a one-micropolygon ramp).
        const std::string rib = test::orthographicView(16, 16, d.option()) + kPerSampleShadows + "WorldBegin\n" +
                                "Attribute \"light\" \"shadows\" \"on\"\n" +
                                "LightSource \"distantlight\" 1 \"from\" [0 1 -1] \"to\" [0 0 0]\nAttributeBegin\n" +
                                "Attribute \"displacementbound\" \"sphere\" [8]\nDisplacement \"lift\" \"d\" " +
                                std::to_string(lift) + "\n" + test::square(-10, 26, 26, 76, 90) + "AttributeEnd\n" +
                                "Surface \"matte\" \"Ka\" 0\n" + test::square(0, 16, 0, 16, 100) + "WorldEnd\n";
        const test::RenderResult r = test::renderRib(rib);
        ASSERT_GT(r.stats.counters.shadowRays + r.stats.counters.shadowVertexRays, 0u);
        const float lit = float(std::sqrt(0.5));  // Kd 1, the light at 45 degrees
        for (int py = 0; py < 16; ++py) {
            const double y0 = 16 - py - 1;  // the pixel row is [y0, y0 + 1]
            const double want = lit * std::clamp(16 - lift - y0, 0.0, 1.0);
            for (int px = 0; px < 16; ++px) EXPECT_NEAR(r.channel(0, px, py, 0), want, 1e-4) << px << " " << py;
        }
    }
}

// A bump on the near edge of a plane (depth 80, y in [34, 70]) moves it towards the camera by
// h (1 - r^2 / R^2) within R of (16, 34). Seen along the light's direction (0, -1, 1) it bulges
// the plane's edge out: for |x - 16| < R the edge is at y' = y + z - 100 = 14 - h (1 - (x - 16)^2 /
// R^2), 4/3 R h more area. The rasterizer draws it under a camera sheared so that its view is
// the light's, onto the floor's own pixels (y' = y at depth 100); the ray tracer casts the
// shadow of it onto the floor. Pixel for pixel the same, but where the two dicings differ.
TEST(DisplacedTrace, ABumpsTracedShadowIsTheRasterizersSilhouetteSeenFromTheLight) {
    test::ShaderDir d;
    // In world space: the two renders' cameras differ.
    d.add("bump", "displacement bump(float h = 0, R = 8) {\n"
                  "  point W = transform(\"world\", P);\n"
                  "  float r2 = (xcomp(W) - 16) * (xcomp(W) - 16) + (ycomp(W) - 34) * (ycomp(W) - 34);\n"
                  "  P = transform(\"world\", \"current\", W + vector(0, 0, -h * max(0, 1 - r2 / (R * R))));\n"
                  "  N = calculatenormal(P); }\n");
    constexpr int W = 32, H = 32;
    constexpr double kH = 4, kR = 8;
    auto occluder = [&](double h) {
        return "AttributeBegin\nAttribute \"displacementbound\" \"sphere\" [4]\nShadingRate 0.25\nDisplacement \"bump\" \"h\" " +
               std::to_string(h) + "\nSurface \"constant\"\n" + test::square(2, 30, 34, 70, 80) + "AttributeEnd\n";
    };
    // The rasterizer's silhouette from the light: alpha under the sheared camera.
    auto silhouette = [&](double h) {
        const std::string rib = test::orthographicView(W, H, d.option()) + "Transform [1 0 0 0  0 1 0 0  0 1 1 0  0 -100 0 1]\nWorldBegin\n" +
                                occluder(h) + "WorldEnd\n";
        return test::renderRib(rib);
    };
    // The traced shadow on the floor: 1 - lit share.
    auto shadow = [&](double h) {
        const std::string rib = test::orthographicView(W, H, d.option()) + kPerSampleShadows + "WorldBegin\n" +
                                "Attribute \"light\" \"shadows\" \"on\"\n" +
                                "LightSource \"distantlight\" 1 \"from\" [0 1 -1] \"to\" [0 0 0]\n" + occluder(h) + "Surface \"matte\" \"Ka\" 0\n" +
                                test::square(0, W, 0, H, 100) + "WorldEnd\n";
        return test::renderRib(rib);
    };
    const float lit = float(std::sqrt(0.5));
    double area[2][2] = {};  // [flat, bumped][silhouette, shadow]
    for (int b = 0; b < 2; ++b) {
        const test::RenderResult sil = silhouette(b * kH), sh = shadow(b * kH);
        ASSERT_GT(sh.stats.counters.shadowRays + sh.stats.counters.shadowVertexRays, 0u);
        int differ = 0;
        for (int py = 0; py < H; ++py)
            for (int px = 0; px < W; ++px) {
                const double a = sil.alpha(0, px, py), s = 1 - sh.channel(0, px, py, 0) / lit;
                ASSERT_TRUE(std::isfinite(a) && std::isfinite(s));
                area[b][0] += a;
                area[b][1] += s;
                differ += std::fabs(a - s) > 0.3;  // more than one of the four samples
            }
        SCOPED_TRACE(b ? "bumped" : "flat");
        // Edge pixels may differ by a sample where the two cameras dice the bump differently.
        EXPECT_LE(differ, b ? 4 : 0);
    }
    // The flat plane: 18 rows of 28 pixels in view (y' from 14 to 32).
    EXPECT_NEAR(area[0][0], 28 * 18, 0.5);
    EXPECT_NEAR(area[0][1], 28 * 18, 0.5);
    // The bulge: 4/3 R h, to 2% (the micropolygons' chords fall short of the parabola).
    const double bulge = 4.0 / 3.0 * kR * kH;
    EXPECT_NEAR(area[1][0] - area[0][0], bulge, 0.02 * bulge);
    EXPECT_NEAR(area[1][1] - area[0][1], bulge, 0.02 * bulge);
}

}  // namespace
}  // namespace streyes
