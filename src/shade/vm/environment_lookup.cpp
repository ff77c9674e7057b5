// The environment lookup of indirectdiffuse() and occlusion() (environment_lookup.h).
#include "shade/vm/environment_lookup.h"

#include <cmath>

namespace streyes::sl {

namespace {

// An orthonormal frame about unit r (Duff et al. 2017; the ray tracer's frameOf): the footprint's axes.
void perpendiculars(const float r[3], float t[3], float b[3]) {
    const float sign = std::copysign(1.0f, r[2]);
    const float a = -1.0f / (sign + r[2]);
    const float c = r[0] * r[1] * a;
    t[0] = 1.0f + sign * r[0] * r[0] * a, t[1] = sign * c, t[2] = -sign * r[0];
    b[0] = c, b[1] = sign + r[1] * r[1] * a, b[2] = -r[1];
}

}  // namespace

bool lookupEnvironment(TextureSource* textures, const RayOptions& o, const float* d, int n, const float* widths,
                       float width, float time, std::vector<float>& scratch, float* out) {
    if (!textures || n <= 0) return false;
    scratch.resize(size_t(n) * 12);
    float* a = scratch.data();
    auto column = [&](int k) { return a + size_t(k) * size_t(n); };
    DirectionQuery q;
    q.n = n;
    q.time = time;
    float* result[3];
    for (int c = 0; c < 3; ++c) {
        q.R[c] = column(c);
        q.dRdu[c] = column(3 + c);
        q.dRdv[c] = column(6 + c);
        result[c] = column(9 + c);
    }
    const float* m = o.environmentFromCurrent;  // row vectors: r = d * M
    for (int i = 0; i < n; ++i) {
        const float* v = d + size_t(i) * 3;
        float r[3] = {v[0] * m[0] + v[1] * m[4] + v[2] * m[8], v[0] * m[1] + v[1] * m[5] + v[2] * m[9],
                      v[0] * m[2] + v[1] * m[6] + v[2] * m[10]};
        const float len = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
        if (len > 0)
            for (float& x : r) x /= len;
        float t[3], b[3];
        perpendiculars(r, t, b);
        const float w = widths ? widths[i] : width;
        for (int c = 0; c < 3; ++c) {
            column(c)[i] = r[c];
            column(3 + c)[i] = t[c] * w;
            column(6 + c)[i] = b[c] * w;
        }
    }
    TextureOptions opt;
    opt.channels = 3;
    opt.shader = o.shader;
    if (!textures->environment(o.environmentmap, opt, q, result)) return false;
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) out[size_t(i) * 3 + size_t(c)] = result[c][i];
    return true;
}

}  // namespace streyes::sl
