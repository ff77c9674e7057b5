// Pixel reconstruction: the pixel filter and the frames it resolves samples into.
//
// Filters are tabulated over [-xwidth/2, xwidth/2] x [-ywidth/2, ywidth/2] (RenderMan's widths):
// box, triangle, gaussian, catmull-rom, sinc, mitchell and blackman-harris as separable products
// f(dx) * f(dy) (the "separable-" names are the same), disk as 1 inside the ellipse the widths span. Colour and alpha are the filter-weighted mean of
// the samples around the pixel centre; Z is the nearest camera-space depth among the pixel's
// own samples (+inf where none hit: Z is not filtered), or as DepthFilter says.
//
// See-through fragments (image_block.h) are composited per sample, nearest first, over the sample's
// opaque hit: C = sum of T_k Ci_k + T c_opaque with T_k the product of (1 - Oi) of the fragments in
// front (per channel); alpha is the mean over channels of 1 - T (1 - a_opaque). Z stays the opaque
// hit's, as with RenderMan's default zthreshold; output variables are the opaque hit's.
//
// Output variables (util/aov.h) are the filter-weighted mean of the samples that hit, divided by
// the weight of those samples only: a normal at a silhouette is the surface's, not averaged with
// the background's nothing (pixels where no sample hits hold 0).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "film/tiled_frames.h"
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
    float weight(float dx, float dy) const {
        if (radial_) {
            if (!(dx >= -rx_ && dx < rx_ && dy >= -ry_ && dy < ry_)) return 0.0f;
            const float u = dx / rx_, v = dy / ry_;
            return u * u + v * v < 1.0f ? 1.0f : 0.0f;
        }
        return weightX(dx) * weightY(dy);
    }
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
    bool radial_ = false;      // the disk: not a product of two functions
    std::vector<float> tx_, ty_;
};

// The filter's weight for every sample of every pattern (PatternTable), towards each pixel it
// reaches: samples sit at the same sub-pixel positions in every frame, so the weights are
// computed once per render, not once per sample and frame. weights(p, ox, oy)[j] is the weight
// of sample j of a pixel with pattern p for the pixel (ox, oy) away from it.
// How a pixel's Z comes from the depths of its own samples (Hider "hidden" "depthfilter"): the
// nearest (misses count as +inf), or the farthest or the mean of those that hit (+inf where none do).
// Midpoint: each sample's depth is the mean of the two nearest surfaces it crosses (+inf where it
// crosses fewer), the pixel's the nearest of those; it needs every surface a sample crosses, which
// a depth pass keeps as fragments (RenderOptions::depthPass).
enum class DepthFilter { Min, Max, Average, Midpoint };
bool depthFilterFromName(const std::string& name, DepthFilter* out);

class FilterWeights {
  public:
    FilterWeights(const PixelFilter& filter, const PatternTable& patterns, DepthFilter depth = DepthFilter::Min);
    DepthFilter depthFilter() const { return depth_; }
    int reachX() const { return gx_; }  // pixels a sample reaches on each side (the guard band)
    int reachY() const { return gy_; }
    const float* weights(int pattern, int ox, int oy) const {
        return &w_[((size_t(pattern) * size_t(2 * gy_ + 1) + size_t(oy + gy_)) * size_t(2 * gx_ + 1) + size_t(ox + gx_)) *
                   size_t(S_)];
    }

  private:
    int gx_, gy_, S_;
    DepthFilter depth_;
    std::vector<float> w_;  // patterns x (2 gy + 1) x (2 gx + 1) x S
};

// "Over", nearest first: see-through layers (Ci premultiplied by Oi, as shaders give it) composited
// front to back. The rasterizer's fragments (resolveTile) and the ray tracer's hits along an eye
// ray both go through it.
struct OverComposite {
    Color c{0, 0, 0};  // the colour so far
    Color t{1, 1, 1};  // what still gets through, per channel
    // A layer of colour ci that lets ti (1 - Oi) through.
    void add(Color ci, Color ti) {
        c += t * ci;
        t = t * ti;
    }
    // Alpha over what lies behind, of coverage a: the channel mean of 1 - t (1 - a).
    float alpha(float a = 0) const {
        const float clear = 1 - a;
        return ((1 - t.x * clear) + (1 - t.y * clear) + (1 - t.z * clear)) / 3;
    }
};

// A sample with its see-through fragments composited over its opaque hit: what the filter
// weighs. Alpha first, then R G B, so that film.cpp's accumulate reads the four side by side.
struct CompositeSample {
    float a;  // alpha
    Color c;  // colour, premultiplied
};
static_assert(sizeof(CompositeSample) == 4 * sizeof(float));

// What resolving keeps from bucket to bucket.
struct ResolveScratch {
    std::vector<float> weightSum;  // per tile pixel: the weights of every sample it sees
    std::vector<float> still;      // per tile pixel: R G B A Z resolved from the still layer
    std::vector<uint8_t> gathered; // per tile pixel, in the frame being resolved: gathered again
    std::vector<float> aov;        // one pixel's output variables being gathered
    std::vector<float> stillAov;   // per tile pixel: output variables resolved from the still layer
    // With see-through fragments: each sample's fragments composited over its opaque hit, for the
    // still layer and (made when first asked for) for the frame being resolved.
    std::vector<CompositeSample> stillComposite, frameComposite;
    std::vector<int32_t> compositedFrame;  // per block pixel: the frame frameComposite holds it for, or -1
    std::vector<SampleFragment> fragments;  // one sample's, being sorted
    SolidWalk solidWalk;                    // one sample's crossings of solids (geom/solid_tree.h)
    std::vector<SampleHit> solidHits;       // one pixel's hits with solids' depths (film.cpp solidDepths)
    std::vector<float> solidAov;            // and its output variables, a solid's where it shows one (solidSurfaces)
    std::vector<int32_t> fragmentIndices;   // one sample's solids' fragments, being sorted
};

// Resolves the samples of every frame of the block into the pixels of tile `tileIndex` of `frames`
// (inside the block's rect, which must include the filter's guard band around it). Each pixel
// gathers the samples of the pixels around it; a pixel none of whose neighbours has a record in a
// frame shows the still layer there, resolved once for the block, and a frame whose whole tile
// shows it keeps a reference to those pixels (tiled_frames.h). The same gather makes both, so a
// pixel has the same bits whichever way it is resolved.
// Exposure: rgb = (gain * rgb)^(1 / gamma) per channel (negative values stay linear), after the
// imager, before the frame is written. Alpha and Z are kept. Nothing is done for gain = gamma = 1.
void applyExposure(FrameImage& image, double gain, double gamma);

void resolveTile(const ImageBlock& block, const FilterWeights& weights, TiledFrames& frames, size_t tileIndex,
                 ResolveScratch& scratch);

}  // namespace streyes
