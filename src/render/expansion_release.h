// Frees what procedurals expanded into once no bucket left can reach it.
//
// A kept expansion (ProceduralBody::children) is shared by every bucket that reaches the
// procedural, so it cannot be freed when one bucket is done. But the buckets that can reach it
// are known: those whose rectangle its raster reach overlaps, as the split loop's view cull takes
// it (BucketWorker::reach). When the last of them is done, the expansion is let go
// (ProceduralBody::release) and freed with the last hold on it: a render then holds the
// expansions of the buckets at work and of those still to come, not of every bucket done.
//
// Safety does not rest on the reach: a bucket holds what it takes until it is done (a lease), and
// a bucket that asks for a released expansion gets it made again, the same bodies (child ids
// depend on the parent's), not counted again. The reach only decides when memory goes.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <unordered_set>
#include <utility>
#include <vector>

#include "procedural/procedural.h"
#include "streyes/vecmath.h"

namespace streyes {

class ExpansionRelease {
  public:
    // A frame block's buckets (spacetime: one a tile, by tile index), their rectangles; `enabled`
    // false keeps every expansion to the end (a block followed by others, which would make them
    // again; ray tracing, which holds the bodies itself). Expansions are let go only once
    // madeBytes() (what the bodies made so far hold) passes `threshold`: then every one no bucket
    // left can reach. Forgets the last block's expansions.
    void start(std::vector<PixelRect> bucketRects, bool enabled, uint64_t threshold,
               std::function<uint64_t()> madeBytes);
    bool enabled() const { return enabled_.load(); }

    // Bucket `by` took `procedural`'s expansion at `level` (made then, or in a block before: the
    // first take in a block counts, the others are ignored). It reaches the buckets whose
    // rectangle `raster` overlaps (everywhere: all of them), and `by`. `holder`: what holds the
    // procedural itself (its parent's children; null for the scene's own), kept until then.
    void add(const ProceduralBody& procedural, int level, const Bounds3f& raster, bool everywhere, size_t by,
             ChildrenLease holder);
    // Bucket i is done (and holds nothing any more): lets go of what no bucket left can reach.
    void bucketDone(size_t i);

    // From now on nothing is let go, and `leases` live until the render ends: a procedural outgrew
    // its bound, and the renderer keeps it, and the procedurals it came from, for the next pass.
    void keepEverything(std::vector<ChildrenLease>&& leases);

    uint64_t released() const;  // expansions let go so far

  private:
    struct Entry {
        const ProceduralBody* procedural;
        int level;
        ChildrenLease holder;
        int waiting;  // buckets that can still reach it
    };
    mutable std::mutex mutex_;
    std::atomic<bool> enabled_{false};
    bool keepAll_ = false;
    std::vector<PixelRect> rects_;
    std::vector<char> done_;
    std::vector<std::vector<uint32_t>> waitingOn_;  // per bucket: the entries it holds back
    std::vector<Entry> entries_;
    struct KeyHash {
        size_t operator()(const std::pair<const ProceduralBody*, int>& k) const {
            return std::hash<const void*>()(k.first) ^ (size_t(uint32_t(k.second)) * 0x9e3779b97f4a7c15ull);
        }
    };
    std::unordered_set<std::pair<const ProceduralBody*, int>, KeyHash> taken_;  // entries waiting
    std::vector<ChildrenLease> kept_;
    uint64_t threshold_ = 0;
    std::function<uint64_t()> madeBytes_;
    bool pressed_ = false;            // madeBytes_ passed threshold_
    std::vector<uint32_t> complete_;  // entries no bucket left can reach, not let go yet
    uint64_t released_ = 0;
};

}  // namespace streyes
