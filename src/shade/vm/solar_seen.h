// What the last solar(axis, angle) statement a light ran saw: its axis and angle at the first
// point it reached, and whether both were uniform (ShadingVM::solarSeen). The probe that finds a
// light's direction and cone for its shadow rays reads it after one run (shade/light_direction.h).
#pragma once

#include "streyes/vecmath.h"

namespace streyes::sl {

struct SolarSeen {
    bool seen = false;
    bool uniform = false;
    Vec3f axis{0, 0, 0};
    float angle = 0;
};

}  // namespace streyes::sl
