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
                        const std::vector<std::string>& aovNames, const PixelRect* window) {
    width_ = width;
    height_ = height;
    window_ = window ? *window : PixelRect{0, 0, width - 1, height - 1};
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
    const PixelRect& w = window_;
    const int W = w.width(), H = w.height();
    if (out.width != W || out.height != H || out.aovNames != aovNames_ || out.rgba.size() != size_t(W) * size_t(H) * 4) {
        out.aovNames = aovNames_;
        out.resize(W, H);  // every pixel is written below
    }
    out.frame = firstFrame_ + slot;
    for (const Tile& t : tiles_) {
        const float* p = t.pixels(slot);
        if (!p)
            throw std::logic_error("TiledFrames::assemble: a tile of frame " + std::to_string(out.frame) +
                                   " was not resolved");
        const int C = t.channels_, tw = t.rect_.width();
        for (int y = std::max(t.rect_.y0, w.y0); y <= std::min(t.rect_.y1, w.y1); ++y)
            for (int x = std::max(t.rect_.x0, w.x0); x <= std::min(t.rect_.x1, w.x1); ++x) {
                const float* q = p + (size_t(y - t.rect_.y0) * size_t(tw) + size_t(x - t.rect_.x0)) * size_t(C);
                const size_t i = size_t(y - w.y0) * size_t(W) + size_t(x - w.x0);
                std::copy(q, q + 4, &out.rgba[i * 4]);
                out.z[i] = q[4];
                if (A) std::copy(q + 5, q + 5 + A, &out.aov[i * A]);
            }
    }
}

}  // namespace streyes
