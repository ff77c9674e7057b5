#include "bodies/render_scene.h"

namespace streyes {

std::unique_ptr<RenderScene> buildRenderScene(const Scene& scene, int firstFrame, int lastFrame, int xres, int yres,
                                              Log& log) {
    auto rs = std::make_unique<RenderScene>();
    CameraDesc cam = scene.camera;
    if (xres > 0 && yres > 0) {
        cam.xres = xres;
        cam.yres = yres;
    }
    rs->camera = Camera(cam);
    rs->shutter = {scene.settings.shutterOpen, scene.settings.shutterClose};
    rs->lights = LightSet(scene.lights, cam.worldToCamera);
    rs->windowStart = firstFrame + rs->shutter.open;
    rs->windowEnd = lastFrame + rs->shutter.close;
    rs->factory = std::make_unique<BodyFactory>(cam.worldToCamera, rs->windowStart, rs->windowEnd, log);
    rs->factory->setCamera(&rs->camera);
    // Primitive ids in scene order from 1: patches, then procedurals, then the curved and
    // polygon-mesh primitives.
    uint64_t id = 0;
    for (const BilinearPatchDesc& p : scene.patches) rs->factory->addPatch(p, ++id, rs->roots);
    for (const ProceduralDesc& p : scene.procedurals) rs->factory->addProcedural(p, ++id, 0, rs->roots);
    for (const PatchMeshDesc& p : scene.patchMeshes) rs->factory->addPatchMesh(p, ++id, rs->roots);
    for (const SubdivisionMeshDesc& p : scene.subdivisionMeshes) rs->factory->addSubdivisionMesh(p, ++id, rs->roots);
    for (const QuadricDesc& q : scene.quadrics) rs->factory->addQuadric(q, ++id, rs->roots);
    for (const PolygonMeshDesc& p : scene.polygonMeshes) rs->factory->addPolygonMesh(p, ++id, rs->roots);
    return rs;
}

}  // namespace streyes
