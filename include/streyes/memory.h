// Memory: what a render will hold at once, estimated before anything large is allocated, and the
// budget it must fit (--max-memory; by default three quarters of the machine's memory).
//
// A render holds the frame block's resolved images (RGBA and Z, float) until the block is done,
// and each worker thread holds one bucket's samples (positions, hits and the slice table, for
// every frame of the block in spacetime mode), its filter accumulators and, with occlusion
// culling, its coverage volume and summed-volume table. The frame block shrinks
// until one worker fits; then as many workers run as fit (never more than the threads asked for).
// Thread count never changes the pixels, so that is the knob turned first; a smaller frame block
// can change them in the last bits (moving bodies are cut at block boundaries).
#pragma once

#include <cstdint>
#include <string>

namespace streyes {

// What sets a render's memory.
struct MemoryShape {
    int width = 0, height = 0;
    int samplesPerPixel = 1;
    int tileSize = 32, guardX = 0, guardY = 0;  // bucket tile and the filter's guard band
    bool spacetime = true;                      // a bucket holds every frame of the block
    uint64_t bodyBytes = 0;                     // what the bodies made before rendering hold (roots,
                                                // and procedurals expanded up front for ray tracing)
    bool occlusion = false;                     // buckets keep coverage and a summed-volume table
    int shadowSlots = 0;                        // lights casting shadows: a colour per sample each
    uint64_t traceBytes = 0;                    // ray tracing's bodies and spacetime hierarchy
    uint64_t traceBytesPerFrame = 0;            // hierarchies built for each frame block, per frame of it
    uint64_t traceBuildBytesPerFrame = 0;       // their builds' scratch, per frame of the block
    int traceMinFrames = 1;                     // ... counted as at least this many frames' (a hierarchy
                                                // over one exposure is not cut in time, over two it is)
    uint64_t traceBytesPerWorker = 0;           // a tracing thread's scratch (its mailbox)
    uint64_t traceBuildBytes = 0;               // a hierarchy build's own scratch, let go before the
                                                // buckets start (raytrace-frames: during them)
    uint64_t sharedBytes = 0;                   // what bodies share beyond themselves: point clouds
    int aovFloats = 0;                          // output variables: floats per sample and per pixel
    uint64_t gridCacheBytes = 0;                // grids shared between buckets, at most (grid_cache.h)
};

// Bytes, by what holds them.
struct MemoryEstimate {
    uint64_t baseline = 0;       // the executable and its libraries
    uint64_t scene = 0;          // bodies made before rendering
    uint64_t trace = 0;          // ray tracing: bodies and hierarchies (per frame of the block for raytrace-frames)
    uint64_t frameImages = 0;    // the frame block's images
    uint64_t perWorker = 0;      // one bucket's samples and filter accumulators
    int workers = 1;
    uint64_t writer = 0;         // one frame being encoded and written
    uint64_t gridCache = 0;      // grids shared between buckets: the cache's capacity
    uint64_t traceBuild = 0;     // building the ray tracer's hierarchies: gone before the buckets
    int frameBlock = 1;
    uint64_t total() const {
        const uint64_t rendering = frameImages + perWorker * uint64_t(workers) + writer + gridCache;
        return baseline + scene + trace + (traceBuild > rendering ? traceBuild : rendering);
    }
    // "2.3 GiB: frame images 1.5 GiB (64 frames of 1920x1080), samples 0.6 GiB (2 workers x ...), ..."
    std::string describe(const MemoryShape& shape) const;
};

MemoryEstimate estimateMemory(const MemoryShape& shape, int frameBlock, int workers);

// What a render that ran out of memory (an allocation failed: std::bad_alloc) is told instead:
// what ran out, where, and what to try. `budget` is the one it planned for (--max-memory, or
// the default), `frameBlock` the most frames it renders together (--frame-block).
std::string outOfMemoryMessage(int firstFrame, int lastFrame, int width, int height, int frameBlock, uint64_t budget);

// The largest frame block up to `maxBlock` with which one worker fits `budget`, and as many
// workers (up to `maxWorkers`) as then fit. Throws InputError, with what a block of one frame would
// need and what to change, when even that does not fit.
MemoryEstimate planMemory(const MemoryShape& shape, int maxBlock, int maxWorkers, uint64_t budget);

// Three quarters of the physical memory, or of the control group's limit when that is lower.
uint64_t defaultMemoryBudget();
uint64_t physicalMemoryBytes();

// "1.5 GiB", "640 MiB", "12 KiB".
std::string formatBytes(uint64_t bytes);
// "8G", "512M", "1.5GiB", "4096" (bytes): binary units K M G T, an optional "B" or "iB".
// Returns false on anything else or on zero.
bool parseByteSize(const std::string& text, uint64_t* bytes);

}  // namespace streyes
