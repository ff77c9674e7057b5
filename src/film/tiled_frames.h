// The resolved frames of a block, kept tile by tile until they are handed out one at a time.
//
// A bucket that spans every frame of the block resolves its tile's still layer once; a frame with no
// moving sample under the tile's filter footprint shows exactly those pixels, so it keeps a
// reference to them instead of a copy. A still shot of 64 frames then holds about one frame of
// pixels, where 64 full frame images were allocated, zeroed and faulted in (half its CPU time).
// Frames with moving samples near get their own tile buffer. Buffers are kept from block to block
// (no new pages after the first). assemble() copies one frame's tiles into a FrameImage for the
// sink: a pixel has the same bits whichever way it was stored.
//
// Pixel layout in a tile buffer: R G B A Z, then the frame's output variables, row-major.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "streyes/frame_image.h"
#include "streyes/vecmath.h"

namespace streyes {

class TiledFrames {
  public:
    // One tile's pixels in every frame of the block. Written only by the bucket that resolves the
    // tile (for --algorithm frames, one bucket a frame: each writes only its own frame's slot).
    class Tile {
      public:
        const PixelRect& rect() const { return rect_; }
        int channels() const { return channels_; }
        size_t pixelCount() const { return size_t(rect_.area()); }
        // The still layer's pixels, shared by the frames that show only them.
        float* still();
        // Frame `slot` (an index in the block) shows the still pixels.
        void showStill(int slot) { shows_[size_t(slot)] = Shows::Still; }
        // Frame `slot`'s own pixels, to be written in full.
        float* own(int slot);
        // Frame `slot`'s pixels, the still ones or its own; null until resolved.
        const float* pixels(int slot) const;

      private:
        friend class TiledFrames;
        enum class Shows : uint8_t { Nothing, Still, Own };
        PixelRect rect_;
        int channels_ = 5;
        std::vector<float> still_;
        std::vector<Shows> shows_;                 // per frame slot
        std::vector<std::vector<float>> buffers_;  // per frame slot its own pixels, made when first asked for
    };

    // Starts a block of `frameCount` frames from `firstFrame`, cut into `tiles` (which cover the
    // width x height image once, or all of `window`), each pixel with the named output variables
    // after R G B A Z. With a window (a CropWindow's pixels), frames are that window only.
    void reset(int width, int height, const std::vector<PixelRect>& tiles, int firstFrame, int frameCount,
               const std::vector<std::string>& aovNames, const PixelRect* window = nullptr);
    int firstFrame() const { return firstFrame_; }
    int frameCount() const { return frameCount_; }
    Tile& tile(size_t index) { return tiles_[index]; }

    // Frame `slot` of the block as one image (reusing out's storage when its shape fits). Throws
    // std::logic_error if a tile was not resolved for that frame.
    void assemble(int slot, FrameImage& out) const;

  private:
    int width_ = 0, height_ = 0, firstFrame_ = 0, frameCount_ = 0;
    PixelRect window_;  // the pixels assembled: the whole frame unless cropped
    std::vector<std::string> aovNames_;
    std::vector<Tile> tiles_;
};

}  // namespace streyes
