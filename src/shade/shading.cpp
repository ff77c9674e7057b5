#include "shade/shading.h"

#include <cmath>

#include "geom/grid.h"

namespace streyes {

namespace {

// RenderMan's faceforward(N, I): N turned to face against the incident direction I.
inline Vec3f faceForward(Vec3f n, Vec3f i) { return dot(n, i) < 0 ? n : -n; }

}  // namespace

Color shadePoint(const Material& m, Color cs, Vec3f p, Vec3f n, bool orthographic,
                 const std::vector<CameraLight>& lights, Color* shadowed, int slots) {
    for (int k = 0; k < slots; ++k) shadowed[k] = {0, 0, 0};
    if (m.kind == SurfaceKind::Constant) return cs * m.Os;
    Vec3f I = orthographic ? Vec3f{0, 0, 1} : normalize(p);
    Vec3f Nf = faceForward(normalize(n), I);
    if (m.kind == SurfaceKind::Default) {
        const float d = dot(Nf, I);  // Pixar's defaultsurface: Ka + Kd (N.I)^2
        return cs * m.Os * (0.2f + 0.8f * (d * d));
    }
    Color ambient{0, 0, 0}, diffuse{0, 0, 0}, specular{0, 0, 0};
    Vec3f V = -I;
    for (int li : m.lights) {
        const CameraLight& l = lights[size_t(li)];
        if (l.kind == LightKind::Ambient) {
            ambient += l.color;
            continue;
        }
        if (l.kind == LightKind::Shader) continue;  // lights only Shading Language surfaces
        Vec3f L;
        Color cl = l.color;
        if (l.kind == LightKind::Distant) {
            L = l.direction;
        } else {
            Vec3f d = l.position - p;
            float d2 = dot(d, d);
            if (!(d2 > 0)) continue;
            cl = cl * (1.0f / d2);
            L = d * (1.0f / std::sqrt(d2));
        }
        float ndl = dot(Nf, L);
        if (ndl <= 0) continue;
        if (shadowed && l.shadowSlot >= 0) {  // this light's share, kept apart for its shadow test
            Color part = cs * (cl * ndl) * m.Kd;
            if (m.kind == SurfaceKind::Plastic) {
                Vec3f H = normalize(L + V);
                float ndh = std::max(0.0f, dot(Nf, H));
                part += m.specularColor * (cl * std::pow(ndh, m.specularExponent / std::max(m.roughness, 1e-4f))) * m.Ks;
            }
            shadowed[l.shadowSlot] = part * m.Os;
            continue;
        }
        diffuse += cl * ndl;
        if (m.kind == SurfaceKind::Plastic) {
            Vec3f H = normalize(L + V);
            float ndh = std::max(0.0f, dot(Nf, H));
            specular += cl * std::pow(ndh, m.specularExponent / std::max(m.roughness, 1e-4f));
        }
    }
    Color c = cs * (ambient * m.Ka + diffuse * m.Kd);
    if (m.kind == SurfaceKind::Plastic) c += m.specularColor * specular * m.Ks;
    return c * m.Os;
}

void shadeGridSlot(Grid& grid, int k, double time, const LightSet& lights, bool orthographic,
                   std::vector<CameraLight>& scratch, const uint8_t* need) {
    const Material& m = *grid.material;
    const int n = grid.vertexCount();
    if (m.kind != SurfaceKind::Constant && m.kind != SurfaceKind::Default && !m.lights.empty()) lights.at(time, scratch);
    const int K = grid.shadowSlots;
    for (int i = 0; i < n; ++i)
        if (!need || need[i])
            grid.Ci[k][size_t(i)] = shadePoint(m, grid.Cs[size_t(i)], grid.P[k][size_t(i)], grid.N[k][size_t(i)], orthographic,
                                               scratch, K ? &grid.Cl[k][size_t(i) * size_t(K)] : nullptr, K);
}

void shadeGrid(Grid& grid, const LightSet& lights, bool orthographic, std::vector<CameraLight>& scratch) {
    for (int k = 0; k < (grid.moving ? 2 : 1); ++k)
        shadeGridSlot(grid, k, k == 0 ? grid.t0 : grid.t1, lights, orthographic, scratch);
}

}  // namespace streyes
