// The chunks of frames a moving root is cut into before the split loop (render/bucket.cpp,
// BucketWorker::pushRoot): each piece of the root spans a chunk, a power of two of frames aligned
// to multiples of itself in absolute frame numbers, so that a frame's pieces (and so its pixels)
// are the same in every block of frames it is rendered in.
#pragma once

#include "geom/body.h"
#include "geom/camera.h"

namespace streyes {

// The longest chunk: a still part of a long shot is diced once for at most this many frames.
constexpr int kMaxChunkFrames = 8;

// Frames a moving root's pieces span: as many as keep its raster motion over a piece under
// 8 pixels (a slow leaf is diced once for several frames, a fast body once an exposure), at most
// kMaxChunkFrames. A function of the body and the camera only; bodies reaching the eye plane
// cannot be measured: one frame a piece. Kept in root.rootChunk once made.
//
// `stillInWorld`: the root moves in camera space only because the camera does
// (Body::stillInWorld), and the split loop samples each frame of its pieces through that frame's
// camera (render/bucket_world.cpp): its chunk is kept under kWorldChunkMotion pixels of motion
// instead, up to kMaxWorldChunkFrames. The caller passes the same for a root every time.
int rootChunkFrames(const Body& root, const Camera& camera, bool stillInWorld = false);

// A still-in-world root's longest chunk and the raster motion it may make over one: its pieces
// are split and diced once for the chunk, and their swept bounds reach the buckets that motion
// crosses (docs/ARCHITECTURE.md, "The split loop").
constexpr int kMaxWorldChunkFrames = 16;
constexpr float kWorldChunkMotion = 256.0f;

}  // namespace streyes
