// The rays shaders cast: occlusion(), indirectdiffuse(), trace() and transmission() answered by
// the spacetime ray tracer (sl::RaySource, shade/vm/ray_source.h).
//
// One per thread and ray depth: a bucket worker's GridShader asks the first (depth 1); hits it
// shades run their own shaders on a GridShader of its own, whose rays go to the next depth, made
// when first needed. Past the render's maximum depth every call gives its no-hit value.
//
// Determinism: every ray is cast at the time the grid is shaded, through a hierarchy in which
// whether a ray meets a body does not depend on the rest of the hierarchy, and its directions
// are a function of the point's position, that time, the grid's seed, the call site and the
// sample's number: a frame's pixels are the same whatever block it is rendered in, whatever the
// threads.
#pragma once

#include <memory>
#include <vector>

#include "shade/grid_shader.h"
#include "shade/scene_shaders.h"
#include "shade/vm/environment_lookup.h"
#include "shade/vm/ray_source.h"
#include "streyes/stats.h"
#include "trace/trace.h"

namespace streyes {

class ShaderRays final : public sl::RaySource {
  public:
    // `depth`: 1 for rays from the grids being rendered. Past `maxDepth` nothing is traced.
    ShaderRays(const TraceScene& trace, const SceneShaders* shaders, int depth = 1, int maxDepth = kDefaultMaxDepth);
    ~ShaderRays() override;

    // Option "trace" "maxdepth"'s default, as in PRMan.
    static constexpr int kDefaultMaxDepth = 10;

    void occlusion(const sl::RayOptions& o, const sl::RayQuery& q, float* const* out) override;
    void indirectdiffuse(const sl::RayOptions& o, const sl::RayQuery& q, float* const* out) override;
    void trace(const sl::RayOptions& o, const sl::RayQuery& q, float* const* out) override;
    void transmission(const sl::RayOptions& o, const sl::RayQuery& q, float* const* out) override;
    void gather(const sl::RayOptions& o, const sl::RayQuery& q, int sample, const sl::GatherHits& out) override;

    const TraceScene* scene() const { return &trace_; }
    const SceneShaders* shaders() const { return shaders_; }

    // Adds the rays cast and the hits shaded since the last call (every depth) to `out`.
    void takeCounters(RenderCounters& out);

  private:
    const SpacetimeBVH& hierarchyAt(double time) const;
    float biasAt(const sl::RayOptions& o, Vec3f p, double time) const;
    // The colour the ray brings back from its nearest hits within (tMin, tMax): shaded at the next
    // depth, see-through ones composited over what lies behind them, and over `background` (what
    // it meets past them: an environment map's colour, or black). False: nothing is hit.
    bool shadeAlong(const Ray& ray, double time, float tMin, float tMax, Color background, Color* c);
    // `env`: the call's environment map for rays that hit nothing (null: black); `hitShare`
    // (when not null): the share of the s rays that hit something.
    Color coneMean(Vec3f p, Vec3f axis, float cone, bool cosine, uint32_t s, uint64_t h, double time, float bias,
                   float maxdist, const sl::RayOptions* env = nullptr, float* hitShare = nullptr);
    // The environment map o.environmentmap in current-space directions d[0, n) (into o's
    // "environmentspace"), each filtered over a cone of about `width` radians: into out (left as
    // it is where the map cannot be read; the texture source warns).
    void environmentColors(const sl::RayOptions& o, const Vec3f* d, uint32_t n, float width, double time, Color* out);
    Color shadeHit(const TrilinearBody& body, const TraceHit& h, const Ray& ray, double time, Color* opacity);
    // The GridShader hits and volumes run on (its rays go to the next depth), made when first needed.
    GridShader& hitShader();
    // The volume over the part of `ray` on the side of hit h's surface the ray meets it from:
    // its Interior where the ray leaves the surface (meets it from inside), else its Exterior
    // (`after`: the part past the hit, on the side the ray goes on into). Null: none.
    struct Volume {
        const Material* material = nullptr;
        const sl::ShaderInstance* shader = nullptr;
        const MotionTransform* space = nullptr;
    };
    Volume volumeAt(const TrilinearBody& body, const TraceHit& h, const Ray& ray, double time, bool after) const;
    // The volume's shader over [from, to] on what the ray brings from `to` on (c, *o).
    Color runVolume(const Volume& v, Vec3f from, Vec3f to, double time, Color c, Color* o);
    // c plus the parts of the lights that cast shadows a shadow ray from p reaches.
    Color addReachedLights(Color c, Vec3f p, double time, const SpacetimeBVH& bvh);
    const std::vector<CameraLight>& lightsAt(double time);

    const TraceScene& trace_;
    const SceneShaders* shaders_;
    const int depth_, maxDepth_;
    TraceContext ctx_;
    std::unique_ptr<GridShader> hitShader_;  // shades hits; its rays go to next_
    std::unique_ptr<ShaderRays> next_;
    std::vector<CameraLight> lights_;
    double lightsTime_ = 0;
    bool lightsValid_ = false;
    std::vector<Color> shadowed_;
    struct Layer {  // a hit along a ray, with the volume of the part of the ray before it
        Color ci, oi;
        float t;
        Volume volume;
    };
    std::vector<Layer> layers_;
    std::vector<Vec3f> directions_;  // coneMean's, a point at a time
    std::vector<Color> background_;  // and what each brings where it hits nothing
    std::vector<float> envScratch_;     // environmentColors' query and result arrays
    std::vector<float> envDirections_;  // its directions and colours, interleaved
    const char* rayType_ = "specular";  // what rayinfo("type") says at the hits shaded now
    uint64_t rays_ = 0, bodyTests_ = 0, boxTests_ = 0;
};

}  // namespace streyes
