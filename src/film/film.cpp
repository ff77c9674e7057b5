#include "film/film.h"

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
    sx_ = float(kTableSize) / rx_;
    sy_ = float(kTableSize) / ry_;
    tx_.assign(kTableSize + 1, 0.0f);
    ty_.assign(kTableSize + 1, 0.0f);
    for (int i = 0; i < kTableSize; ++i) {  // bin centres; entry kTableSize stays 0
        float u = (float(i) + 0.5f) / kTableSize;
        tx_[size_t(i)] = filter1D(desc.type, u * rx_, rx_);
        ty_[size_t(i)] = filter1D(desc.type, u * ry_, ry_);
    }
}

// A sample in pixel p lies in [p, p+1); it reaches a pixel centre c + 0.5 when
// |s - c - 0.5| < r, so pixels up to ceil(r - 0.5) away contribute.
int PixelFilter::guardX() const { return std::max(0, int(std::ceil(rx_ - 0.5f))); }
int PixelFilter::guardY() const { return std::max(0, int(std::ceil(ry_ - 0.5f))); }

void resolveTile(const ImageBlock& block, const PixelRect& tile, const PixelFilter& filter, FrameImage* frames,
                 std::vector<float>& acc) {
    const PixelRect& R = block.rect();
    const int tw = tile.width(), K = block.slices(), F = block.frameCount();
    const int gx = filter.guardX(), gy = filter.guardY();
    // Accumulators r g b a weight, per tile pixel, per frame: the frames of one pixel adjoin,
    // as they do in the block, so both are walked in order.
    acc.assign(size_t(tw) * size_t(tile.height()) * size_t(F) * 5, 0.0f);
    const SamplePosition* pos = block.positions();
    const SampleHit* hit = block.hits();

    // Splat each sample into the pixels whose centre lies within the filter radius: pixel o
    // takes the sample when |s - (o + 0.5)| < r, i.e. o in (s - 0.5 - r, s - 0.5 + r).
    constexpr int kMaxTaps = 64;
    float wx[kMaxTaps], wy[kMaxTaps];
    const float rx = filter.radiusX(), ry = filter.radiusY();
    auto floorInt = [](float v) {
        int i = int(v);
        return i - (float(i) > v);
    };
    const size_t tapStride = size_t(F) * 5;  // from one tile pixel to the next
    for (int y = std::max(R.y0, tile.y0 - gy); y <= std::min(R.y1, tile.y1 + gy); ++y) {
        for (int x = std::max(R.x0, tile.x0 - gx); x <= std::min(R.x1, tile.x1 + gx); ++x) {
            const size_t pixel = block.pixelOffset(x, y);
            for (int fi = 0; fi < F; ++fi) {
                for (int k = 0; k < K; ++k) {
                    const size_t si = pixel + size_t(fi) * size_t(K) + size_t(k);
                    const SamplePosition& p = pos[si];
                    const SampleHit& h = hit[si];
                    const int ox0 = std::max(tile.x0, floorInt(p.x - 0.5f - rx) + 1);
                    const int ox1 = std::min(tile.x1, floorInt(p.x - 0.5f + rx));
                    const int oy0 = std::max(tile.y0, floorInt(p.y - 0.5f - ry) + 1);
                    const int oy1 = std::min(tile.y1, floorInt(p.y - 0.5f + ry));
                    if (ox0 > ox1 || oy0 > oy1 || ox1 - ox0 >= kMaxTaps || oy1 - oy0 >= kMaxTaps) continue;
                    for (int ox = ox0; ox <= ox1; ++ox) wx[ox - ox0] = filter.weightX(p.x - (float(ox) + 0.5f));
                    for (int oy = oy0; oy <= oy1; ++oy) wy[oy - oy0] = filter.weightY(p.y - (float(oy) + 0.5f));
                    const bool background = h.a == 0;  // contributes weight only
                    for (int oy = oy0; oy <= oy1; ++oy) {
                        float* a = &acc[((size_t(oy - tile.y0) * size_t(tw) + size_t(ox0 - tile.x0)) * size_t(F) +
                                         size_t(fi)) * 5];
                        const float wyv = wy[oy - oy0];
                        for (int ox = ox0; ox <= ox1; ++ox, a += tapStride) {
                            const float w = wx[ox - ox0] * wyv;
                            a[4] += w;
                            if (background) continue;
                            a[0] += w * h.c.x;
                            a[1] += w * h.c.y;
                            a[2] += w * h.c.z;
                            a[3] += w * h.a;
                        }
                    }
                }
            }
        }
    }

    // Normalise; Z is the nearest of the pixel's own samples.
    const float inf = std::numeric_limits<float>::infinity();
    for (int y = tile.y0; y <= tile.y1; ++y) {
        for (int x = tile.x0; x <= tile.x1; ++x) {
            const size_t pixel = block.pixelOffset(x, y);
            for (int fi = 0; fi < F; ++fi) {
                FrameImage& out = frames[fi];
                const float* a = &acc[((size_t(y - tile.y0) * size_t(tw) + size_t(x - tile.x0)) * size_t(F) + size_t(fi)) * 5];
                float* px = &out.rgba[(size_t(y) * size_t(out.width) + size_t(x)) * 4];
                const float inv = std::fabs(a[4]) > 1e-8f ? 1.0f / a[4] : 0.0f;
                for (int c = 0; c < 4; ++c) px[c] = a[c] * inv;
                float z = inf;
                for (int k = 0; k < K; ++k) z = std::min(z, hit[pixel + size_t(fi) * size_t(K) + size_t(k)].z);
                out.z[size_t(y) * size_t(out.width) + size_t(x)] = z;
            }
        }
    }
}

}  // namespace streyes
