// MakeTexture and MakeLatLongEnvironment as the parser records them (rib_textures.cpp): names
// beside the RIB file, wraps checked, a missing picture an error at its line.
#include <gtest/gtest.h>

#include <fstream>

#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

TEST(RibTextures, RequestsAreRecordedInOrderBesideTheirFile) {
    const test::TempDir dir("rib-textures");
    std::ofstream(dir.path() + "/in.tif") << "x";
    std::ofstream(dir.path() + "/scene.rib")
        << "MakeTexture \"in.tif\" \"out.tx\" \"periodic\" \"clamp\" \"gaussian\" 2 2\n"
           "MakeLatLongEnvironment \"in.tif\" \"/abs/sky.env\" \"box\" 1 1\nWorldBegin\nWorldEnd\n";
    Log log;
    const Scene scene = parseRibFile(dir.path() + "/scene.rib", log);
    EXPECT_TRUE(log.warnings().empty());
    ASSERT_EQ(scene.settings.makeTextures.size(), 2u);
    const MakeTextureDesc& t = scene.settings.makeTextures[0];
    EXPECT_FALSE(t.latLongEnvironment);
    EXPECT_EQ(t.input, dir.path() + "/in.tif");
    EXPECT_EQ(t.output, dir.path() + "/out.tx");
    EXPECT_EQ(t.swrap, "periodic");
    EXPECT_EQ(t.twrap, "clamp");
    EXPECT_EQ(t.filter, "gaussian");
    EXPECT_EQ(t.swidth, 2);
    EXPECT_EQ(t.loc.line, 1);
    const MakeTextureDesc& e = scene.settings.makeTextures[1];
    EXPECT_TRUE(e.latLongEnvironment);
    EXPECT_EQ(e.output, "/abs/sky.env");
    EXPECT_EQ(e.loc.line, 2);
}

// A picture that is not there reads: a frame of the same input may write it before the map is
// made (then a missing one is an error at its line: tests/cli/texture_test.cpp). A bad wrap mode
// is an error at its line.
TEST(RibTextures, ABadWrapIsAnErrorAtItsLineAPictureNotYetThereIsNot) {
    std::string e = test::ribError("Format 8 8 1\nMakeTexture \"/nonexistent/in.tif\" \"o.tx\" \"black\" "
                                   "\"black\" \"box\" 1 1\nWorldBegin\nWorldEnd\n");
    EXPECT_EQ(e, "");
    const test::TempDir dir("rib-textures-wrap");
    std::ofstream(dir.path() + "/in.tif") << "x";
    e = test::ribError("MakeTexture \"" + dir.path() + "/in.tif\" \"o.tx\" \"mirror\" \"black\" \"box\" 1 1\n");
    EXPECT_NE(e.find("\"mirror\""), std::string::npos) << e;
}

// MakeCubeFaceEnvironment: its six faces (+x, -x, +y, -y, +z, -z) beside the file, the map a
// lat-long environment, the fov kept; a fov outside (0, 180) is an error at the value.
TEST(RibTextures, CubeFaceEnvironmentRecordsItsFacesInOrderAndItsFov) {
    const test::TempDir dir("rib-textures-cube");
    std::ofstream(dir.path() + "/scene.rib")
        << "Format 8 8 1\nMakeCubeFaceEnvironment \"a.tif\" \"b.tif\" \"c.tif\" \"d.tif\" \"e.tif\" \"/abs/f.tif\" "
           "\"cube.env\" 95.5 \"gaussian\" 2 2\nWorldBegin\nWorldEnd\n";
    Log log;
    const Scene scene = parseRibFile(dir.path() + "/scene.rib", log);
    EXPECT_TRUE(log.warnings().empty());
    ASSERT_EQ(scene.settings.makeTextures.size(), 1u);
    const MakeTextureDesc& c = scene.settings.makeTextures[0];
    EXPECT_TRUE(c.latLongEnvironment);
    const std::vector<std::string> faces = {dir.path() + "/a.tif", dir.path() + "/b.tif", dir.path() + "/c.tif",
                                            dir.path() + "/d.tif", dir.path() + "/e.tif", "/abs/f.tif"};
    EXPECT_EQ(c.cubeFaces, faces);
    EXPECT_EQ(c.input, faces[0]);
    EXPECT_EQ(c.output, dir.path() + "/cube.env");
    EXPECT_EQ(c.cubeFov, 95.5);
    EXPECT_EQ(c.filter, "gaussian");
    EXPECT_EQ(c.swrap, "periodic");
    EXPECT_EQ(c.twrap, "clamp");
    EXPECT_EQ(c.loc.line, 2);

    const std::string request = "MakeCubeFaceEnvironment \"a\" \"b\" \"c\" \"d\" \"e\" \"f\" \"o.env\" ";
    for (const char* fov : {"0", "180", "-1"}) {
        const std::string e = test::ribError(request + fov + " \"box\" 1 1\n");
        EXPECT_NE(e.find("field of view"), std::string::npos) << fov << ": " << e;
    }
    EXPECT_NE(test::ribError(request + "90 \"box\" 1\n"), "");  // twidth missing
    EXPECT_EQ(test::ribError(request + "90 \"box\" 1 1\nWorldBegin\nWorldEnd\n"), "");
}

}  // namespace
}  // namespace streyes
