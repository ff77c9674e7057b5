// Tessellation for the ray tracer: every body the rasterizer draws that is not a bilinear patch
// (bicubic patches, quadrics, subdivision surfaces, NURBS, curves, points) becomes one
// TrilinearBody per micropolygon, so that rays and shadow rays see what the rasterizer draws.
//
// The rate is the split loop's (render/split_decision.h, which trace may not include): split a
// body in time while its motion is much larger than it is, split it in u or v while its grid
// would exceed the grid size, dice it into micropolygons shadingRate pixels in area. So a body
// in front of the camera is cut into the very micropolygons the rasterizer samples (the split
// tree depends on the body and the camera only), and the two agree sample for sample. Pieces
// across the eye plane are split a few times in camera space; what lies behind it cannot be
// measured or diced and is left out (with one warning): it casts no shadows.
//
// A displaced surface (a material with a displacement shader) is diced the same way and its
// grid displaced before it is cut into micropolygons, as the rasterizer displaces the grids it
// samples: rays, shadows and occlusion() see the displaced surface.
#pragma once

#include <deque>
#include <vector>

#include "geom/body.h"
#include "geom/grid.h"
#include "shade/grid_shader.h"
#include "streyes/error.h"
#include "streyes/render_options.h"

namespace streyes {

class Tessellator {
  public:
    // Micropolygons one root body may make (1 GB of them); past it the body is left out, with
    // one warning (a body reaching the near plane measures in millions of pixels).
    static constexpr size_t kMaxMicropolygonsPerBody = size_t(1) << 22;
    // Splits of a piece across the eye plane before what still straddles it is left out.
    static constexpr int kMaxEyeSplits = 12;

    // `exposure`: the shutter's length in frames (GeometricApproximation "motionfactor" needs it).
    // `cameras`: each frame's (a zoom); a body is measured under its own frames'.
    Tessellator(const FrameCameras& cameras, const RenderOptions& options, double exposure, Log& log)
        : cameras_(cameras), options_(options), exposure_(exposure), log_(log) {}

    // Runs displacement shaders on the grids diced (null: surfaces are traced undisplaced).
    void setDisplacer(GridShader* displacer) { displacer_ = displacer; }

    // Appends the micropolygons of `body` (diceable in time, not a procedural) to `out`. False
    // (nothing appended, nothing warned) when it would make more than kMaxMicropolygonsPerBody.
    bool tessellate(const Body& body, std::deque<TrilinearBody>& out);

  private:
    // Walks the split tree of `body`; counts micropolygons into count_, and makes them when out_.
    void process(const Body& body, int depth, int eyeDepth);
    void split(const Body& body, SplitAxis axis, int depth, int eyeDepth);
    void dice(const Body& body, int nu, int nv);

    const FrameCameras& cameras_;
    const RenderOptions& options_;
    double exposure_;
    Log& log_;
    size_t count_ = 0;
    bool dropped_ = false, behind_ = false;
    std::deque<TrilinearBody>* out_ = nullptr;
    Grid grid_;  // reused: dicing allocates nothing once warm
    GridShader* displacer_ = nullptr;
};

// Does the material's displacement shader read `time` (so its surface changes while it stands
// still, and the ray tracer takes it frame by frame)?
bool displacementReadsTime(const Material& m);

}  // namespace streyes
