// The scene as the renderer sees it: camera, shutter, lights, materials and the root bodies in
// camera space, for the time window of one render.
//
// Motion is turned into bodies here (BodyFactory). A primitive's camera-space corners are
// evaluated at the union of its own motion keys, its transform's keys and the camera's keys
// (within the render's time window); between consecutive keys the corners move linearly, which
// makes one TrilinearBody per segment. A primitive that does not move in camera space over the
// whole window is one still body, split, diced and shaded once for every frame. Procedurals
// become ProceduralBodies whose children the factory builds the same way when they expand.
#pragma once

#include <atomic>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "streyes/body.h"
#include "streyes/camera.h"
#include "streyes/rasterizer.h"
#include "streyes/scene.h"
#include "streyes/shading.h"

namespace streyes {

class ProceduralBody;

// Makes camera-space bodies from scene descriptions. Thread-safe: procedurals expand on worker
// threads while other buckets render.
class BodyFactory {
  public:
    BodyFactory(const MotionTransform& worldToCamera, double windowStart, double windowEnd, Log& log);

    double windowStart() const { return windowStart_; }
    double windowEnd() const { return windowEnd_; }

    // One body per motion segment of the patch, appended to `out`. Patches whose corners are not
    // finite in camera space warn and are skipped.
    void addPatch(const BilinearPatchDesc& patch, uint32_t primitiveId, std::vector<BodyPtr>& out);
    // A procedural, `depth` expansions below the scene (deeper than kMaxProceduralDepth: dropped
    // with a warning).
    void addProcedural(const ProceduralDesc& procedural, uint32_t primitiveId, int depth, std::vector<BodyPtr>& out);
    // Everything a procedural produced; child ids are derived from the parent's, so they do not
    // depend on which thread expanded it.
    void addChildren(const Scene& fragment, uint32_t parentId, int depth, std::vector<BodyPtr>& out);

    // Camera-space box around an object-space box over the whole window (all transform keys).
    Bounds3f cameraBound(const Bounds3d& objectBound, const MotionTransform& objectToWorld) const;

    // Procedurals whose children reached outside their declared bound (the renderer renders again).
    std::vector<ProceduralBody*> takeOutgrown();
    void reportOutgrown(ProceduralBody* p);

    uint64_t bodiesMade() const { return bodiesMade_.load(); }
    uint64_t proceduralsMade() const { return proceduralsMade_.load(); }
    std::vector<uint64_t> proceduralsMadeByDepth() const;

  private:
    const Material* material(const AttributesPtr& attributes);
    const SourceLoc* source(const SourceLoc& loc);

    MotionTransform worldToCamera_;
    double windowStart_, windowEnd_;
    Log& log_;
    std::mutex mutex_;
    std::deque<Material> materials_;  // deques: bodies keep pointers into them
    std::deque<SourceLoc> sources_;
    std::map<const Attributes*, const Material*> materialOf_;
    std::map<std::pair<const std::string*, int>, const SourceLoc*> sourceOf_;
    std::vector<AttributesPtr> keepAlive_;  // materials point at these
    std::vector<ProceduralBody*> outgrown_;
    std::atomic<uint64_t> bodiesMade_{0}, proceduralsMade_{0};
    std::vector<uint64_t> proceduralsByDepth_;  // under mutex_
};

struct RenderScene {
    Camera camera;
    Shutter shutter;
    LightSet lights;
    double windowStart = 0, windowEnd = 0;    // [first + open, last + close]
    std::unique_ptr<BodyFactory> factory;
    std::vector<BodyPtr> roots;
};

// Builds the render scene for frames [firstFrame, lastFrame]. Camera resolution overrides
// (xres/yres > 0) replace the scene's Format.
std::unique_ptr<RenderScene> buildRenderScene(const Scene& scene, int firstFrame, int lastFrame, int xres,
                                              int yres, Log& log);

}  // namespace streyes
