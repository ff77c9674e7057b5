#include "film/tiled_frames.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "film/film.h"

namespace streyes {
namespace {

const PatternTable& patterns() {
    static const PatternTable table(SamplePattern{2, 2, 1});
    return table;
}

// A block over `rect` whose still layer is `grey` everywhere at depth 5.
void fillStill(ImageBlock& block, const PixelRect& rect, int firstFrame, int frames, float grey) {
    block.reset(rect, firstFrame, frames, patterns(), false);
    for (size_t i = 0; i < size_t(block.pixelCount()); ++i)
        for (int k = 0; k < 4; ++k) block.still(i)[k] = {5.0f, {grey, grey, grey}, 1};
}

// A still tile is stored once for all the block's frames; a frame with a record near gets its own
// pixels, which differ from the still ones only where its filter reaches the record.
TEST(TiledFrames, StillFramesShareOneCopyAndAMovingFrameHasItsOwn) {
    const FilterWeights weights(PixelFilter(FilterDesc{"gaussian", 2, 2}), patterns());
    ImageBlock block;
    fillStill(block, {0, 0, 9, 9}, 10, 3, 0.25f);
    SampleHit* r = block.makeRecord(1, block.pixelIndex(5, 5));
    for (int k = 0; k < 4; ++k) r[k] = {2.0f, {1, 0, 0}, 2};
    TiledFrames frames;
    frames.reset(10, 10, {PixelRect{0, 0, 9, 9}}, 10, 3, {});
    ResolveScratch scratch;
    resolveTile(block, weights, frames, 0, scratch);
    const TiledFrames::Tile& t = frames.tile(0);
    EXPECT_EQ(t.pixels(0), t.pixels(2));  // one copy
    EXPECT_NE(t.pixels(0), t.pixels(1));

    FrameImage still, moving;
    frames.assemble(0, still);
    frames.assemble(1, moving);
    EXPECT_EQ(still.frame, 10);
    EXPECT_EQ(moving.frame, 11);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x) {
            const size_t p = size_t(y * 10 + x);
            const bool reached = std::abs(x - 5) <= 1 && std::abs(y - 5) <= 1;
            EXPECT_EQ(moving.rgba[p * 4] != still.rgba[p * 4], reached) << x << "," << y;
            EXPECT_EQ(moving.z[p] == 2.0f, x == 5 && y == 5) << x << "," << y;
            if (x >= 2 && x <= 7 && y >= 2 && y <= 7) {
                EXPECT_NEAR(still.rgba[p * 4 + 1], 0.25f, 1e-6f);
            }
        }
}

// Tiles land where they belong; frames rendered one bucket a frame (--algorithm frames) each fill
// their own slot, and nothing is shared between them.
TEST(TiledFrames, AssemblesTilesAndPerFrameBuckets) {
    const FilterWeights weights(PixelFilter(FilterDesc{"box", 1, 1}), patterns());
    const std::vector<PixelRect> tiles = {{0, 0, 3, 1}, {4, 0, 5, 1}};
    TiledFrames frames;
    frames.reset(6, 2, tiles, 0, 2, {});
    ResolveScratch scratch;
    for (int f = 0; f < 2; ++f)
        for (size_t i = 0; i < tiles.size(); ++i) {
            ImageBlock block;
            fillStill(block, tiles[i], f, 1, 0.1f * float(1 + f) + 0.5f * float(i));
            resolveTile(block, weights, frames, i, scratch);
        }
    EXPECT_NE(frames.tile(0).pixels(0), frames.tile(0).pixels(1));
    FrameImage img;
    for (int f = 0; f < 2; ++f) {
        frames.assemble(f, img);
        ASSERT_EQ(img.width, 6);
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 6; ++x) {
                const float want = 0.1f * float(1 + f) + (x >= 4 ? 0.5f : 0.0f);
                EXPECT_FLOAT_EQ(img.rgba[size_t(y * 6 + x) * 4], want) << f << ": " << x << "," << y;
                EXPECT_EQ(img.rgba[size_t(y * 6 + x) * 4 + 3], 1.0f);
            }
    }
}

// A frame a tile was not resolved for is an error, not a black tile; the buffers outlive reset()
// so the next block of the same shape touches no new memory.
TEST(TiledFrames, UnresolvedTileThrowsAndBuffersAreKept) {
    const FilterWeights weights(PixelFilter(FilterDesc{"box", 1, 1}), patterns());
    TiledFrames frames;
    frames.reset(4, 4, {PixelRect{0, 0, 3, 3}}, 0, 2, {});
    FrameImage img;
    EXPECT_THROW(frames.assemble(0, img), std::logic_error);
    ImageBlock block;
    fillStill(block, {0, 0, 3, 3}, 1, 1, 0.5f);  // frame 1 alone: its own pixels
    ResolveScratch scratch;
    resolveTile(block, weights, frames, 0, scratch);
    EXPECT_THROW(frames.assemble(0, img), std::logic_error);
    const float* before = frames.tile(0).pixels(1);
    frames.assemble(1, img);
    EXPECT_EQ(img.rgba[0], 0.5f);
    frames.reset(4, 4, {PixelRect{0, 0, 3, 3}}, 2, 2, {});
    EXPECT_EQ(frames.tile(0).pixels(1), nullptr);
    fillStill(block, {0, 0, 3, 3}, 3, 1, 0.75f);
    resolveTile(block, weights, frames, 0, scratch);
    EXPECT_EQ(frames.tile(0).pixels(1), before);
    frames.assemble(1, img);
    EXPECT_EQ(img.frame, 3);
    EXPECT_EQ(img.rgba[0], 0.75f);
}

}  // namespace
}  // namespace streyes
