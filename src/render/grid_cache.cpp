#include "render/grid_cache.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "util/sampling.h"

namespace streyes {

namespace {

template <typename T>
uint64_t bitsOf(T v) {
    static_assert(sizeof(T) <= sizeof(uint64_t));
    uint64_t b = 0;
    std::memcpy(&b, &v, sizeof v);
    return b;
}

// Along one axis of `size` pixels: the pixels tile i's bucket samples, [first, last] (the tile,
// `tile` pixels from i * tile, and the guard band g each side, in the image).
std::pair<int, int> bucketSpan(int i, int size, int tile, int g) {
    return {std::max(0, i * tile - g), std::min(size - 1, std::min(size, (i + 1) * tile) - 1 + g)};
}

// Tiles whose pixels with guard band g reach [lo, hi] along one axis of `size` pixels.
int tilesReached(float lo, float hi, int size, int tile, int g) {
    if (!(lo <= hi)) return 0;  // NaN or empty
    const int n = (size + tile - 1) / tile;
    // A first guess from the division (clamped before converting: bounds may be huge), then the
    // view cull's own test on each candidate and its neighbours.
    const float span = float(size);
    const int a = int(std::floor(std::clamp(lo, -span, 2 * span) / float(tile))) - 1;
    const int b = int(std::floor(std::clamp(hi, -span, 2 * span) / float(tile))) + 1;
    int count = 0;
    for (int i = std::max(0, a); i <= std::min(n - 1, b); ++i) {
        const auto [x0, x1] = bucketSpan(i, size, tile, g);
        if (hi >= float(x0) && lo < float(x1 + 1)) ++count;
    }
    return count;
}

}  // namespace

size_t GridKeyHash::operator()(const GridKey& k) const {
    uint64_t h = hashCombine(k.piece, bitsOf(k.uv[0]) | bitsOf(k.uv[1]) << 32);
    h = hashCombine(h, bitsOf(k.uv[2]) | bitsOf(k.uv[3]) << 32);
    h = hashCombine(h, bitsOf(k.t0));
    h = hashCombine(h, bitsOf(k.t1));
    h = hashCombine(h, uint64_t(uint32_t(k.nu)) | uint64_t(uint32_t(k.nv)) << 32);
    h = hashCombine(h, uint64_t(uint32_t(k.firstFrame)) | uint64_t(uint32_t(k.frameCount)) << 32);
    return size_t(h);
}

PixelRect TileLayout::tile(int tx, int ty) const {
    return {tx * tileSize, ty * tileSize, std::min(width, (tx + 1) * tileSize) - 1, std::min(height, (ty + 1) * tileSize) - 1};
}

PixelRect TileLayout::bucketRect(int tx, int ty) const {
    const auto [x0, x1] = bucketSpan(tx, width, tileSize, guardX);
    const auto [y0, y1] = bucketSpan(ty, height, tileSize, guardY);
    return {x0, y0, x1, y1};
}

int TileLayout::bucketsReached(const Bounds3f& raster) const {
    if (tileSize <= 0) return 0;
    // The view cull's test (rasterOutside) is separable: a bucket is reached when its columns
    // and its rows are.
    return tilesReached(raster.lo.x, raster.hi.x, width, tileSize, guardX) *
           tilesReached(raster.lo.y, raster.hi.y, height, tileSize, guardY);
}

uint64_t gridBytes(const Grid& g) {
    uint64_t n = sizeof(Grid) + g.hole.capacity();
    for (int k = 0; k < 2; ++k)
        n += (g.P[k].capacity() + g.N[k].capacity()) * sizeof(Vec3f) +
             (g.Ci[k].capacity() + g.Oi[k].capacity() + g.Cl[k].capacity()) * sizeof(Color) +
             g.aov[k].capacity() * sizeof(float);
    return n + g.Cs.capacity() * sizeof(Color);
}

void GridCache::configure(const TileLayout& layout, uint64_t capacityBytes) {
    std::lock_guard<std::mutex> lock(mutex_);
    layout_ = layout;
    capacity_ = capacityBytes;
    entries_.clear();
    lru_.clear();
    bytes_ = peakBytes_ = evictions_ = 0;
}

GridCache::Lease GridCache::acquire(const GridKey& key) {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        auto it = entries_.find(key);
        if (it == entries_.end()) {
            Entry& e = entries_[key];
            e.maker = std::this_thread::get_id();
            return {nullptr, true};
        }
        Entry& e = it->second;
        if (e.grid) {
            std::shared_ptr<const Grid> grid = e.grid;
            if (--e.uses <= 0) erase(it);
            else lru_.splice(lru_.begin(), lru_, e.lru);
            return {std::move(grid), false};
        }
        // This thread is making it further up its own stack (a bucket task stolen while it
        // waited elsewhere): waiting would wait for itself.
        if (e.maker == std::this_thread::get_id()) return {nullptr, false};
        made_.wait(lock);
    }
}

void GridCache::publish(const GridKey& key, std::shared_ptr<const Grid> grid, int uses) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = entries_.find(key);
        if (it != entries_.end() && !it->second.grid) {
            Entry& e = it->second;
            if (uses <= 0 || !grid) {
                erase(it);
            } else {
                e.bytes = gridBytes(*grid);
                e.grid = std::move(grid);
                e.uses = uses;
                lru_.push_front(key);
                e.lru = lru_.begin();
                bytes_ += e.bytes;
                while (bytes_ > capacity_ && !lru_.empty()) {
                    erase(entries_.find(lru_.back()));
                    ++evictions_;
                }
                peakBytes_ = std::max(peakBytes_, bytes_);
            }
        }
    }
    made_.notify_all();
}

void GridCache::abandon(const GridKey& key) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = entries_.find(key);
        if (it != entries_.end() && !it->second.grid) erase(it);
    }
    made_.notify_all();
}

void GridCache::clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.clear();
    lru_.clear();
    spares_.clear();
    bytes_ = 0;
}

std::shared_ptr<Grid> GridCache::spare() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!spares_.empty()) {
            std::shared_ptr<Grid> g = std::move(spares_.back());
            spares_.pop_back();
            return g;
        }
    }
    return std::make_shared<Grid>();
}

void GridCache::erase(std::unordered_map<GridKey, Entry, GridKeyHash>::iterator it) {
    Entry& e = it->second;
    if (e.grid) {
        bytes_ -= e.bytes;
        lru_.erase(e.lru);
        keepSpare(std::move(e.grid));
    }
    entries_.erase(it);
}

void GridCache::recycle(std::shared_ptr<const Grid> grid) {
    std::lock_guard<std::mutex> lock(mutex_);
    keepSpare(std::move(grid));
}

// Kept for the next grid made when nothing else holds it: no entry (which would hold a copy) and
// no bucket sampling it. A few: about as many as buckets publish between two drops.
void GridCache::keepSpare(std::shared_ptr<const Grid>&& grid) {
    constexpr size_t kMaxSpares = 64;
    if (grid && grid.use_count() == 1 && grid->nu > 0 && spares_.size() < kMaxSpares)
        spares_.push_back(std::const_pointer_cast<Grid>(std::move(grid)));
}

}  // namespace streyes
