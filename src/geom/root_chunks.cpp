#include "geom/root_chunks.h"

#include <algorithm>

namespace streyes {

int rootChunkFrames(const Body& root, const Camera& camera, bool stillInWorld) {
    if (const uint8_t made = root.rootChunk.load(std::memory_order_relaxed)) return made;
    constexpr float kChunkMotion = 8.0f;
    if (!root.moving()) return 1;
    // A root reaching the eye plane cannot be measured in raster space. Still in the world, its
    // pieces that can be projected are measured and culled one by one, each frame sampled
    // through its own camera: the longest chunk. Otherwise one frame a piece.
    if (!(root.bound().swept().lo.z >= camera.eyePlane())) {
        const int frames = stillInWorld ? kMaxWorldChunkFrames : 1;
        root.rootChunk.store(uint8_t(frames), std::memory_order_relaxed);
        return frames;
    }
    const TimeSpan& span = root.time();
    const RasterMeasure m = root.measure(camera);
    // The motion measured is over the whole span, or between neighbouring keys for a keyed body.
    const double keys = root.diceableInTime() ? 1.0 : double(static_cast<const KeyedPatchBody&>(root).keyCount() - 1);
    const double perFrame = double(m.motion) / std::max(1e-9, (span.t1 - span.t0) / keys);
    const int most = stillInWorld ? kMaxWorldChunkFrames : kMaxChunkFrames;
    const float motion = stillInWorld ? kWorldChunkMotion : kChunkMotion;
    int frames = 1;
    while (frames < most && perFrame * double(2 * frames) <= double(motion)) frames *= 2;
    root.rootChunk.store(uint8_t(frames), std::memory_order_relaxed);
    return frames;
}

}  // namespace streyes
