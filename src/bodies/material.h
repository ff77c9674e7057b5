// Materials: what a body is shaded with. One per attribute state, made when bodies are made from
// the scene (BodyFactory); the shading stage evaluates them (shading.h).
#pragma once

#include <vector>

#include "streyes/scene.h"

namespace streyes {

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

}  // namespace streyes
