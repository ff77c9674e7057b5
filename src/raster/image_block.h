// The samples of one bucket: a block of pixels (a tile plus the filter's guard band) times a
// block of frames, S samples per pixel per frame.
//
// A pixel's samples lie at the same sub-pixel positions in every frame (sample_pattern.h), so
// what is still in raster space over the whole block is sampled once: into the *still layer*,
// S hits per pixel that every frame sees. A frame gets its own *record* of a pixel (S hits, a
// copy of the still layer to start from) only when something that frame alone sees (a moving
// grid, or a still one that exists in part of the block) comes nearer than the still layer at one
// of its samples. Resolving (film.h) then filters the still layer once for the block and only the
// pixels near a record again per frame. In *dense* mode every frame has a record of every pixel
// from the start and the still layer is unused: for the ray tracer, and for shadows tested per
// sample, whose rays leave every sample at its own time. Shadows tested at still grids' vertices
// keep the block sparse: a still grid whose shadows are folded into its colour writes the still
// layer, any other grid the records, which carry its lights' parts for the per-sample test.
//
// Layout: pixel index i = (y - y0) * width + (x - x0); sample j of a pixel is in (x, y) stratum
// (j % sx, j / sx). A still micropolygon visits only the strata its bound overlaps; a moving one
// is bounded over one time slice at a time and needs the one sample per pixel in that slice
// (sampleOfStratum). Records sit in chunks, so a record never moves once made.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "geom/solid_tree.h"
#include "raster/sample_pattern.h"
#include "streyes/render_options.h"
#include "streyes/vecmath.h"

namespace streyes {

// The id of "no primitive": no hit yet.
constexpr uint64_t kNoPrimitive = UINT64_MAX;

// A sample's nearest opaque hit so far. A hit covers its sample fully: there is one exactly where
// z < +inf (Camera clamps the far plane to the largest finite float), so coverage is not stored.
// 24 bytes: a render bucket's still layer (66 x 66 pixels of 16 samples) is 1.7 MB, 2.2 MB at 32,
// so that with the sample positions (0.56 MB) it nearly fits 2 MB of L2; see-through coverage
// lives in fragments (below).
struct SampleHit {
    float z;      // camera-space depth of the nearest hit so far; +inf when none
    Color c;      // colour of that hit
    uint64_t id;  // primitive of that hit (kNoPrimitive when none)

    // No opaque hit yet: coverage 0 (else 1).
    bool empty() const { return !(z < std::numeric_limits<float>::infinity()); }

    // Whether a hit (z, id, c) beats this one. Lexicographic on (depth, primitive, colour): the
    // result does not depend on the order hits arrive in, and at equal depth the primitive
    // with the smaller id wins (ids are numbered by kind of primitive: BodyFactory::addPrimitives).
    bool beatenBy(float z2, uint64_t id2, Color c2) const {
        if (z2 != z) return z2 < z;
        if (id2 != id) return id2 < id;
        if (c2.x != c.x) return c2.x < c.x;
        if (c2.y != c.y) return c2.y < c.y;
        return c2.z < c.z;
    }
};
// The resolve reads a hit's z r g b as four floats side by side (film.cpp's accumulate), and the
// still kernel writes them so (sample_kernels.cpp).
static_assert(offsetof(SampleHit, c) == sizeof(float) && offsetof(SampleHit, id) == 4 * sizeof(float) &&
              sizeof(SampleHit) == 24);
// The top bit of a hit's or fragment's id marks a matte surface's (a holdout's, Matte 1): resolving
// gives such an opaque hit colour 0 and alpha 0, while it hides and culls as any opaque hit does.
// The other bits name the primitive (procedurals' children have hashed ids that may set the top
// bit: it is cleared for every surface that is no matte, hitId).
constexpr uint64_t kMatteBit = uint64_t(1) << 63;
constexpr uint64_t hitId(uint64_t primitiveId, bool matte) {
    return matte ? primitiveId | kMatteBit : primitiveId & ~kMatteBit;
}
// Whether a sample's opaque hit is a matte's (an empty hit is none).
inline bool matteHit(const SampleHit& h) { return (h.id & kMatteBit) != 0 && h.id != kNoPrimitive; }

constexpr SampleHit kNoHit{std::numeric_limits<float>::infinity(), {0, 0, 0}, kNoPrimitive};

// A see-through hit (Oi < 1 in some channel) of a sample. Kept apart from SampleHit, in a list per
// sample, and composited in depth order when the block is resolved (film.h): the SampleHit stays
// the nearest *opaque* hit, so what hides a micropolygon, what the occlusion tables count and what
// culls are opaque coverage only, and a fragment behind the final opaque hit is dropped whatever
// order the two arrived in.
struct SampleFragment {
    float z;
    Color c;       // Ci (premultiplied by Oi, as shaders give it)
    Color t;       // what it lets through, per channel: 1 - Oi
    uint64_t id;   // primitive: with z and c orders fragments independently of arrival
    int32_t next;  // the sample's next fragment (unordered), or -1
    // A crossing of a solid's boundary (geom/solid_tree.h solidTag: its leaf and whether it enters),
    // resolved when the block is: drawn only where it bounds the solid's result. -1: any other
    // surface. In what was padding: the fragment stays 48 bytes.
    int32_t solid = -1;

    // The order fragments are composited in, nearest first: SampleHit::beatenBy's.
    bool before(const SampleFragment& b) const { return SampleHit{b.z, b.c, b.id}.beatenBy(z, id, c); }
};
static_assert(sizeof(SampleFragment) == 48);

class ImageBlock {
  public:
    // Sizes the block, places the samples and clears the hits (reusing memory). shadowSlots > 0
    // also keeps, with each record's hits, the contribution of each light that casts shadows
    // before its shadow test (shadowed()), per record; the still layer of a sparse block holds
    // only hits whose shadows are in their colour (Grid::stillShadows == kFoldedShadows), and a
    // record made from it starts so. `lens` also places each sample's
    // lens position (depth of field: lus(), lvs()).
    void reset(const PixelRect& rect, int firstFrame, int frameCount, const PatternTable& patterns, bool dense,
               int shadowSlots = 0, bool lens = false);

    const PixelRect& rect() const { return rect_; }
    int firstFrame() const { return firstFrame_; }
    int frameCount() const { return frameCount_; }
    const PatternTable& patterns() const { return *patterns_; }
    const SamplePattern& pattern() const { return patterns_->pattern(); }
    int samplesPerPixel() const { return S_; }  // per frame; also the number of time slices
    // Kept beside rect_ at reset: the samplers index pixels and frames for every pixel they visit.
    int pixelCount() const { return pixels_; }
    size_t pixelIndex(int x, int y) const { return size_t(y - rect_.y0) * size_t(width_) + size_t(x - rect_.x0); }
    bool dense() const { return dense_; }

    // The pattern of pixel i (PatternTable::patternOf, kept: resolving asks for it often).
    int patternOf(size_t i) const { return int(pattern_[i]); }
    // Raster positions of sample j of pixel i: xs()[i * S + j], ys()[i * S + j], made by reset
    // from the pixel's pattern (float(x) + offsets[2 j], PatternTable::offsets). Read-only: the
    // moving sampler computes them from the pattern instead, with the same bits.
    const float* xs() const { return xs_.data(); }
    const float* ys() const { return ys_.data(); }
    // With depth of field, the unit-disc lens position of sample j of pixel i: lus()[i * S + j],
    // lvs()[i * S + j], the same in every frame (PatternTable::lens). Null without.
    bool hasLens() const { return lens_; }
    const float* lus() const { return lens_ ? lus_.data() : nullptr; }
    const float* lvs() const { return lens_ ? lvs_.data() : nullptr; }

    // Time: the permutation of pixel i in frame fi (PatternTable: stratumOfSample,
    // sampleOfStratum, stratumTimes). The sample of slice k is sampleOfStratum(q)[k]. A frame's
    // permutations are made when first needed (a still scene never needs them), a pixel at a
    // time (a moving grid that reaches a few pixels of a bucket hashes only those):
    // needTimes(fi) before permutation(fi, ...).
    void needTimes(int fi) const {
        if (!timesMade_[size_t(fi)]) makeTimes(fi);
    }
    int permutation(int fi, size_t i) const {
        uint8_t& q = permutation_[size_t(fi) * size_t(pixelCount()) + i];
        if (q == kUnmade) q = makePermutation(fi, i);
        return int(q);
    }
    // For tests: pixel i of frame fi takes the table's permutation q instead.
    void setPermutation(int fi, size_t i, int q) {
        needTimes(fi);
        permutation_[size_t(fi) * size_t(pixelCount()) + i] = uint8_t(q);
    }
    float sampleTime(int fi, size_t i, int j) const {
        const int q = permutation(fi, i);
        return patterns_->stratumTimes(q)[patterns_->stratumOfSample(q)[j]];
    }
    // A level of detail's dissolve (Grid::dissolveLo/Hi): whether sample j of pixel i is one of
    // the share [lo, hi) of frame fi's samples that sees a dissolving surface. The pixel's samples
    // are ranked in that frame by one of the table's permutations, half the table away from the one
    // that orders their times (so that the share does not follow the time within the exposure): a
    // pure function of the pixel, frame and seed, as sample times are; two representations whose
    // shares split [0, 1) are seen by complementary samples. needTimes(fi) first.
    bool dissolveKeeps(int fi, size_t i, int j, float lo, float hi) const {
        const int Q = patterns_->permutationCount();
        const int q = (permutation(fi, i) + Q / 2) % Q;
        const float u = (float(patterns_->stratumOfSample(q)[j]) + 0.5f) / float(S_);
        return u >= lo && u < hi;
    }
    SamplePosition position(int fi, size_t i, int j) const {
        needTimes(fi);
        const size_t s = i * size_t(S_) + size_t(j);
        return {xs_[s], ys_[s], sampleTime(fi, i, j)};
    }

    // The still layer: S hits per pixel, seen by every frame without a record of the pixel.
    SampleHit* still(size_t i) { return &still_[i * size_t(S_)]; }
    const SampleHit* still(size_t i) const { return &still_[i * size_t(S_)]; }
    // Frame fi's own record of pixel i (S hits), or null when it has none and sees the still layer.
    SampleHit* record(int fi, size_t i) {
        const int32_t r = slotOf(fi, i);
        return r < 0 ? nullptr : recordAt(uint32_t(r));
    }
    const SampleHit* record(int fi, size_t i) const { return const_cast<ImageBlock*>(this)->record(fi, i); }
    bool hasRecord(int fi, size_t i) const { return slotOf(fi, i) >= 0; }
    // How many frames have a record of pixel i (a hit on the still layer must reach them too).
    int recordsOf(size_t i) const { return dense_ ? frameCount_ : int(recordsOf_[i]); }
    // Makes frame fi's record of pixel i, a copy of the still layer (which it then differs from).
    SampleHit* makeRecord(int fi, size_t i);
    // What frame fi sees at pixel i: its record, or the still layer.
    const SampleHit* hits(int fi, size_t i) const {
        const SampleHit* r = record(fi, i);
        return r ? r : still(i);
    }
    size_t recordCount() const { return records_; }
    // Frame fi's bound on the farthest depth pixel i's samples see, |value|: -inf until measured,
    // then what was last measured, negated (stale) when a hit replaces the sample that was the
    // farthest, so that it is measured again only then. A sample's depth only comes nearer (a hit
    // replaces it only when it beats it; a record starts as a copy of the still layer), so a
    // measured value stays a bound, and a quad behind it is hidden from every sample of the
    // pixel: one float read instead of the S hits (GridRasterizer::sampleMoving, deep in foliage).
    float& farthestBound(int fi, size_t i) {
        if (!rowMade_[size_t(fi)]) makeRow(fi);
        return farthest_[size_t(fi) * size_t(pixelCount()) + i];
    }
    // Pixels an opaque hit was written to (in the still layer or a record) since the occlusion
    // coverage last measured them (raster/coverage.h): the samplers touch what they write, and a
    // pixel left untouched keeps the farthest hit coverage measured. Depths only come nearer, so
    // a write that is not marked only leaves that measure a looser bound (less is culled, not
    // more). A new block has nothing to measure again: an empty pixel's farthest hit is +inf.
    void touch(size_t i) { touched_[i] = 1; }
    bool touched(size_t i) const { return touched_[i] != 0; }
    void untouchAll() { std::fill(touched_.begin(), touched_.end(), uint8_t(0)); }
    // The still layer, the touch flags and recordsOf's counts as arrays (a sparse block's), for
    // the still kernel that writes them itself (sample_kernels.h, StillWrite).
    SampleHit* stillLayer() { return still_.data(); }
    uint8_t* touchFlags() { return touched_.data(); }
    const uint16_t* recordCounts() const { return recordsOf_.data(); }

    // With shadows: the shadowed parts of the S hits of frame fi's record of pixel i (which it
    // must have), shadowSlots() colours each, valid where a sample has a hit.
    int shadowSlots() const { return shadowSlots_; }
    Color* shadowed(int fi, size_t i);
    // Beside them, one flag a sample: non-zero where its parts already carry the still occluders'
    // shadow (tested at the still grid's vertices: Grid::stillShadows, whose bits it holds), so that its own
    // shadow rays test only what moves (trace.h, SampleTracer::shadeShadows).
    uint8_t* stillTested(int fi, size_t i) { return &stillTested_[size_t(slotOf(fi, i)) * size_t(S_)]; }

    // Output variables (util/aov.h): aovCount() floats per sample beside each hit, in arrays
    // parallel to the still layer and the records (a record's copy of the still layer copies them
    // too). Set before reset(); 0 (the default) keeps none.
    void setAovCount(int n) { aovs_ = n; }
    int aovCount() const { return aovs_; }
    float* stillAov(size_t i) { return &stillAov_[i * size_t(S_) * size_t(aovs_)]; }
    const float* stillAov(size_t i) const { return &stillAov_[i * size_t(S_) * size_t(aovs_)]; }
    float* recordAov(int fi, size_t i) {
        const int32_t r = slotOf(fi, i);
        return r < 0 ? nullptr : recordAovAt(uint32_t(r));
    }
    // What frame fi sees at pixel i: its record's, or the still layer's (S x aovCount() floats).
    const float* aovs(int fi, size_t i) const {
        const int32_t r = slotOf(fi, i);
        return r < 0 ? &stillAov_[i * size_t(S_) * size_t(aovs_)] : const_cast<ImageBlock*>(this)->recordAovAt(uint32_t(r));
    }

    // See-through fragments: lists per sample of the still layer (fragments of still grids every
    // frame sees) and of frames' records (fragments only that frame sees; a frame's list and the
    // still layer's both apply where it has a record). List heads are made when the bucket's
    // first fragment arrives, so blocks without any pay nothing.
    bool hasFragments() const { return fragmentsOn_; }
    int32_t* stillFragments(size_t i) { return &stillHeads_[i * size_t(S_)]; }
    const int32_t* stillFragments(size_t i) const { return &stillHeads_[i * size_t(S_)]; }
    // Frame fi's lists of pixel i: it must have a record (makeRecord).
    int32_t* recordFragments(int fi, size_t i) {
        return &recordHeads_[size_t(slotOf(fi, i)) * size_t(S_)];
    }
    const int32_t* recordFragments(int fi, size_t i) const { return const_cast<ImageBlock*>(this)->recordFragments(fi, i); }
    // Puts f at the head of list `*head` (which startFragments made): its index.
    int32_t addFragment(int32_t* head, SampleFragment f) {
        f.next = *head;
        *head = int32_t(fragments_.size());
        fragments_.push_back(f);
        if (shadowSlots_ > 0) {
            fragmentShadowed_.resize(fragments_.size() * size_t(shadowSlots_));
            fragmentStillTested_.resize(fragments_.size());
        }
        // A solid's crossing may be the surface its sample shows: its output variables are kept.
        if (aovs_ > 0 && f.solid >= 0) fragmentAov_.resize(fragments_.size() * size_t(aovs_));
        return *head;
    }
    // Makes the list heads (call before the first addFragment of a bucket; then a no-op).
    void startFragments() {
        if (!fragmentsOn_) makeFragmentHeads();
    }
    const SampleFragment& fragment(int32_t k) const { return fragments_[size_t(k)]; }
    SampleFragment& fragment(int32_t k) { return fragments_[size_t(k)]; }
    // With shadows: the shadowed parts of fragment k, shadowSlots() colours.
    Color* fragmentShadowed(int32_t k) { return &fragmentShadowed_[size_t(k) * size_t(shadowSlots_)]; }
    uint8_t* fragmentStillTested(int32_t k) { return &fragmentStillTested_[size_t(k)]; }  // as stillTested()
    // With output variables: those of fragment k, a solid's crossing (aovCount() floats; written by
    // the samplers, read where the resolve's walk keeps it as the sample's surface).
    float* fragmentAov(int32_t k) { return &fragmentAov_[size_t(k) * size_t(aovs_)]; }
    const float* fragmentAov(int32_t k) const { return &fragmentAov_[size_t(k) * size_t(aovs_)]; }

    // The scene's solids, which fragments' tags (SampleFragment::solid) point into; null when the
    // scene has none. Set after reset, read when the block is resolved.
    void setSolids(const SolidTree* solids) { solids_ = solids; }
    const SolidTree* solids() const { return solids_; }

    size_t bytes() const;

  private:
    const SolidTree* solids_ = nullptr;
    float* recordAovAt(uint32_t r) {
        return &aovChunks_[r / kRecordsPerChunk][size_t(r % kRecordsPerChunk) * size_t(S_) * size_t(aovs_)];
    }
    void addChunk();
    SampleHit* recordAt(uint32_t r) {
        return &chunks_[r / kRecordsPerChunk][size_t(r % kRecordsPerChunk) * size_t(S_)];
    }
    static constexpr uint32_t kRecordsPerChunk = 256;

    PixelRect rect_;
    int width_ = 0, pixels_ = 0;  // rect_.width(), rect_.area()
    int firstFrame_ = 0, frameCount_ = 0, S_ = 0;
    bool dense_ = false;
    const PatternTable* patterns_ = nullptr;
    std::vector<float> xs_, ys_;
    bool lens_ = false;
    std::vector<float> lus_, lvs_;      // with depth of field only
    std::vector<uint8_t> pattern_;      // per pixel
    void makeTimes(int fi) const;
    uint8_t makePermutation(int fi, size_t i) const;
    static constexpr uint8_t kUnmade = 0xFF;  // a permutation not hashed yet (tables have fewer)
    // Frame fi's record number of pixel i, or -1. A frame's row of record numbers and farthest
    // bounds is written when the frame first needs one (makeRow), not by reset: 8 bytes a pixel a
    // frame, 1.7 MB for a 66-pixel bucket over 48 frames, which a still bucket never reads.
    int32_t slotOf(int fi, size_t i) const {
        return rowMade_[size_t(fi)] ? slot_[size_t(fi) * size_t(pixelCount()) + i] : -1;
    }
    void makeRow(int fi);
    mutable std::vector<uint8_t> permutation_;  // frames x pixels
    mutable std::vector<uint8_t> timesMade_;    // per frame
    mutable std::vector<uint64_t> permutationKeys_;  // per pixel, where keyMade_
    mutable std::vector<uint8_t> keyMade_;           // per pixel, cleared by reset
    std::vector<SampleHit> still_;
    std::vector<int32_t> slot_;         // frames x pixels: record number, or -1
    std::vector<float> farthest_;       // frames x pixels: farthestBound
    std::vector<uint8_t> rowMade_;      // per frame: its rows of slot_ and farthest_ are written
    std::vector<uint16_t> recordsOf_;   // per pixel: frames with a record of it (sparse)
    std::vector<uint8_t> touched_;      // per pixel: touch
    std::vector<std::unique_ptr<SampleHit[]>> chunks_;  // records, kept from bucket to bucket
    size_t chunkSamples_ = 0;           // S x kRecordsPerChunk when the chunks were made
    uint32_t records_ = 0;
    int shadowSlots_ = 0;
    std::vector<Color> shadowed_;       // with shadows: records x S x shadowSlots
    std::vector<uint8_t> stillTested_;  // with shadows: records x S
    int aovs_ = 0;
    std::vector<float> stillAov_;       // pixels x S x aovs_
    std::vector<std::unique_ptr<float[]>> aovChunks_;  // beside chunks_, one to one
    int aovChunkWidth_ = 0;             // aovs_ when aovChunks_ were made
    void makeFragmentHeads();
    bool fragmentsOn_ = false;
    std::vector<int32_t> stillHeads_;    // pixels x S (sparse mode)
    std::vector<int32_t> recordHeads_;   // records x S
    std::vector<SampleFragment> fragments_;
    std::vector<Color> fragmentShadowed_;  // fragments x shadowSlots
    std::vector<uint8_t> fragmentStillTested_;  // per fragment
    std::vector<float> fragmentAov_;            // fragments x aovs_, up to the last solid's
};

}  // namespace streyes
