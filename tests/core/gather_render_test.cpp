// gather() loops against closed forms: the hits of a uniform roof over the hemisphere, the mean
// direction of rays that all miss (cosine-weighted: 2/3 along the axis), the hit positions.
#include <gtest/gtest.h>


#include "shader_test_util.h"
#include "test_util.h"

namespace streyes {
namespace {

std::string view(const test::ShaderDir& d) {
    return "Format 8 8 1\nProjection \"orthographic\"\nScreenWindow 0 8 0 8\nPixelFilter \"box\" 1 1\n"
           "PixelSamples 1 1\n" +
           d.option();
}

// The floor's rays go up (+z, away from the camera) over the hemisphere: red, the mean of the
// hits' colours over all samples; green, the hits' mean height; blue, the misses' mean direction
// along the axis.
const char* kGatherer = R"(
surface gatherer(float samples = 256) {
    color sum = 0, hitCi = 0;
    point hitP = 0;
    vector dir = 0;
    float hits = 0, misses = 0, height = 0, along = 0;
    gather("illuminance", P, vector(0, 0, 1), PI / 2, samples, "surface:Ci", hitCi, "surface:P", hitP,
           "ray:direction", dir, "bias", 0.001) {
        sum += hitCi;
        hits += 1;
        height += zcomp(hitP);
    } else {
        misses += 1;
        along += zcomp(dir);
    }
    Ci = color(comp(sum, 0) / samples, hits > 0 ? height / hits : 0, misses > 0 ? along / misses : 0);
    Oi = 1;
}
)";

TEST(GatherRender, AUniformRoofGivesItsColourAndItsHeight) {
    test::ShaderDir d;
    d.add("gatherer", kGatherer);
    // A roof 10 above the floor, 1e5 wide: rays within 0.006 degrees of the horizon miss it.
    const std::string rib = view(d) + "WorldBegin\nAttributeBegin\nSurface \"constant\"\nColor [0.6 0.3 0.2]\n" +
                            test::square(-1e5, 1e5, -1e5, 1e5, 110) + "AttributeEnd\nSurface \"gatherer\"\n" +
                            test::square(0, 8, 0, 8, 100) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    ASSERT_GT(r.stats.counters.shaderRays, 0u);
    for (int py = 0; py < 8; ++py)
        for (int px = 0; px < 8; ++px) {
            EXPECT_NEAR(r.channel(0, px, py, 0), 0.6f, 1e-4f) << px << " " << py;
            EXPECT_NEAR(r.channel(0, px, py, 1), 110.0f, 1e-2f) << px << " " << py;
            EXPECT_EQ(r.channel(0, px, py, 2), 0.0f) << px << " " << py;  // no misses
        }
}

TEST(GatherRender, MissesRunTheElseBranchAlongCosineWeightedDirections) {
    test::ShaderDir d;
    d.add("gatherer", kGatherer);
    const std::string rib = view(d) + "WorldBegin\nSurface \"gatherer\"\n" + test::square(0, 8, 0, 8, 100) + "WorldEnd\n";
    const test::RenderResult r = test::renderRib(rib);
    for (int py = 0; py < 8; ++py)
        for (int px = 0; px < 8; ++px) {
            EXPECT_EQ(r.channel(0, px, py, 0), 0.0f);
            // E[cos theta] under the cosine-weighted hemisphere: 2/3; 256 stratified samples.
            EXPECT_NEAR(r.channel(0, px, py, 2), 2.0f / 3.0f, 0.01f) << px << " " << py;
        }
}

TEST(GatherRender, BadFormsAreErrorsAtTheirPlace) {
    test::ShaderDir d;
    const std::string head = view(d) + "WorldBegin\n";
    const std::string floor = test::square(0, 4, 0, 4, 100) + "WorldEnd\n";
    struct Case {
        const char* source;
        const char* where;
        const char* what;
    } cases[] = {
        {"surface bad() {\n  color c;\n  gather(\"\", P, N, 1, 4, \"surface:Cx\", c) Ci += c;\n}\n", ":3:26",
         "unknown gather output"},
        {"surface bad() {\n  float c;\n  gather(\"\", P, N, 1, 4, \"surface:Ci\", c) Ci += c;\n}\n", ":3:40",
         "is a color, not a float"},
        {"surface bad() {\n  gather(\"\", P, N, 1) Ci += 1;\n}\n", ":2:3", "gather takes"},
        {"surface bad() {\n  gather(\"\", P, Cs, 1, 4) Ci += 1;\n}\n", ":2:17", "cannot use a color"},
        {"surface bad() {\n  gather(\"\", P, N, 1, 4, \"far\", 2) Ci += 1;\n}\n", ":2:26", "unknown gather option"},
        {"surface bad() {\n  color c;\n  gather(\"\", P, N, 1, 4, \"surface:Ci\", c + 1) Ci += c;\n}\n", ":3:", "variable"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.source);
        d.add("bad", c.source);
        std::string err;
        try {
            test::renderRib(head + "Surface \"bad\"\n" + floor);
        } catch (const InputError& e) {
            err = e.what();
        }
        EXPECT_NE(err.find("bad.sl" + std::string(c.where)), std::string::npos) << err;
        EXPECT_NE(err.find(c.what), std::string::npos) << err;
    }
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// Two planes facing each other, each shaded 1 plus what it sees of the other: the floor the
// camera sees adds up one for each level of rays, trace() and gather() alike, up to
// Option "trace" "maxdepth" (PRMan's default 10).
TEST(GatherRender, TraceMaxdepthCountsLevelsAcrossTraceAndGather) {
    test::ShaderDir d;
    d.add("bounce", R"(
surface bounce() {
    vector up = zcomp(P) < 105 ? vector(0, 0, 1) : vector(0, 0, -1);
    color seen = 0, c = 0;
    if (zcomp(P) < 105) {
        seen = trace(P, up);
    } else {
        gather("", P, up, 0.01, 1, "surface:Ci", c) seen = c;
    }
    Ci = 1 + seen;
    Oi = 1;
}
)");
    const std::string scene = "WorldBegin\nSurface \"bounce\"\n" + test::square(-1e4, 1e4, -1e4, 1e4, 110) +
                              test::square(0, 8, 0, 8, 100) + "WorldEnd\n";
    for (int depth : {-1, 0, 1, 4}) {
        SCOPED_TRACE(depth);
        const std::string option = depth < 0 ? "" : "Option \"trace\" \"maxdepth\" [" + std::to_string(depth) + "]\n";
        const test::RenderResult r = test::renderRib(view(d) + option + scene);
        const float want = 1.0f + float(depth < 0 ? 10 : depth);
        // Inside the floor, two pixels from its edges: the gather's 0.01-radian cone drifts less
        // than half a unit over five crossings (the edges' rays may leave the floor).
        for (int py = 2; py < 6; ++py)
            for (int px = 2; px < 6; ++px) EXPECT_EQ(r.channel(0, px, py, 0), want) << px << " " << py;
    }
}

}  // namespace
}  // namespace streyes

namespace streyes {
namespace {

// rayinfo() on the floor the eye sees (depth 0, "camera") and on the roof its rays hit: depth 1,
// "specular" through trace(), "diffuse" through gather(). An unknown name gives 0.
TEST(GatherRender, RayinfoSaysTheDepthAndTypeOfTheRay) {
    test::ShaderDir d;
    d.add("info", R"(
surface info() {
    float depth = -1, t = -1, unknown = 7;
    string type = "none";
    rayinfo("depth", depth);
    rayinfo("type", type);
    float none = rayinfo("nosuch", unknown);
    t = type == "camera" ? 1 : type == "specular" ? 2 : type == "diffuse" ? 3 : 0;
    Ci = color(depth, t, unknown + none);
    if (zcomp(P) < 105) {
        color up = trace(P, vector(0, 0, 1)), c = 0, g = 0;
        gather("", P, vector(0, 0, 1), 0.01, 1, "surface:Ci", c) g = c;
        Ci += 10 * up + 100 * g;
    }
    Oi = 1;
}
)");
    const test::RenderResult r = test::renderRib(view(d) + "WorldBegin\nSurface \"info\"\n" +
                                                 test::square(-1e4, 1e4, -1e4, 1e4, 110) +
                                                 test::square(0, 8, 0, 8, 100) + "WorldEnd\n");
    EXPECT_EQ(r.channel(0, 4, 4, 0), 0 + 10 * 1 + 100 * 1);  // depths 0, 1, 1
    EXPECT_EQ(r.channel(0, 4, 4, 1), 1 + 10 * 2 + 100 * 3);  // camera, specular, diffuse
    EXPECT_EQ(r.channel(0, 4, 4, 2), 7 + 10 * 7 + 100 * 7);
}

}  // namespace
}  // namespace streyes
