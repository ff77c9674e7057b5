// The scene as the renderer sees it: camera, shutter, lights and the root bodies in camera space,
// for the time window of one render (frames [first, last] with their exposures).
#pragma once

#include <climits>
#include <memory>
#include <vector>

#include "bodies/body_factory.h"
#include "geom/body.h"
#include "geom/camera.h"
#include "geom/lights.h"
#include "geom/solid_tree.h"
#include "streyes/scene.h"

namespace streyes {

struct RenderScene {
    Camera camera;  // the first frame's; camera space, clipping, lens and resolution are every frame's
    FrameCameras cameras{&camera};  // each frame's projection (a zoom); bodies ask by their time
    Shutter shutter;
    LightSet lights;
    double windowStart = 0, windowEnd = 0;    // the shot's exposures: [first + open, last + close]
    // The exposures of the frames rendered, inside the window: nothing outside them is sampled or
    // traced, so motion segments and trace bodies that miss them are not made.
    double renderedStart = 0, renderedEnd = 0;
    std::unique_ptr<BodyFactory> factory;
    std::vector<BodyPtr> roots;
    SolidTree solids;  // the scene's solids (Material::solid points at their leaves); empty: none
};

// Builds the render scene for the shot, frames [firstFrame, lastFrame] (see RenderOptions::hasShot:
// the frames rendered lie inside it, and bodies do not depend on which). Camera resolution overrides
// (xres/yres > 0) replace the scene's Format.
// `binder` binds the materials' Shading Language shaders (null: built-in shading only).
// [renderedFirst, renderedLast]: the frames that will be rendered, inside the shot; the motion
// segments of primitives that none of their exposures meet are not made (BodyFactory::setWanted).
// Default: the shot.
std::unique_ptr<RenderScene> buildRenderScene(const Scene& scene, int firstFrame, int lastFrame, int xres,
                                              int yres, Log& log, const MaterialBinder* binder = nullptr,
                                              int renderedFirst = INT_MIN, int renderedLast = INT_MAX);

}  // namespace streyes
