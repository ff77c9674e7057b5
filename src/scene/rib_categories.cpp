// Option and Attribute values: kept for whoever reads them, and sorted into what streyes uses, what
// only tunes another renderer and what it warns about (rib_categories.h).
#include "scene/rib_categories.h"

#include <algorithm>
#include <set>

namespace streyes {

void keepCategoryValues(const std::string& category, const ParamList& params, ParamList& into) {
    for (const Param& given : params.params) {
        Param p = given;
        p.name = category + ":" + p.name;
        auto same = std::find_if(into.params.begin(), into.params.end(), [&](const Param& q) { return q.name == p.name; });
        if (same != into.params.end()) *same = std::move(p);
        else into.params.push_back(std::move(p));
    }
}

namespace {

// Option categories that only tune how another renderer works (memory, statistics, bucket order,
// ray depth, RIB output) or hold values for shaders and other passes: accepted silently. The
// "limits" streyes reads (bucketsize, gridsize) are read in rib_options.cpp.
const std::set<std::string> kTuningOptions = {"limits", "statistics", "render", "Render", "trace", "texture", "bucket",
                                              "rib",    "user",       "checkpoint", "dice",  "shadow"};

// Attribute categories that tune another renderer's dicing, culling, ray tracing or caches, or
// describe what streyes does anyway (Aqsis's "render" "truedisplacement": displacement moves points).
const std::set<std::string> kTuningAttributes = {"trace", "dice",  "cull",        "render",     "shade", "grouping",
                                                 "sides", "stochastic", "derivatives", "irradiance", "photon"};

double firstNumber(const Param& p, double fallback) { return p.nums.empty() ? fallback : p.nums[0]; }

}  // namespace

void reviewOption(RibParser& reader, const std::string& category, const ParamList& params, const SourceLoc& loc) {
    if (kTuningOptions.count(category)) return;
    // Option "environment:NAME": an environment that is a shader (shade/shader_environment.h).
    if (category.compare(0, 12, "environment:") == 0 && category.size() > 12) return;
    (void)params;
    reader.log().lenient("option:" + category, loc,
                         "Option \"" + category + "\" is not read by streyes: ignored (docs/SCENE-FORMAT.md lists the options it reads)");
}

void reviewAttribute(RibParser& reader, const std::string& category, const ParamList& params, const SourceLoc& loc) {
    if (kTuningAttributes.count(category)) return;
    if (category == "visibility") {
        // Visibility to reflection, diffuse and photon rays tunes a ray tracer streyes does not have
        // for them; to the camera and to shadows it changes the picture.
        for (const Param& p : params.params) {
            if (p.name == "camera" && firstNumber(p, 1) == 0)
                reader.log().lenient("visibility:camera", p.loc,
                                     "Attribute \"visibility\" \"camera\" 0 is not supported: the surface is drawn");
            const bool noShadow = p.name == "transmission" &&
                                  (p.type == ParamType::String ? !p.strings.empty() && p.strings[0] == "transparent"
                                                               : firstNumber(p, 1) == 0);
            if (noShadow)
                reader.log().lenient("visibility:transmission", p.loc,
                                     "Attribute \"visibility\" \"transmission\": surfaces that cast no shadow are not "
                                     "supported: where shadows are on, it casts one");
        }
        return;
    }
    reader.log().lenient("attribute:" + category, loc,
                         "Attribute \"" + category +
                             "\" is not read by streyes: ignored (docs/SCENE-FORMAT.md lists the attributes it reads)");
}

}  // namespace streyes
