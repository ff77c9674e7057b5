#include "shade/occlusion_maps.h"

#include <algorithm>
#include <cmath>

#include "shade/shadow_maps.h"
#include "shade/vm/texture_source.h"

namespace streyes {

bool OcclusionViews::set(const DepthMap& map, const Matrix4& currentToWorld, std::string* error) {
    views_.clear();
    std::vector<const DepthMap*> chain;  // the file's maps, last first
    for (const DepthMap* m = &map; m; m = m->previous.get()) chain.push_back(m);
    views_.reserve(chain.size());
    auto add = [&](const DepthMap& m) {
        View v;
        if (!v.lookup.set(m, currentToWorld, error)) return false;
        // The camera's +z in current space: the row of (current -> camera)^-1 that z = 1 picks.
        Matrix4 cameraToCurrent;
        if (!invert(currentToWorld * m.worldToCamera, &cameraToCurrent)) {
            *error = "its world-to-camera matrix is singular";
            return false;
        }
        const Vec3d z = cameraToCurrent.vector({0, 0, 1});
        const double len = std::sqrt(dot(z, z));
        if (!(len > 0) || !std::isfinite(len)) {
            *error = "its world-to-camera matrix has no viewing direction";
            return false;
        }
        v.skyward = z * (-1.0 / len);
        views_.push_back(v);
        return true;
    };
    for (auto it = chain.rbegin(); it != chain.rend(); ++it)
        if (!add(**it)) return false;
    return true;
}

float OcclusionViews::occlusion(const Vec3d& p, const Vec3d& n, float blur, float bias, float samples) const {
    const double nl = std::sqrt(dot(n, n));
    if (!(nl > 0) || !std::isfinite(nl) || views_.empty()) return 0;
    const Vec3d nu = n * (1 / nl);
    ShadowFilter f;
    f.sblur = f.tblur = std::max(0.0f, blur);
    f.bias = bias;
    const double perMap = 4.0 * double(std::max(1.0f, samples)) / double(views_.size());
    double sum = 0, weights = 0;
    const Vec3d none{0, 0, 0};  // no footprint of P's own: the box is the blur (Aqsis's)
    for (const View& v : views_) {
        const double w = dot(nu, v.skyward);
        if (!(w > 0)) continue;
        f.samples = std::max(1, int(std::ceil(perMap * w)));
        sum += w * double(v.lookup.occlusion(p, none, none, f));
        weights += w;
    }
    return weights > 0 ? float(sum / weights) : 0.0f;
}

bool ShadowMaps::occlusion(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q,
                           const float* const* normal, float* out) {
    const DepthMap* m = map(q.time, name);
    if (!m) return false;
    if (m->width == 0) {  // this frame has no map of the name (another pass's frame): open sky
        for (int i = 0; i < q.n; ++i) out[i] = 0;
        return true;
    }
    Matrix4 currentToWorld;
    if (!invert(worldToCameraAt(q.time), &currentToWorld)) return false;
    OcclusionViews views;
    std::string error;
    if (!views.set(*m, currentToWorld, &error)) {
        const SourceLoc where = binding_ && binding_->namedAt.count(name) ? binding_->namedAt.at(name) : SourceLoc{};
        throw InputError(where, "occlusion map \"" + name + "\": " + error);
    }
    const float bias = o.bias > 0 ? o.bias : float(bias_);
    for (int i = 0; i < q.n; ++i) {
        if (q.active && !q.active[i]) continue;
        const Vec3d p{q.R[0][i], q.R[1][i], q.R[2][i]};
        const Vec3d nn{normal[0][i], normal[1][i], normal[2][i]};
        out[i] = views.occlusion(p, nn, o.sblur, bias, o.samples);
    }
    return true;
}

}  // namespace streyes
