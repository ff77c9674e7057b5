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

}  // namespace
}  // namespace streyes
