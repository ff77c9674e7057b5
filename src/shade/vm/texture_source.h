// Where texture(), environment() and shadow() get their values: an interface the renderer
// implements (with OpenImageIO's TextureSystem, or by tracing rays for shadows) and tests
// replace with a double.
//
// One call looks up every active point of a grid (one virtual call per call site and grid,
// never per point). Arrays are structure-of-arrays, n long; the source writes out[c][i] for
// each channel c < options.channels and each active point i (the rest are ignored).
#pragma once

#include <cstdint>
#include <string>

#include "shade/vm/state_queries.h"

namespace streyes::sl {

// The named arguments of a lookup ("blur", "width", "fill", ...), uniform over the grid.
struct TextureOptions {
    float sblur = 0, tblur = 0;    // "blur" sets both
    float swidth = 1, twidth = 1;  // "width" sets both: multiplies the footprint
    float fill = 0;                // value of channels the file lacks
    float bias = 0;                // shadow: depth bias (0: the source's default)
    float samples = 0;             // shadow: samples (0: the source's default)
    std::string filter;            // "" : the source's default
    int firstChannel = 0;          // texture("name"[c]) starts at channel c
    int channels = 1;              // 1 for float lookups, 3 for color lookups
    const std::string* shader = nullptr;  // the calling shader's name, for the source's warnings
};

// texture(): the point's (s, t) and its footprint: the change of s and t across one
// micropolygon along u (dsdu = Du(s) du) and along v. The four-corner form (s1,t1 .. s4,t4)
// arrives converted: the centre is the corners' mean, d?du = ((x2 - x1) + (x4 - x3)) / 2 and
// d?dv = ((x3 - x1) + (x4 - x2)) / 2.
struct TextureQuery {
    int n = 0;
    const uint8_t* active = nullptr;  // nullptr: every point
    const float *s = nullptr, *t = nullptr;
    const float *dsdu = nullptr, *dtdu = nullptr, *dsdv = nullptr, *dtdv = nullptr;
    float time = 0;
};

// environment(): a direction (world of the map is the caller's business: shaders pass what
// they computed, usually in "world" space) with its change along u and v. shadow(): a
// position in current space, with the same footprint.
struct DirectionQuery {
    int n = 0;
    const uint8_t* active = nullptr;
    const float* R[3] = {};
    const float* dRdu[3] = {};
    const float* dRdv[3] = {};
    // shadow() inside a light's illuminate(from ...): the light's position per point (current
    // space), so that a source can trace a ray from R to it instead of reading a map. Null
    // elsewhere (and inside solar, where `lightDir` is the direction light travels).
    const float* lightFrom[3] = {};
    const float* lightDir[3] = {};
    float time = 0;
};

class TextureSource {
  public:
    virtual ~TextureSource() = default;
    // Each returns false when `name` cannot be read; the interpreter then fills the result
    // with options.fill (texture, environment) or 0 (shadow: unoccluded) and counts it.
    virtual bool texture(const std::string& name, const TextureOptions& options, const TextureQuery& q,
                         float* const* out) = 0;
    virtual bool environment(const std::string& name, const TextureOptions& options, const DirectionQuery& q,
                             float* const* out) = 0;
    // The fraction of light blocked at each point: 0 lit, 1 in shadow.
    virtual bool shadow(const std::string& name, const TextureOptions& options, const DirectionQuery& q,
                        float* const* out) = 0;
    // occlusion(mapname, P, N, ...): the occlusion at each point R of q about normal[c][i] from
    // the depth maps of a multi-map file (shade/occlusion_maps.h). False: not read (0, counted).
    virtual bool occlusionMap(const std::string& name, const TextureOptions& options, const DirectionQuery& q,
                              const float* const* normal, float* out) {
        (void)name, (void)options, (void)q, (void)normal, (void)out;
        return false;
    }
    // textureinfo(name, field): "resolution" (float[2]), "type" ("texture", "environment" or
    // "shadow"), "channels" (float), "viewingmatrix" and "projectionmatrix" (the world to camera
    // and world to screen matrices of a map rendered by a camera). False when the map cannot be
    // read or has no such field.
    virtual bool textureInfo(const std::string& name, const std::string& field, QueryValue& out) {
        (void)name, (void)field, (void)out;
        return false;
    }
};

}  // namespace streyes::sl
