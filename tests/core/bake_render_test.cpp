// bake3d() and texture3d() in renders: the cloud a still scene bakes is the same bytes whatever the
// thread count and the frame block, and a later render reads it back where it was baked.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "shade/point_cloud.h"
#include "shader_test_util.h"
#include "test_util.h"

namespace streyes::test {
namespace {

std::string bytesOf(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

// A 16 x 16 square at depth 5 (one unit a pixel) and a smaller one in front of it, still, over
// frames 0 to 3.
std::string stillScene(const ShaderDir& shaders, const std::string& surface) {
    return orthographicView(16, 16, shaders.option()) + "WorldBegin\n" + surface + "\n" +
           "Patch \"bilinear\" \"P\" [0 0 5  16 0 5  0 16 5  16 16 5]\n"
           "Patch \"bilinear\" \"P\" [4 4 3  9 4 3  4 9 3  9 9 3]\nWorldEnd\n";
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

TEST(BakeRender, CloudIsTheSameBytesWhateverTheThreadsAndTheFrameBlock) {
    ShaderDir shaders;
    TempDir out("bake3d-render");
    shaders.add("b", "surface b(string f = \"\") {\n"
                     "  point Pw = transform(\"world\", P);\n"
                     "  bake3d(f, \"\", P, normalize(N), \"x\", xcomp(Pw), \"_area\", area(P));\n  Ci = 1;\n}\n");
    auto bakeWith = [&](int threads, int block, const std::string& name) {
        const std::string file = out.path() + "/" + name;
        const RenderResult r = renderRib(stillScene(shaders, "Surface \"b\" \"f\" \"" + file + "\""), shot(threads, block));
        EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
        return bytesOf(file);
    };
    const std::string one = bakeWith(1, 1, "a.ptc");
    const std::string two = bakeWith(2, 64, "b.ptc");
    const std::string twoBlocks = bakeWith(2, 2, "c.ptc");
    ASSERT_GT(one.size(), 100u);
    EXPECT_TRUE(one == two) << "threads 1 / blocks of 1 frame against threads 2 / one block";
    EXPECT_TRUE(one == twoBlocks) << "blocks of 2 frames";

    // The points cover both squares' visible and hidden parts: positions within them, x in world
    // space as baked, and the areas of the front square's micropolygons add up to about its 25.
    BakedPointCloud c;
    std::string error;
    ASSERT_TRUE(c.read(out.path() + "/a.ptc", &error)) << error;
    int xo = 0, xc = 0, ao = 0, ac = 0;
    ASSERT_TRUE(c.channel("x", &xo, &xc));
    ASSERT_TRUE(c.channel("_area", &ao, &ac));
    double front = 0;
    for (size_t i = 0; i < c.size(); ++i) {
        const float* p = c.point(i);
        EXPECT_EQ(p[xo], p[0]);
        EXPECT_TRUE(p[0] >= -1e-3f && p[0] <= 16.001f && p[1] >= -1e-3f && p[1] <= 16.001f) << p[0] << " " << p[1];
        EXPECT_GT(p[6], 0.0f);  // a radius
        if (std::fabs(p[2] - 3) < 1e-3f) front += p[ao];
    }
    // area() is each point's micropolygon's: the points of a w x h grid hold (w + 1)(h + 1) of them,
    // so the sum overshoots the square's 25 by its border's share.
    EXPECT_GT(front, 25 * 0.98);
    EXPECT_LT(front, 25 * 1.6);
}

TEST(BakeRender, ALaterRenderReadsTheCloudBackWhereItWasBaked) {
    ShaderDir shaders;
    TempDir out("bake3d-read");
    const std::string file = out.path() + "/x.ptc";
    shaders.add("b", "surface b(string f = \"\") {\n"
                     "  bake3d(f, \"\", P, normalize(N), \"x\", xcomp(transform(\"world\", P)));\n  Ci = 1;\n}\n");
    shaders.add("r", "surface r(string f = \"\") {\n  float x = -1;\n"
                     "  float ok = texture3d(f, P, normalize(N), \"x\", x);\n  Ci = color(x, ok, 0);\n}\n");
    RenderOptions o;
    renderRib(stillScene(shaders, "Surface \"b\" \"f\" \"" + file + "\""), o);
    const RenderResult r = renderRib(stillScene(shaders, "Surface \"r\" \"f\" \"" + file + "\""), o);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    // Each pixel's samples see the cloud's blend of the baked x near them: the pixel's centre x
    // within about a micropolygon (the points are a micropolygon apart, the blend their mean).
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            EXPECT_EQ(r.channel(0, x, y, 1), 1.0f);
            EXPECT_NEAR(r.channel(0, x, y, 0), float(x) + 0.5f, 0.75f) << x << "," << y;
        }
}

// Counts a cloud's points at depth z (world z here: the view looks down +z from the origin); a
// render that baked no point writes no file.
size_t pointsAtDepth(const std::string& file, float z) {
    if (!std::ifstream(file)) return 0;
    BakedPointCloud c;
    std::string error;
    EXPECT_TRUE(c.read(file, &error)) << error;
    size_t n = 0;
    for (size_t i = 0; i < c.size(); ++i) n += std::fabs(c.point(i)[2] - z) < 1e-3f;
    return n;
}

// Attribute "cull" "hidden" 0 and "backfacing" 0, as baking passes set them (Aqsis's cornell box):
// a surface wholly hidden behind another, or one-sided and turned away, is shaded all the same,
// so what its shader bakes covers it; the picture does not change.
TEST(BakeRender, CullAttributesOffBakeHiddenAndBackFacingSurfaces) {
    ShaderDir shaders;
    TempDir out("bake3d-cull");
    shaders.add("b", "surface b(string f = \"\") {\n  bake3d(f, \"\", P, normalize(N), \"_area\", area(P));\n  Ci = 1;\n}\n");
    // A 16 x 16 square at depth 3 hides the square behind it (4..9 at depth 5) wholly.
    auto hidden = [&](const std::string& attribute, const std::string& name) {
        const std::string file = out.path() + "/" + name;
        const std::string scene = orthographicView(16, 16, shaders.option()) + "WorldBegin\nSurface \"b\" \"f\" \"" + file +
                                  "\"\nPatch \"bilinear\" \"P\" [0 0 3  16 0 3  0 16 3  16 16 3]\nAttributeBegin\n" +
                                  attribute + "Patch \"bilinear\" \"P\" [4 4 5  9 4 5  4 9 5  9 9 5]\nAttributeEnd\nWorldEnd\n";
        RenderResult r = renderRib(scene, RenderOptions{});
        EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
        return std::make_pair(pointsAtDepth(file, 5), r);
    };
    const auto [culled, culledImage] = hidden("", "culled.ptc");
    const auto [kept, keptImage] = hidden("Attribute \"cull\" \"int hidden\" 0\n", "kept.ptc");
    EXPECT_EQ(culled, 0u) << "the hidden square is culled unshaded by default";
    EXPECT_GE(kept, 36u) << "a grid over the 5 x 5 square: at least 6 x 6 points";
    EXPECT_TRUE(culledImage.frames.at(0).rgba == keptImage.frames.at(0).rgba) << "the picture is the same";

    // Sides 1: one of the two orientations of a square faces away from the eye and is not drawn;
    // with "backfacing" 0 it is shaded (and baked) all the same, still not drawn.
    auto oneSided = [&](const std::string& attribute, bool reversed, const std::string& name) {
        const std::string file = out.path() + "/" + name;
        const std::string scene = orthographicView(16, 16, shaders.option()) + "WorldBegin\nSurface \"b\" \"f\" \"" + file +
                                  "\"\nSides 1\n" + (reversed ? "ReverseOrientation\n" : "") + attribute +
                                  "Patch \"bilinear\" \"P\" [4 4 5  9 4 5  4 9 5  9 9 5]\nWorldEnd\n";
        RenderResult r = renderRib(scene, RenderOptions{});
        EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
        float coverage = 0;  // the frame's summed alpha
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) coverage += r.alpha(0, x, y);
        return std::make_pair(pointsAtDepth(file, 5), coverage);
    };
    const auto [frontPoints, frontAlpha] = oneSided("", false, "f.ptc");
    const auto [backPoints, backAlpha] = oneSided("", true, "b.ptc");
    const bool firstFaces = frontAlpha > 0;
    EXPECT_NE(frontAlpha > 0, backAlpha > 0) << "exactly one orientation faces the eye";
    EXPECT_EQ(firstFaces ? backPoints : frontPoints, 0u) << "the turned-away square is culled unshaded by default";
    EXPECT_GE(firstFaces ? frontPoints : backPoints, 36u);
    const auto [turnedPoints, turnedAlpha] =
        oneSided("Attribute \"cull\" \"int backfacing\" 0\n", firstFaces, "t.ptc");
    EXPECT_EQ(turnedAlpha, 0.0f) << "still not drawn";
    EXPECT_EQ(turnedPoints, firstFaces ? frontPoints : backPoints) << "baked as the square facing the eye is";
}

}  // namespace
}  // namespace streyes::test
