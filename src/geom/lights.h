// Lights in camera space: the scene's light sources, carried through the camera's and their own
// motion, evaluated at an instant. Shading reads them; so does the ray tracer, for shadow rays.
#pragma once

#include <string>
#include <vector>

#include "streyes/scene.h"
#include "streyes/transform.h"

namespace streyes {

// Shader: a Shading Language light (spotlight, a studio's own); only Shading Language surfaces
// see it, and its shadow rays go to its "from" point (but a directional one's: parallel, below).
enum class LightKind { Ambient, Distant, Point, Shader };

// Light shaders that are distant lights (their illumination is solar(axis, angle):
// shade/light_direction.h finds them, LightSet::setDirectional marks them): their shadow rays
// are parallel to the axis, as distantlight's, spread over the cone of half-angle `angle` (at most
// kMaxConeDegrees) by kConeShadowSamples directions.
constexpr int kConeShadowSamples = 16;
constexpr double kMaxConeDegrees = 10;

struct Light {
    LightKind kind = LightKind::Ambient;
    Color color{1, 1, 1};        // intensity * lightcolor
    Vec3d from{0, 0, 0}, to{0, 0, 1};  // light space
    MotionTransform lightToWorld;
    bool castsShadows = false;
    bool parallel = false;  // a Shader light whose shadow rays run along `towards` (setDirectional)
    Vec3d towards{0, 0, 1};  // light space: towards the light (against its solar axis)
    float coneTan = 0;      // its cone: the tangent of the half-angle
    // An area light (AreaLightSource): its shader runs at these points of its shape, each with the
    // shape's unit normal there, every result weighted 1 / count; lightToWorld takes them to
    // world space (LightDesc::areaToWorld).
    std::vector<Vec3d> areaP, areaN;
};

// Points an area light's shader runs at: stratified by area over its patches.
constexpr int kAreaLightSamples = 16;

// A light at one instant in camera space.
struct CameraLight {
    LightKind kind;
    Color color;
    Vec3f position;   // point and shader lights
    Vec3f direction;  // distant lights: unit vector from the surface towards the light
    int shadowSlot = -1;  // >= 0: the light casts shadows (its slot among those that do)
    bool parallel = false;  // a Shader light with a direction (LightSet::setDirectional)
    float coneTan = 0;      // > 0: shadow rays spread over the cone of this tangent about direction
};

// Whether the light's shadow rays go to its point (point lights, light shaders but parallel ones)
// rather than along its direction.
inline bool shadowsTowardsPoint(const CameraLight& l) {
    return l.kind == LightKind::Point || (l.kind == LightKind::Shader && !l.parallel);
}
// Shadow directions of a directional light: l.direction without a cone; with one, the j-th of
// kConeShadowSamples directions spread evenly over its disc (a Vogel spiral), the same set for
// every point, so that the still test and the per-sample path agree.
Vec3f coneShadowDirection(const CameraLight& l, int j);
int coneShadowSamples(const CameraLight& l);  // 1 without a cone

class LightSet {
  public:
    LightSet() = default;
    LightSet(const std::vector<LightDesc>& lights, const MotionTransform& worldToCamera);
    bool empty() const { return lights_.empty(); }
    // Light `light` (a light shader's, not an area light's) shines along `axis` (its own space:
    // the direction light travels) from a cone of half-angle `angle` radians (clamped to
    // [0, kMaxConeDegrees]): its shadow rays run parallel, against the axis, over the cone.
    // Other lights are left as they are.
    void setDirectional(size_t light, const Vec3d& axis, double angle);
    size_t size() const { return lights_.size(); }
    // Every light in camera space at time t (cached when nothing moves).
    void at(double t, std::vector<CameraLight>& out) const;
    bool isStatic() const { return static_; }
    // Does any of these lights (indices) move in camera space? A frame sequence holds every
    // frame's lights, each held outside its frame: a body reads only its own frames' lights.
    bool anyMoves(const std::vector<int>& lights) const {
        for (int i : lights)
            if (moves_[size_t(i)]) return true;
        return false;
    }
    // Does any of these lights move in world space (a light declared before WorldBegin, which
    // rides with a moving camera, does)? Under a moving camera, a surface whose shading does
    // not read the view is shaded alike from every camera only under lights still in the world.
    bool anyMovesInWorld(const std::vector<int>& lights) const {
        for (int i : lights)
            if (!lights_[size_t(i)].lightToWorld.isStatic()) return true;
        return false;
    }
    // Lights that cast shadows (not ambient lights), numbered 0 .. shadowSlots()-1 in
    // declaration order; shadowLight(slot) is the light's index.
    int shadowSlots() const { return int(shadowLights_.size()); }
    int shadowLight(int slot) const { return shadowLights_[size_t(slot)]; }
    int shadowSlotOf(int light) const { return slotOf_[size_t(light)]; }  // -1: casts none
    LightKind kind(int light) const { return lights_[size_t(light)].kind; }
    // Light `light`'s own space to camera space at time t: its shader's "shader" space.
    Matrix4 lightToCamera(int light, double t) const {
        return lights_[size_t(light)].lightToWorld.at(t) * worldToCamera_.at(t);
    }
    // Area lights: the points the shader runs at (0 for other lights, and for an area light
    // given no geometry: it lights nothing). Sample j's "shader" space is the shape's space moved
    // to the point (world space, but in a frame sequence); its normal is the shape's, in camera
    // space.
    int areaSamples(int light) const { return int(lights_[size_t(light)].areaP.size()); }
    bool isArea(int light) const { return areaLight_[size_t(light)]; }
    Matrix4 areaSampleToCamera(int light, int j, double t) const {
        return Matrix4::translate(lights_[size_t(light)].areaP[size_t(j)]) * lightToCamera(light, t);
    }
    Vec3f areaPoint(int light, int j, double t) const {
        return Vec3f(lightToCamera(light, t).point(lights_[size_t(light)].areaP[size_t(j)]));
    }
    Vec3f areaNormal(int light, int j, double t) const {
        return Vec3f(normalize(lightToCamera(light, t).vector(lights_[size_t(light)].areaN[size_t(j)])));
    }

  private:
    std::vector<Light> lights_;
    MotionTransform worldToCamera_;
    bool static_ = true;
    std::vector<CameraLight> staticLights_;
    std::vector<int> shadowLights_;
    std::vector<int> slotOf_;  // per light: its shadow slot or -1
    std::vector<bool> moves_;  // per light
    std::vector<bool> areaLight_;  // per light
};

}  // namespace streyes
