#include "film/film.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <utility>

namespace streyes {

namespace {

// RenderMan's filter functions, one dimension; x in [0, r), r = width / 2 (the RenderMan
// Interface 3.2's built-in filters, which are separable but for the disk; mitchell as PRMan
// defines it, B = C = 1/3 over [-2, 2] stretched to the radius).
float filter1D(const std::string& type, float x, float r) {
    if (type == "box") return 1.0f;
    if (type == "triangle") return 1.0f - std::fabs(x) / r;  // RiTriangleFilter
    if (type == "sinc") {
        // RiSincFilter: sin(pi x) / (pi x) under the specification's cosine window.
        if (x == 0) return 1.0f;
        const double px = 3.14159265358979323846 * double(x);
        return float(std::cos(0.5 * px / (2.0 * double(r))) * std::sin(px) / px);
    }
    if (type == "mitchell") {
        const double t = std::fabs(double(x)) * 2.0 / double(r), B = 1.0 / 3.0, C = 1.0 / 3.0;
        if (t < 1) return float(((12 - 9 * B - 6 * C) * t * t * t + (-18 + 12 * B + 6 * C) * t * t + (6 - 2 * B)) / 6);
        if (t < 2)
            return float(((-B - 6 * C) * t * t * t + (6 * B + 30 * C) * t * t + (-12 * B - 48 * C) * t + (8 * B + 24 * C)) / 6);
        return 0.0f;
    }
    if (type == "disk") return 1.0f;  // radial: the disk's own table decides (PixelFilter)
    if (type == "blackman-harris") {
        // The four-term Blackman-Harris window over [-r, r] (Harris 1978; Cycles' and Blender's
        // default pixel filter): 1 at the centre, about 6e-5 at the ends.
        const double pi = 3.14159265358979323846, a = pi * (double(x) / double(r) + 1.0);
        return float(0.35875 - 0.48829 * std::cos(a) + 0.14128 * std::cos(2 * a) - 0.01168 * std::cos(3 * a));
    }
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
    radial_ = desc.type == "disk";
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

bool depthFilterFromName(const std::string& name, DepthFilter* out) {
    if (name == "min") *out = DepthFilter::Min;
    else if (name == "max") *out = DepthFilter::Max;
    else if (name == "average") *out = DepthFilter::Average;
    else if (name == "midpoint") *out = DepthFilter::Midpoint;
    else return false;
    return true;
}

FilterWeights::FilterWeights(const PixelFilter& filter, const PatternTable& patterns, DepthFilter depth)
    : gx_(filter.guardX()), gy_(filter.guardY()), S_(patterns.samples()), depth_(depth) {
    const int P = patterns.patternCount();
    w_.resize(size_t(P) * size_t(2 * gy_ + 1) * size_t(2 * gx_ + 1) * size_t(S_));
    for (int p = 0; p < P; ++p) {
        const float* o = patterns.offsets(p);
        for (int oy = -gy_; oy <= gy_; ++oy)
            for (int ox = -gx_; ox <= gx_; ++ox) {
                float* w = const_cast<float*>(weights(p, ox, oy));
                // A sample at s in its pixel is s - (o + 0.5) from the centre of the pixel o away.
                for (int j = 0; j < S_; ++j)
                    w[j] = filter.weight(o[2 * j] - (float(ox) + 0.5f), o[2 * j + 1] - (float(oy) + 0.5f));
            }
    }
}

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Four floats in one register (GCC's and Clang's vector extension): a sample's A R G B weighted
// and summed lane by lane, one multiply and one add each, as four separate sums would be.
using Float4 = float __attribute__((vector_size(16)));

// A sample's A R G B, weighted by w, added to acc (A R G B; the background adds w * 0, which
// leaves a sum as it is).
inline void accumulate(Float4& acc, float w, const CompositeSample& s) {
    Float4 v;
    std::memcpy(&v, &s.a, sizeof v);  // a r g b
    acc += w * v;
}
// R G B A of a pixel from its sums (A R G B) and the weight they are divided by.
inline void normalise(Float4 acc, float inv, float* out) {
    for (int c = 0; c < 4; ++c) out[c] = acc[(c + 1) % 4] * inv;
}

// The depth of tile pixel (x, y): of the opaque hits of the pixel's own samples, as the depth
// filter says.
inline float pixelDepth(const ImageBlock& block, const FilterWeights& fw, const SampleHit* own) {
    const int S = block.samplesPerPixel();
    float z = kInf;
    switch (fw.depthFilter()) {
        case DepthFilter::Min:
            for (int j = 0; j < S; ++j) z = std::min(z, own[j].z);
            break;
        case DepthFilter::Max: {
            float far = -kInf;
            for (int j = 0; j < S; ++j)
                if (own[j].z < kInf) far = std::max(far, own[j].z);  // fragments alone: no depth
            if (far > -kInf) z = far;
            break;
        }
        case DepthFilter::Average: {
            float sum = 0;
            int n = 0;
            for (int j = 0; j < S; ++j)
                if (own[j].z < kInf) sum += own[j].z, ++n;
            if (n > 0) z = sum / float(n);
            break;
        }
        case DepthFilter::Midpoint:  // from the fragments (midpointDepth); the opaque hits alone: the nearest
            for (int j = 0; j < S; ++j) z = std::min(z, own[j].z);
            break;
    }
    return z;
}

// Depthfilter "midpoint": each sample's two nearest surfaces, its opaque hit and the fragments of
// lists `own` and `shared` (per sample heads, null: none), averaged (+inf with fewer than two); the
// pixel's depth the nearest of its samples'. A solid's crossings count where they bound its result
// (walked nearest first, as composite walks them) and are not clear (a see-through member's:
// no surface of a depth map, as a see-through surface's fragment is none).
inline float midpointDepth(const ImageBlock& block, const SampleHit* hits, const int32_t* own, const int32_t* shared,
                           ResolveScratch& scratch) {
    const int S = block.samplesPerPixel();
    float best = kInf;
    for (int j = 0; j < S; ++j) {
        float z1 = kInf, z2 = kInf;
        auto add = [&](float z) {
            if (z < z1) z2 = z1, z1 = z;
            else if (z < z2) z2 = z;
        };
        if (hits[j].z < kInf) add(hits[j].z);
        if (!block.solids()) {
            for (const int32_t* heads : {own, shared})
                if (heads)
                    for (int32_t k = heads[j]; k >= 0; k = block.fragment(k).next) add(block.fragment(k).z);
        } else {
            std::vector<SampleFragment>& frags = scratch.fragments;
            frags.clear();
            for (const int32_t* heads : {own, shared})
                if (heads)
                    for (int32_t k = heads[j]; k >= 0; k = block.fragment(k).next) frags.push_back(block.fragment(k));
            std::sort(frags.begin(), frags.end(), [](const SampleFragment& x, const SampleFragment& y) { return x.before(y); });
            scratch.solidWalk.reset(*block.solids());
            for (const SampleFragment& f : frags) {
                if (f.solid >= 0 && (!scratch.solidWalk.cross(solidLeafOf(f.solid), solidEnters(f.solid)) ||
                                     f.t == Color{1, 1, 1}))
                    continue;
                add(f.z);
            }
        }
        if (z2 < kInf) best = std::min(best, 0.5f * (z1 + z2));
    }
    return best;
}

// Gathers what `hitsOf(pixel index)` holds around tile pixel (x, y): R G B A weighted. The
// neighbours and samples are visited in one fixed order whatever the hits come from, so the same
// hits give the same bits.
template <typename HitsOf>
inline void gather(const ImageBlock& block, const FilterWeights& fw, int x, int y, float weightSum, HitsOf hitsOf,
                   float* out) {
    const PixelRect& R = block.rect();
    const int S = block.samplesPerPixel(), gx = fw.reachX(), gy = fw.reachY();
    Float4 acc = {0, 0, 0, 0};
    for (int py = std::max(R.y0, y - gy); py <= std::min(R.y1, y + gy); ++py)
        for (int px = std::max(R.x0, x - gx); px <= std::min(R.x1, x + gx); ++px) {
            const CompositeSample* h = hitsOf(block.pixelIndex(px, py));
            const float* w = fw.weights(block.patternOf(block.pixelIndex(px, py)), x - px, y - py);
            for (int j = 0; j < S; ++j) accumulate(acc, w[j], h[j]);
        }
    normalise(acc, std::fabs(weightSum) > 1e-8f ? 1.0f / weightSum : 0.0f, out);
}

// gather for the four tile pixels (x .. x + 3, y), whose filters lie inside the block in x: each
// pixel's sum is made in gather's order, so with gather's bits, but the four are interleaved. One
// pixel's sum is a chain of dependent adds, waiting on each other; four chains keep the adder busy.
constexpr int kGatherRun = 4;
inline bool gatherRunFits(const PixelRect& R, const FilterWeights& fw, int x) {
    return x - fw.reachX() >= R.x0 && x + kGatherRun - 1 + fw.reachX() <= R.x1;
}
template <typename HitsOf>
inline void gatherRun(const ImageBlock& block, const FilterWeights& fw, int x, int y, const float* weightSums,
                      HitsOf hitsOf, float* const* out) {
    const PixelRect& R = block.rect();
    const int S = block.samplesPerPixel(), gx = fw.reachX(), gy = fw.reachY();
    Float4 acc[kGatherRun] = {};
    for (int py = std::max(R.y0, y - gy); py <= std::min(R.y1, y + gy); ++py)
        for (int ox = -gx; ox <= gx; ++ox) {  // pixel k's neighbour x + k + ox
            const CompositeSample* h[kGatherRun];
            const float* w[kGatherRun];
            for (int k = 0; k < kGatherRun; ++k) {
                const size_t pi = block.pixelIndex(x + k + ox, py);
                h[k] = hitsOf(pi);
                w[k] = fw.weights(block.patternOf(pi), -ox, y - py);
            }
            for (int j = 0; j < S; ++j)
                for (int k = 0; k < kGatherRun; ++k) accumulate(acc[k], w[k][j], h[k][j]);
        }
    for (int k = 0; k < kGatherRun; ++k)
        normalise(acc[k], std::fabs(weightSums[k]) > 1e-8f ? 1.0f / weightSums[k] : 0.0f, out[k]);
}

// Gathers the tile pixels `wanted(t)` picks (t: index in the tile) into outOf(t), four neighbours
// at once (gatherRun) where all four are wanted and their filters lie inside the block, one at a
// time elsewhere: R G B A from hitsOf (pixel index -> its samples' CompositeSamples), Z from the
// pixel's own samples, depthOf(pixel index); then finish(x, y, out) for each.
template <typename Wanted, typename HitsOf, typename DepthOf, typename OutOf, typename Finish>
void gatherTile(const ImageBlock& block, const FilterWeights& fw, const PixelRect& tile, const float* weightSums,
                Wanted wanted, HitsOf hitsOf, DepthOf depthOf, OutOf outOf, Finish finish) {
    const int tw = tile.width();
    for (int y = tile.y0; y <= tile.y1; ++y)
        for (int x = tile.x0; x <= tile.x1;) {
            const size_t t = size_t(y - tile.y0) * size_t(tw) + size_t(x - tile.x0);
            if (!wanted(t)) {
                ++x;
                continue;
            }
            bool run = x + kGatherRun - 1 <= tile.x1 && gatherRunFits(block.rect(), fw, x);
            for (int k = 1; run && k < kGatherRun; ++k) run = wanted(t + size_t(k));
            if (run) {
                float* outs[kGatherRun];
                for (int k = 0; k < kGatherRun; ++k) outs[k] = outOf(t + size_t(k));
                gatherRun(block, fw, x, y, weightSums + t, hitsOf, outs);
                for (int k = 0; k < kGatherRun; ++k) {
                    outs[k][4] = depthOf(block.pixelIndex(x + k, y));
                    finish(x + k, y, outs[k]);
                }
                x += kGatherRun;
                continue;
            }
            float* out = outOf(t);
            gather(block, fw, x, y, weightSums[t], hitsOf, out);
            out[4] = depthOf(block.pixelIndex(x, y));
            finish(x, y, out);
            ++x;
        }
}

// The output variables of tile pixel (x, y) from `samplesOf` (pixel index -> its S hits and their
// S x A floats): the weighted mean over the samples that hit (coverage-aware: see film.h).
template <typename SamplesOf>
void gatherAovs(const ImageBlock& block, const FilterWeights& fw, int x, int y, SamplesOf samplesOf, float* acc,
                float* out) {
    const PixelRect& R = block.rect();
    const int S = block.samplesPerPixel(), gx = fw.reachX(), gy = fw.reachY(), A = block.aovCount();
    std::fill(acc, acc + A, 0.0f);
    float sum = 0;
    for (int py = std::max(R.y0, y - gy); py <= std::min(R.y1, y + gy); ++py)
        for (int px = std::max(R.x0, x - gx); px <= std::min(R.x1, x + gx); ++px) {
            const size_t i = block.pixelIndex(px, py);
            const auto [h, av] = samplesOf(i);
            const float* w = fw.weights(block.patternOf(i), x - px, y - py);
            for (int j = 0; j < S; ++j) {
                if (h[j].empty() || w[j] == 0) continue;
                sum += w[j];
                for (int a = 0; a < A; ++a) acc[a] += w[j] * av[size_t(j) * size_t(A) + size_t(a)];
            }
        }
    const float inv = std::fabs(sum) > 1e-8f ? 1.0f / sum : 0.0f;
    for (int a = 0; a < A; ++a) out[a] = acc[a] * inv;
}

// A sample with no fragments: its opaque hit, of coverage 1 where it has a depth. The hit's
// z r g b in one register, z replaced by that coverage (SampleHit::empty's test).
inline CompositeSample opaqueSample(const SampleHit& h) {
    if (matteHit(h)) return {0.0f, {0, 0, 0}};  // a holdout: nothing (Matte 1)
    using Int4 = int32_t __attribute__((vector_size(16)));
    Float4 v;
    std::memcpy(&v, &h.z, sizeof v);
    const Int4 rgbLanes = {0, -1, -1, -1}, one = {0x3f800000, 0, 0, 0};  // 1.0f in lane 0
    const Int4 covered = v < Float4{kInf, kInf, kInf, kInf};
    v = Float4((Int4(v) & rgbLanes) | (covered & one));
    CompositeSample s;
    std::memcpy(static_cast<void*>(&s), &v, sizeof s);
    return s;
}

// The sample whose opaque hit is `opaque` and whose fragments are in lists `a` and `b` (-1: none),
// composited (film.h): the composited alpha and colour. Crossings of solids' boundaries are drawn
// only where they bound a solid's result (geom/solid_tree.h), walked nearest first with the rest.
CompositeSample composite(const ImageBlock& block, const SampleHit& opaque, int32_t a, int32_t b,
                          std::vector<SampleFragment>& frags, SolidWalk& walk) {
    if (a < 0 && b < 0) return opaqueSample(opaque);
    frags.clear();
    for (int32_t list : {a, b})
        for (int32_t k = list; k >= 0; k = block.fragment(k).next) {
            const SampleFragment& f = block.fragment(k);
            if (opaque.beatenBy(f.z, f.id, f.c)) frags.push_back(f);
        }
    if (frags.empty()) return opaqueSample(opaque);
    std::sort(frags.begin(), frags.end(), [](const SampleFragment& x, const SampleFragment& y) { return x.before(y); });
    OverComposite over;
    bool walking = false;
    for (const SampleFragment& f : frags) {
        if (f.solid >= 0 && block.solids()) {
            if (!walking) walk.reset(*block.solids()), walking = true;
            if (!walk.cross(solidLeafOf(f.solid), solidEnters(f.solid))) continue;  // inside or outside the result
        }
        over.add(f.c, f.t);
    }
    // Over a matte's hit (a holdout): what is in front of it over nothing.
    const bool matte = matteHit(opaque);
    return {over.alpha(opaque.empty() || matte ? 0.0f : 1.0f), over.c + over.t * (matte ? Color{0, 0, 0} : opaque.c)};
}

// With solids: the samples' hits with each depth the nearest opaque surface, which may be a
// solid's crossing that the walk keeps (composite's walk again, for the depth filters). Into
// scratch.solidHits; `own` and `shared` the samples' lists (null: none).
const SampleHit* solidDepths(const ImageBlock& block, const SampleHit* hits, const int32_t* own,
                             const int32_t* shared, ResolveScratch& scratch) {
    const int S = block.samplesPerPixel();
    scratch.solidHits.assign(hits, hits + S);
    std::vector<SampleFragment>& frags = scratch.fragments;
    for (int j = 0; j < S; ++j) {
        frags.clear();
        for (const int32_t* heads : {own, shared})
            if (heads)
                for (int32_t k = heads[j]; k >= 0; k = block.fragment(k).next) {
                    const SampleFragment& f = block.fragment(k);
                    if (f.solid >= 0 && hits[j].beatenBy(f.z, f.id, f.c)) frags.push_back(f);
                }
        if (frags.empty()) continue;
        std::sort(frags.begin(), frags.end(), [](const SampleFragment& x, const SampleFragment& y) { return x.before(y); });
        scratch.solidWalk.reset(*block.solids());
        for (const SampleFragment& f : frags)
            if (scratch.solidWalk.cross(solidLeafOf(f.solid), solidEnters(f.solid)) && f.t == Color{0, 0, 0}) {
                scratch.solidHits[size_t(j)].z = f.z;  // an opaque surface of a solid's result
                break;
            }
    }
    return scratch.solidHits.data();
}

// With solids and output variables: a sample whose nearest opaque surface is a solid's crossing
// the walk keeps (solidDepths' surface) shows that crossing's variables, as its colour does, and
// counts as a hit. The samples' hits and variables into scratch.solidHits and scratch.solidAov.
void solidSurfaces(const ImageBlock& block, const SampleHit* hits, const float* aovs, const int32_t* own,
                   const int32_t* shared, ResolveScratch& scratch) {
    const int S = block.samplesPerPixel();
    const size_t A = size_t(block.aovCount());
    scratch.solidHits.assign(hits, hits + S);
    scratch.solidAov.assign(aovs, aovs + size_t(S) * A);
    std::vector<int32_t>& ks = scratch.fragmentIndices;
    for (int j = 0; j < S; ++j) {
        ks.clear();
        for (const int32_t* heads : {own, shared})
            if (heads)
                for (int32_t k = heads[j]; k >= 0; k = block.fragment(k).next) {
                    const SampleFragment& f = block.fragment(k);
                    if (f.solid >= 0 && hits[j].beatenBy(f.z, f.id, f.c)) ks.push_back(k);
                }
        if (ks.empty()) continue;
        std::sort(ks.begin(), ks.end(), [&](int32_t x, int32_t y) { return block.fragment(x).before(block.fragment(y)); });
        scratch.solidWalk.reset(*block.solids());
        for (const int32_t k : ks) {
            const SampleFragment& f = block.fragment(k);
            if (scratch.solidWalk.cross(solidLeafOf(f.solid), solidEnters(f.solid)) && f.t == Color{0, 0, 0}) {
                scratch.solidHits[size_t(j)].z = f.z;
                std::copy(block.fragmentAov(k), block.fragmentAov(k) + A, &scratch.solidAov[size_t(j) * A]);
                break;
            }
        }
    }
}

// Frame fi's samples of pixel i for its output variables, with solids (solidSurfaces). Out of
// line, so that resolveTile's code for scenes without solids stays as it was.
__attribute__((noinline)) std::pair<const SampleHit*, const float*> frameSolidSurfaces(const ImageBlock& block, int fi,
                                                                                      size_t i, ResolveScratch& scratch) {
    const SampleHit* rec = block.record(fi, i);
    const bool own = rec != nullptr;
    solidSurfaces(block, own ? rec : block.still(i), own ? block.aovs(fi, i) : block.stillAov(i),
                  own ? block.recordFragments(fi, i) : block.stillFragments(i),
                  own && !block.dense() ? block.stillFragments(i) : nullptr, scratch);
    return {scratch.solidHits.data(), scratch.solidAov.data()};
}

}  // namespace

void resolveTile(const ImageBlock& block, const FilterWeights& fw, TiledFrames& frames, size_t tileIndex,
                 ResolveScratch& scratch) {
    TiledFrames::Tile& out = frames.tile(tileIndex);
    const PixelRect& tile = out.rect();
    const PixelRect& R = block.rect();
    const int tw = tile.width(), F = block.frameCount(), S = block.samplesPerPixel();
    const int gx = fw.reachX(), gy = fw.reachY();
    const size_t tilePixels = size_t(tw) * size_t(tile.height());

    // The weights each tile pixel sees: the same in every frame. Summed in gather's order, four
    // neighbours at once where their filters lie inside the block (as gatherRun).
    scratch.weightSum.assign(tilePixels, 0.0f);
    for (int y = tile.y0; y <= tile.y1; ++y)
        for (int x = tile.x0; x <= tile.x1;) {
            float* sums = &scratch.weightSum[size_t(y - tile.y0) * size_t(tw) + size_t(x - tile.x0)];
            const int n = x + kGatherRun - 1 <= tile.x1 && gatherRunFits(R, fw, x) ? kGatherRun : 1;
            float sum[kGatherRun] = {};
            for (int py = std::max(R.y0, y - gy); py <= std::min(R.y1, y + gy); ++py)
                for (int ox = -gx; ox <= gx; ++ox) {
                    if (n == 1 && (x + ox < R.x0 || x + ox > R.x1)) continue;
                    const float* w[kGatherRun];
                    for (int k = 0; k < n; ++k)
                        w[k] = fw.weights(block.patternOf(block.pixelIndex(x + k + ox, py)), -ox, y - py);
                    if (n == 1)
                        for (int j = 0; j < S; ++j) sum[0] += w[0][j];
                    else
                        for (int j = 0; j < S; ++j)
                            for (int k = 0; k < kGatherRun; ++k) sum[k] += w[k][j];
                }
            std::copy(sum, sum + n, sums);
            x += n;
        }

    // What the filter reads of each sample, A R G B (CompositeSample): its see-through
    // fragments composited over its opaque hit, or the hit and its coverage. The still layer's
    // here; a frame's when its gather first asks for a pixel with a record. Made once, where the
    // gather reads each sample once for every pixel its filter reaches.
    const bool dense = block.dense();
    const bool fragments = block.hasFragments();
    const size_t blockPixels = size_t(block.pixelCount());
    if (!dense) {
        scratch.stillComposite.resize(blockPixels * size_t(S));
        for (size_t i = 0; i < blockPixels; ++i) {
            const SampleHit* h = block.still(i);
            CompositeSample* to = &scratch.stillComposite[i * size_t(S)];
            if (const int32_t* heads = fragments ? block.stillFragments(i) : nullptr)
                for (int j = 0; j < S; ++j) to[j] = composite(block, h[j], heads[j], -1, scratch.fragments, scratch.solidWalk);
            else
                for (int j = 0; j < S; ++j) to[j] = opaqueSample(h[j]);
        }
    }
    scratch.frameComposite.resize(blockPixels * size_t(S));
    scratch.compositedFrame.assign(blockPixels, -1);
    auto stillHits = [&](size_t i) -> const CompositeSample* { return &scratch.stillComposite[i * size_t(S)]; };
    auto frameHits = [&](int fi, size_t i) -> const CompositeSample* {
        const SampleHit* rec = block.record(fi, i);
        if (!rec) return stillHits(i);
        CompositeSample* to = &scratch.frameComposite[i * size_t(S)];
        if (scratch.compositedFrame[i] != fi) {
            if (fragments) {
                const int32_t* own = block.recordFragments(fi, i);
                const int32_t* shared = dense ? nullptr : block.stillFragments(i);
                for (int j = 0; j < S; ++j)
                    to[j] = composite(block, rec[j], own[j], shared ? shared[j] : -1, scratch.fragments, scratch.solidWalk);
            } else
                for (int j = 0; j < S; ++j) to[j] = opaqueSample(rec[j]);
            scratch.compositedFrame[i] = fi;
        }
        return to;
    };

    // Pixels' depths: from their own samples' opaque hits, or for "midpoint" from every surface
    // they cross (the fragments a depth pass keeps).
    const bool midpoint = fw.depthFilter() == DepthFilter::Midpoint;
    const bool solidFragments = fragments && block.solids();  // depths may be solids' (solidDepths)
    auto stillDepth = [&](size_t i) {
        if (!midpoint && solidFragments)
            return pixelDepth(block, fw, solidDepths(block, block.still(i), block.stillFragments(i), nullptr, scratch));
        if (!midpoint) return pixelDepth(block, fw, block.still(i));
        return midpointDepth(block, block.still(i), fragments ? block.stillFragments(i) : nullptr, nullptr, scratch);
    };
    auto frameDepth = [&](int fi, size_t i) {
        const SampleHit* rec = block.record(fi, i);
        if (!rec) return stillDepth(i);
        if (!midpoint && solidFragments)
            return pixelDepth(block, fw,
                              solidDepths(block, rec, block.recordFragments(fi, i), dense ? nullptr : block.stillFragments(i),
                                          scratch));
        if (!midpoint) return pixelDepth(block, fw, rec);
        return midpointDepth(block, rec, fragments ? block.recordFragments(fi, i) : nullptr,
                             fragments && !dense ? block.stillFragments(i) : nullptr, scratch);
    };

    // The still layer, resolved once for every frame that shows it.
    if (!dense) {
        scratch.still.resize(tilePixels * 5);
        gatherTile(
            block, fw, tile, scratch.weightSum.data(), [](size_t) { return true; }, stillHits, stillDepth,
            [&](size_t t) { return &scratch.still[t * 5]; }, [](int, int, float*) {});
    }

    // Output variables likewise, weighed by the opaque hits: the still layer's once, a frame's own
    // where it has records near.
    // A solid's crossing may be a sample's surface (solidSurfaces).
    const int A = block.aovCount();
    const size_t Az = size_t(A);
    using Samples = std::pair<const SampleHit*, const float*>;
    auto stillSamples = [&](size_t i) -> Samples {
        if (!solidFragments) return {block.still(i), block.stillAov(i)};
        solidSurfaces(block, block.still(i), block.stillAov(i), block.stillFragments(i), nullptr, scratch);
        return {scratch.solidHits.data(), scratch.solidAov.data()};
    };
    if (A > 0) {
        scratch.aov.resize(Az);
        if (!dense) {
            scratch.stillAov.resize(tilePixels * Az);
            for (int y = tile.y0; y <= tile.y1; ++y)
                for (int x = tile.x0; x <= tile.x1; ++x)
                    gatherAovs(block, fw, x, y, stillSamples, scratch.aov.data(),
                               &scratch.stillAov[(size_t(y - tile.y0) * size_t(tw) + size_t(x - tile.x0)) * Az]);
        }
    }

    // Where the pixels go: frame fi of the block is slot firstSlot + fi of `frames`. A bucket that
    // spans all of its frames stores the still layer's pixels once, for every frame that shows only
    // them; output variables are written when the frames ask for the block's (zeros otherwise).
    const int C = out.channels();
    const bool writeAov = A > 0 && size_t(C - 5) == Az;
    const int firstSlot = block.firstFrame() - frames.firstFrame();
    const bool shareStill = !dense && block.frameCount() == frames.frameCount();
    auto putStill = [&](size_t t, float* px) {
        std::copy(&scratch.still[t * 5], &scratch.still[t * 5] + 5, px);
        if (writeAov) std::copy(&scratch.stillAov[t * Az], &scratch.stillAov[t * Az] + Az, px + 5);
        else std::fill(px + 5, px + C, 0.0f);
    };
    if (shareStill) {
        float* px = out.still();
        for (size_t t = 0; t < tilePixels; ++t) putStill(t, px + t * size_t(C));
    }

    // Per frame: the tile pixels whose filter reaches a pixel with a record of that frame are
    // gathered again; the others show the still layer.
    scratch.gathered.resize(tilePixels);
    for (int fi = 0; fi < F; ++fi) {
        std::fill(scratch.gathered.begin(), scratch.gathered.end(), uint8_t(dense));
        bool moving = dense;
        if (!dense)
            for (int py = R.y0; py <= R.y1; ++py)
                for (int px = R.x0; px <= R.x1; ++px) {
                    if (!block.hasRecord(fi, block.pixelIndex(px, py))) continue;
                    for (int y = std::max(tile.y0, py - gy); y <= std::min(tile.y1, py + gy); ++y)
                        for (int x = std::max(tile.x0, px - gx); x <= std::min(tile.x1, px + gx); ++x) {
                            scratch.gathered[size_t(y - tile.y0) * size_t(tw) + size_t(x - tile.x0)] = 1;
                            moving = true;
                        }
                }
        if (shareStill && !moving) {
            out.showStill(firstSlot + fi);
            continue;
        }
        float* own = out.own(firstSlot + fi);
        for (size_t t = 0; t < tilePixels; ++t)
            if (!scratch.gathered[t]) putStill(t, own + t * size_t(C));
        auto outputVariables = [&](int x, int y, float* px) {
            if (writeAov)
                gatherAovs(
                    block, fw, x, y,
                    [&](size_t i) -> Samples {
                        if (!solidFragments) return {block.hits(fi, i), block.aovs(fi, i)};
                        return frameSolidSurfaces(block, fi, i, scratch);
                    },
                    scratch.aov.data(), px + 5);
            else
                std::fill(px + 5, px + C, 0.0f);
        };
        gatherTile(
            block, fw, tile, scratch.weightSum.data(), [&](size_t t) { return scratch.gathered[t] != 0; },
            [&](size_t i) { return frameHits(fi, i); }, [&](size_t i) { return frameDepth(fi, i); },
            [&](size_t t) { return own + t * size_t(C); }, outputVariables);
    }
}

void applyExposure(FrameImage& image, double gain, double gamma) {
    if (gain == 1 && gamma == 1) return;
    const float g = float(gain), invGamma = float(1 / gamma);
    for (size_t p = 0; p < image.rgba.size(); p += 4)
        for (size_t c = 0; c < 3; ++c) {
            float& v = image.rgba[p + c];
            v *= g;
            if (gamma != 1 && v > 0) v = std::pow(v, invGamma);
        }
}

}  // namespace streyes
