// Map-based ambient occlusion: occlusion(mapname, P, N, samples, ...) over the depth maps of a
// multi-map file (Display "shadow" | "zfile" with "append": one map a direction, rendered from
// around the scene), as Aqsis computes it (libs/tex/filtering/occlusionsampler.cpp).
//
// Each map looks along its camera's +z; it sees what blocks the sky in the opposite direction,
// -z. A point's occlusion is the mean of the maps' percentage-closer lookups at P (the fraction
// of the filter box whose depth lies in front of P, as shadow() with no footprint of its own:
// the box is "blur" times the map's size, at least one texel, compared with P's own depth less
// the bias), each weighted by the cosine between N and the map's -z, over the maps facing N
// (cosine > 0):
//
//     occlusion = sum_i w_i occ_i / sum_i w_i,   w_i = max(0, N . -z_i)
//
// which is the cosine-weighted fraction of the hemisphere about N that is blocked, when the maps'
// directions spread evenly over the sphere. Aqsis draws 4 * samples * w_i / nmaps jittered taps
// from map i and averages them all, whose expectation is this sum; here each box is weighed
// exactly (up to kExactTexels texels, else that many stratified taps), so the answer has no noise
// and does not depend on how a grid is split. No map facing N: 0 (Aqsis divides 0 by 0).
#pragma once

#include <vector>

#include "shade/shadow_map.h"

namespace streyes {

// The maps of one file, each read from "current" space, with the sky direction each one sees.
class OcclusionViews {
  public:
    // `map` and the maps before it in its file (DepthMap::previous), in file order; false (with *error) when one has singular matrices.
    bool set(const DepthMap& map, const Matrix4& currentToWorld, std::string* error);
    size_t size() const { return views_.size(); }
    // The occlusion at p (current space) about the normal n (need not be unit length). `samples`:
    // the call's "samples" (taps of a box larger than kExactTexels texels, shared as Aqsis shares
    // them: 4 * samples * w_i / nmaps to map i, at least one).
    float occlusion(const Vec3d& p, const Vec3d& n, float blur, float bias, float samples) const;
    // The direction map i sees the sky along (unit, current space: its camera's -z).
    const Vec3d& skyward(size_t i) const { return views_[i].skyward; }

  private:
    struct View {
        ShadowLookup lookup;
        Vec3d skyward;
    };
    std::vector<View> views_;
};

}  // namespace streyes
