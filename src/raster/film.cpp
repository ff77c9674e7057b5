#include "streyes/film.h"

#include <cmath>
#include <limits>

namespace streyes {

namespace {

// RenderMan's filter functions, one dimension; x in [0, r), r = width / 2.
float filter1D(const std::string& type, float x, float r) {
    if (type == "box") return 1.0f;
    if (type == "catmull-rom") {
        // The Catmull-Rom cubic over [-2, 2], stretched to the filter's radius.
        float t = std::fabs(x) * 2.0f / r;
        if (t < 1) return 1.5f * t * t * t - 2.5f * t * t + 1.0f;
        if (t < 2) return -0.5f * t * t * t + 2.5f * t * t - 4.0f * t + 2.0f;
        return 0.0f;
    }
    // gaussian: RiGaussianFilter, exp(-2 (2x/width)^2) = exp(-2 (x/r)^2)
    float u = x / r;
    return std::exp(-2.0f * u * u);
}

}  // namespace

PixelFilter::PixelFilter(const FilterDesc& desc)
    : rx_(float(std::max(desc.xwidth, 1e-3) * 0.5)), ry_(float(std::max(desc.ywidth, 1e-3) * 0.5)) {
    tx_.resize(kTableSize + 1);
    ty_.resize(kTableSize + 1);
    // Tabulate at bin centres; the extra entry guards a / r rounding up to exactly 1.
    for (int i = 0; i <= kTableSize; ++i) {
        float u = (float(std::min(i, kTableSize - 1)) + 0.5f) / kTableSize;
        tx_[size_t(i)] = filter1D(desc.type, u * rx_, rx_);
        ty_[size_t(i)] = filter1D(desc.type, u * ry_, ry_);
    }
}

// A sample in pixel p lies in [p, p+1); it reaches a pixel centre c + 0.5 when
// |s - c - 0.5| < r, so pixels up to ceil(r - 0.5) away contribute.
int PixelFilter::guardX() const { return std::max(0, int(std::ceil(rx_ - 0.5f))); }
int PixelFilter::guardY() const { return std::max(0, int(std::ceil(ry_ - 0.5f))); }

void resolveTile(const ImageBlock& block, int fi, const PixelRect& tile, const PixelFilter& filter,
                 FrameImage& out, std::vector<float>& acc) {
    const PixelRect& R = block.rect();
    const int tw = tile.width();
    acc.assign(size_t(tw) * size_t(tile.height()) * 5, 0.0f);  // r g b a weight
    const float rx = filter.radiusX(), ry = filter.radiusY();
    const float inf = std::numeric_limits<float>::infinity();

    // Splat each sample into the pixels whose centre lies within the filter radius.
    for (int k = 0; k < block.slices(); ++k) {
        for (int y = std::max(R.y0, tile.y0 - filter.guardY()); y <= std::min(R.y1, tile.y1 + filter.guardY()); ++y) {
            const Sample* row = block.row(fi, k, y) - R.x0;
            for (int x = std::max(R.x0, tile.x0 - filter.guardX()); x <= std::min(R.x1, tile.x1 + filter.guardX());
                 ++x) {
                const Sample& s = row[x];
                const int ox0 = std::max(tile.x0, int(std::ceil(s.x - 0.5f - rx)));
                const int ox1 = std::min(tile.x1, int(std::floor(s.x - 0.5f + rx)));
                const int oy0 = std::max(tile.y0, int(std::ceil(s.y - 0.5f - ry)));
                const int oy1 = std::min(tile.y1, int(std::floor(s.y - 0.5f + ry)));
                for (int oy = oy0; oy <= oy1; ++oy) {
                    for (int ox = ox0; ox <= ox1; ++ox) {
                        float w = filter.weight(s.x - (float(ox) + 0.5f), s.y - (float(oy) + 0.5f));
                        if (w == 0) continue;
                        float* a = &acc[(size_t(oy - tile.y0) * size_t(tw) + size_t(ox - tile.x0)) * 5];
                        a[0] += w * s.c.x;
                        a[1] += w * s.c.y;
                        a[2] += w * s.c.z;
                        a[3] += w * s.a;
                        a[4] += w;
                    }
                }
            }
        }
    }

    for (int y = tile.y0; y <= tile.y1; ++y) {
        for (int x = tile.x0; x <= tile.x1; ++x) {
            const float* a = &acc[(size_t(y - tile.y0) * size_t(tw) + size_t(x - tile.x0)) * 5];
            float* px = &out.rgba[(size_t(y) * size_t(out.width) + size_t(x)) * 4];
            float wsum = a[4];
            float inv = std::fabs(wsum) > 1e-8f ? 1.0f / wsum : 0.0f;
            for (int c = 0; c < 4; ++c) px[c] = a[c] * inv;
            float z = inf;
            for (int k = 0; k < block.slices(); ++k) z = std::min(z, block.row(fi, k, y)[x - R.x0].z);
            out.z[size_t(y) * size_t(out.width) + size_t(x)] = z;
        }
    }
}

}  // namespace streyes
