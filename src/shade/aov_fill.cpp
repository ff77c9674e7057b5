#include "shade/aov_fill.h"

#include <cmath>

#include "bodies/material.h"

namespace streyes {

void fillAovs(Grid& grid, const AovLayout& layout, const Camera& camera) {
    const int A = layout.count;
    if (A == 0) return;
    const bool moves = grid.moving && grid.t1 > grid.t0;
    const float invSpan = moves ? float(1.0 / (grid.t1 - grid.t0)) : 0.0f;
    const float du = grid.nu > 0 ? (grid.u1 - grid.u0) / float(grid.nu) : 0.0f;
    const float dv = grid.nv > 0 ? (grid.v1 - grid.v0) / float(grid.nv) : 0.0f;
    for (int k = 0; k < (grid.moving ? 2 : 1); ++k) {
        float* out = grid.aov[k].data();
        for (size_t vi = 0; vi < layout.vars.size(); ++vi) {
            if (layout.vars[vi].var == AovVar::Shader) continue;  // the surface shader wrote it (GridShader)
            const int o = layout.offset[vi];
            for (int j = 0; j <= grid.nv; ++j)
                for (int i = 0; i <= grid.nu; ++i) {
                    const int v = grid.index(i, j);
                    float* d = out + size_t(v) * size_t(A) + size_t(o);
                    switch (layout.vars[vi].var) {
                        case AovVar::N: {
                            const Vec3f nn = grid.N[k][size_t(v)];
                            const float len = std::sqrt(dot(nn, nn));
                            const float inv = len > 0 ? 1.0f / len : 0.0f;
                            d[0] = nn.x * inv, d[1] = nn.y * inv, d[2] = nn.z * inv;
                            break;
                        }
                        case AovVar::P: {
                            const Vec3f p = grid.P[k][size_t(v)];
                            d[0] = p.x, d[1] = p.y, d[2] = p.z;
                            break;
                        }
                        // As GridShader::prepare places them: borders exactly.
                        case AovVar::s: d[0] = i == grid.nu ? grid.u1 : grid.u0 + float(i) * du; break;
                        case AovVar::t: d[0] = j == grid.nv ? grid.v1 : grid.v0 + float(j) * dv; break;
                        case AovVar::Ci: {
                            const Color c = grid.Ci[k][size_t(v)];
                            d[0] = c.x, d[1] = c.y, d[2] = c.z;
                            break;
                        }
                        case AovVar::Oi: {
                            const Color o = grid.Oi[k].size() > size_t(v) ? grid.Oi[k][size_t(v)] : Color{1, 1, 1};
                            d[0] = o.x, d[1] = o.y, d[2] = o.z;
                            break;
                        }
                        case AovVar::Cs: {  // the surface colour the shader was given (Color, or primvar Cs)
                            const Color c = grid.Cs.size() > size_t(v) ? grid.Cs[size_t(v)] : Color{1, 1, 1};
                            d[0] = c.x, d[1] = c.y, d[2] = c.z;
                            break;
                        }
                        case AovVar::Shader: break;
                        case AovVar::Motion: {
                            if (!moves) {
                                d[0] = d[1] = 0;
                                break;
                            }
                            const Vec3f a = camera.toRaster(grid.P[0][size_t(v)]), b = camera.toRaster(grid.P[1][size_t(v)]);
                            d[0] = (b.x - a.x) * invSpan, d[1] = (b.y - a.y) * invSpan;
                            break;
                        }
                    }
                }
        }
    }
}

}  // namespace streyes
