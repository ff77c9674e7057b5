// A program's RI session (RiBegin/RiEnd, src/io/ri_session.cpp): the scene written as RIB, or
// rendered to its display, with procedurals of the program's own functions and of a plug-in.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "ri.h"
#include "scene/rib_gzip.h"
#include "scene/rib_writer.h"
#include "streyes/rib.h"
#include "streyes/image_io.h"
#include "streyes/scene_access.h"
#include "test_util.h"

namespace streyes {
namespace {

// A 32 x 32 orthographic view, one unit a pixel, box filter: coverage is area.
void view(const std::string& display) {
    RiFormat(32, 32, 1);
    RiProjection(RI_ORTHOGRAPHIC, RI_NULL);
    RiScreenWindow(0, 32, 0, 32);
    RiPixelFilter(RiBoxFilter, 1, 1);
    RiPixelSamples(2, 2);
    if (!display.empty()) RiDisplay(display.c_str(), RI_FILE, RI_RGBA, RI_NULL);
}

// A square [x, x+s]^2 at depth 5, made when its procedural is expanded.
struct Square {
    float x, y, s;
    int* subdivided;
    int* freed;
    float detail = -1;  // what Subdivide was given
};
void subdivideSquare(RtPointer data, RtFloat detail) {
    Square* q = static_cast<Square*>(data);
    ++*q->subdivided;
    q->detail = detail;
    RtFloat P[12] = {q->x, q->y, 5, q->x + q->s, q->y, 5, q->x, q->y + q->s, 5, q->x + q->s, q->y + q->s, 5};
    RiPatch(RI_BILINEAR, RI_P, P, RI_NULL);
}
void freeSquare(RtPointer data) {
    Square* q = static_cast<Square*>(data);
    ++*q->freed;
    // The detail is the bound's raster area (s^2 pixels here) rounded up to a power of two.
    EXPECT_GE(q->detail, q->s * q->s);
    EXPECT_LT(q->detail, 2 * q->s * q->s);
    EXPECT_EQ(std::exp2(std::round(std::log2(q->detail))), q->detail);
    delete q;
}

double alphaSum(const ImageData& image) {
    double sum = 0;
    const int a = image.channelIndex("A");
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) sum += image.at(x, y, a);
    return sum;
}

TEST(RiSession, RiBeginWithAFileNameWritesTheRib) {
    test::TempDir dir("ri-session");
    const std::string rib = dir.path() + "/scene.rib";
    RiBegin(rib.c_str());
    view("");
    RiWorldBegin();
    RtFloat P[12] = {0, 0, 5, 8, 0, 5, 0, 8, 5, 8, 8, 5};
    RiPatch(RI_BILINEAR, RI_P, P, RI_NULL);
    RiWorldEnd();
    RiEnd();
    std::ifstream in(rib);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(),
              "Format 32 32 1\nProjection \"orthographic\"\nScreenWindow 0 32 0 32\nPixelFilter \"box\" 1 1\n"
              "PixelSamples 2 2\nWorldBegin\nPatch \"bilinear\" \"P\" [ 0 0 5 8 0 5 0 8 5 8 8 5 ]\nWorldEnd\n");
    // And it renders as such: 64 covered pixels.
    const test::RenderResult r = test::renderFile(rib);
    double sum = 0;
    for (size_t i = 3; i < r.frame(0).rgba.size(); i += 4) sum += r.frame(0).rgba[i];
    EXPECT_NEAR(sum, 64.0, 1e-4);
}

// Option "rib" as PRMan has it: "format" before RiBegin, "compression" inside; the file is gzip of
// binary RIB with the calls' floats as 32-bit floats, and reads as the ASCII session's scene.
TEST(RiSession, OptionRibWritesBinaryAndGzip) {
    test::TempDir dir("ri-session");
    auto session = [&](const std::string& rib, bool stored) {
        RtString binary = "binary", gzip = "gzip";
        if (stored) RiOption("rib", "format", &binary, RI_NULL);
        RiBegin(rib.c_str());
        if (stored) RiOption("rib", "string compression", &gzip, RI_NULL);
        view("");
        RiWorldBegin();
        RtFloat P[12] = {0.1f, 0.2f, 5, 8.3f, 0, 5, 0, 8, 5, 8, 8.7f, 5};
        RiPatch(RI_BILINEAR, RI_P, P, RI_NULL);
        RiSphere(3.3f, -3.3f, 3.3f, 360, RI_NULL);
        RiWorldEnd();
        RiEnd();
        RtString ascii = "ascii", none = "none";
        RiOption("rib", "format", &ascii, "compression", &none, RI_NULL);  // for the tests after
    };
    const std::string text = dir.path() + "/text.rib", stored = dir.path() + "/stored.rib";
    session(text, false);
    session(stored, true);
    std::ifstream in(stored, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    ASSERT_GT(bytes.str().size(), 2u);
    EXPECT_EQ(bytes.str().substr(0, 2), "\x1f\x8b");
    const std::string inflated = gunzip(bytes.str(), stored);
    EXPECT_EQ(inflated.substr(0, 2), std::string("\314\000", 2));  // request code 0 defined
    EXPECT_EQ(inflated.find("Option"), std::string::npos);  // Option "rib" is not in the scene
    // The ASCII file with its floats as 32-bit floats: the same scene, the same pixels.
    std::ifstream t(text);
    std::stringstream ascii;
    ascii << t.rdbuf();
    Log log;
    const Scene expected = parseRibString(encodeRib(ascii.str(), text, {false, true, false}), text, log);
    const test::RenderResult a = test::renderScene(expected), b = test::renderFile(stored);
    EXPECT_TRUE(test::identicalPixels(a, b));
    EXPECT_GT(test::alphaSum(b), 64.0);
}

TEST(RiSession, RiBeginNullRendersToTheDisplayWithTheProgramsOwnProcedurals) {
    test::TempDir dir("ri-session");
    const std::string out = dir.path() + "/frame.exr";
    int subdivided = 0, freed = 0;
    RiBegin(RI_NULL);
    view(out);
    RiWorldBegin();
    RiSurface("constant", RI_NULL);
    // Two squares of the program's own subdivide function: 4 x 4 and 8 x 8 pixels.
    RtBound a = {2, 6, 2, 6, 5, 5}, b = {16, 24, 16, 24, 5, 5};
    RiProcedural(new Square{2, 2, 4, &subdivided, &freed}, a, subdivideSquare, freeSquare);
    RiProcedural(new Square{16, 16, 8, &subdivided, &freed}, b, subdivideSquare, freeSquare);
    // And a level-1 Menger sponge of edge 9 through the plug-in: 72 pixels.
    RtString menger[2] = {STREYES_PLUGIN_DIR "/menger.so", "level=1 x=20 y=2 z=1 size=9"};
    RtBound c = {20, 29, 2, 11, 1, 10};
    RiProcedural(menger, c, RiProcDynamicLoad, nullptr);
    RiWorldEnd();
    RiEnd();
    EXPECT_EQ(subdivided, 2);
    EXPECT_EQ(freed, 2);  // after the render
    ASSERT_TRUE(std::filesystem::exists(out));
    EXPECT_NEAR(alphaSum(readImage(out)), 16.0 + 64.0 + 72.0, 1e-3);
}

// What --safe refuses (streyes/scene_access.h: no programs, no plug-ins) is what a scene names;
// a program's own functions are the program's code, and stay.
TEST(RiSession, WithoutProgramsAndPlugInsTheProgramsOwnProceduralsStay) {
    test::TempDir dir("ri-session");
    const SceneAccess before = sceneAccess();
    SceneAccess safe;
    safe.programs = false;
    safe.safe = true;
    setSceneAccess(safe);
    const std::string out = dir.path() + "/frame.exr";
    int subdivided = 0, freed = 0;
    RiBegin(RI_NULL);
    view(out);
    RiWorldBegin();
    RiSurface("constant", RI_NULL);
    RtBound a = {2, 6, 2, 6, 5, 5};
    RiProcedural(new Square{2, 2, 4, &subdivided, &freed}, a, subdivideSquare, freeSquare);
    RiWorldEnd();
    RiEnd();
    EXPECT_EQ(subdivided, 1);
    ASSERT_TRUE(std::filesystem::exists(out));
    EXPECT_NEAR(alphaSum(readImage(out)), 16.0, 1e-3);

    const std::string refused = dir.path() + "/refused.exr";
    RiBegin(RI_NULL);
    view(refused);
    RiWorldBegin();
    RtString menger[2] = {STREYES_PLUGIN_DIR "/menger.so", "level=1 x=20 y=2 z=1 size=9"};
    RtBound c = {20, 29, 2, 11, 1, 10};
    RiProcedural(menger, c, RiProcDynamicLoad, nullptr);
    RiWorldEnd();
    testing::internal::CaptureStderr();
    RiEnd();
    const std::string err = testing::internal::GetCapturedStderr();
    setSceneAccess(before);
    EXPECT_NE(err.find("is refused by --safe: it would load a plug-in"), std::string::npos) << err;
    EXPECT_FALSE(std::filesystem::exists(refused));
}

TEST(RiSession, ABadCallRendersNothing) {
    test::TempDir dir("ri-session");
    const std::string out = dir.path() + "/frame.exr";
    RiBegin(RI_NULL);
    view(out);
    RiWorldBegin();
    RiSphere(1, -1, 1, 360, "undeclared", std::vector<RtFloat>{1}.data(), RI_NULL);  // the 8th call
    RiWorldEnd();
    testing::internal::CaptureStderr();
    RiEnd();
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("call 8 (RiSphere): parameter \"undeclared\" is not declared"), std::string::npos) << err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace streyes
