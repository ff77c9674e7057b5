// Diced and shaded grids shared by the buckets of a frame block.
//
// Each bucket runs its own split loop, so a piece whose bound reaches several buckets is made in
// each of them: the same split path from the same root gives the same piece, bit for bit
// (docs/ARCHITECTURE.md, "The split loop"). A moving grid's swept bound reaches more buckets than
// a still one's, which made a moving surface cost 3 to 3.5 times the micropolygons of the same
// surface still. The first bucket that needs such a grid dices and shades it and leaves it here;
// the others sample it. A grid is the same whichever bucket makes it, so pixels never depend on
// whether it came from here: the cache changes what is paid, not what is drawn.
//
// An entry is dropped when every other bucket its bound reaches has taken it, and the least
// recently used go first when the cache is over its capacity (then a bucket that comes later
// dices the grid again). While a bucket makes a grid, the others that want it wait for it, so
// with room to spare the counts (grids_diced, micropolygons) do not depend on threads.
#pragma once

#include <array>
#include <condition_variable>
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <thread>
#include <unordered_map>
#include <vector>

#include "geom/grid.h"
#include "streyes/vecmath.h"

namespace streyes {

// Names a grid: the piece (Body::pieceKey, its parameter rectangle and time span), the lattice,
// and the frames of the bucket that wants it (shading may depend on them).
struct GridKey {
    uint64_t piece = 0;
    std::array<float, 4> uv{};
    double t0 = 0, t1 = 0;
    int32_t nu = 0, nv = 0;
    int32_t firstFrame = 0, frameCount = 0;
    bool operator==(const GridKey& o) const {
        return piece == o.piece && uv == o.uv && t0 == o.t0 && t1 == o.t1 && nu == o.nu && nv == o.nv &&
               firstFrame == o.firstFrame && frameCount == o.frameCount;
    }
};

struct GridKeyHash {
    size_t operator()(const GridKey& k) const;
};

// The buckets' tiles: tileSize squares from the image's corner, each sampled with a guard band.
struct TileLayout {
    int width = 0, height = 0, tileSize = 64, guardX = 0, guardY = 0;
    // Tile (tx, ty) and the pixels its bucket samples: the tile and its guard band, in the image.
    PixelRect tile(int tx, int ty) const;
    PixelRect bucketRect(int tx, int ty) const;
    // How many buckets' pixels a raster bound reaches, as the split loop's view cull decides it
    // (rasterOutside).
    int bucketsReached(const Bounds3f& raster) const;
};

// A grid's bytes, as the cache counts them (the vectors' capacity: what it holds).
uint64_t gridBytes(const Grid& grid);

class GridCache {
  public:
    void configure(const TileLayout& layout, uint64_t capacityBytes);
    const TileLayout& layout() const { return layout_; }
    bool enabled() const { return capacity_ > 0; }

    // A grid asked for: the grid itself, when it is here (or once the bucket making it has left
    // it); otherwise the caller makes it, and when `make` is set it must then call publish() or
    // abandon() with the same key (unset: this thread is already making it further up its stack,
    // so the caller makes its own copy and keeps it).
    struct Lease {
        std::shared_ptr<const Grid> grid;
        bool make = false;
    };
    Lease acquire(const GridKey& key);
    // Leaves a grid made by the caller for `uses` more buckets. A grid with nu == 0 stands for
    // "nothing to sample" (every micropolygon faces away).
    void publish(const GridKey& key, std::shared_ptr<const Grid> grid, int uses);
    // A grid to swap a made one into before publishing it, instead of copying it: one the cache
    // dropped (its vectors keep their capacity: dicing a grid no larger allocates nothing), else new.
    std::shared_ptr<Grid> spare();
    // A grid a bucket took is done with: kept as a spare when nothing else holds it.
    void recycle(std::shared_ptr<const Grid> grid);
    // The caller will not make it after all (it threw): a bucket waiting for it makes it itself.
    void abandon(const GridKey& key);
    // Forgets every grid (between frame blocks).
    void clear();

    // Counted since configure().
    uint64_t evictions() const { return evictions_; }
    uint64_t peakBytes() const { return peakBytes_; }

  private:
    struct Entry {
        std::shared_ptr<const Grid> grid;  // null while a bucket makes it
        std::thread::id maker;
        int uses = 0;
        uint64_t bytes = 0;
        std::list<GridKey>::iterator lru;
    };
    void erase(std::unordered_map<GridKey, Entry, GridKeyHash>::iterator it);
    void keepSpare(std::shared_ptr<const Grid>&& grid);  // with the lock held

    TileLayout layout_;
    uint64_t capacity_ = 0, bytes_ = 0, peakBytes_ = 0, evictions_ = 0;
    std::mutex mutex_;
    std::condition_variable made_;
    std::unordered_map<GridKey, Entry, GridKeyHash> entries_;
    std::list<GridKey> lru_;  // made grids, most recently used first
    std::vector<std::shared_ptr<Grid>> spares_;  // dropped grids no bucket holds any more
};

}  // namespace streyes
