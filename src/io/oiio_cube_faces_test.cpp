// MakeCubeFaceEnvironment (io/oiio_cube_faces.cpp) read back through environment(): each face's
// colour along its axis, directions inside a face where its perspective projection puts them (up
// and right of each face as RenderMan and Aqsis orient them, fov 90 and more), the map read by a
// shader in a render after the frames that render its faces, and bad faces or fov exit 2 at the
// request's line.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cli/cli_run.h"
#include "image_test_util.h"
#include "shade/vm/texture_source.h"
#include "streyes/textures.h"
#include "test_util.h"

namespace streyes::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

const char* const kFaceNames[6] = {"px.exr", "nx.exr", "py.exr", "ny.exr", "pz.exr", "nz.exr"};

// Each face's view as RenderMan (RI Spec 3.2) and Aqsis orient it: forward, right, up.
struct FaceAxes {
    double forward[3], right[3], up[3];
};
const FaceAxes kAxes[6] = {
    {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},
    {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
};

// Makes `dir`/cube.env from the six faces there.
void makeCube(const std::string& dir, double fov) {
    Scene scene;
    MakeTextureDesc d;
    for (const char* f : kFaceNames) d.cubeFaces.push_back(dir + "/" + f);
    d.input = d.cubeFaces.front();
    d.output = dir + "/cube.env";
    d.latLongEnvironment = true;
    d.swrap = "periodic";
    d.twrap = "clamp";
    d.cubeFov = fov;
    scene.settings.makeTextures.push_back(d);
    makeSceneTextures(scene);
}

// environment("cube.env", R) for each direction (a footprint of 1e-4 radians): RGB per direction.
std::vector<std::array<float, 3>> lookUp(const std::string& dir, const std::vector<std::array<double, 3>>& dirs) {
    Log log;
    auto source = openImageTextures({dir}, log);
    const int n = int(dirs.size());
    std::vector<float> R[3], dR[3];
    for (int c = 0; c < 3; ++c) {
        for (const auto& d : dirs) R[c].push_back(float(d[size_t(c)]));
        dR[c].assign(size_t(n), 1e-4f);
    }
    sl::DirectionQuery q;
    q.n = n;
    for (int c = 0; c < 3; ++c) {
        q.R[c] = R[c].data();
        q.dRdu[c] = q.dRdv[c] = dR[c].data();
    }
    std::vector<float> out[3];
    float* o[3];
    for (int c = 0; c < 3; ++c) {
        out[c].assign(size_t(n), -1.0f);
        o[c] = out[c].data();
    }
    sl::TextureOptions opt;
    opt.channels = 3;
    EXPECT_TRUE(source->environment("cube.env", opt, q, o));
    EXPECT_TRUE(log.warnings().empty());
    std::vector<std::array<float, 3>> rgb;
    for (int i = 0; i < n; ++i) rgb.push_back({out[0][size_t(i)], out[1][size_t(i)], out[2][size_t(i)]});
    return rgb;
}

// Six faces of one colour each; looking along each axis, and 30 degrees off it towards each of
// its face's edges, gives that face's colour. Every texel the lookup's bilinear filter reaches
// there comes from that one face (the nearest seam is 15 degrees away, the lat-long map's texels
// under 3), so the answer is the colour itself, to float rounding.
TEST(CubeFaceEnvironment, ConstantFacesGiveEachFaceItsColourAlongItsAxis) {
    const TempDir dir("cubeenv-constant");
    const int n = 16;
    for (int f = 0; f < 6; ++f) {
        const std::vector<float> px = [&] {
            std::vector<float> v;
            for (int i = 0; i < n * n; ++i) v.insert(v.end(), {float(f + 1), float(10 * (f + 1)), 0.5f + float(f)});
            return v;
        }();
        writeFloatImage(dir.path() + "/" + kFaceNames[f], n, n, 3, px);
    }
    makeCube(dir.path(), 90);
    std::vector<std::array<double, 3>> dirs;
    std::vector<int> faceOf;
    const double off = std::tan(30 * kPi / 180);
    for (int f = 0; f < 6; ++f) {
        const FaceAxes& a = kAxes[f];
        const double offsets[5][2] = {{0, 0}, {off, 0}, {-off, 0}, {0, off}, {0, -off}};
        for (const auto& o : offsets) {
            std::array<double, 3> d;
            for (int c = 0; c < 3; ++c) d[size_t(c)] = a.forward[c] + o[0] * a.right[c] + o[1] * a.up[c];
            dirs.push_back(d);
            faceOf.push_back(f);
        }
    }
    const auto rgb = lookUp(dir.path(), dirs);
    for (size_t i = 0; i < dirs.size(); ++i) {
        const int f = faceOf[i];
        EXPECT_NEAR(rgb[i][0], float(f + 1), 1e-5f * float(f + 1)) << "face " << f << " direction " << i;
        EXPECT_NEAR(rgb[i][1], float(10 * (f + 1)), 1e-5f * float(10 * (f + 1))) << "face " << f << " direction " << i;
        EXPECT_NEAR(rgb[i][2], 0.5f + float(f), 1e-5f * (0.5f + float(f))) << "face " << f << " direction " << i;
    }
}

// Faces whose red grows left to right and green top to bottom ((x + 0.5) / n, (y + 0.5) / n at
// pixel (x, y)), blue the face's number. A direction forward + a tan(fov/2) right + b tan(fov/2)
// up lands at screen (a, b) of its face: red (1 + a) / 2, green (1 - b) / 2. A face flipped or
// turned, or taken at another fov, is off by 0.05 or more at the points below. What the lookup may
// be off by: the faces' bilinear resampling of a linear ramp is exact, and the lat-long map's
// bilinear interpolation (texels h = pi / 2n radians square) of the smooth ramp is off by at most
// h^2 / 8 times the sum of its second derivatives in longitude and latitude (red and green are
// tan(angle off the axis) / (2 tan(fov/2)): about 2.5 at most where the points lie), under 2e-4
// for n = 64; 5e-4 leaves room for float.
constexpr double kTolerance = 5e-4;
void expectProjection(double fov, double reach) {
    const TempDir dir("cubeenv-ramp");
    const int n = 64;
    for (int f = 0; f < 6; ++f) {
        std::vector<float> px;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) px.insert(px.end(), {(float(x) + 0.5f) / n, (float(y) + 0.5f) / n, float(f)});
        writeFloatImage(dir.path() + "/" + kFaceNames[f], n, n, 3, px);
    }
    makeCube(dir.path(), fov);
    const double tanHalf = std::tan(fov * kPi / 360);
    std::vector<std::array<double, 3>> dirs;
    std::vector<std::array<double, 3>> expected;
    const double steps[] = {-1.0, -0.55, -0.2, 0.0, 0.3, 0.65, 1.0};
    for (int f = 0; f < 6; ++f)
        for (double sa : steps)
            for (double sb : steps) {
                const double a = sa * reach, b = sb * reach;
                std::array<double, 3> d;
                for (int c = 0; c < 3; ++c)
                    d[size_t(c)] = kAxes[f].forward[c] + a * tanHalf * kAxes[f].right[c] + b * tanHalf * kAxes[f].up[c];
                dirs.push_back(d);
                expected.push_back({(1 + a) / 2, (1 - b) / 2, double(f)});
            }
    const auto rgb = lookUp(dir.path(), dirs);
    // The poles (+y and -y, the centres of py and ny) lie half a texel row (pi / 2 / 2n radians)
    // beyond the lat-long map's first and last rows' centres, and the lookup clamps there rather
    // than interpolating across the pole: it reads a direction that far off, which moves the ramp
    // by that angle times its slope at the face's centre, 1 / (2 tan(fov/2)) a radian.
    const double poleSlack = kPi / (4.0 * n) / (2 * tanHalf);
    for (size_t i = 0; i < dirs.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(rgb[i][size_t(c)], expected[i][size_t(c)],
                        kTolerance + (expected[i][0] == 0.5 && expected[i][1] == 0.5 && (expected[i][2] == 2 ||
                                                                                       expected[i][2] == 3)
                                          ? poleSlack
                                          : 0.0))
                << "fov " << fov << " face " << expected[i][2] << " screen (" << 2 * expected[i][0] - 1 << ", "
                << 1 - 2 * expected[i][1] << ") channel " << c;
}

// fov 90: the faces meet at their edges; points out to 0.75 of the way to the edge (37 degrees;
// the seam is 45 away).
TEST(CubeFaceEnvironment, DirectionsLandWhereEachFacesProjectionSaysAtFov90) { expectProjection(90, 0.75); }

// fov 120: the faces overlap; a direction is read from the face of its largest component, whose
// picture spans tan(60 degrees) on either side: points out to 0.5 of the way to its edge (41
// degrees off its axis, inside the 45 degrees where its face is the one read).
TEST(CubeFaceEnvironment, DirectionsLandWhereEachFacesProjectionSaysAtFov120) { expectProjection(120, 0.5); }

// fov 93 (Aqsis's fisheye scene): points out to 0.7 of the way to the edge.
TEST(CubeFaceEnvironment, DirectionsLandWhereEachFacesProjectionSaysAtFov93) { expectProjection(93, 0.7); }

// A render reads the map: six frames render the faces (a square of one colour filling each 8-bit
// TIFF), MakeCubeFaceEnvironment follows them, and the last frame's squares look along +x and -y
// through a shader's environment(): the faces' colours (8-bit values 0, 51 and 255: exact).
TEST(CubeFaceEnvironment, AShaderReadsTheMapMadeFromFramesBeforeIt) {
    const TempDir dir("cubeenv-render");
    const std::string d = dir.path();
    writeFile(d, "envlook.sl",
              "surface envlook(vector dir = (0, 0, 1)) { Ci = color environment(\"cube.env\", dir); Oi = 1; }\n");
    const char* colours[6] = {"1 0 0", "0 1 0", "0 0 1", "1 1 0", "0 1 1", "1 0 1"};
    const char* names[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    std::string rib;
    for (int f = 0; f < 6; ++f)
        rib += "FrameBegin " + std::to_string(f + 1) + "\nDisplay \"" + d + "/" + names[f] +
               ".tif\" \"file\" \"rgba\"\n" + orthoHeader(4, 4) + "Color [" + colours[f] + "]\n" +
               square(0, 4, 0, 4, 5) + "WorldEnd\nFrameEnd\n";
    rib += "MakeCubeFaceEnvironment \"px.tif\" \"nx.tif\" \"py.tif\" \"ny.tif\" \"pz.tif\" \"nz.tif\" \"cube.env\" 90 "
           "\"box\" 1 1\n";
    rib += "FrameBegin 7\nDisplay \"" + d + "/out.exr\" \"file\" \"rgba\"\n" + orthoHeader(8, 8) +
           "Surface \"envlook\" \"vector dir\" [1 0 0]\n" + square(0, 4, 0, 8, 5) +
           "Surface \"envlook\" \"vector dir\" [0 -1 0]\n" + square(4, 8, 0, 8, 5) + "WorldEnd\nFrameEnd\n";
    const std::string path = writeFile(d, "scene.rib", rib);
    const CliRun run = runStreyes("render " + path);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_EQ(run.output.find("warning"), std::string::npos) << run.output;
    auto in = OIIO::ImageInput::open(d + "/out.exr");
    ASSERT_TRUE(in) << OIIO::geterror();
    const int nc = in->spec().nchannels;
    std::vector<float> px(size_t(8 * 8 * nc));
    ASSERT_TRUE(in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, px.data()));
    const float left[3] = {1, 0, 0}, right[3] = {1, 1, 0};  // +x (px), -y (ny)
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(px[size_t((y * 8 + x) * nc + c)], x < 4 ? left[c] : right[c], 1e-4f)
                    << "pixel (" << x << ", " << y << ") channel " << c;
}

// The faces of the bad-input tests: six 4 x 4 float pictures in `dir`, `odd` (if any) 8 x 8.
void writeFaces(const std::string& dir, const std::string& odd = "") {
    for (const char* f : kFaceNames) {
        const int n = odd == f ? 8 : 4;
        writeFloatImage(dir + "/" + f, n, n, 3, std::vector<float>(size_t(n * n * 3), 0.5f));
    }
}

CliRun renderCube(const std::string& dir, const std::string& request) {
    const std::string rib = writeFile(dir, "scene.rib", request + "\n" + orthoHeader(4, 4) + "WorldEnd\n");
    return runStreyes("render " + rib + " -o " + dir + "/out.####.exr");
}

const std::string kRequest = "MakeCubeFaceEnvironment \"px.exr\" \"nx.exr\" \"py.exr\" \"ny.exr\" \"pz.exr\" \"nz.exr\" "
                             "\"cube.env\" ";

TEST(CubeFaceEnvironment, AMissingFaceExitsTwoNamingItAtTheRequestsLine) {
    const TempDir dir("cubeenv-missing");
    writeFaces(dir.path());
    std::filesystem::remove(dir.path() + "/ny.exr");
    const CliRun run = renderCube(dir.path(), kRequest + "90 \"box\" 1 1");
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(run.output.find("scene.rib:1:"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("ny.exr"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir.path() + "/cube.env"));
    EXPECT_FALSE(std::filesystem::exists(dir.path() + "/out.0000.exr"));
}

TEST(CubeFaceEnvironment, FacesOfDifferentSizesExitTwoNamingThemAtTheRequestsLine) {
    const TempDir dir("cubeenv-sizes");
    writeFaces(dir.path(), "pz.exr");
    const CliRun run = renderCube(dir.path(), kRequest + "90 \"box\" 1 1");
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(run.output.find("scene.rib:1:"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("px.exr' is 4 x 4, '" + dir.path() + "/pz.exr' 8 x 8"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir.path() + "/cube.env"));
}

TEST(CubeFaceEnvironment, AFaceThatIsNoPictureExitsTwoNamingIt) {
    const TempDir dir("cubeenv-garbage");
    writeFaces(dir.path());
    writeFile(dir.path(), "nx.exr", "not a picture");
    const CliRun run = renderCube(dir.path(), kRequest + "90 \"box\" 1 1");
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_NE(run.output.find("scene.rib:1:"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("nx.exr"), std::string::npos) << run.output;
}

// A field of view outside (0, 180) (or not a number) is an error at its line; under 90 the faces
// leave gaps: a warning, and the map is made.
TEST(CubeFaceEnvironment, ABadFovExitsTwoAtItsLineANarrowOneWarns) {
    const TempDir dir("cubeenv-fov");
    writeFaces(dir.path());
    for (const char* fov : {"0", "-30", "180", "200", "\"wide\""}) {
        const CliRun run = renderCube(dir.path(), "\n" + kRequest + fov + " \"box\" 1 1");
        EXPECT_EQ(run.exitCode, 2) << fov << ": " << run.output;
        EXPECT_NE(run.output.find("scene.rib:2:"), std::string::npos) << fov << ": " << run.output;
        EXPECT_FALSE(std::filesystem::exists(dir.path() + "/cube.env")) << fov;
    }
    const CliRun run = renderCube(dir.path(), kRequest + "60 \"box\" 1 1");
    EXPECT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("scene.rib:1: warning: MakeCubeFaceEnvironment: faces of field of view 60"),
              std::string::npos)
        << run.output;
    EXPECT_TRUE(std::filesystem::exists(dir.path() + "/cube.env"));
}

}  // namespace
}  // namespace streyes::test
