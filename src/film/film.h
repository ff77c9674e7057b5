// Pixel reconstruction: the pixel filter and the frames it resolves samples into.
//
// Filters are separable, tabulated products f(dx) * f(dy) over [-xwidth/2, xwidth/2] x
// [-ywidth/2, ywidth/2] (RenderMan's widths). Colour and alpha are the filter-weighted mean of
// the samples around the pixel centre; Z is the nearest camera-space depth among the pixel's
// own samples (+inf where none hit: Z is not filtered).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "raster/image_block.h"
#include "streyes/frame_image.h"
#include "streyes/scene.h"

namespace streyes {

class PixelFilter {
  public:
    explicit PixelFilter(const FilterDesc& desc);
    float radiusX() const { return rx_; }
    float radiusY() const { return ry_; }
    // Weight at offset (dx, dy) from the pixel centre; 0 outside the support [-r, r) per axis.
    // The support is half-open like the pixels: a sample exactly on a pixel's left or top edge
    // (d = -r for a box of width 1) belongs to that pixel, and to no other.
    float weight(float dx, float dy) const { return weightX(dx) * weightY(dy); }
    float weightX(float dx) const { return lookup(tx_, dx, sx_, rx_); }
    float weightY(float dy) const { return lookup(ty_, dy, sy_, ry_); }
    // Pixels of guard band a bucket needs on each side so its own pixels see every sample.
    int guardX() const;
    int guardY() const;

  private:
    static constexpr int kTableSize = 256;
    // Table entry for |d| * (kTableSize / r); the last entry is 0, so anything at or past the
    // radius reads 0, except d = -r exactly, which reads the last bin inside.
    static float lookup(const std::vector<float>& t, float d, float scale, float r) {
        float i = std::min(std::fabs(d) * scale, float(kTableSize));
        if (d == -r) i = float(kTableSize - 1);
        return t[size_t(i)];
    }
    float rx_, ry_, sx_, sy_;  // radii, and kTableSize / radius
    std::vector<float> tx_, ty_;
};

// Resolves the samples of every frame of the block into the pixels of `tile` (inside the
// block's rect, which must include the filter's guard band around it): frames[fi] receives frame
// block.firstFrame() + fi. One pass in the block's pixel-major order.
void resolveTile(const ImageBlock& block, const PixelRect& tile, const PixelFilter& filter, FrameImage* frames,
                 std::vector<float>& scratch);

}  // namespace streyes
