// Textures through OpenImageIO (streyes/textures.h): texture() at texel centres gives the texel,
// over a known footprint the texels' mean; environment() reads a lat-long map by direction;
// MakeTexture makes tiled MIP-mapped maps; a missing map warns once and gives the fill value.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cli_run.h"
#include "image_test_util.h"
#include "streyes/textures.h"
#include "shade/vm/texture_source.h"
#include "test_util.h"

namespace streyes::test {
namespace {

void makeMap(const std::string& in, const std::string& out, bool latLong = false) {
    Scene scene;
    MakeTextureDesc d;
    d.input = in;
    d.output = out;
    d.latLongEnvironment = latLong;
    scene.settings.makeTextures.push_back(d);
    makeSceneTextures(scene);
}

// n lookups at (s[i], t[i]) with the same footprint (ds along u, dt along v); channel 0 .. 2.
std::vector<std::vector<float>> lookUp(sl::TextureSource& source, const std::string& name,
                                       const std::vector<float>& s, const std::vector<float>& t, float ds, float dt,
                                       const sl::TextureOptions& options = {}) {
    const int n = int(s.size());
    std::vector<float> dsdu(size_t(n), ds), dtdv(size_t(n), dt), zero(size_t(n), 0.0f);
    sl::TextureQuery q;
    q.n = n;
    q.s = s.data();
    q.t = t.data();
    q.dsdu = dsdu.data();
    q.dtdu = zero.data();
    q.dsdv = zero.data();
    q.dtdv = dtdv.data();
    std::vector<std::vector<float>> out(3, std::vector<float>(size_t(n), -1.0f));
    float* o[3] = {out[0].data(), out[1].data(), out[2].data()};
    sl::TextureOptions opt = options;
    opt.channels = 3;
    EXPECT_TRUE(source.texture(name, opt, q, o));
    return out;
}

// Texel (x, y) of an 8 x 4 RGB image: (x, y, x + 10 y).
float texel(int x, int y, int c) { return c == 0 ? float(x) : c == 1 ? float(y) : float(x + 10 * y); }

TEST(Textures, TexelCentresGiveTheTexel) {
    const TempDir dir("tex-centres");
    const int w = 8, h = 4;
    std::vector<float> px;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) px.push_back(texel(x, y, c));
    writeFloatImage(dir.path() + "/img.exr", w, h, 3, px);
    makeMap(dir.path() + "/img.exr", dir.path() + "/img.tx");
    Log log;
    auto source = openImageTextures({dir.path()}, log);
    // The made map and the plain image (MIP levels made in memory), found along the search path.
    for (const char* name : {"img.tx", "img.exr"}) {
        std::vector<float> s, t;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                s.push_back((float(x) + 0.5f) / float(w));  // s left to right, t top to bottom
                t.push_back((float(y) + 0.5f) / float(h));
            }
        // A footprint of a tenth of a texel: the finest level, bilinear at the centre.
        const auto out = lookUp(*source, name, s, t, 0.1f / w, 0.1f / h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(out[size_t(c)][size_t(y * w + x)], texel(x, y, c), 1e-4f)
                        << name << " texel " << x << "," << y << " channel " << c;
    }
    // "filter" "closest": anywhere inside a texel, the texel.
    std::vector<float> s, t;
    for (int x = 0; x < w; ++x) {
        s.push_back((float(x) + 0.8f) / float(w));
        t.push_back(0.3f / float(h));
    }
    sl::TextureOptions closest;
    closest.filter = "closest";
    const auto out = lookUp(*source, "img.tx", s, t, 0.1f / w, 0.1f / h, closest);
    for (int x = 0; x < w; ++x) EXPECT_NEAR(out[0][size_t(x)], texel(x, 0, 0), 1e-6f) << "closest, texel " << x;
    EXPECT_TRUE(log.warnings().empty());
}

TEST(Textures, AFootprintGivesTheMeanOfTheTexelsItCovers) {
    const TempDir dir("tex-footprint");
    const int w = 4, h = 4;
    std::vector<float> px;  // channel 0: distinct values 0, 1, 4, 9, ...; channels 1, 2: 0
    for (int i = 0; i < w * h; ++i) px.insert(px.end(), {float(i * i % 17), 0.0f, 0.0f});
    writeFloatImage(dir.path() + "/img.exr", w, h, 3, px);
    makeMap(dir.path() + "/img.exr", dir.path() + "/img.tx");
    Log log;
    auto source = openImageTextures({dir.path()}, log);
    auto at = [&](int x, int y) { return px[size_t(y * w + x) * 3]; };
    // A 2 x 2 texel footprint on the centre of a texel of the next level: the mean of the four
    // texels it covers (the finest level interpolates to it there, and the next level holds it).
    {
        const auto out = lookUp(*source, dir.path() + "/img.tx", {0.75f, 0.25f}, {0.25f, 0.75f}, 2.0f / w, 2.0f / h);
        EXPECT_NEAR(out[0][0], (at(2, 0) + at(3, 0) + at(2, 1) + at(3, 1)) / 4, 1e-4f);
        EXPECT_NEAR(out[0][1], (at(0, 2) + at(1, 2) + at(0, 3) + at(1, 3)) / 4, 1e-4f);
    }
    // The whole image: the last level, the mean of all.
    double mean = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) mean += at(x, y) / double(w * h);
    {
        const auto out = lookUp(*source, dir.path() + "/img.tx", {0.5f}, {0.5f}, 1.0f, 1.0f);
        EXPECT_NEAR(out[0][0], mean, 1e-4);
    }
    // "blur" widens a point's footprint the same way.
    {
        sl::TextureOptions o;
        o.sblur = o.tblur = 1;
        const auto out = lookUp(*source, dir.path() + "/img.tx", {0.5f}, {0.5f}, 0.0f, 0.0f, o);
        EXPECT_NEAR(out[0][0], mean, 1e-4);
    }
}

// A lat-long map 16 x 8 in 4 x 4 blocks: block (bx, by) is bx + 10 by. +y is up, the image's top
// row looks up, its centre column along +z, s growing towards -x (OIIO's lat-long layout).
TEST(Textures, EnvironmentReadsALatLongMapByDirection) {
    const TempDir dir("tex-env");
    const int w = 16, h = 8;
    std::vector<float> px;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) px.insert(px.end(), {float(x / 4 + 10 * (y / 4)), 0.0f, 0.0f});
    writeFloatImage(dir.path() + "/sky.exr", w, h, 3, px);
    makeMap(dir.path() + "/sky.exr", dir.path() + "/sky.env", true);
    Log log;
    auto source = openImageTextures({dir.path()}, log);
    std::vector<float> R[3], dR[3];
    std::vector<float> expected;
    const float pi = 3.14159265f;
    for (int by = 0; by < 2; ++by)
        for (int bx = 0; bx < 4; ++bx) {
            const float s = (float(bx) + 0.5f) / 4, t = (float(by) + 0.5f) / 2;
            const float phi = 2 * pi * (s - 0.5f), theta = pi * (0.5f - t);
            R[0].push_back(-std::sin(phi) * std::cos(theta));
            R[1].push_back(std::sin(theta));
            R[2].push_back(std::cos(phi) * std::cos(theta));
            expected.push_back(float(bx + 10 * by));
        }
    const int n = int(expected.size());
    sl::DirectionQuery q;
    q.n = n;
    for (int c = 0; c < 3; ++c) {
        dR[c].assign(size_t(n), 0.001f);
        q.R[c] = R[c].data();
        q.dRdu[c] = q.dRdv[c] = dR[c].data();
    }
    std::vector<float> out(size_t(n), -1.0f);
    float* o[1] = {out.data()};
    sl::TextureOptions opt;
    ASSERT_TRUE(source->environment("sky.env", opt, q, o));
    for (int i = 0; i < n; ++i) EXPECT_NEAR(out[size_t(i)], expected[size_t(i)], 1e-4f) << "direction " << i;
}

// A shader's texture() in a render: the image's top-left quadrant where t = 0 and s = 0.
TEST(Textures, ARenderShowsTheMapWithTZeroAtTheTop) {
    const TempDir dir("tex-render");
    const int w = 8, h = 8;
    const float colours[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};  // TL, TR, BL, BR
    std::vector<float> px;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) px.push_back(colours[(y < h / 2 ? 0 : 2) + (x < w / 2 ? 0 : 1)][c]);
    writeFloatImage(dir.path() + "/quads.exr", w, h, 3, px);
    makeMap(dir.path() + "/quads.exr", dir.path() + "/quads.tx");
    writeFile(dir.path(), "tex.sl", "surface tex(string map = \"\") { Ci = color texture(map, s, t); }\n");
    // v = 0 (t = 0) along the frame's top edge (screen y = 8: raster row 0).
    const std::string rib = writeFile(dir.path(), "scene.rib",
                                      orthoHeader(8, 8) + "ShadingRate 0.25\nSurface \"tex\" \"map\" \"quads.tx\"\n" +
                                          square(0, 8, 8, 0, 5) + "WorldEnd\n");
    RenderOptions options;
    options.textureSource = openImageTextures;
    const RenderResult r = renderFile(rib, options);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    // Pixels one texel from any quadrant edge see only their quadrant's texels.
    for (int y : {1, 2, 5, 6})
        for (int x : {1, 2, 5, 6})
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(r.channel(0, x, y, c), colours[(y < 4 ? 0 : 2) + (x < 4 ? 0 : 1)][c], 1e-3f)
                    << "pixel " << x << "," << y << " channel " << c;
}

// indirectdiffuse()'s "environmentmap" read through OpenImageIO: under a lat-long map of one
// colour every ray that hits nothing brings that colour, and a white floor shows it.
TEST(Textures, IndirectDiffuseUnderAConstantEnvironmentMapIsItsColour) {
    const TempDir dir("tex-envlight");
    const float c[3] = {0.2f, 0.5f, 0.9f};
    std::vector<float> px;
    for (int i = 0; i < 16 * 8; ++i) px.insert(px.end(), {c[0], c[1], c[2]});
    writeFloatImage(dir.path() + "/sky.exr", 16, 8, 3, px);
    makeMap(dir.path() + "/sky.exr", dir.path() + "/sky.env", true);
    writeFile(dir.path(), "gi.sl",
              "surface gi() { Ci = indirectdiffuse(P, normal(0, 0, 1), 64, \"environmentmap\", \"sky.env\"); }\n");
    const std::string rib =
        writeFile(dir.path(), "scene.rib", orthoHeader(8, 8) + "Surface \"gi\"\n" + square(0, 8, 8, 0, 5) + "WorldEnd\n");
    RenderOptions options;
    options.textureSource = openImageTextures;
    const RenderResult r = renderFile(rib, options);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.channel(0, x, y, k), c[k], 1e-3f) << x << "," << y;
}

// The shipped paintedplastic multiplies its colour by the map (ambient light only: Ci = the map).
TEST(Textures, ThePaintedPlasticShaderPaintsWithTheMap) {
    const TempDir dir("tex-painted");
    std::vector<float> px;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) px.insert(px.end(), {x < 4 ? 0.2f : 0.9f, 0.5f, y < 4 ? 0.1f : 0.7f});
    writeFloatImage(dir.path() + "/paint.exr", 8, 8, 3, px);
    const std::string rib = writeFile(dir.path(), "scene.rib",
                                      orthoHeader(8, 8) + "LightSource \"ambientlight\" 1 \"intensity\" 1\n" +
                                          "Surface \"paintedplastic\" \"texturename\" \"paint.exr\" \"Ka\" 1 \"Kd\" 0 "
                                          "\"Ks\" 0\n" + square(0, 8, 8, 0, 5) + "WorldEnd\n");
    RenderOptions options;
    options.textureSource = openImageTextures;
    const RenderResult r = renderFile(rib, options);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    for (int y : {1, 6})
        for (int x : {1, 6}) {
            EXPECT_NEAR(r.channel(0, x, y, 0), x < 4 ? 0.2f : 0.9f, 1e-3f) << x << "," << y;
            EXPECT_NEAR(r.channel(0, x, y, 1), 0.5f, 1e-3f) << x << "," << y;
            EXPECT_NEAR(r.channel(0, x, y, 2), y < 4 ? 0.1f : 0.7f, 1e-3f) << x << "," << y;
        }
}

TEST(Textures, TheSearchPathIsTakenInOrder) {
    const TempDir a("tex-path-a"), b("tex-path-b");
    writeFloatImage(a.path() + "/m.exr", 2, 2, 3, std::vector<float>(12, 0.25f));
    writeFloatImage(b.path() + "/m.exr", 2, 2, 3, std::vector<float>(12, 0.75f));
    Log log;
    EXPECT_NEAR(lookUp(*openImageTextures({a.path(), b.path()}, log), "m.exr", {0.5f}, {0.5f}, 0.1f, 0.1f)[0][0], 0.25f,
                1e-6f);
    EXPECT_NEAR(lookUp(*openImageTextures({b.path(), a.path()}, log), "m.exr", {0.5f}, {0.5f}, 0.1f, 0.1f)[0][0], 0.75f,
                1e-6f);
}

// One TextureSystem serves every bucket thread: many small buckets on four threads give the
// pixels one thread gives.
TEST(Textures, ThreadsShareTheRendersTextures) {
    const TempDir dir("tex-threads");
    const int w = 64, h = 64;
    std::vector<float> px;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) px.insert(px.end(), {float(x) / w, float(y) / h, float((x * 7 + y * 3) % 11) / 11});
    writeFloatImage(dir.path() + "/ramp.exr", w, h, 3, px);
    writeFile(dir.path(), "tex.sl", "surface tex() { Ci = color texture(\"ramp.exr\", s, t); }\n");
    const std::string rib = writeFile(dir.path(), "scene.rib",
                                      orthoHeader(64, 64) + "Surface \"tex\"\n" + square(0, 64, 64, 0, 5) + "WorldEnd\n");
    RenderOptions one;
    one.textureSource = openImageTextures;
    one.threads = 1;
    one.bucketSize = 8;
    RenderOptions four = one;
    four.threads = 4;
    const RenderResult r1 = renderFile(rib, one), r4 = renderFile(rib, four);
    EXPECT_TRUE(r1.warnings.empty() && r4.warnings.empty());
    EXPECT_TRUE(identicalPixels(r1, r4));
    EXPECT_NEAR(r1.channel(0, 40, 20, 0), 40.5f / 64, 0.02f);  // the ramp is there
    EXPECT_NEAR(r1.channel(0, 40, 20, 1), 20.5f / 64, 0.02f);
}

TEST(Textures, AMissingMapWarnsOnceNamingItAndTheShaderAndGivesTheFill) {
    const TempDir dir("tex-missing");
    writeFile(dir.path(), "tex.sl", "surface tex() { Ci = color texture(\"nothere.tx\", s, t, \"fill\", 0.25); }\n");
    const std::string rib = writeFile(dir.path(), "scene.rib",
                                      orthoHeader(8, 8) + "Surface \"tex\"\n" + square(0, 8, 8, 0, 5) + "WorldEnd\n");
    RenderOptions options;
    options.textureSource = openImageTextures;
    const RenderResult r = renderFile(rib, options);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("nothere.tx"), std::string::npos) << r.warnings[0];
    EXPECT_NE(r.warnings[0].find("shader \"tex\""), std::string::npos) << r.warnings[0];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.channel(0, 3, 3, c), 0.25f, 1e-6f);
}

TEST(Textures, MakeTextureMakesATiledMipMappedMapBeforeTheRender) {
    const TempDir dir("tex-make");
    std::vector<float> px(16 * 16 * 3, 0.5f);
    writeFloatImage(dir.path() + "/in.exr", 16, 16, 3, px);
    writeFile(dir.path(), "tex.sl", "surface tex() { Ci = color texture(\"made.tx\", s, t); }\n");
    const std::string rib = writeFile(dir.path(), "scene.rib",
                                      "MakeTexture \"in.exr\" \"made.tx\" \"periodic\" \"clamp\" \"box\" 1 1\n" +
                                          orthoHeader(8, 8) + "Surface \"tex\"\n" + square(0, 8, 8, 0, 5) + "WorldEnd\n");
    const CliRun run = runStreyes("render " + rib + " -o " + dir.path() + "/out.####.exr");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    auto in = OIIO::ImageInput::open(dir.path() + "/made.tx");
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().tile_width, 64);
    EXPECT_EQ(in->spec().get_string_attribute("wrapmodes"), "periodic,clamp");
    int levels = 0;
    while (in->seek_subimage(0, levels)) ++levels;
    EXPECT_EQ(levels, 5);  // 16, 8, 4, 2, 1
    auto frame = OIIO::ImageInput::open(dir.path() + "/out.0000.exr");
    ASSERT_TRUE(frame);
    std::vector<float> rgba(8 * 8 * size_t(frame->spec().nchannels));
    ASSERT_TRUE(frame->read_image(0, 0, 0, frame->spec().nchannels, OIIO::TypeDesc::FLOAT, rgba.data()));
    EXPECT_NEAR(rgba[size_t(3 * 8 + 3) * size_t(frame->spec().nchannels)], 0.5f, 1e-3f);
}

// RenderMan files name maps ".tex" (fisheye's and sticky's scenes): whatever the extension the map
// is a tiled, MIP-mapped TIFF (OpenImageIO has no writer for ".tex" by that name), read back by
// texture() with the picture's value.
TEST(Textures, MakeTextureWritesTiledTiffWhateverTheExtension) {
    const TempDir dir("tex-ext");
    std::vector<float> px(16 * 16 * 3, 0.25f);
    writeFloatImage(dir.path() + "/in.exr", 16, 16, 3, px);
    writeFile(dir.path(), "tex.sl", "surface tex() { Ci = color texture(\"made.tex\", s, t); }\n");
    const std::string rib = writeFile(dir.path(), "scene.rib",
                                      "MakeTexture \"in.exr\" \"made.tex\" \"periodic\" \"periodic\" \"box\" 1 1\n" +
                                          orthoHeader(8, 8) + "Surface \"tex\"\n" + square(0, 8, 8, 0, 5) + "WorldEnd\n");
    const CliRun run = runStreyes("render " + rib + " -o " + dir.path() + "/out.####.exr");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    auto in = OIIO::ImageInput::open(dir.path() + "/made.tex");
    ASSERT_TRUE(in);
    EXPECT_STREQ(in->format_name(), "tiff");
    EXPECT_EQ(in->spec().tile_width, 64);
    int levels = 0;
    while (in->seek_subimage(0, levels)) ++levels;
    EXPECT_EQ(levels, 5);
    auto frame = OIIO::ImageInput::open(dir.path() + "/out.0000.exr");
    ASSERT_TRUE(frame);
    std::vector<float> rgba(8 * 8 * size_t(frame->spec().nchannels));
    ASSERT_TRUE(frame->read_image(0, 0, 0, frame->spec().nchannels, OIIO::TypeDesc::FLOAT, rgba.data()));
    EXPECT_NEAR(rgba[size_t(3 * 8 + 3) * size_t(frame->spec().nchannels)], 0.25f, 1e-3f);
}

TEST(Textures, MakeTextureOfAMissingPictureExitsTwoAtItsLine) {
    const TempDir dir("tex-make-bad");
    const std::string rib = writeFile(dir.path(), "scene.rib",
                                      "MakeTexture \"nothere.exr\" \"made.tx\" \"periodic\" \"periodic\" \"box\" 1 1\n" +
                                          orthoHeader(8, 8) + "WorldEnd\n");
    const CliRun run = runStreyes("render " + rib + " -o " + dir.path() + "/out.####.exr");
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(run.output.find("scene.rib:1:"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("nothere.exr"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir.path() + "/out.0000.exr"));
}

}  // namespace
}  // namespace streyes::test

namespace streyes::test {
namespace {

// textureinfo() through OpenImageIO: a map's resolution, type and channels; 0 for a map that
// cannot be read (the variable left as it was).
TEST(Textures, TextureInfoReadsTheMap) {
    const TempDir dir("tex-info");
    writeFloatImage(dir.path() + "/wide.exr", 16, 4, 3, std::vector<float>(16 * 4 * 3, 0.5f));
    makeMap(dir.path() + "/wide.exr", dir.path() + "/wide.tx");
    Log log;
    log.setQuiet(true);
    std::shared_ptr<sl::TextureSource> source = openImageTextures({dir.path()}, log);
    ASSERT_TRUE(source);
    sl::QueryValue v;
    ASSERT_TRUE(source->textureInfo("wide.tx", "resolution", v));
    EXPECT_EQ(v.floats, (std::vector<float>{16, 4}));
    ASSERT_TRUE(source->textureInfo("wide.tx", "channels", v));
    EXPECT_EQ(v.floats, (std::vector<float>{3}));
    ASSERT_TRUE(source->textureInfo("wide.tx", "type", v));
    EXPECT_EQ(v.strings, (std::vector<std::string>{"texture"}));
    EXPECT_FALSE(source->textureInfo("wide.tx", "viewingmatrix", v));  // not a rendered map
    EXPECT_FALSE(source->textureInfo("nosuch.tx", "resolution", v));

    // In a render: the resolution reaches the shader.
    writeFile(dir.path(), "info.sl",
              "surface info(string map = \"\") {\n  float res[2] = {0, 0};\n"
              "  float ok = textureinfo(map, \"resolution\", res);\n  Ci = color(ok, res[0] / 100, res[1] / 100);\n}\n");
    const std::string rib = writeFile(dir.path(), "scene.rib",
                                      orthoHeader(8, 8) + "Surface \"info\" \"map\" \"wide.tx\"\n" + square(0, 8, 8, 0, 5) +
                                          "WorldEnd\n");
    RenderOptions options;
    options.textureSource = openImageTextures;
    const RenderResult r = renderFile(rib, options);
    EXPECT_NEAR(r.channel(0, 4, 4, 0), 1.0f, 1e-6f);
    EXPECT_NEAR(r.channel(0, 4, 4, 1), 0.16f, 1e-6f);
    EXPECT_NEAR(r.channel(0, 4, 4, 2), 0.04f, 1e-6f);
}

}  // namespace
}  // namespace streyes::test
