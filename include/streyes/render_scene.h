// The scene as the renderer sees it: camera, shutter, lights, materials and the root bodies in
// camera space, for the time window of one render.
//
// Motion is turned into bodies here. A primitive's camera-space control points are evaluated at
// the union of its own motion keys, its transform's keys and the camera's keys (within the
// render's time window); between consecutive keys they move linearly, which makes one set of
// bodies per segment: a TrilinearBody per bilinear patch or polygon face, and a SurfaceMesh
// (shared) with a CurvedBody per face for patch meshes, subdivision meshes and quadrics. A
// primitive that does not move in camera space over the whole window is one still segment,
// split, diced and shaded once for every frame.
#pragma once

#include <deque>
#include <memory>
#include <vector>

#include "streyes/body.h"
#include "streyes/camera.h"
#include "streyes/rasterizer.h"
#include "streyes/scene.h"
#include "streyes/shading.h"
#include "streyes/surface_mesh.h"

namespace streyes {

struct RenderScene {
    Camera camera;
    Shutter shutter;
    LightSet lights;
    double windowStart = 0, windowEnd = 0;    // [first + open, last + close]
    std::deque<Material> materials;           // deque: bodies keep pointers into it
    std::deque<SourceLoc> sources;            // where each root body came from
    std::vector<BodyPtr> roots;
    std::vector<std::unique_ptr<SurfaceMesh>> surfaces;  // shared by the curved bodies in roots
};

// Builds the render scene for frames [firstFrame, lastFrame]. Camera resolution overrides
// (xres/yres > 0) replace the scene's Format. Primitives whose corners are not finite in camera
// space warn and are skipped.
std::unique_ptr<RenderScene> buildRenderScene(const Scene& scene, int firstFrame, int lastFrame, int xres,
                                              int yres, Log& log);

}  // namespace streyes
