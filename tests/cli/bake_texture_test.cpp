// bake() then MakeTexture: a bake file of a known function of (s, t) made a texture gives the
// function back within the splat's and the texture filter's reach; a broken bake file is an
// error at the MakeTexture line.
#include <gtest/gtest.h>

#include <fstream>

#include "shader_test_util.h"
#include "shade/vm/texture_source.h"
#include "streyes/textures.h"
#include "test_util.h"

namespace streyes::test {
namespace {

TEST(BakeTexture, ABakedFunctionOfSTComesBackFromItsTexture) {
    ShaderDir shaders;
    TempDir out("bake-tex");
    const std::string bake = out.path() + "/f.bake", tex = out.path() + "/f.tx";
    shaders.add("b", "surface b(string f = \"\") {\n  bake(f, s, t, color(s, t, 0.25 + 0.5 * s * t));\n  Ci = 1;\n}\n");
    // A 32 x 32 square, two micropolygons a pixel: records about 1/64 apart in s and t, 65 x 65 of
    // them: a 64 x 64 picture.
    const RenderResult r = renderRib(orthographicView(32, 32, shaders.option()) +
                                     "WorldBegin\nShadingRate 0.25\nSurface \"b\" \"f\" \"" + bake + "\"\n" +
                                     "Patch \"bilinear\" \"P\" [0 0 5  32 0 5  0 32 5  32 32 5]\nWorldEnd\n");
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    Scene scene;
    MakeTextureDesc d;
    d.input = bake;
    d.output = tex;
    d.swrap = d.twrap = "clamp";
    scene.settings.makeTextures.push_back(d);
    makeSceneTextures(scene);

    Log log;
    auto source = openImageTextures({out.path()}, log);
    std::vector<float> s, t;
    for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 9; ++i) s.push_back(0.1f + 0.1f * float(i)), t.push_back(0.1f + 0.1f * float(j));
    const int n = int(s.size());
    std::vector<float> fp(size_t(n), 1.0f / 64), zero(size_t(n), 0.0f);
    sl::TextureQuery q;
    q.n = n;
    q.s = s.data(), q.t = t.data();
    q.dsdu = fp.data(), q.dtdu = zero.data(), q.dsdv = zero.data(), q.dtdv = fp.data();
    std::vector<std::vector<float>> v(3, std::vector<float>(size_t(n), -1.0f));
    float* o[3] = {v[0].data(), v[1].data(), v[2].data()};
    sl::TextureOptions opt;
    opt.channels = 3;
    ASSERT_TRUE(source->texture(tex, opt, q, o));
    // s and t are linear: the mean over a disk of radius 4 texels about a texel is its centre's
    // value, give or take the record spacing (1/64) and the half float (~1e-3). s t is not: its
    // mean over the disk adds (r^2 / 4) d2/dsdt = 0, and the lookup's texel footprint smooths it.
    for (int i = 0; i < n; ++i) {
        EXPECT_NEAR(v[0][size_t(i)], s[size_t(i)], 0.012f) << s[size_t(i)] << "," << t[size_t(i)];
        EXPECT_NEAR(v[1][size_t(i)], t[size_t(i)], 0.012f) << s[size_t(i)] << "," << t[size_t(i)];
        EXPECT_NEAR(v[2][size_t(i)], 0.25f + 0.5f * s[size_t(i)] * t[size_t(i)], 0.012f);
    }
}

TEST(BakeTexture, ABrokenBakeFileIsAnErrorAtTheMakeTextureLine) {
    TempDir dir("bake-bad");
    const std::string bad = dir.path() + "/bad.bake";
    std::ofstream(bad) << "Aqsis bake file\n3\n0.5 0.5 1 2\n";
    Scene scene;
    MakeTextureDesc d;
    d.input = bad;
    d.output = dir.path() + "/bad.tx";
    scene.settings.makeTextures.push_back(d);
    try {
        makeSceneTextures(scene);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("line 3 is not 5 numbers"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace streyes::test
