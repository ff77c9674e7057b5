// Shades diced grids: a displacement shader first, when the material has one (moving P and
// setting N before anything else reads them); then the built-in shading (shading.h) for materials it serves, the Shading
// Language interpreter (shade/vm) over the whole grid for the others. One per thread: it keeps
// the interpreter's registers and its own scratch arrays from grid to grid, so shading
// allocates nothing once warm.
//
// What a shader sees (RI Spec 3.2, section 12.1), all in camera ("current") space: P, N and Ng
// (the diced geometric normal), I (from the eye; from the eye plane along +z under an
// orthographic camera), E (the eye),
// Cs and Os, u and v (the piece's parameter rectangle, Body::uv, over the grid), s = u and t = v
// (unless the primitive gives "s", "t" or "st"), du and dv, time; its primitive variables
// (Material::primvars) bound to parameters of the same name. "world", "object" and "shader" spaces come from the camera and the transform
// in force where the surface was declared; lights see their own transform as "shader" space.
//
// Lights that cast shadows are kept apart as the built-in shading keeps them: Cl[slot] is what
// the surface gives with that light on minus what it gives without it (exact for shaders that
// add up their lights' contributions, as illuminance loops and diffuse/specular do).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "geom/camera.h"
#include "geom/grid.h"
#include "geom/lights.h"
#include "shade/scene_shaders.h"
#include "shade/layer_network.h"
#include "shade/vm/vm.h"
#include "streyes/stats.h"
#include "util/aov.h"

namespace streyes {

class GridShader {
  public:
    // `shaders` may be null (no Shading Language: every material is built in).
    GridShader(const SceneShaders* shaders, const Camera& camera, const LightSet& lights);
    ~GridShader();

    void setShaders(const SceneShaders* shaders) {
        shaders_ = shaders;
        safePrograms_.clear();
        refused_.clear();
        if (vm_) vm_->setTextureSource(shaders ? shaders->textures() : nullptr);
        if (vm_) vm_->setLog(shaders ? &shaders->log() : nullptr);
    }
    // Where occlusion(), trace() and the other ray-traced calls go (trace/shader_rays.h; null:
    // they give their no-hit values). Set by whoever owns the ray tracer, above this stage.
    void setRaySource(sl::RaySource* rays) {
        rays_ = rays;
        if (vm_) vm_->setRaySource(rays);
    }
    // Output variables (util/aov.h): the surface shader's output parameters the layout names are
    // copied into grids that carry it (Grid::aovCount == layout->count); others read 0.
    void setAovs(const AovLayout* layout) { aovs_ = layout && layout->shaderOutputs ? layout : nullptr; }

    // A depth pass with depthfilter "midpoint" (RenderOptions::depthPass): every opaque point is
    // made a see-through layer (Oi 1/2, Ci 0), so that samples keep each surface they cross as a
    // fragment, and the rest clear (not a surface of the depth map). Colours mean nothing then.
    void setDepthLayers(bool on) { depthLayers_ = on; }
    // A depth pass: only depth and opacity matter. Lights are not run (a light reading the map
    // this pass makes would read nothing), nor atmospheres; the built-in surfaces are not shaded.
    void setDepthOnly(bool on) { depthOnly_ = on; }

    // Ci (and Cl) of slot k of `grid` from its P[k] and N[k] at `time`.
    void shadeSlot(Grid& grid, int k, double time);
    // Both slots of a moving grid (t0 and t1), or the one of a still grid.
    void shade(Grid& grid);
    // The same where only the vertices `need` marks are read: the built-in surfaces, which shade
    // each vertex on its own, shade only those (the others keep what they held); a shader, whose
    // derivatives read neighbours, shades all.
    void shade(Grid& grid, const uint8_t* need);
    // A slot to shade (shadeSlots): slot k of `grid` at `time`.
    struct Slot {
        Grid* grid = nullptr;
        int k = 0;
        double time = 0;
    };
    // Grids of at most this many points may share a run; a run takes at most kBatchPoints.
    static constexpr int kBatchGridPoints = 64;
    static constexpr int kBatchPoints = 512;
    // Can a grid of `points` points under `m` share an interpreter run with others (shadeSlots)?
    // A language surface without displacement, atmosphere, layers, primitive variables or shader
    // output variables, whose programs (the surface's and its lights') batchProgramSafe() accepts.
    bool batchable(const Material* m, int points, int aovCount);
    // Each slot as shadeSlot(*grid, k, time) shades it, bit for bit; the slots of batchable grids
    // whose runs would see the same uniform values (one material, the same spaces at their
    // shading times, shadow slots) are shaded together, up to kBatchPoints a run, each grid
    // differenced on its own (du and dv bound point by point).
    void shadeSlots(const Slot* slots, size_t count);
    // Off: shadeSlots shades one slot a run (for comparing).
    void setBatching(bool on) { batching_ = on; }

    // Only the material's displacement shader (if any) over each slot, at t0 and t1: the ray
    // tracer's micropolygons are the displaced grid the rasterizer samples (trace/tessellate.h).
    void displaceOnly(Grid& grid);

    // One point (a ray's hit): its colour, and with `shadowed` the parts of the lights that cast
    // shadows (as shadePoint gives them), and with `opacity` its Oi. No derivatives: du, dv and
    // Du(), Dv() are 0.
    Color shadeHit(const Material& m, Color cs, Vec3f p, Vec3f n, double time, float u, float v,
                   uint64_t primitiveId, Color* shadowed, int slots, Color* opacity = nullptr,
                   const float* primvarCorners = nullptr);

    // A volume shader (m's Interior or Exterior) over one segment of a ray, from `from` to `to`:
    // its P is `to`, I the segment (to - from), E `from`, and Ci, Oi what the ray brings from `to`
    // on; gives its Ci and sets *oi to its Oi. Its "shader" space is where the request was given.
    Color runVolume(const Material& m, const sl::ShaderInstance& shader, const MotionTransform* shaderToWorld,
                    Vec3f from, Vec3f to, double time, Color ci, Color* oi);

    // What rayinfo() says of the grids shaded next: the depth of the ray whose hits they are (0:
    // the eye's) and its type ("camera", "specular", "diffuse").
    void setRayContext(int depth, const char* type) {
        sgrid_.rayDepth = depth;
        sgrid_.rayType = type;
    }

    // Adds what was shaded since the last call to `out` (the stats' shading.* counters).
    void takeCounters(RenderCounters& out);

  private:
    // The batch's slots (all batchable, one key) in one run over their points together.
    void shadeBatch(const Slot* const* slots, size_t count);
    // Appends to `out` every space a run of `m` at `time` is given (the camera's, "world",
    // "shader", "object", the lights'): slots whose spaces are equal may share a run. False
    // (nothing comparable) when a program reads `time` or a light is an area light.
    bool spacesAt(const Material& m, double time, std::vector<double>& out) const;
    // The class of (m, time) in this flush: equal for times at which m's runs see the same spaces.
    int timeClass(const Material& m, double time);
    bool programSafe(const sl::ShaderProgram& p);

    void displace(const Material& m, Grid& grid, int k, double time);
    void shadeSurface(Grid& grid, int k, double time, const uint8_t* need = nullptr);
    void runSurface(const Material& m, Grid& grid, int k, double time);
    // The surface's shader, or each layer of a layered one, over sgrid_ with `lights`.
    void runSurfaceShaders(const Material& m, const std::vector<sl::LightRef>& lights);
    // After runSurfaceShaders: the surface's value of `g` (a layered one's, LayerNetworkRunner::result).
    sl::ValueRef surfaceResult(const Material& m, sl::Global g) const {
        return m.layers ? network_.result(*vm_, g) : vm_->result(g);
    }
    void runAtmosphere(const Material& m, Grid& grid, int k, double time);
    // The shading grid's inputs for slot k (once per slot, before any of its shaders runs).
    void prepare(const Material& m, const Grid& grid, int k, double time);
    void useShaderSpace(const MotionTransform* shaderToWorld, const Material* m, double time);
    // The material's primitive variables over the grid (u_, v_ set): bound by name, s and t
    // from "s", "t" or "st".
    void bindPrimvars(const Material& m, const Grid& grid, int n, double time);
    void addLight(const sl::ShaderInstance* s, int li, double time, std::vector<sl::LightRef>& out) const;
    void setIncident(const Grid& grid, int k);

    const SceneShaders* shaders_;
    bool depthLayers_ = false, depthOnly_ = false;
    const Camera& camera_;
    const LightSet& lights_;
    std::vector<CameraLight> lightScratch_;
    std::unique_ptr<sl::ShadingVM> vm_;  // made when a grid first needs it
    sl::RaySource* rays_ = nullptr;
    sl::ShadingGrid sgrid_;
    SceneQueries queries_;  // the grid's material's attributes: what attribute() reads
    std::vector<float> u_, v_;
    float du_ = 0, dv_ = 0, time_ = 0;  // uniform inputs the shading grid points at
    Matrix4 worldToCamera_;             // at the slot's time: the render camera's (primitives' space)
    Matrix4 world_;                     // "world" space: the camera of the frame the slot's time falls in
    std::vector<sl::NamedSpace> namedSpaces_;  // the scene's coordinate systems to current space
    std::vector<sl::LightRef> unshadowed_, withOne_;
    std::vector<Color> base_, withLight_;
    std::vector<Vec3f> orthoI_;  // I under an orthographic camera
    std::vector<sl::Primvar> primvars_;
    LayerNetworkRunner network_;  // a layered surface's or displacement's (one after the other)
    std::vector<float> primvarData_;  // their values: constant ones, or n per component
    Grid hit_;  // one point, for shadeHit and runVolume
    Vec3f volumeI_, volumeE_;
    Color volumeCi_, volumeOi_;
    uint64_t builtinPoints_ = 0;
    uint64_t batchRuns_ = 0, batchedGrids_ = 0;
    bool batching_ = true;
    std::vector<std::pair<const sl::ShaderProgram*, bool>> safePrograms_;  // batchProgramSafe, once a program
    Grid batch_;                                  // the batch's points, concatenated
    std::vector<sl::ShadingGridPart> parts_;      // its grids' shapes
    std::vector<float> batchDu_, batchDv_;        // its grids' du and dv, point by point
    // Materials whose batched run refused (a grid-wide operation ran): shaded alone. Only speed
    // depends on it (a material freed and another made at its address is shaded alone too).
    std::vector<const Material*> refused_;
    std::vector<const Slot*> group_;              // slots of one key, in order
    std::vector<uint8_t> slotDone_;
    std::vector<int> slotClass_;                  // each slot's timeClass (-1: not batchable)
    struct TimeClass {
        const Material* material;
        double time;
        int cls;
        size_t signature, length;  // its spaces in signatures_ (length 0: none comparable)
    };
    std::vector<TimeClass> timeClasses_;
    std::vector<double> signatures_;
    const AovLayout* aovs_ = nullptr;  // set when it names shader outputs
    void clearShaderOutputs(Grid& grid, int k) const;
    void copyShaderOutputs(Grid& grid, int k) const;
};

}  // namespace streyes
