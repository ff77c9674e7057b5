// Makes camera-space spacetime bodies from scene descriptions, for the time window of one render.
//
// Motion is turned into bodies here. A primitive's camera-space corners (control points) are
// evaluated at the union of its own motion keys, its transform's keys and the camera's keys
// (within the render's time window); between consecutive keys they move linearly, which makes
// one TrilinearBody per segment (polygon faces likewise), or for patch meshes, subdivision meshes
// and quadrics a SurfaceMesh per segment with a CurvedBody per face. A primitive that does not
// move in camera space over the whole window is one still body (or mesh), split, diced and
// shaded once for every frame. Procedurals become ProceduralBodies whose children the factory
// builds the same way when they expand (it is their ChildBodyMaker).
#pragma once

#include <atomic>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "bodies/material.h"
#include "bodies/polygons.h"
#include "geom/body.h"
#include "geom/camera.h"
#include "geom/surface_mesh.h"
#include "procedural/procedural.h"
#include "streyes/scene.h"

namespace streyes {

class SubdivisionShape;

// A procedural's children get ids hashed from the parent's id and their index: a pure function,
// so ids do not depend on which thread expanded what. 64 bits, because ids decide exact depth
// ties: among the ~10^6 bodies of a forest, 32-bit hashes collide by the dozen; 64-bit ones
// collide with a chance of about 10^-7. Never 0, never the "no hit" value.
uint64_t childPrimitiveId(uint64_t parent, uint64_t index);

// Thread-safe: procedurals expand on worker threads while other buckets render.
class BodyFactory final : public ChildBodyMaker {
  public:
    BodyFactory(const MotionTransform& worldToCamera, double windowStart, double windowEnd, Log& log);

    double windowStart() const override { return windowStart_; }
    double windowEnd() const override { return windowEnd_; }
    // The exposures of the frames rendered, inside the window: a primitive's motion segments
    // wholly outside them are not made (a frame of a long shot converts only its own keys of a
    // deforming mesh). The segments made are the same, so the pixels are. Default: every segment.
    void setWanted(double a, double b) { wantedStart_ = a, wantedEnd_ = b; }

    // One body per motion segment of the patch, appended to `out`. Patches whose corners are not
    // finite in camera space, or lie beyond 1e37 (where float overflows when they are split),
    // warn and are skipped. With the camera set, a patch it cannot see (wholly inside the near
    // plane) or sees imprecisely (so far from the world's origin that double rounding shows)
    // warns too.
    // primvarCorners: a polygon mesh face's own primitive variables (Body::primvarCorners).
    void addPatch(const BilinearPatchDesc& patch, uint64_t primitiveId, std::vector<BodyPtr>& out,
                  const float* primvarCorners = nullptr);
    // Curved primitives: a SurfaceMesh per motion segment (kept by the factory) and a CurvedBody
    // per face. The camera must be set: curved bodies
    // measure their edges in raster space. A subdivision mesh OpenSubdiv rejects is an InputError.
    // Under a zoom, `cameras` gives each frame's (a primitive is measured under its life's).
    void setCamera(const Camera* camera, const FrameCameras* cameras = nullptr) {
        camera_ = camera;
        cameras_ = cameras;
    }
    // The shutter's length in frames: GeometricApproximation "motionfactor" measures motion per exposure.
    void setExposure(double exposure) { exposure_ = exposure; }
    // Binds the Shading Language shaders of every material made from now on (see material.h).
    void setMaterialBinder(const MaterialBinder* binder) { binder_ = binder; }
    // Level of detail: the frames of the shot, whose cameras decide which representation of a model
    // each draws (level_of_detail.h), and RelativeDetail. Needs the camera. Unset: every
    // representation is drawn in every frame.
    void setDetailFrames(int first, int last, const Shutter& shutter, double relativeDetail) {
        detailFrames_ = {first, last, shutter, relativeDetail, true};
    }
    // The meshes the bodies point into go to `keep` when given (freed with the bodies by their
    // owner), else the factory keeps them for the whole render.
    using Keep = std::vector<std::shared_ptr<const void>>;
    void addPatchMesh(const PatchMeshDesc& mesh, uint64_t primitiveId, std::vector<BodyPtr>& out, Keep* keep = nullptr);
    void addSubdivisionMesh(const SubdivisionMeshDesc& mesh, uint64_t primitiveId, std::vector<BodyPtr>& out,
                            Keep* keep = nullptr);
    void addQuadric(const QuadricDesc& quadric, uint64_t primitiveId, std::vector<BodyPtr>& out, Keep* keep = nullptr);
    // Curves: a BezierMesh of ribbons per motion segment (geom/curves.h), a CurvedBody per segment
    // of each curve. Points: a PointCloud per motion segment with one root body over all its
    // points, split spatially (geom/points.h). Both in curve_bodies.cpp.
    void addCurves(const CurvesDesc& curves, uint64_t primitiveId, std::vector<BodyPtr>& out, Keep* keep = nullptr);
    void addPoints(const PointsDesc& points, uint64_t primitiveId, std::vector<BodyPtr>& out, Keep* keep = nullptr);
    void addNuPatch(const NuPatchDesc& patch, uint64_t primitiveId, std::vector<BodyPtr>& out, Keep* keep = nullptr);
    // A polygon mesh's faces (bodies/polygons.h), each as a patch.
    void addPolygonFaces(const PolygonMeshDesc& mesh, const PolygonFaces& faces, uint64_t primitiveId,
                         std::vector<BodyPtr>& out);
    // A procedural, `depth` expansions below the scene (deeper than kMaxProceduralDepth: dropped
    // with a warning), with the generator its description names (InputError when it names none)
    // or one a generator made.
    void addProcedural(const ProceduralDesc& procedural, uint64_t primitiveId, int depth, std::vector<BodyPtr>& out);
    void addProcedural(const ProceduralDesc& procedural, std::shared_ptr<const ProceduralGenerator> generator,
                       uint64_t primitiveId, int depth, std::vector<BodyPtr>& out);
    // Every primitive of a scene, or of a procedural's output with the procedurals its generator
    // made, each with the id nextId() gives, taken in the order ids have always been given: the
    // bilinear patches with the Polygons that are one (in the order read), procedurals, generated
    // procedurals, patch meshes, subdivision meshes, quadrics, polygons cut into faces, then curves and points, then NuPatches. Ids
    // decide exact depth ties: this order keeps the pixels.
    void addPrimitives(const Scene& scene, const std::vector<GeneratedProcedural>& generated, int depth,
                       const std::function<uint64_t()>& nextId, std::vector<BodyPtr>& out, Keep* keep = nullptr);
    // Everything a procedural produced; child ids are derived from the parent's, so they do not
    // depend on which thread expanded it.
    void addChildren(const ProceduralOutput& output, uint64_t parentId, int depth, std::vector<BodyPtr>& out,
                     Keep* keep = nullptr, bool count = true) override;

    // Camera-space box around an object-space box over the whole window (all transform keys), or
    // during [a, b].
    Bounds3f cameraBound(const Bounds3d& objectBound, const MotionTransform& objectToWorld) const;
    Bounds3f cameraBound(const Bounds3d& objectBound, const MotionTransform& objectToWorld, double a,
                         double b) const override;

    // Procedurals whose children reached outside their declared bound (the renderer renders again).
    std::vector<ProceduralBody*> takeOutgrown();
    bool anyOutgrown() {
        std::lock_guard<std::mutex> lock(mutex_);
        return !outgrown_.empty();
    }
    void reportOutgrown(ProceduralBody* p) override;

    uint64_t bodiesMade() const { return bodiesMade_.load(); }
    // What the bodies made so far hold (Body::memoryBytes, summed as they are made; an object
    // instance's expansion, freed by each bucket that makes it, is counted each time).
    uint64_t bodyBytes() const { return bodyBytes_.load(); }
    // Bytes of what bodies share beyond their own (point clouds), for the memory estimate.
    uint64_t sharedBytes() const { return sharedBytes_.load(); }
    // While set (bytes > 0), expanding procedurals beyond this much memory of bodies is an
    // InputError naming the budget: the ray tracer expands every procedural before the memory
    // estimate can count them, and a forest expanded whole may not fit.
    // `budget` is the whole render's, for the message.
    void setBodyBudget(uint64_t budget, uint64_t forBodies) {
        renderBudget_ = budget;
        bodyBudget_ = forBodies;
    }
    uint64_t proceduralsMade() const { return proceduralsMade_.load(); }
    // Distinct subdivision shapes built so far (meshes of one topology share one).
    size_t subdivisionShapes() {
        std::lock_guard<std::mutex> lock(mutex_);
        return shapes_.size();
    }
    std::vector<uint64_t> proceduralsMadeByDepth() const;
    // A frame sequence's cameras (Scene::frameWorldToCamera, its frames' exposures opening at
    // frame + open): the worlds its procedurals were written in (level_of_detail.cpp).
    void setFrameWorlds(std::map<int, MotionTransform> frames, double open) {
        frameWorlds_ = std::move(frames);
        frameOpen_ = open;
    }
    Matrix4 sceneToWorld(const Lifetime& life, double t) const override;

  private:
    // The part of the render's window a primitive exists in (its Lifetime), and whether it ends
    // open (the next frame's exposure begins there).
    struct Window {
        double a, b;
        bool openEnd;
        bool empty() const { return !(a <= b); }
    };
    Window windowOf(const Lifetime& life) const;
    // The material of an attribute state, for a primitive placed by objectToWorld (whether it
    // mirrors decides which way its normals face; cameraFacing: Points and camera-facing Curves).
    // A primitive with primitive variables gets a material of its own that carries them (one per
    // primitive id: the faces of a mesh share it).
    const Material* material(const AttributesPtr& attributes, const MotionTransform& objectToWorld,
                             bool cameraFacing = false, const ParamList* primvars = nullptr, uint64_t primitiveId = 0,
                             bool primvarBezier = false);
    float objectSpaceBound(const Material& m, const MotionTransform& objectToWorld) const;
    const Material* withObjectSpace(const Material* shared, const MotionTransform& objectToWorld, Facing facing,
                                    uint64_t primitiveId);
    const SourceLoc* source(const SourceLoc& loc);
    // Calls add(q) for each copy of primitive p its level of detail draws: p itself when it has
    // none, else one copy a run of frames that draw it alike, living over those frames'
    // exposures, with attributes that carry the run's share of samples where it dissolves.
    template <class Desc, class Add>
    void addWithDetail(const Desc& p, Add add);
    AttributesPtr dissolving(const AttributesPtr& attributes, float lo, float hi);
    // A curved primitive's segment times and camera-space points at each (false, with a warning,
    // when they are not finite).
    bool keyedPoints(const PrimitiveDesc& p, const std::vector<std::vector<Vec3d>>& P, std::vector<double>* ts,
                     std::vector<std::vector<Vec3d>>* points);
    // The subdivision shape (OpenSubdiv's refined topology) of a mesh, shared by every mesh of the
    // same topology and tags: the instances of an object, and meshes written out alike.
    std::shared_ptr<const SubdivisionShape> subdivisionShape(const SubdivisionMeshDesc& mesh);
    // Keeps a segment's mesh and appends a body per face.
    // `primvarBlock`: `primvarWidth` floats a face (Body::primvarCorners), or null.
    void addSurface(std::unique_ptr<SurfaceMesh> mesh, const SourceLoc* src, uint64_t primitiveId,
                    std::vector<BodyPtr>& out, Keep* keep, const float* primvarBlock = nullptr, size_t primvarWidth = 0);
    // The corner values of a mesh's faces for its primitive variables that vary from face to face,
    // from `cornersOf` (the mesh's own reading of "Cs" by class), three components at a time; kept
    // here (or in `keep`). With `bezierOf` (a bicubic patch mesh's change to Bezier form), vertex
    // ones take a face's 16 Bezier control values instead (Material::primvarBezier). Null when none varies.
    const float* meshPrimvars(const ParamList& primvars, size_t faces,
                              const std::function<std::vector<std::array<Color, 4>>(const ColorPrimvar&)>& cornersOf,
                              Keep* keep, size_t* width,
                              const std::function<std::vector<BezierPatch>(const std::vector<Vec3d>&)>& bezierOf = nullptr);

    MotionTransform worldToCamera_;
    double windowStart_, windowEnd_;
    double wantedStart_ = -std::numeric_limits<double>::infinity(), wantedEnd_ = std::numeric_limits<double>::infinity();
    Log& log_;
    std::mutex mutex_;
    const MaterialBinder* binder_ = nullptr;
    std::deque<Material> materials_;  // deques: bodies keep pointers into them
    std::deque<std::vector<float>> primvarBlocks_;  // polygon meshes' faces' primitive variables (Body::primvarCorners)
    std::deque<SourceLoc> sources_;
    std::map<std::pair<const Attributes*, Facing>, const Material*> materialOf_;
    std::map<std::tuple<const Attributes*, Facing, uint64_t>, const Material*> ownMaterialOf_;  // with primitive variables
    std::map<std::pair<const std::string*, int>, const SourceLoc*> sourceOf_;
    std::vector<AttributesPtr> keepAlive_;  // materials point at these
    std::deque<std::unique_ptr<SurfaceMesh>> surfaces_;  // curved bodies point at these
    std::vector<std::shared_ptr<const void>> clouds_;    // point bodies point at these (under mutex_)
    const Camera* camera_ = nullptr;
    const FrameCameras* cameras_ = nullptr;
    std::map<int, MotionTransform> frameWorlds_;  // setFrameWorlds
    double frameOpen_ = 0;
    // The camera a primitive living during `life` is measured under (a zoom's frame's).
    const Camera* cameraOf(const Lifetime& life) const {
        return camera_ && cameras_ ? &cameras_->during(life.t0, life.t1) : camera_;
    }
    double exposure_ = 1;
    struct DetailFrames {
        int first = 0, last = 0;
        Shutter shutter;
        double relative = 1;
        bool set = false;
    } detailFrames_;
    // Copies of attribute states whose materials see only a share [lo, hi) of a frame's samples
    // (a level of detail's dissolve), made once per state and share (under mutex_).
    std::map<std::tuple<const Attributes*, float, float>, AttributesPtr> dissolving_;
    std::map<const Attributes*, std::pair<float, float>> dissolveOf_;
    std::vector<ProceduralBody*> outgrown_;
    std::atomic<uint64_t> bodiesMade_{0}, proceduralsMade_{0}, sharedBytes_{0}, bodyBytes_{0};
    std::atomic<uint64_t> bodyBudget_{0}, renderBudget_{0};
    std::vector<uint64_t> proceduralsByDepth_;  // under mutex_
    std::unordered_map<std::string, std::shared_ptr<const SubdivisionShape>> shapes_;  // under mutex_
};

}  // namespace streyes
