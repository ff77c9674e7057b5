#include "film/tiled_frames.h"

#include <algorithm>
#include <stdexcept>

namespace streyes {

float* TiledFrames::Tile::still() {
    still_.resize(pixelCount() * size_t(channels_));
    return still_.data();
}

float* TiledFrames::Tile::own(int slot) {
    std::vector<float>& b = buffers_[size_t(slot)];
    b.resize(pixelCount() * size_t(channels_));
    shows_[size_t(slot)] = Shows::Own;
    return b.data();
}

const float* TiledFrames::Tile::pixels(int slot) const {
    switch (shows_[size_t(slot)]) {
        case Shows::Still: return still_.data();
        case Shows::Own: return buffers_[size_t(slot)].data();
        default: return nullptr;
    }
}

void TiledFrames::reset(int width, int height, const std::vector<PixelRect>& tiles, int firstFrame, int frameCount,
                        const std::vector<std::string>& aovNames) {
    width_ = width;
    height_ = height;
    firstFrame_ = firstFrame;
    frameCount_ = frameCount;
    aovNames_ = aovNames;
    // Tiles keep their buffers (and so their pages) when the next block has the same layout.
    tiles_.resize(tiles.size());
    for (size_t i = 0; i < tiles.size(); ++i) {
        Tile& t = tiles_[i];
        t.rect_ = tiles[i];
        t.channels_ = 5 + int(aovNames.size());
        t.shows_.assign(size_t(frameCount), Tile::Shows::Nothing);
        t.buffers_.resize(size_t(frameCount));
    }
}

void TiledFrames::assemble(int slot, FrameImage& out) const {
    const size_t A = aovNames_.size();
    if (out.width != width_ || out.height != height_ || out.aovNames != aovNames_ ||
        out.rgba.size() != size_t(width_) * size_t(height_) * 4) {
        out.aovNames = aovNames_;
        out.resize(width_, height_);  // every pixel is written below
    }
    out.frame = firstFrame_ + slot;
    for (const Tile& t : tiles_) {
        const float* p = t.pixels(slot);
        if (!p)
            throw std::logic_error("TiledFrames::assemble: a tile of frame " + std::to_string(out.frame) +
                                   " was not resolved");
        const int C = t.channels_;
        for (int y = t.rect_.y0; y <= t.rect_.y1; ++y)
            for (int x = t.rect_.x0; x <= t.rect_.x1; ++x, p += C) {
                const size_t i = size_t(y) * size_t(width_) + size_t(x);
                std::copy(p, p + 4, &out.rgba[i * 4]);
                out.z[i] = p[4];
                if (A) std::copy(p + 5, p + 5 + A, &out.aov[i * A]);
            }
    }
}

}  // namespace streyes
