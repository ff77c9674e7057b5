#include "bodies/render_scene.h"

#include <algorithm>

namespace streyes {

std::unique_ptr<RenderScene> buildRenderScene(const Scene& scene, int firstFrame, int lastFrame, int xres, int yres,
                                              Log& log, const MaterialBinder* binder, int renderedFirst,
                                              int renderedLast) {
    auto rs = std::make_unique<RenderScene>();
    CameraDesc cam = scene.camera;
    if (xres > 0 && yres > 0) {
        cam.xres = xres;
        cam.yres = yres;
    }
    rs->camera = Camera(cam);
    rs->shutter = {scene.settings.shutterOpen, scene.settings.shutterClose};
    rs->cameras.setShutter(rs->shutter);
    // A zoom: each frame's projection; all else (camera space, clipping, lens, resolution) the scene's.
    for (const auto& [frame, desc] : scene.frameCamera) {
        CameraDesc c = cam;
        c.fov = desc.fov;
        c.hasScreenWindow = desc.hasScreenWindow;
        std::copy(desc.screenWindow, desc.screenWindow + 4, c.screenWindow);
        c.frameAspect = desc.frameAspect;
        rs->cameras.add(frame, c);
    }
    rs->lights = LightSet(scene.lights, cam.worldToCamera);
    rs->windowStart = firstFrame + rs->shutter.open;
    rs->windowEnd = lastFrame + rs->shutter.close;
    rs->renderedStart = std::max(firstFrame, renderedFirst) + rs->shutter.open;
    rs->renderedEnd = std::min(lastFrame, renderedLast) + rs->shutter.close;
    rs->cameras.setRendered(std::max(firstFrame, renderedFirst), std::min(lastFrame, renderedLast));
    rs->factory = std::make_unique<BodyFactory>(cam.worldToCamera, rs->windowStart, rs->windowEnd, log);
    rs->factory->setCamera(&rs->camera, &rs->cameras);
    rs->factory->setExposure(rs->shutter.close - rs->shutter.open);
    rs->factory->setMaterialBinder(binder);
    rs->factory->setWanted(rs->renderedStart, rs->renderedEnd);
    rs->factory->setDetailFrames(firstFrame, lastFrame, rs->shutter, scene.settings.relativeDetail);
    rs->factory->setFrameWorlds(scene.frameWorldToCamera, rs->shutter.open);
    // Primitive ids from 1, in the order BodyFactory::addPrimitives takes them.
    uint64_t id = 0;
    rs->factory->addPrimitives(scene, {}, 0, [&id] { return ++id; }, rs->roots);
    rs->solids = SolidTree(scene.solids);
    return rs;
}

}  // namespace streyes
