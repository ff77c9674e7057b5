// Shading: the built-in surface shaders (constant, matte, plastic, defaultsurface) and lights
// (ambientlight, distantlight, pointlight), evaluated at grid vertices in camera space.
//
// REYES shades the vertices of a diced grid, not samples. A moving grid is shaded at t0 and at
// t1 and the colour is interpolated in time between them; a still grid is shaded once.
//
// Shadows: a light declared with Attribute "light" "shadows" "on" has a shadow slot. Its
// contribution is kept apart from the rest (shadePoint's `shadowed` parts; Grid::Cl per vertex)
// and added per sample where a shadow ray at the sample's own time reaches the light (trace.h),
// so shadows blur with motion even on still geometry shaded once.
#pragma once

#include <string>
#include <vector>

#include "streyes/scene.h"
#include "streyes/util/transform.h"

namespace streyes {

struct Grid;

enum class SurfaceKind { Constant, Matte, Plastic, Default };

// A surface shader bound to its attribute state: what a body points at.
struct Material {
    SurfaceKind kind = SurfaceKind::Default;
    Color Cs{1, 1, 1};
    Color Os{1, 1, 1};
    float Ka = 1, Kd = 1, Ks = 0.5f, roughness = 0.1f;
    Color specularColor{1, 1, 1};
    float shadingRate = 1;
    std::vector<int> lights;  // indices into the render's LightSet
    const Attributes* attributes = nullptr;
};

// Builds a Material from an attribute state; unknown shader names have been handled by the
// parser (they fall back to defaultsurface).
Material makeMaterial(const Attributes& attributes);

enum class LightKind { Ambient, Distant, Point };

struct Light {
    LightKind kind = LightKind::Ambient;
    Color color{1, 1, 1};        // intensity * lightcolor
    Vec3d from{0, 0, 0}, to{0, 0, 1};  // light space
    MotionTransform lightToWorld;
    bool castsShadows = false;
};

// A light at one instant in camera space.
struct CameraLight {
    LightKind kind;
    Color color;
    Vec3f position;   // point lights
    Vec3f direction;  // distant lights: unit vector from the surface towards the light
    int shadowSlot = -1;  // >= 0: the light casts shadows (its slot among those that do)
};

class LightSet {
  public:
    LightSet() = default;
    LightSet(const std::vector<LightDesc>& lights, const MotionTransform& worldToCamera);
    bool empty() const { return lights_.empty(); }
    size_t size() const { return lights_.size(); }
    // Every light in camera space at time t (cached when nothing moves).
    void at(double t, std::vector<CameraLight>& out) const;
    bool isStatic() const { return static_; }
    // Lights that cast shadows (not ambient lights), numbered 0 .. shadowSlots()-1 in
    // declaration order; shadowLight(slot) is the light's index.
    int shadowSlots() const { return int(shadowLights_.size()); }
    int shadowLight(int slot) const { return shadowLights_[size_t(slot)]; }

  private:
    std::vector<Light> lights_;
    MotionTransform worldToCamera_;
    bool static_ = true;
    std::vector<CameraLight> staticLights_;
    std::vector<int> shadowLights_;
};

// The colour Ci of one surface point (position p, unnormalised normal n, surface colour cs, all
// in camera space): what shadeGrid computes at each vertex and the ray tracer at each hit.
// With `shadowed` given (room for `slots` colours), the contribution of each light that casts
// shadows goes to shadowed[its slot] instead of the result (0 where it does not reach); without
// it, every light is in the result.
Color shadePoint(const Material& m, Color cs, Vec3f p, Vec3f n, bool orthographic,
                 const std::vector<CameraLight>& lights, Color* shadowed = nullptr, int slots = 0);

// Shades grid.Ci[k] for every vertex at the grid's t0 (and t1 when moving). `orthographic`
// sets the view direction to +z instead of from the eye. With grid.shadowSlots > 0 the lights
// that cast shadows go to grid.Cl[k] instead.
void shadeGrid(Grid& grid, const LightSet& lights, bool orthographic, std::vector<CameraLight>& scratch);

}  // namespace streyes
