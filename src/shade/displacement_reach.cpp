// Displacement past its bound (shade/displacement_reach.h).
#include "shade/displacement_reach.h"

#include <cstdio>

#include "scene/bound_spaces.h"

namespace streyes {

namespace {

std::string reachNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", v);
    return text;
}

}  // namespace

void DisplacementReach::noteOver(const Material& m, float largest) {
    const Attributes* a = m.attributes;
    const SourceLoc loc = a ? a->displacement.loc : SourceLoc{};
    const std::string key = loc.str();
    std::lock_guard<std::mutex> lock(mutex_);
    Over& o = over_[key];
    // The worst move against its own bound (attribute sets sharing a request may differ in bound).
    if (o.largest > 0 && !(largest - m.displacementBound > o.largest - o.cameraBound)) return;
    o.loc = loc;
    o.shader = a ? a->displacement.name : std::string();
    o.space = a ? a->displacementBoundSpace : std::string("object");
    o.bound = a ? a->displacementBound : 0;
    o.cameraBound = m.displacementBound;
    o.largest = largest;
}

void DisplacementReach::report(Log& log) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [key, o] : over_) {
        // The bound that would hold the largest move, in the space the bound was given in (its
        // scale to camera space is the given bound's; with none given, camera space itself).
        // Image spaces ("screen", "NDC", "raster") fall back to object space under a perspective
        // projection: the hint is then given in camera space, right under either projection.
        const bool scaled = o.bound > 0 && o.cameraBound > 0 && !isImageBoundSpace(o.space);
        const double need = scaled ? o.largest * o.bound / o.cameraBound : o.largest;
        const std::string space = scaled ? o.space : std::string("camera");
        const std::string given =
            o.bound > 0 ? "its bound is " + reachNumber(o.bound) + " (Attribute \"displacementbound\" \"sphere\" in \"" +
                              o.space + "\" space; " + reachNumber(o.cameraBound) + " in camera space)"
                        : "it has no Attribute \"displacementbound\" (a bound of 0)";
        log.warnOnce("displacementbound:" + key, o.loc,
                     "Displacement \"" + o.shader + "\" moved points up to " + reachNumber(o.largest) +
                         " (camera space) but " + given +
                         ": parts of the surface moved past the bound may be missing from the picture; raise it to "
                         "at least Attribute \"displacementbound\" \"sphere\" [" + reachNumber(need * 1.01) +
                         "] \"coordinatesystem\" [\"" + space + "\"]");
    }
}

}  // namespace streyes
