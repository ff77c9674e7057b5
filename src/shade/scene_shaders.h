// The scene's Shading Language shaders: the compiled programs (one ShaderCache per render, along
// the shader search path) and the instances the scene's Surface and LightSource requests make.
//
// A material keeps the built-in shading (shading.h) when its surface is constant, matte, plastic
// or defaultsurface and every light on it is ambientlight, distantlight or pointlight: the
// shipped .sl sources of these give the same numbers (test), and the built-ins are about three
// times faster. Any other surface or light runs its shader over whole grids (grid_shader.h).
// Option "shading" "builtin" "off" runs every material through its shader.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "bodies/material.h"
#include "shade/displacement_reach.h"
#include "shade/light_direction.h"
#include "shade/point_clouds.h"
#include "shade/shader_environment.h"
#include "shade/shadow_maps.h"
#include "shade/scene_queries.h"
#include "shade/sl/compiler.h"
#include "shade/vm/shader_instance.h"
#include "shade/vm/shading_grid.h"
#include "shade/vm/texture_source.h"
#include "streyes/error.h"
#include "streyes/frame_image.h"
#include "streyes/render_options.h"
#include "streyes/scene.h"

namespace streyes {

// The folder of the shipped shaders (shaders/ of the source tree, or share/streyes/shaders of
// an installation): what '@' stands for in the shader search path.
std::string standardShaderDir();

// The render's texture source, made by the factory on the first lookup from any thread (a
// render without lookups never loads the image library), then shared. A factory that fails
// (the library cannot be loaded) warns once, and lookups give their fill value.
// shadow() of a map name goes to the render's ShadowMaps (shade/shadow_maps.h), which the
// library's texture source never sees.
class LazyTextureSource final : public sl::TextureSource {
  public:
    LazyTextureSource(TextureSourceFactory factory, std::vector<std::string> searchPath, ShadowMaps* maps, Log& log)
        : factory_(std::move(factory)), searchPath_(std::move(searchPath)), maps_(maps), log_(log) {}
    bool texture(const std::string& name, const sl::TextureOptions& o, const sl::TextureQuery& q,
                 float* const* out) override;
    bool environment(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q,
                     float* const* out) override;
    bool shadow(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q,
                float* const* out) override;
    bool occlusionMap(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q,
                      const float* const* normal, float* out) override;
    bool textureInfo(const std::string& name, const std::string& field, sl::QueryValue& out) override;
    // Environments that are shaders, looked up before any map of their name (null: none).
    void setShaderEnvironments(const ShaderEnvironments* e) { environments_ = e; }

  private:
    sl::TextureSource* source();
    const ShaderEnvironments* environments_ = nullptr;
    TextureSourceFactory factory_;
    std::vector<std::string> searchPath_;
    ShadowMaps* maps_;
    Log& log_;
    std::once_flag once_;
    std::shared_ptr<sl::TextureSource> source_;
};

class SceneShaders final : public MaterialBinder {
  public:
    // Compiles the scene's light shaders. A shader that does not compile, or a parameter that
    // does not fit its declaration, is an InputError (file:line:column of the shader, or the
    // RIB line of the parameter); a light whose shader is not found warns once and is dark.
    // `textures` makes the texture source when a shader first looks a map up (none: fill values).
    // `maps`: the depth maps shadow() reads (null: only files on disk... none without a reader).
    SceneShaders(const Scene& scene, Log& log, TextureSourceFactory textures = {},
                 std::shared_ptr<const ShadowMapBinding> maps = {});
    // The render's resolution (Format's, or --res): what a pixel of a "raster" displacement bound
    // is. Before materials are bound; Format's until then.
    void setResolution(int width, int height);

    // Sets material.surface (and readsTime, readsMaps, tracesRays, viewUse) unless the built-in
    // shading serves it.
    void bind(Material& material, const Attributes& attributes) const override;

    // Runs the scene's Imager shader (or each layer of a layered one) over a finished frame
    // (nothing without one): Ci and alpha are the pixel's, P its raster position (x + 0.5, y + 0.5,
    // depth).
    void runImager(FrameImage& frame) const;
    bool hasImager() const { return imager_ != nullptr; }

    // What texture() and environment() read, for every thread's interpreter (null: none).
    sl::TextureSource* textures() const { return textures_.get(); }
    // What bake3d(), texture3d() and bake() write and read (written when the render ends).
    PointClouds* pointClouds() const { return clouds_.get(); }
    // How far displacement moved points against its bound (warned when the render ends).
    DisplacementReach& displacementReach() const { return reach_; }

    // What option() and attribute() read on a grid whose primitive has `attributes` (may be null).
    SceneQueries queries(const Attributes* attributes) const { return SceneQueries(&options_, attributes); }
    // The scene's named coordinate systems (CoordinateSystem), each's toCurrent its object-to-world
    // matrix (GridShader follows it with the grid's world space): transform("name", ...).
    const std::vector<sl::NamedSpace>& coordinateSystems() const { return coordinateSystems_; }
    // Where shaders' run-time warnings go (an array index out of range, a runaway loop).
    Log& log() const { return log_; }
    // specular()'s exponent over roughness (RenderSettings::specularExponent).
    float specularExponent() const { return specularExponent_; }

    // Light `i` of the scene as a shader (null when its shader was not found).
    const sl::ShaderInstance* light(size_t i) const { return i < lights_.size() ? lights_[i].get() : nullptr; }
    // Light `i`'s solar cone when its shader is a directional light (shade/light_direction.h).
    const std::optional<SolarCone>& solarCone(size_t i) const { return solar_[i]; }

    // World -> current space at time t: the camera's, or in a merged frame sequence the camera of
    // the frame t falls in (shaders' "world" and "shader" spaces, shadow maps' lookups).
    Matrix4 worldToCameraAt(double t) const { return maps_->worldToCameraAt(t); }
    // Option "trace" "maxdepth": how many levels of rays shaders may cast (trace(), gather(),
    // indirectdiffuse() ... counted together); -1 when the scene does not say.
    int traceMaxDepth() const {
        const sl::QueryValue* v = options_.find("trace:maxdepth");
        if (!v || v->floats.empty() || !(v->floats[0] >= 0)) return -1;
        return v->floats[0] < 1000 ? int(v->floats[0]) : 1000;
    }
    // Do the frames' cameras differ (a still grid's "world" space then changes between frames)?
    bool worldVaries() const { return maps_->worldVaries(); }
    // Does the camera of the frame t falls in move within its exposure ("world" then moves
    // against current space within it)?
    bool worldMovesAt(double t) const { return maps_->worldMovesAt(t); }
    // Do frames read different depth maps under one name (what reads maps then varies)?
    bool mapsVary() const { return maps_->varies(); }
    // Are there depth maps made frame by frame by the input's passes (ShadowMaps::perFrame)?
    bool mapsPerFrame() const { return maps_->perFrame(); }
    // Has a light, or a material bound so far, a shader that casts rays (the renderer then builds
    // the ray tracer's scene)?
    bool tracesRays() const { return tracesRays_.load(std::memory_order_relaxed); }
    // The first Interior or Exterior of a material bound so far (null: none). They run on
    // shaders' rays only: the renderer warns when no shader casts any.
    const ShaderDesc* firstVolume() const { return firstVolume_.load(std::memory_order_relaxed); }

  private:
    void addShaderEnvironments(const Scene& scene);
    std::shared_ptr<sl::ShaderInstance> instance(const std::string& name, const ParamList& params,
                                                 const SourceLoc& loc, sl::ShaderType type) const;
    // A layered shader of `type` (ShaderLayer): each layer's instance, a layer whose shader is not
    // found warned about and left out with its connections; the network when more than one is left.
    struct BoundLayers {
        std::vector<std::shared_ptr<const sl::ShaderInstance>> shaders;
        std::vector<const ShaderDesc*> descs;
        std::shared_ptr<const LayerNetwork> network;  // null: one layer or none
    };
    BoundLayers bindLayers(const ShaderNetwork& net, sl::ShaderType type) const;

    MotionTransform worldToCamera_;
    // One unit of a displacement bound in "screen", "NDC" and "raster" space, in camera space
    // (an orthographic projection's: the larger of its x and y scales across the image, the
    // largest over a zoom's frames), and the projections they come from.
    double screenUnit_ = 1, ndcUnit_ = 1, rasterUnit_ = 1;
    std::vector<CameraDesc> imageCameras_;
    bool perspective_ = false;  // then a bound in them has no single size (the reader warns when it knows)
    OptionValues options_;
    std::vector<sl::NamedSpace> coordinateSystems_;
    std::unique_ptr<sl::ShaderCache> cache_;  // thread-safe: materials are bound on worker threads too
    bool searchPathSet_ = false;
    std::vector<std::shared_ptr<sl::ShaderInstance>> lights_;
    std::vector<bool> builtinLight_;
    std::vector<std::optional<SolarCone>> solar_;  // per light
    ShaderEnvironments environments_;  // Option "environment:NAME" (shade/shader_environment.h)
    std::shared_ptr<const sl::ShaderInstance> imager_;       // the last layer of a layered one
    std::shared_ptr<const LayerNetwork> imagerLayers_;      // a layered imager (ShaderLayer "imager")
    bool builtinShading_ = true;
    float specularExponent_ = 8;
    // Every camera of the render (a sequence's frames' too) moves by rotation and translation
    // only: the view-use analysis's metric rules hold (Material::viewUse).
    bool cameraRigid_ = true;
    Log& log_;
    std::unique_ptr<ShadowMaps> maps_;
    std::unique_ptr<LazyTextureSource> textures_;
    std::unique_ptr<PointClouds> clouds_;
    std::vector<bool> lightReadsMaps_;
    std::vector<bool> lightTracesRays_;
    std::vector<bool> lightStillInWorld_;  // Material::viewUse: a light moving in world reads the view
    mutable DisplacementReach reach_;
    mutable std::atomic<bool> tracesRays_{false};
    mutable std::atomic<const ShaderDesc*> firstVolume_{nullptr};
};

// Sets `params` on `shader`: RIB's types (inline or Declare'd) are checked against the shader's
// declarations; a parameter named without a declaration takes the shader's type. Errors name
// the parameter's RIB file:line. A parameter the shader does not have is left out with a warning
// (Log::lenient: an error under --strict), as PRMan and Aqsis do.
void setShaderParams(sl::ShaderInstance& shader, const ParamList& params, Log& log);

}  // namespace streyes
