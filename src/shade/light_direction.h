// Directional light shaders: a light whose illumination is solar(axis, angle) shines along its
// axis from a cone of half-angle `angle` about it (the RenderMan Shading Language's distant
// light). Its ray-traced shadows then run parallel to the axis, spread over the cone
// (geom/lights.h), whatever the shader is called: what decides is what its code does.
#pragma once

#include <optional>

#include "shade/vm/shader_instance.h"
#include "streyes/transform.h"

namespace streyes {

struct SolarCone {
    Vec3d axis;    // the direction the light travels, in the light's "shader" space
    double angle;  // the cone's half-angle, radians (0: one direction)
};

// The axis and angle of `light`'s solar statement with this instance's parameters, when the
// shader has solar(axis, angle) and no illuminate, and both arguments are uniform (the same for
// every point lit: parameters, constants and what is computed from them). They are read off one
// run of the light over a probe point: "shader" space is the light's own, "world" space is
// lightToWorld's at time 0 (an axis named in world space on a moving light is taken then).
// nullopt otherwise (a light that lights from a point, a solar() without an axis, an axis or
// angle that varies over the points, a solar statement the probe point does not reach).
std::optional<SolarCone> solarCone(const sl::ShaderInstance& light, const Matrix4& lightToWorld);

}  // namespace streyes
