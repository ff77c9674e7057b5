// Displacement bounds given in the image's spaces (Attribute "displacementbound"
// "coordinatesystem"): read by the RIB reader, bound by the shading stage, reported by the
// past-the-bound warning.
#pragma once

#include <string>

namespace streyes {

// "screen", "NDC" and "raster": a bound measured across the image, which has one size in camera
// space only under an orthographic projection.
inline bool isImageBoundSpace(const std::string& space) {
    return space == "screen" || space == "NDC" || space == "raster";
}

// What is said of such a bound under a perspective projection (it is then taken in object space).
inline std::string perspectiveImageBoundMessage(const std::string& space) {
    return "Attribute \"displacementbound\": coordinatesystem \"" + space +
           "\" under a perspective projection has no single size in camera space (it grows with depth): the "
           "bound is taken in object space; give it in \"camera\" or \"object\" space";
}

}  // namespace streyes
