// The cheap layered depth-of-field preview (the seed paper's remark that depth layers make
// "computationally cheap depth-of-field effects"): the scene is rendered through a pinhole once per
// depth layer (the layer's slab of depth as the clipping range, so what a nearer layer hides is
// still there to show through its blur), each layer's premultiplied image is blurred by a disc of
// the circle of confusion at the layer's middle depth, and the layers are composited back to front.
//
// Approximate where the lens render is exact: one blur radius per layer (layers are spaced evenly
// in 1/z, where the circle of confusion is linear), no geometry outside the image blurs in, and a
// surface crossing a layer boundary is cut there. docs/results/depth-of-field.md compares the two.
#pragma once

#include <vector>

#include "streyes/frame_image.h"
#include "streyes/renderer.h"

namespace streyes {

// Layer boundaries from zmin to zmax (both > 0), evenly spaced in 1/z: layers + 1 depths.
std::vector<double> dofLayerDepths(double zmin, double zmax, int layers);

// `in` blurred by an elliptic disc of radii (rx, ry) pixels (each tap weighted by the share of its
// pixel inside the disc; weights renormalised where the disc leaves the image). RGBA only.
void blurDisc(const FrameImage& in, float rx, float ry, FrameImage& out);

// `front` over `back`, premultiplied: back = front + (1 - front alpha) back. Z: the nearer.
void compositeOver(const FrameImage& front, FrameImage& back);

// Renders the scene's frames as the layered preview of its DepthOfField in `layers` layers; the
// stats are the layers' summed. Without depth of field, an ordinary render.
RenderStats renderDofPreview(const Scene& scene, const RenderOptions& options, int layers, Log& log,
                             const Renderer::FrameSink& sink, const Renderer::Progress& progress = {});

}  // namespace streyes
