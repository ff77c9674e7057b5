#include "streyes/shading.h"

#include <cmath>

#include "streyes/grid.h"

namespace streyes {

Material makeMaterial(const Attributes& a) {
    Material m;
    m.Cs = a.color;
    m.Os = a.opacity;
    m.shadingRate = float(a.shadingRate);
    m.lights = a.lights;
    m.attributes = &a;
    const ParamList& p = a.surface.params;
    const std::string& name = a.surface.name;
    if (name == "constant") {
        m.kind = SurfaceKind::Constant;
    } else if (name == "matte") {
        m.kind = SurfaceKind::Matte;
        m.Ka = float(p.getFloat("Ka", 1));
        m.Kd = float(p.getFloat("Kd", 1));
    } else if (name == "plastic") {
        m.kind = SurfaceKind::Plastic;
        m.Ka = float(p.getFloat("Ka", 1));
        m.Kd = float(p.getFloat("Kd", 0.5));
        m.Ks = float(p.getFloat("Ks", 0.5));
        m.roughness = float(p.getFloat("roughness", 0.1));
        m.specularColor = p.getColor("specularcolor", {1, 1, 1});
    } else {
        m.kind = SurfaceKind::Default;
    }
    return m;
}

LightSet::LightSet(const std::vector<LightDesc>& lights, const MotionTransform& worldToCamera)
    : worldToCamera_(worldToCamera) {
    static_ = worldToCamera.isStatic();
    for (const LightDesc& d : lights) {
        Light l;
        if (d.type == "distantlight") l.kind = LightKind::Distant;
        else if (d.type == "pointlight") l.kind = LightKind::Point;
        else l.kind = LightKind::Ambient;
        l.color = d.params.getColor("lightcolor", {1, 1, 1}) * float(d.params.getFloat("intensity", 1));
        l.from = d.params.getPoint("from", {0, 0, 0});
        l.to = d.params.getPoint("to", {0, 0, 1});
        l.lightToWorld = d.lightToWorld;
        l.castsShadows = d.castsShadows && l.kind != LightKind::Ambient;
        if (l.castsShadows) shadowLights_.push_back(int(lights_.size()));
        static_ = static_ && l.lightToWorld.isStatic();
        lights_.push_back(l);
    }
    if (static_) at(0, staticLights_);
}

void LightSet::at(double t, std::vector<CameraLight>& out) const {
    if (static_ && staticLights_.size() == lights_.size()) {
        out = staticLights_;
        return;
    }
    out.clear();
    Matrix4 w2c = worldToCamera_.at(t);
    int slot = 0;
    for (const Light& l : lights_) {
        Matrix4 m = l.lightToWorld.at(t) * w2c;
        CameraLight c{l.kind, l.color, {}, {}, l.castsShadows ? slot++ : -1};
        Vec3d from = m.point(l.from);
        if (l.kind == LightKind::Point) c.position = Vec3f(from);
        if (l.kind == LightKind::Distant) c.direction = Vec3f(normalize(from - m.point(l.to)));
        out.push_back(c);
    }
}

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
        float d = std::fabs(dot(Nf, I));
        return cs * m.Os * (0.2f + 0.8f * d);
    }
    Color ambient{0, 0, 0}, diffuse{0, 0, 0}, specular{0, 0, 0};
    Vec3f V = -I;
    for (int li : m.lights) {
        const CameraLight& l = lights[size_t(li)];
        if (l.kind == LightKind::Ambient) {
            ambient += l.color;
            continue;
        }
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
                part += m.specularColor * (cl * std::pow(ndh, 1.0f / std::max(m.roughness, 1e-4f))) * m.Ks;
            }
            shadowed[l.shadowSlot] = part * m.Os;
            continue;
        }
        diffuse += cl * ndl;
        if (m.kind == SurfaceKind::Plastic) {
            Vec3f H = normalize(L + V);
            float ndh = std::max(0.0f, dot(Nf, H));
            specular += cl * std::pow(ndh, 1.0f / std::max(m.roughness, 1e-4f));
        }
    }
    Color c = cs * (ambient * m.Ka + diffuse * m.Kd);
    if (m.kind == SurfaceKind::Plastic) c += m.specularColor * specular * m.Ks;
    return c * m.Os;
}

void shadeGrid(Grid& grid, const LightSet& lights, bool orthographic, std::vector<CameraLight>& scratch) {
    const Material& m = *grid.material;
    const int n = grid.vertexCount();
    for (int k = 0; k < (grid.moving ? 2 : 1); ++k) {
        if (m.kind != SurfaceKind::Constant && m.kind != SurfaceKind::Default && !m.lights.empty())
            lights.at(k == 0 ? grid.t0 : grid.t1, scratch);
        const int K = grid.shadowSlots;
        for (int i = 0; i < n; ++i)
            grid.Ci[k][size_t(i)] = shadePoint(m, grid.Cs[size_t(i)], grid.P[k][size_t(i)], grid.N[k][size_t(i)],
                                               orthographic, scratch, K ? &grid.Cl[k][size_t(i) * size_t(K)] : nullptr, K);
    }
}

}  // namespace streyes
