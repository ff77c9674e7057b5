#include "streyes/memory.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "film/film.h"
#include "raster/image_block.h"
#include "streyes/error.h"

namespace streyes {

namespace {

// Measured: a tiny render's peak resident set is about 31 MiB (the program, oneTBB's threads,
// OpenEXR; OpenImageIO is not loaded for rendering: it took it to 124 MiB).
constexpr uint64_t kBaselineBytes = uint64_t(40) << 20;
// Per sample of a bucket (the same in every frame): its position and its still-layer hit, the
// moving sampler's slot for it (GridRasterizer::GroupSamples: position, time, depth and lens
// point as floats, and the sample's index; a slot a sample at most), and what resolving reads of
// it, for the still layer and for the frame being resolved (ResolveScratch).
constexpr uint64_t kBytesPerSample =
    2 * sizeof(float) + sizeof(SampleHit) + 6 * sizeof(float) + sizeof(uint16_t) + 2 * sizeof(CompositeSample);
// Per sample and frame: the frame's record of it, at most (records are made only where something
// that frame alone sees comes nearest; dense blocks have them all).
constexpr uint64_t kBytesPerRecordSample = sizeof(SampleHit);
// Per pixel of a bucket: the key its time permutations are hashed from, and whether it is made
// yet (ImageBlock::makePermutation).
constexpr uint64_t kBytesPerBucketPixel = sizeof(uint64_t) + sizeof(uint8_t);
// Per pixel and frame: its record's slot, its time permutation and its farthest-depth bound.
constexpr uint64_t kBytesPerPixelFrame = sizeof(int32_t) + sizeof(uint8_t) + sizeof(float);
// Per pixel and frame of a bucket, with occlusion culling: its coverage cell and table entry.
constexpr uint64_t kOcclusionBytesPerCell = sizeof(uint8_t) + sizeof(uint32_t);
// Per pixel of a resolved frame: RGBA and Z as float.
constexpr uint64_t kBytesPerPixel = 5 * sizeof(float);
// Per pixel of a frame being written: up to five float channels, then the encoded file (at most
// the half-float data, before compression); the last frame encoded, its pixels and bytes, kept
// so that an identical next frame reuses them (image_io.cpp); the last file's chunks, packed
// and as stored (no larger), kept so that the next file's unchanged chunks reuse them
// (exr_file.cpp); and the writer's queue of two frames' RGBA and Z (io/frame_writer.h).
constexpr uint64_t kWriterBytesPerPixel =
    2 * (5 * sizeof(float) + 5 * 2) + 2 * 5 * sizeof(float) + 2 * 5 * sizeof(float);

// The block's frames are held tile by tile (film/tiled_frames.h): at most a copy a frame (where
// everything moves), the tiles' still pixels when a bucket spans several frames, and the frame
// assembled for the writer.
int framesHeld(const MemoryShape& s, int frameBlock) {
    return frameBlock + 1 + (s.spacetime && frameBlock > 1 ? 1 : 0);
}

uint64_t bucketPixels(const MemoryShape& s) {
    const uint64_t w = uint64_t(std::min(s.tileSize + 2 * s.guardX, std::max(1, s.width)));
    const uint64_t h = uint64_t(std::min(s.tileSize + 2 * s.guardY, std::max(1, s.height)));
    return w * h;
}

uint64_t tilePixels(const MemoryShape& s) {
    return uint64_t(std::min(s.tileSize, std::max(1, s.width))) * uint64_t(std::min(s.tileSize, std::max(1, s.height)));
}

std::string budgetAdvice(const MemoryShape& shape, uint64_t budget, const MemoryEstimate& one) {
    return "this render needs about " + formatBytes(one.total()) + " of memory even one frame at a time (" +
           one.describe(shape) + "), more than its budget of " + formatBytes(budget) +
           " (--max-memory; by default three quarters of this machine's " + formatBytes(physicalMemoryBytes()) +
           "): lower --res or --samples, use a smaller --bucket, or raise --max-memory";
}

}  // namespace

MemoryEstimate estimateMemory(const MemoryShape& s, int frameBlock, int workers) {
    MemoryEstimate e;
    e.frameBlock = std::max(1, frameBlock);
    e.workers = std::max(1, workers);
    const uint64_t pixels = uint64_t(std::max(0, s.width)) * uint64_t(std::max(0, s.height));
    const uint64_t framesPerBucket = s.spacetime ? uint64_t(e.frameBlock) : 1;
    e.baseline = kBaselineBytes;
    e.scene = s.bodyBytes + s.sharedBytes;
    const uint64_t traceFrames = uint64_t(std::max(e.frameBlock, s.traceMinFrames));
    e.trace = s.traceBytes + s.traceBytesPerFrame * traceFrames;
    // A build's scratch: before the buckets (raytrace-frames: held with what they hold when each
    // block builds its frames' hierarchies).
    if (s.traceBytesPerFrame > 0 && s.traceBuildBytesPerFrame == 0) e.trace += s.traceBuildBytes;
    else e.traceBuild = std::max(s.traceBuildBytes, s.traceBuildBytesPerFrame * traceFrames);
    const uint64_t aov = uint64_t(std::max(0, s.aovFloats)) * sizeof(float);
    e.frameImages = uint64_t(framesHeld(s, e.frameBlock)) * pixels * (kBytesPerPixel + aov);
    const uint64_t S = uint64_t(std::max(1, s.samplesPerPixel));
    // With shadows, a sample's shadowed parts and its still-tested flag (ImageBlock::stillTested).
    const uint64_t recordSample =
        kBytesPerRecordSample + (s.shadowSlots > 0 ? uint64_t(s.shadowSlots) * sizeof(Color) + 1 : 0) + aov;
    e.perWorker = bucketPixels(s) * (kBytesPerBucketPixel + S * (kBytesPerSample + aov) +
                                     framesPerBucket * (kBytesPerPixelFrame + S * recordSample)) +
                  s.traceBytesPerWorker + tilePixels(s) * 6 * sizeof(float) +  // resolving: weights, still pixels
                  (s.occlusion ? bucketPixels(s) * framesPerBucket * kOcclusionBytesPerCell : 0);
    // Output variables the same way, as floats, and interleaved then planar while one is encoded,
    // and their files' chunks kept packed and as stored.
    e.writer = pixels * (kWriterBytesPerPixel + 10 * aov);
    e.gridCache = s.gridCacheBytes;
    return e;
}

std::string MemoryEstimate::describe(const MemoryShape& s) const {
    const int bw = std::min(s.tileSize + 2 * s.guardX, std::max(1, s.width));
    const int bh = std::min(s.tileSize + 2 * s.guardY, std::max(1, s.height));
    const int frames = s.spacetime ? frameBlock : 1;
    return "frame images " + formatBytes(frameImages) + " (" + std::to_string(frameBlock) + " frame" +
           (frameBlock == 1 ? "" : "s") + " of " + std::to_string(s.width) + "x" + std::to_string(s.height) +
           (framesHeld(s, frameBlock) > frameBlock + 1 ? ", their still pixels" : "") +
           " and one being written), samples " + formatBytes(perWorker * uint64_t(workers)) + " (" + std::to_string(workers) + " worker" +
           (workers == 1 ? "" : "s") + " with a bucket of " + std::to_string(bw) + "x" + std::to_string(bh) +
           " pixels x " + std::to_string(frames) + " frame" + (frames == 1 ? "" : "s") + " x " +
           std::to_string(s.samplesPerPixel) + " samples" + (s.shadowSlots ? " with shadows" : "") +
           "), writing " + formatBytes(writer) + ", scene " + formatBytes(scene) +
           (trace ? ", ray tracing " + formatBytes(trace) : "") + (gridCache ? ", shared grids " + formatBytes(gridCache) : "") +
           ", program " + formatBytes(baseline);
}

MemoryEstimate planMemory(const MemoryShape& asked, int maxBlock, int maxWorkers, uint64_t budget) {
    // The grid cache saves work and never changes pixels: it gets what the frame block and the
    // workers leave of the budget, up to its size (below).
    MemoryShape shape = asked;
    shape.gridCacheBytes = 0;
    const MemoryEstimate one = estimateMemory(shape, 1, 1);
    if (one.total() > budget) throw InputError(budgetAdvice(shape, budget, one));
    // With one worker the estimate grows linearly with the block from two frames on (a block of
    // several frames also holds its tiles' still pixels).
    int block = std::max(1, maxBlock);
    if (block > 1) {
        const uint64_t two = estimateMemory(shape, 2, 1).total();
        const uint64_t perFrame = estimateMemory(shape, 3, 1).total() - two;
        if (two > budget) block = 1;
        else if (perFrame > 0) block = int(std::min<uint64_t>(uint64_t(block), 2 + (budget - two) / perFrame));
    }
    MemoryEstimate e = estimateMemory(shape, block, 1);
    const uint64_t room = budget - e.total();
    e.workers = int(std::min<uint64_t>(uint64_t(std::max(1, maxWorkers)), 1 + room / std::max<uint64_t>(1, e.perWorker)));
    e.gridCache = std::min(asked.gridCacheBytes, budget - std::min(budget, e.total()));
    return e;
}

std::string outOfMemoryMessage(int firstFrame, int lastFrame, int width, int height, int frameBlock, uint64_t budget) {
    const std::string frames = firstFrame == lastFrame ? "frame " + std::to_string(firstFrame)
                                                       : "frames " + std::to_string(firstFrame) + "-" +
                                                             std::to_string(lastFrame);
    const int together = std::max(1, std::min(frameBlock, lastFrame - firstFrame + 1));
    return "out of memory rendering " + frames + " at " + std::to_string(width) + "x" + std::to_string(height) +
           " (an allocation failed: the machine or a limit on this process, ulimit or a container, gave less than "
           "the memory budget of " + formatBytes(budget) + " it planned for): render fewer frames together (" +
           (together > 1 ? "--frame-block " + std::to_string(std::max(1, together / 2)) + ", or down to 1"
                         : "--frame-block 1, as now") +
           ": a block's images and samples, and with ray tracing its hierarchies of moving bodies, grow with its frames), lower --res or "
           "--samples, or give --max-memory the memory this render may have (frame blocks and workers shrink to "
           "fit it; by default three quarters of this machine's " + formatBytes(physicalMemoryBytes()) +
           "). Frames already written are complete; no other frame was written";
}

uint64_t physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && size > 0 ? uint64_t(pages) * uint64_t(size) : uint64_t(8) << 30;
}

uint64_t defaultMemoryBudget() {
    uint64_t limit = physicalMemoryBytes();
    // A container's limit (cgroup v2, then v1), when it is lower.
    for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        std::ifstream f(path);
        unsigned long long v = 0;
        if (f >> v && v > 0) limit = std::min<uint64_t>(limit, v);
    }
    return limit / 4 * 3;
}

std::string formatBytes(uint64_t bytes) {
    const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB"};
    double v = double(bytes);
    int u = 0;
    while (v >= 1024 && u < 5) v /= 1024, ++u;
    char buf[32];
    if (u == 0) std::snprintf(buf, sizeof buf, "%llu bytes", (unsigned long long)bytes);
    else std::snprintf(buf, sizeof buf, v < 10 ? "%.2f %s" : v < 100 ? "%.1f %s" : "%.0f %s", v, units[u]);
    return buf;
}

bool parseByteSize(const std::string& text, uint64_t* bytes) {
    size_t i = 0;
    while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.')) ++i;
    if (i == 0) return false;
    char* end = nullptr;
    const std::string number = text.substr(0, i);
    const double v = std::strtod(number.c_str(), &end);
    if (end != number.c_str() + number.size() || !(v > 0)) return false;
    std::string unit = text.substr(i);
    for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
    int shift = 0;
    if (!unit.empty() && std::string("KMGT").find(unit[0]) != std::string::npos) {
        shift = 10 * int(1 + std::string("KMGT").find(unit[0]));
        unit.erase(0, 1);
        if (unit == "IB" || unit == "B") unit.clear();
    } else if (unit == "B") {
        unit.clear();
    }
    if (!unit.empty()) return false;
    const double b = std::ldexp(v, shift);
    if (!(b >= 1 && b < 0x1p63)) return false;
    *bytes = uint64_t(b);
    return true;
}

}  // namespace streyes
