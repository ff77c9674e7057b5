// Interior and Exterior volume shaders over the segments of shaders' rays (trace/shader_rays.h),
// against Beer's law and the fog shader's closed form: a volume that lets through
// exp(-k length(I)) of what comes from the far end of its segment gives exp(-k L) through a slab
// of thickness L and exp(-k * chord) through a sphere it fills; transmission() the same.
//
// The camera is orthographic along +z, one unit a pixel (raster x = x, raster y = H - y).
#include <gtest/gtest.h>

#include <cmath>

#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

constexpr int kW = 32, kH = 32;

void addShaders(const test::ShaderDir& d) {
    d.add("absorb", "volume absorb(float k = 1) { Ci *= exp(-k * length(I)); }\n");
    // Looks straight through itself, along the view.
    d.add("see", "surface see() { Ci = trace(P, normalize(I)); Oi = 1; }\n");
    d.add("through", "surface through() { Ci = transmission(P, P + vector(0, 0, 300)); Oi = 1; }\n");
}

// A slab of thickness L = 2 (z in [110, 112]) over x < 16, its two faces see-through (Opacity
// 0), outward (the near face towards the eye, the far one away), filled with `volume`.
std::string slab(const std::string& volume) {
    return "AttributeBegin\nOpacity [0 0 0]\nSurface \"constant\"\n" + volume + "\nReverseOrientation\n" +
           test::square(-10, 16, -10, 42, 110) + "ReverseOrientation\n" + test::square(-10, 16, -10, 42, 112) +
           "AttributeEnd\n";
}

// The columns a pixel from the slab's edge (x = 16) see it or not depending on where the floor's
// micropolygons fall: left out.
bool nearEdge(int px) { return px == 15 || px == 16; }

// Every pixel away from the slab's edge: `behind` where the slab covers (x < 16), 1 beside it.
void expectBehindTheSlab(const test::RenderResult& r, double behind) {
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            if (nearEdge(px)) continue;
            const double want = px < 16 ? behind : 1.0;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.channel(0, px, py, c), want, 1e-4) << px << " " << py;
        }
}

// trace() from a floor at depth 100 through the slab onto a white wall at 150: exp(-k L) of the
// white where the slab is, 1 beside it.
TEST(VolumeRays, TraceThroughAnAbsorbingSlabIsExpOfMinusDensityTimesThickness) {
    test::ShaderDir d;
    addShaders(d);
    for (double k : {0.1, 0.7}) {
        SCOPED_TRACE(k);
        const std::string rib = test::orthographicView(kW, kH, d.option()) + "WorldBegin\n" +
                                slab("Interior \"absorb\" \"k\" " + std::to_string(k)) +
                                "AttributeBegin\nSurface \"constant\"\n" + test::square(-100, 200, -100, 200, 150) +
                                "AttributeEnd\nSurface \"see\"\n" + test::square(0, kW, 0, kH, 100) + "WorldEnd\n";
        const test::RenderResult r = test::renderRib(rib);
        ASSERT_GT(r.stats.counters.shaderRays, 0u);
        expectBehindTheSlab(r, std::exp(-k * 2));
    }
}

// The same slab seen by transmission() from the floor to a point 300 beyond it.
TEST(VolumeRays, TransmissionThroughAnAbsorbingSlabIsExpOfMinusDensityTimesThickness) {
    test::ShaderDir d;
    addShaders(d);
    for (double k : {0.1, 0.7}) {
        SCOPED_TRACE(k);
        const std::string rib = test::orthographicView(kW, kH, d.option()) + "WorldBegin\n" +
                                slab("Interior \"absorb\" \"k\" " + std::to_string(k)) + "Surface \"through\"\n" +
                                test::square(0, kW, 0, kH, 100) + "WorldEnd\n";
        const test::RenderResult r = test::renderRib(rib);
        expectBehindTheSlab(r, std::exp(-k * 2));
    }
}

// The slab's Exterior is not its Interior: with only an Exterior, the part of the ray between
// the faces is untouched, and the parts outside (floor to near face, 10; far face to the wall,
// 38) are the exterior's.
TEST(VolumeRays, AnExteriorRunsOutsideTheSlabAndNotInside) {
    test::ShaderDir d;
    addShaders(d);
    const double k = 0.01;
    const std::string rib = test::orthographicView(kW, kH, d.option()) + "WorldBegin\n" +
                            slab("Exterior \"absorb\" \"k\" " + std::to_string(k)) +
                            "AttributeBegin\nSurface \"constant\"\n" + test::square(-100, 200, -100, 200, 150) +
                            "AttributeEnd\nSurface \"see\"\n" + test::square(0, kW, 0, kH, 100) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            if (nearEdge(px)) continue;
            // The segment before the far face is the slab's inside: no volume. The wall is hit
            // from the far face with no volume of its own; the near face is met from outside.
            const double want = px < 16 ? std::exp(-k * 10) : 1.0;
            EXPECT_NEAR(r.channel(0, px, py, 0), want, 1e-4) << px << " " << py;
        }
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

constexpr double kR = 8;
// The spheres are turned to put their poles off the view axis: micropolygons fan in at a pole,
// where the faceted surface stands well inside the sphere.
// Elsewhere the ray tracer's facets (its micropolygons, up to about 2.5 units across at this size)
// stand up to s^2 / 8R = 0.1 inside each side: a chord through the middle is up to 0.2 short.
// The turned sphere's patch seam crosses the view along y = 16 (raster rows 15 and 16): rays there
// meet the tracer's seam between patches, where a far hit can be missed. Those rows are left out.
constexpr double kChordSlack = 0.2;
bool onSeam(int py) { return py == 15 || py == 16; }
double chord(double rho, double shortBy = 0) { return std::max(0.0, 2 * std::sqrt(kR * kR - rho * rho) - shortBy); }

// A sphere of radius 8 with the shipped fog shader as its Interior, its surface seeing through
// itself with trace() onto a white wall: per channel bg + (1 - bg) exp(-chord / distance), the
// chord 2 sqrt(r^2 - rho^2).
TEST(VolumeRays, TraceIntoASphereWithAnInteriorFogIsTheFogOverTheChord) {
    test::ShaderDir d;
    addShaders(d);
    const double dist = 10, bg[3] = {0.2, 0.4, 0.6};
    for (bool fog : {false, true}) {
        SCOPED_TRACE(fog ? "interior fog" : "none");
        const std::string rib = test::orthographicView(kW, kH, d.option()) + "WorldBegin\nAttributeBegin\nSurface \"constant\"\n" +
                                test::square(-100, 200, -100, 200, 200) + "AttributeEnd\nAttributeBegin\n" +
                                (fog ? "Interior \"fog\" \"distance\" 10 \"background\" [0.2 0.4 0.6]\n" : "") +
                                "Surface \"see\"\nTranslate 16 16 100\nRotate 90 1 0 0\nSphere 8 -8 8 360\nAttributeEnd\nWorldEnd\n";
        const test::RenderResult r = test::renderRib(rib);
        ASSERT_GT(r.stats.counters.shaderRays, 0u);
        int checked = 0;
        for (int py = 0; py < kH; ++py)
            for (int px = 0; px < kW; ++px) {
                const double rho = std::hypot(px + 0.5 - 16, kH - py - 0.5 - 16);
                if (rho > kR / 2 || onSeam(py)) continue;  // the middle: the chord, not the faceted rim
                // Between the fog over the whole chord and over the chord the facets may leave.
                const double lo = pixelMean(px, py, [&](double q) { return std::exp(-chord(q) / dist); });
                const double hi = pixelMean(px, py, [&](double q) { return std::exp(-chord(q, kChordSlack) / dist); });
                for (int c = 0; c < 3; ++c) {
                    const float v = r.channel(0, px, py, c);
                    if (!fog) {
                        EXPECT_NEAR(v, 1.0, 1e-5) << px << " " << py << " " << c;
                        continue;
                    }
                    EXPECT_GE(v, bg[c] + (1 - bg[c]) * lo - 1e-4) << px << " " << py << " " << c;
                    EXPECT_LE(v, bg[c] + (1 - bg[c]) * hi + 1e-4) << px << " " << py << " " << c;
                }
                ++checked;
            }
        EXPECT_GT(checked, 30);
    }
}

// A white sphere of radius 40 whose nearest point is 10 beyond the floor, with an Exterior
// absorbing k: the floor sees it through exp(-k (10 + R - sqrt(R^2 - rho^2))).
TEST(VolumeRays, AnExteriorFogBeforeASphereIsBeersLawOverTheDistance) {
    test::ShaderDir d;
    addShaders(d);
    const double R = 40, k = 0.1;
    const std::string rib = test::orthographicView(kW, kH, d.option()) +
                            "WorldBegin\nAttributeBegin\nSurface \"constant\"\nExterior \"absorb\" \"k\" " +
                            std::to_string(k) + "\nTranslate 16 16 150\nSphere 40 -40 40 360\nAttributeEnd\n" +
                            "Surface \"see\"\n" + test::square(0, kW, 0, kH, 100) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            const double want = pixelMean(px, py, [&](double q) { return std::exp(-k * (10 + R - std::sqrt(R * R - q * q))); });
            EXPECT_NEAR(r.channel(0, px, py, 0), want, 0.01 * want) << px << " " << py;
        }
}

// transmission() through a sphere of Opacity 0 filled with the Interior: Beer's law over the
// chord inside the sphere's disc, 1 outside it.
TEST(VolumeRays, TransmissionThroughAnInteriorSphereIsBeersLawOverTheChord) {
    test::ShaderDir d;
    addShaders(d);
    const double k = 0.1;
    const std::string rib = test::orthographicView(kW, kH, d.option()) +
                            "WorldBegin\nAttributeBegin\nOpacity [0 0 0]\nSurface \"constant\"\nInterior \"absorb\" \"k\" " +
                            std::to_string(k) + "\nTranslate 16 16 150\nRotate 90 1 0 0\nSphere 8 -8 8 360\nAttributeEnd\n" +
                            "Surface \"through\"\n" + test::square(0, kW, 0, kH, 100) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    int inside = 0;
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            const double rho = std::hypot(px + 0.5 - 16, kH - py - 0.5 - 16);
            if ((rho > kR - 1.5 && rho < kR + 1.5) || onSeam(py)) continue;  // the rim, where pixels are part in
            const float v = r.channel(0, px, py, 0);
            if (rho < kR / 2) {  // Beer's law over the chord, or over the chord the facets may leave
                EXPECT_GE(v, pixelMean(px, py, [&](double q) { return std::exp(-k * chord(q)); }) - 1e-4) << px << " " << py;
                EXPECT_LE(v, pixelMean(px, py, [&](double q) { return std::exp(-k * chord(q, kChordSlack)); }) + 1e-4)
                    << px << " " << py;
            } else {
                const double want = rho < kR ? pixelMean(px, py, [&](double q) { return std::exp(-k * chord(q)); }) : 1.0;
                EXPECT_NEAR(v, want, 0.05 * want) << px << " " << py;
            }
            inside += rho < kR;
        }
    EXPECT_GT(inside, 80);
}

// A sphere filled with an absorbing Interior moves across the floor's view over frames 0 to 3:
// each frame sees it where it is then, and frame 2 alone is frame 2 of the block, bit for bit;
// blocks of one frame are one block of four.
// A sphere filled with an absorbing Interior moving from x = 4 (frame 0) to x = 28 (frame 3) in
// front of a white wall, seen through by the floor's trace() rays; `turn` is put after its motion.
std::string movingVolume(const test::ShaderDir& d, const std::string& turn) {
    return test::orthographicView(32, 8, d.option() + "Hider \"hidden\" \"jitter\" [0]\nPixelSamples 1 1\n") +
           "Shutter 0 0\nFrameBegin 0\nWorldBegin\nAttributeBegin\nSurface \"constant\"\n" +
           test::square(-100, 200, -100, 200, 200) + "AttributeEnd\nAttributeBegin\n" + "Opacity [0 0 0]\n" +
           "Surface \"constant\"\n" + "Interior \"absorb\" \"k\" 0.2\n" +
           "MotionBegin [0 3]\nTranslate 4 4 150\nTranslate 28 4 150\nMotionEnd\n" + turn + "Sphere 4 -4 4 360\n" +
           "AttributeEnd\nSurface \"see\"\n" + test::square(0, 32, 0, 8, 100) + "WorldEnd\nFrameEnd\n";
}

// The moving volume's shot: frames 0 to 3.
RenderOptions shotOfFrames0To3() {
    RenderOptions o;
    o.hasFrames = true;
    o.hasShot = true;
    o.shotFirst = 0;
    o.shotLast = 3;
    return o;
}

TEST(VolumeRays, AMovingVolumeIsSeenWhereItIsInEachFrameWhateverTheBlock) {
    test::ShaderDir d;
    addShaders(d);
    const std::string rib = movingVolume(d, "");
    RenderOptions o = shotOfFrames0To3();
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Frames}) {
        SCOPED_TRACE(test::testName(a));
        o.algorithm = a;
        test::ShotAndFrame r = test::renderShotAndFrame(rib, o, 0, 3, 2);
        EXPECT_TRUE(r.samePixels(2)) << "frame 2 alone differs from frame 2 of the shot";
        o.firstFrame = 0, o.lastFrame = 3, o.maxFrameBlock = 1;
        const test::RenderResult apart = test::renderRib(rib, o);
        o.maxFrameBlock = 64;
        EXPECT_TRUE(test::identicalPixels(r.shot, apart)) << "blocks of one frame differ from one block";
        // The sphere's centre is at x = 4 in frame 0 and x = 28 in frame 3: through its middle
        // the chord is 8, exp(-0.2 * 8) = 0.20 of the white (here at its pole, where the facets
        // fan in and the chord is a little short: below 0.25); away from it, the white.
        const double centre = std::exp(-0.2 * 8);
        for (auto [f, x] : {std::pair{0, 4}, std::pair{3, 28}}) {
            EXPECT_GE(r.shot.channel(f, x, 4, 0), centre - 1e-4) << f;
            EXPECT_LT(r.shot.channel(f, x, 4, 0), 0.25) << f;
            EXPECT_NEAR(r.shot.channel(3 - f, x, 4, 0), 1.0, 1e-4) << f;
        }
    }
}

// The same sphere turned so that its poles lie off the view axis: the rays grazing its rim meet
// its far side (and run the volume) or not the same way in frame 2 alone and in the shot.
TEST(VolumeRays, AMovingTurnedVolumeIsTheSameWhateverTheBlock) {
    test::ShaderDir d;
    addShaders(d);
    const std::string rib = movingVolume(d, "Rotate 90 1 0 0\n");
    RenderOptions o = shotOfFrames0To3();
    for (Algorithm a : {Algorithm::SpacetimeOcclusion, Algorithm::Frames}) {
        SCOPED_TRACE(test::testName(a));
        o.algorithm = a;
        const test::ShotAndFrame r = test::renderShotAndFrame(rib, o, 0, 3, 2);
        EXPECT_TRUE(r.samePixels(2)) << "frame 2 alone differs from frame 2 of the shot";
        // The volume is there: through the sphere's middle in frame 2 (x = 20) the white is dimmed.
        EXPECT_LT(r.alone.channel(2, 20, 4, 0), 0.25);
    }
}

// An Interior where no shader casts rays changes nothing: one warning at its line, and the
// pixels are those without it.
TEST(VolumeRays, AVolumeWithNoRaysToRunOnWarnsOnceAndChangesNothing) {
    test::ShaderDir d;
    addShaders(d);
    const std::string head = test::orthographicView(kW, kH, d.option()) + "WorldBegin\n";
    const std::string tail = "Surface \"constant\"\nSphere 8 -8 8 360\nWorldEnd\n";
    const test::RenderResult with = test::renderRib(head + "Interior \"absorb\"\nTranslate 16 16 100\n" + tail);
    const test::RenderResult without = test::renderRib(head + "Translate 16 16 100\n" + tail);
    EXPECT_TRUE(test::identicalPixels(with, without));
    ASSERT_EQ(with.warnings.size(), 1u);
    EXPECT_NE(with.warnings[0].find(":8:"), std::string::npos) << with.warnings[0];  // the Interior's line
    EXPECT_NE(with.warnings[0].find("\"absorb\""), std::string::npos) << with.warnings[0];
    EXPECT_TRUE(without.warnings.empty());
}

// A volume shader that does not compile stops the render at its file:line:column.
TEST(VolumeRays, AnInteriorThatDoesNotCompileIsAnErrorAtItsPlace) {
    test::ShaderDir d;
    addShaders(d);
    d.add("broken", "volume broken() {\n  Ci *= undefinedThing;\n}\n");
    const std::string rib = test::orthographicView(kW, kH, d.option()) + "WorldBegin\nInterior \"broken\"\nSurface \"see\"\n" +
                            test::square(0, kW, 0, kH, 100) + "WorldEnd\n";
    std::string e;
    try {
        test::renderRib(rib);
    } catch (const InputError& err) {
        e = err.what();
    }
    EXPECT_NE(e.find("broken.sl:2:"), std::string::npos) << e;
    EXPECT_NE(e.find("undefinedThing"), std::string::npos) << e;
}

}  // namespace
}  // namespace streyes
