// Point-based occlusion() in renders: a floor under a half-open box whose discs are in a cloud
// on disk gives the box's form factor (Lambert's, as the ray-traced test has it) without casting
// a ray; the same pixels whatever the threads and the frame block; a missing cloud warns once
// and gives 0; "pointbased" 0 keeps the ray tracer. indirectdiffuse() under an environment map
// sees the map where no disc covers, and its "occlusion" output is occlusion()'s bits.
//
// The camera looks along +z, one unit a pixel (raster y = H - y): the floor at depth 100, its
// shader's normal +z (away from the camera), the box's discs behind it (the camera never sees
// them: they are only in the cloud).
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "shade/point_cloud.h"
#include "shade/vm/texture_source.h"
#include "form_factor_util.h"
#include "shader_test_util.h"
#include "test_util.h"

namespace streyes::test {
namespace {

using Vec = std::array<double, 3>;
constexpr int kW = 32, kH = 32;
constexpr double kFloor = 100, kRoof = 116;
// The walls stand a hair outside the floor, as in the ray-traced test: the floor's border points
// would otherwise lie in their plane, edge on to their discs.
constexpr double kX0 = -0.05, kX1 = kW + 0.05;

double formFactor(const Vec& p, const std::vector<Vec>& poly) { return lambertFormFactor(p, poly); }

double boxFormFactor(double x, double y) {
    const Vec p = {x, y, kFloor};
    return formFactor(p, {{kX0, 0, kRoof}, {kX1, 0, kRoof}, {kX1, kH, kRoof}, {kX0, kH, kRoof}}) +
           formFactor(p, {{kX0, 0, kFloor}, {kX0, kH, kFloor}, {kX0, kH, kRoof}, {kX0, 0, kRoof}}) +
           formFactor(p, {{kX1, 0, kFloor}, {kX1, kH, kFloor}, {kX1, kH, kRoof}, {kX1, 0, kRoof}});
}

// The box as discs of cell 1/2 (radius half the diagonal, "_area" the cell's), facing into it:
// the roof down, the walls at x = kX0 and x = kX1 inward; open at y = 0 and y = 32.
void writeBoxCloud(const std::string& path) {
    std::vector<float> data;
    auto disc = [&](double x, double y, double z, float nx, float nz) {
        const float rec[] = {float(x), float(y), float(z), nx, 0, nz, float(0.25 * std::sqrt(2.0)), 0.25f, 1, 1, 1};
        data.insert(data.end(), std::begin(rec), std::end(rec));
    };
    for (int j = 0; j < 2 * kH; ++j) {
        for (int i = 0; i < 2 * kW; ++i) disc((i + 0.5) / 2, (j + 0.5) / 2, kRoof, 0, -1);
        for (int k = 0; k < 2 * int(kRoof - kFloor); ++k) {
            disc(kX0, (j + 0.5) / 2, kFloor + (k + 0.5) / 2, 1, 0);
            disc(kX1, (j + 0.5) / 2, kFloor + (k + 0.5) / 2, -1, 0);
        }
    }
    std::string error;
    ASSERT_TRUE(BakedPointCloud({{"_area", 1}, {"_radiosity", 3}}, data).write(path, &error)) << error;
}

RenderOptions shot(int threads, int block) {
    RenderOptions o;
    o.hasFrames = true;
    o.hasShot = true;
    o.shotFirst = 0, o.shotLast = 3;
    o.firstFrame = 0, o.lastFrame = 3;
    o.threads = threads;
    o.maxFrameBlock = block;
    return o;
}

std::string floorScene(const ShaderDir& shaders, const std::string& args) {
    return orthographicView(kW, kH, shaders.option() + "ShadingRate 0.5\n") + "WorldBegin\nSurface \"ao\" " + args + "\n" +
           square(0, kW, 0, kH, kFloor) + "WorldEnd\n";
}

ShaderDir aoShader() {
    ShaderDir shaders;
    shaders.add("ao", "surface ao(string f = \"\"; float pb = 1) {\n"
                      "  Ci = occlusion(P, normal(0, 0, 1), 0, \"filename\", f, \"pointbased\", pb, \"microbufres\", 20);\n"
                      "  Oi = 1;\n}\n");
    return shaders;
}

TEST(PointBasedRender, FloorUnderABoxOfDiscsIsItsFormFactorWithoutARay) {
    TempDir dir("pointbased-render");
    const std::string cloud = dir.path() + "/box.ptc";
    writeBoxCloud(cloud);
    const ShaderDir shaders = aoShader();
    const RenderResult r = renderRib(floorScene(shaders, "\"f\" \"" + cloud + "\""), shot(1, 1));
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    EXPECT_EQ(r.stats.counters.shaderRays, 0u);
    double sum = 0, want = 0, worst = 0;
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            double a = 0;
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) a += boxFormFactor(px + (i + 0.5) / 4, kH - py - 1 + (j + 0.5) / 4);
            a /= 16;
            const double got = r.channel(0, px, py, 0);
            sum += got;
            want += a;
            worst = std::max(worst, std::fabs(got - a));
        }
    const double n = double(kW * kH);
    // Per point the microbuffer's error at res 20 (point_based_test.cpp bounds it), the discs'
    // overhang (a fifth of a cell over the box's edges) and the clusters' approximation; measured:
    // mean 0.702 against 0.707, worst pixel 0.013 off.
    EXPECT_NEAR(sum / n, want / n, 0.01) << "mean " << sum / n << " against " << want / n;
    EXPECT_LT(worst, 0.03);
    EXPECT_GT(want / n, 0.5);

    // The same pixels whatever the threads and the frame block (a still scene: every frame).
    const RenderResult two = renderRib(floorScene(shaders, "\"f\" \"" + cloud + "\""), shot(2, 4));
    const RenderResult blocks = renderRib(floorScene(shaders, "\"f\" \"" + cloud + "\""), shot(2, 2));
    for (int f = 0; f <= 3; ++f) {
        EXPECT_TRUE(r.frame(f).rgba == two.frame(f).rgba) << "frame " << f << ": threads 1, blocks of 1 / threads 2, one block";
        EXPECT_TRUE(r.frame(f).rgba == blocks.frame(f).rgba) << "frame " << f << ": blocks of 2";
        EXPECT_TRUE(r.frame(f).rgba == r.frame(0).rgba) << "frame " << f << ": a still scene";
    }
}

TEST(PointBasedRender, AMissingCloudWarnsOnceAndGivesZeroAndPointbasedZeroTraces) {
    TempDir dir("pointbased-missing");
    const ShaderDir shaders = aoShader();
    const RenderResult r = renderRib(floorScene(shaders, "\"f\" \"" + dir.path() + "/none.ptc\""), shot(2, 4));
    int said = 0;
    for (const std::string& w : r.warnings) said += w.find("none.ptc") != std::string::npos;
    EXPECT_EQ(said, 1) << (r.warnings.empty() ? "" : r.warnings.front());
    EXPECT_EQ(r.stats.counters.shaderRays, 0u);
    for (int f = 0; f <= 3; ++f)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) ASSERT_EQ(r.channel(f, x, y, 0), 0.0f) << f << " " << x << " " << y;
    // "pointbased" 0: the ray tracer, which sees no box (the box is only in the cloud).
    const RenderResult traced = renderRib(floorScene(shaders, "\"f\" \"" + dir.path() + "/none.ptc\" \"pb\" 0"), shot(1, 4));
    EXPECT_TRUE(traced.warnings.empty()) << traced.warnings.front();
    EXPECT_GT(traced.stats.counters.shaderRays, 0u);
}

// Point-based indirectdiffuse() with "environmentmap": the directions no disc covers see the map.
// The maps are analytic (a texture source of the test's own, as environment_rays_test.cpp's):
// "constant.env" (0.2, 0.5, 0.9) everywhere; "upper.env" 1 where z > 0, else 0.25.
class PointBasedSkies final : public sl::TextureSource {
  public:
    bool texture(const std::string&, const sl::TextureOptions&, const sl::TextureQuery&, float* const*) override {
        return false;
    }
    bool shadow(const std::string&, const sl::TextureOptions&, const sl::DirectionQuery&, float* const*) override {
        return false;
    }
    bool environment(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q,
                     float* const* out) override {
        if (name != "constant.env" && name != "upper.env") return false;
        for (int i = 0; i < q.n; ++i) {
            if (q.active && !q.active[i]) continue;
            float c[3] = {0.2f, 0.5f, 0.9f};
            if (name == "upper.env") c[0] = c[1] = c[2] = q.R[2][i] > 0 ? 1.0f : 0.25f;
            for (int k = 0; k < o.channels; ++k) out[k][i] = c[o.firstChannel + k];
        }
        return true;
    }
};

constexpr float kSky[3] = {0.2f, 0.5f, 0.9f};

// Frames 0 to last (a still scene: the frames' pixels are the same).
RenderOptions skyShot(int threads, int block, int last = 0) {
    RenderOptions o = shot(threads, block);
    o.shotLast = o.lastFrame = last;
    o.textureSource = [](const std::vector<std::string>&, Log&) { return std::make_shared<PointBasedSkies>(); };
    return o;
}

// "which": 0 indirectdiffuse()'s colour, 1 its "occlusion" output, 2 occlusion() of the same
// cloud, 3 occlusion()'s "environmentcolor" output.
ShaderDir giShader(const std::string& envOptions) {
    ShaderDir shaders;
    shaders.add("ao", "surface ao(string f = \"\"; float which = 0) {\n"
                      "  float o = -1;\n  color seen = -1;\n"
                      "  color c = indirectdiffuse(P, normal(0, 0, 1), 0, \"filename\", f, \"microbufres\", 20" + envOptions +
                      ", \"occlusion\", o);\n"
                      "  float a = occlusion(P, normal(0, 0, 1), 0, \"filename\", f, \"microbufres\", 20" + envOptions +
                      ", \"environmentcolor\", seen);\n"
                      "  if (which == 0) Ci = c; else if (which == 1) Ci = o; else if (which == 2) Ci = a; else Ci = seen;\n"
                      "  Oi = 1;\n}\n");
    return shaders;
}

std::string emptyCloud(const TempDir& dir) {
    const std::string path = dir.path() + "/empty.ptc";
    std::string error;
    EXPECT_TRUE(BakedPointCloud({{"_area", 1}, {"_radiosity", 3}}, {}).write(path, &error)) << error;
    return path;
}

TEST(PointBasedRender, NothingUnderAConstantEnvironmentIsItsColour) {
    TempDir dir("pointbased-env-empty");
    const std::string cloud = emptyCloud(dir);
    const ShaderDir shaders = giShader(", \"environmentmap\", \"constant.env\"");
    const RenderResult r = renderRib(floorScene(shaders, "\"f\" \"" + cloud + "\""), skyShot(1, 1));
    const RenderResult o = renderRib(floorScene(shaders, "\"f\" \"" + cloud + "\" \"which\" 1"), skyShot(1, 1));
    const RenderResult seen = renderRib(floorScene(shaders, "\"f\" \"" + cloud + "\" \"which\" 3"), skyShot(1, 1));
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    EXPECT_TRUE(o.warnings.empty() && seen.warnings.empty());
    EXPECT_EQ(r.stats.counters.shaderRays, 0u);
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            for (int k = 0; k < 3; ++k) {
                ASSERT_NEAR(r.channel(0, px, py, k), kSky[k], 1e-5f) << px << " " << py << " " << k;
                ASSERT_NEAR(seen.channel(0, px, py, k), kSky[k], 1e-5f) << px << " " << py << " " << k;
            }
            ASSERT_EQ(o.channel(0, px, py, 0), 0.0f) << px << " " << py;
        }
    // Without a map, or with one that cannot be read (the texture source warns), the uncovered
    // directions are black.
    const ShaderDir darkShader = giShader(""), unreadShader = giShader(", \"environmentmap\", \"nosuch.env\"");
    const RenderResult dark = renderRib(floorScene(darkShader, "\"f\" \"" + cloud + "\""), skyShot(1, 4));
    const RenderResult unread = renderRib(floorScene(unreadShader, "\"f\" \"" + cloud + "\""), skyShot(2, 4));
    EXPECT_TRUE(dark.warnings.empty()) << dark.warnings.front();
    EXPECT_TRUE(unread.warnings.empty()) << unread.warnings.front();
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            ASSERT_EQ(dark.channel(0, px, py, 0), 0.0f);
            ASSERT_EQ(unread.channel(0, px, py, 0), 0.0f);
        }
}

// "environmentspace": a coordinate system turned half a turn about x sees the floor's hemisphere
// (current +z) as its -z, where "upper.env" is 0.25; without it, current space's upper half: 1.
TEST(PointBasedRender, TheEnvironmentSpaceTurnsTheDirections) {
    TempDir dir("pointbased-env-space");
    const std::string cloud = emptyCloud(dir);
    const std::string sky = "AttributeBegin\nRotate 180 1 0 0\nCoordinateSystem \"sky\"\nAttributeEnd\n";
    const ShaderDir turnedShader = giShader(", \"environmentmap\", \"upper.env\", \"environmentspace\", \"sky\"");
    const ShaderDir plainShader = giShader(", \"environmentmap\", \"upper.env\"");
    auto scene = [&](const ShaderDir& shaders) {
        std::string rib = floorScene(shaders, "\"f\" \"" + cloud + "\"");
        return rib.insert(rib.find("WorldBegin\n") + 11, sky);
    };
    const RenderResult turned = renderRib(scene(turnedShader), skyShot(1, 4));
    const RenderResult plain = renderRib(scene(plainShader), skyShot(1, 4));
    EXPECT_TRUE(turned.warnings.empty()) << turned.warnings.front();
    EXPECT_TRUE(plain.warnings.empty()) << plain.warnings.front();
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            ASSERT_NEAR(turned.channel(0, px, py, 0), 0.25f, 1e-5f) << px << " " << py;
            ASSERT_NEAR(plain.channel(0, px, py, 0), 1.0f, 1e-5f) << px << " " << py;
        }
}

// The half-open box of white discs under the constant sky: each pixel's colour is the box's
// occlusion o in white plus the sky over the rest, c + (1 - c) o, exactly (the map fills what
// the discs leave); o is the form factor within the point-based test's bounds, and the same
// bits as occlusion() of the cloud; occlusion()'s "environmentcolor" is c (1 - o). The same
// pixels whatever the threads and the frame block.
TEST(PointBasedRender, ABoxUnderAnEnvironmentMixesByItsFormFactor) {
    TempDir dir("pointbased-env-box");
    const std::string cloud = dir.path() + "/box.ptc";
    writeBoxCloud(cloud);
    const ShaderDir shaders = giShader(", \"environmentmap\", \"constant.env\"");
    auto render = [&](int which, int threads, int block, int last) {
        return renderRib(floorScene(shaders, "\"f\" \"" + cloud + "\" \"which\" " + std::to_string(which)),
                         skyShot(threads, block, last));
    };
    const RenderResult colour = render(0, 1, 1, 1), occ = render(1, 1, 4, 0), plain = render(2, 1, 4, 0), seen = render(3, 1, 4, 0);
    for (const RenderResult* r : {&colour, &occ, &plain, &seen}) EXPECT_TRUE(r->warnings.empty()) << r->warnings.front();
    EXPECT_EQ(colour.stats.counters.shaderRays, 0u);
    double sum = 0, want = 0, worst = 0;
    for (int py = 0; py < kH; ++py)
        for (int px = 0; px < kW; ++px) {
            double a = 0;
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) a += boxFormFactor(px + (i + 0.5) / 4, kH - py - 1 + (j + 0.5) / 4);
            a /= 16;
            const float o = occ.channel(0, px, py, 0);
            ASSERT_EQ(o, plain.channel(0, px, py, 0)) << px << " " << py << ": \"occlusion\" is occlusion()'s";
            for (int k = 0; k < 3; ++k) {
                ASSERT_NEAR(colour.channel(0, px, py, k), kSky[k] + (1 - kSky[k]) * o, 2e-6f) << px << " " << py << " " << k;
                ASSERT_NEAR(seen.channel(0, px, py, k), kSky[k] * (1 - o), 2e-6f) << px << " " << py << " " << k;
            }
            sum += o;
            want += a;
            worst = std::max(worst, std::fabs(o - a));
        }
    const double n = double(kW * kH);
    EXPECT_NEAR(sum / n, want / n, 0.01) << "mean " << sum / n << " against " << want / n;
    EXPECT_LT(worst, 0.03);
    EXPECT_GT(want / n, 0.5);
    // The colour against the closed form c + (1 - c) F directly: the occlusion's bound times 1 - c.
    const double red = colour.channel(0, kW / 2, kH / 2, 0), F = boxFormFactor(kW / 2 + 0.5, kH - kH / 2 - 0.5);
    EXPECT_NEAR(red, kSky[0] + (1 - kSky[0]) * F, 0.03 * (1 - kSky[0]));

    // Frames 0 and 1 alone (threads 1, blocks of 1) and in one block (threads 2).
    const RenderResult block = render(0, 2, 2, 1);
    for (int f = 0; f <= 1; ++f) {
        EXPECT_TRUE(colour.frame(f).rgba == block.frame(f).rgba) << "frame " << f << ": threads 1, blocks of 1 / threads 2, one block";
        EXPECT_TRUE(colour.frame(f).rgba == colour.frame(0).rgba) << "frame " << f << ": a still scene";
    }
}

}  // namespace
}  // namespace streyes::test
