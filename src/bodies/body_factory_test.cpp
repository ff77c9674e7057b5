#include "bodies/body_factory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "raster/image_block.h"

namespace streyes {
namespace {

// Ids decide exact depth ties, so two primitives must never share one. A forest makes about a
// million bodies; 32-bit hashed ids collided by the thousand at four million (about n^2 / 2^33).
TEST(BodyFactory, ChildIdsOfFourMillionChildrenAreDistinct) {
    std::vector<uint64_t> ids;
    const uint64_t parents[] = {1, 2, 77, childPrimitiveId(3, 5)};
    for (uint64_t parent : parents)
        for (uint64_t i = 0; i < 1000000; ++i) ids.push_back(childPrimitiveId(parent, i));
    for (uint64_t id : ids) ASSERT_TRUE(id != 0 && id != kNoPrimitive);
    std::sort(ids.begin(), ids.end());
    EXPECT_EQ(std::adjacent_find(ids.begin(), ids.end()), ids.end()) << "two children share an id";
}

TEST(BodyFactory, ChildIdsArePureFunctionsOfParentAndIndex) {
    EXPECT_EQ(childPrimitiveId(12, 7), childPrimitiveId(12, 7));
    EXPECT_NE(childPrimitiveId(12, 7), childPrimitiveId(12, 8));
    EXPECT_NE(childPrimitiveId(12, 7), childPrimitiveId(13, 7));
}

}  // namespace
}  // namespace streyes
