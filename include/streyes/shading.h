// Shading: the built-in surface shaders (constant, matte, plastic, defaultsurface) and lights
// (ambientlight, distantlight, pointlight), evaluated at grid vertices in camera space.
//
// REYES shades the vertices of a diced grid, not samples. A moving grid is shaded at t0 and at
// t1 and the colour is interpolated in time between them; a still grid is shaded once.
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
};

// A light at one instant in camera space.
struct CameraLight {
    LightKind kind;
    Color color;
    Vec3f position;   // point lights
    Vec3f direction;  // distant lights: unit vector from the surface towards the light
};

class LightSet {
  public:
    LightSet() = default;
    LightSet(const std::vector<LightDesc>& lights, const MotionTransform& worldToCamera);
    bool empty() const { return lights_.empty(); }
    size_t size() const { return lights_.size(); }
    // Every light in camera space at time t (cached when nothing moves).
    void at(double t, std::vector<CameraLight>& out) const;

  private:
    std::vector<Light> lights_;
    MotionTransform worldToCamera_;
    bool static_ = true;
    std::vector<CameraLight> staticLights_;
};

// Shades grid.Ci[k] for every vertex at the grid's t0 (and t1 when moving). `orthographic`
// sets the view direction to +z instead of from the eye.
void shadeGrid(Grid& grid, const LightSet& lights, bool orthographic, std::vector<CameraLight>& scratch);

}  // namespace streyes
