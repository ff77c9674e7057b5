// The built-in procedurals' comma-separated parameter lists: the numbers, and an InputError at the
// procedural's line for a wrong count, an empty part, a word or a non-finite value.
#include "procedural/number_list.h"

#include <gtest/gtest.h>

#include <memory>

namespace streyes {
namespace {

TEST(NumberList, ReadsTheNumbersAndRefusesAnythingElse) {
    SourceLoc loc;
    loc.file = std::make_shared<const std::string>("scene.rib");
    loc.line = 7;
    EXPECT_EQ(parseNumberList("forest", "area", "100,2.5e1", 2, loc), (std::vector<double>{100, 25}));
    EXPECT_EQ(parseNumberList("grass", "rect", "-7,1,7,16", 4, loc), (std::vector<double>{-7, 1, 7, 16}));
    for (const char* bad : {"1", "1,2,3", "1,,2", "1,x", "1,inf", "nan,2", ""}) {
        try {
            parseNumberList("tree", "barkcolor", bad, 2, loc);
            ADD_FAILURE() << "'" << bad << "' was read";
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("scene.rib:7"), std::string::npos) << what;
            EXPECT_NE(what.find("tree: 'barkcolor"), std::string::npos) << what;
        }
    }
}

}  // namespace
}  // namespace streyes
