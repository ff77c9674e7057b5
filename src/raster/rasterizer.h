// Sampling diced grids: which samples of an ImageBlock each micropolygon covers.
//
// A micropolygon is the quad between four neighbouring grid vertices, tested as two triangles
// split along its (0,0)-(1,1) diagonal (micropolygon.h; the SIMD kernels of sample_kernels.h test
// many samples at once). Its corners move linearly from t0 to t1 in camera space; a frame's
// exposure has one time slice per sample of a pixel, each slice holding one sample a pixel. A
// moving grid is projected at the ends of a group of slices (as many as keep its motion over the
// group under two pixels, kGroupMotion), the grid's and then each quad's bound over the group
// rejected against the block (a vertex moving linearly in camera space projects inside the box of
// its two ends), the group's samples gathered once a pixel, and each sample tested against the
// quad at the sample's own time (as its lens point sees it, with depth of field), 8 samples at a
// time, a row of the quad's pixels a call (sample_kernels.h, MovingQuad).
//
// A grid that is still and exists over every frame of the block is sampled once, into the
// block's still layer; any other writes into the frames' records of the pixels it comes nearest
// in (image_block.h).
//
// A quad with a corner whose opacity (Grid::Oi) is below 1 is see-through: its hits nearer than a
// sample's opaque hit become fragments (image_block.h), composited when resolving; a quad clear at
// every corner (Oi = Ci = 0) adds nothing and is skipped; the rest are opaque hits as usual.
//
// Edges are evaluated in a canonical direction, so two triangles sharing an edge get exactly
// opposite edge values, and a sample exactly on an edge goes to exactly one of them (as if it
// were nudged by (-e^2, e)): no cracks and no double hits inside a grid or between grids that
// share vertices.
//
// With depth of field each sample has a lens position (lu, lv) and sees every vertex shifted in
// raster space by (ax lu, ay lv) lensShift(z) (geom/camera.h): per vertex, so quads sharing a
// vertex shift it alike and stay watertight. A quad's bound is grown by the circle of confusion
// over its depths, and each sample in it is tested against the quad as its lens point sees it.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "geom/camera.h"
#include "geom/grid.h"
#include "raster/image_block.h"
#include "raster/sample_kernels.h"

namespace streyes {

struct RasterCounters {
    uint64_t micropolygons = 0;
    uint64_t sampleTests = 0;    // samples given the full inside test (after bound and time checks)
    uint64_t sampleHits = 0;     // tests that found the sample inside
    uint64_t samplesBehind = 0;  // samples not tested: all of the micropolygon lay behind their hit
    uint64_t firstHits = 0;      // samples that had no hit before (adaptive depth layers use it)
    uint64_t fragments = 0;      // see-through hits kept for compositing (image_block.h)
    uint64_t gridGroupsBehind = 0;  // a moving grid's groups of slices not sampled: all of it lay behind
    uint64_t patchGroupsBehind = 0;  // the same for a patch of its quads (4 x 4) over a group
    uint64_t patchGroupsOutside = 0;  // a patch whose bound over a group misses the block
};

class GridRasterizer {
  public:
    // Samples every micropolygon of a shaded grid into the block's frames and slices.
    void rasterize(const Grid& grid, const Camera& camera, const Shutter& shutter, ImageBlock& block,
                   RasterCounters& counters);
    // For tests of watertightness: when set, every hit (before the depth test) adds to
    // counts[(fi * pixels + i) * S + j] (frame fi, pixel i, sample j) the number of the
    // micropolygon's triangles holding the sample (2 where a micropolygon folded at a silhouette
    // covers it twice), and to windings[] their orientations in raster space (+1 or -1 each): 0
    // for a closed surface. A separate instance of the sampling loops: rendering pays nothing.
    void countHitsInto(uint32_t* counts, int32_t* windings) {
        hitCounts_ = counts;
        windings_ = windings;
    }

    // A moving grid's slices are bounded in groups: as many slices a group as keep the grid's
    // largest raster motion over a group under this many pixels. A quad's bound over a group
    // holds every sample of it that could hit; a longer group sets up fewer bounds and reads each
    // quad's set-up over more samples, at the cost of a looser bound. 2 pixels was the best
    // overall of 1, 1.5, 2, 2.5, 3 and 4 on the moving benchmarks once a group's samples were read
    // in place (docs/ARCHITECTURE.md); 3 lost 18-25% on the diagonal.
    static constexpr float kGroupMotion = 2.0f;
    // Slices a group for a grid moving `motionPerSlice` pixels a slice at most, S slices a frame.
    // A ratio within 1e-3 of a whole number counts as that number: the motion is measured in
    // float, and 16 pixels a frame over 16 slices must give groups of 2, not of 1.
    static size_t slicesPerGroup(double motionPerSlice, int S) {
        return motionPerSlice > 0 ? size_t(std::clamp(double(kGroupMotion) / motionPerSlice + 1e-3, 1.0, double(S)))
                                  : size_t(S);
    }

  private:
    struct RasterVertex {
        float x, y, z;
    };
    // One time slice of one frame that the grid's time span meets.
    struct Slice {
        int fi, k;          // frame index in the block, slice index
        double ta, tb;      // the slice clipped to the grid's span (frames)
        float tfA, tfB;     // the same as fractions of the frame's exposure
        bool checkTime;     // the grid covers only part of the slice
        bool openB;         // ... and ends at tfB half-open
    };
    // The part of one frame's exposure a still grid exists in.
    struct FrameSpan {
        int fi;
        bool whole;
        bool openB;  // the grid ends at tfB half-open
        float tfA, tfB;
    };
    void collectSlices(const Grid& grid, const Shutter& shutter, const ImageBlock& block);
    void collectFrames(const Grid& grid, const Shutter& shutter, const ImageBlock& block);
    // Shadowed: the grid carries the contributions of lights that cast shadows (Grid::Cl), kept
    // with each hit; Counting: countHitsInto is set. Separate instances, so that scenes without
    // shadows, and renders, pay nothing for either.
    // Lens: depth of field (the block's lens positions): each sample sees the quad with its
    // vertices shifted by their lens shift (Camera::lensShift), tested by the lane kernels.
    template <bool Shadowed, bool Counting, bool Lens>
    void sampleStill(const Grid& grid, const Camera& camera, ImageBlock& block, RasterCounters& counters);
    template <bool Shadowed, bool Counting, bool Lens>
    void sampleMoving(const Grid& grid, const Camera& camera, ImageBlock& block, RasterCounters& counters);
    template <bool Shadowed, bool Counting, bool Lens>
    void sample(const Grid& grid, const Camera& camera, ImageBlock& block, RasterCounters& counters);
    // Raster positions at time t, and optionally the camera-space positions they come from.
    void project(const Grid& grid, double t, const Camera& camera, std::vector<RasterVertex>& out,
                 std::vector<Vec3f>* cameraOut = nullptr) const;

    // Scratch, reused from grid to grid.
    std::vector<RasterVertex> ra_, rb_;
    std::vector<Vec3f> ca_, cb_;  // camera space at the ends of a slice (perspective, moving grids)
    std::vector<uint8_t> exact_;  // per vertex, this slice: projected at each sample's time
    std::vector<uint8_t> patchHidden_;  // per patch of quads, this group: all of it lies behind
    std::vector<uint8_t> opacity_;      // per quad of a moving grid: its QuadOpacity
    std::vector<QuadHit> quadHits_;  // a still quad's hits
    float lensEdges_[kMaxEdgeValues];  // a still quad's edge values at a pixel's samples, with a lens
    std::vector<Slice> slices_;
    // A moving grid's samples over one group of slices, gathered once a pixel (the first time a
    // quad's bound reaches it): the group's g samples of block pixel i in slots [i g, i g + g), in
    // slice order. A quad's lanes over a row of its pixels are then side by side, and the kernel
    // reads them in place, tested up to kLanes at a time (sample_kernels.h, MovingTestFn). A slot
    // whose sample lies outside the part of its slice the grid covers sits at x = y = +inf, outside
    // every bound. z follows the sample's hits as the grid's quads write them.
    static constexpr int kLanes = 64;
    struct GroupSamples {
        std::vector<float> x, y, tf, z, lu, lv;  // lu, lv: with a lens
        std::vector<uint16_t> sample;           // the slot's sample of its pixel
        std::vector<uint32_t> gathered;         // per pixel: the serial of the group last gathered
        uint32_t serial = 0;                    // this group's
    };
    GroupSamples group_;
    MovingQuad quad_{};
    float movingEdges_[kMaxEdgeValues];
    std::vector<FrameSpan> frames_;
    uint32_t* hitCounts_ = nullptr;
    int32_t* windings_ = nullptr;
};

}  // namespace streyes
