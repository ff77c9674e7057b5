#include "geom/lights.h"

#include <algorithm>
#include <cmath>

namespace streyes {

namespace {

double radicalInverse2(uint32_t i) {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
    i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
    i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
    i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
    return double(i) * (1.0 / 4294967296.0);
}

Vec3d bilinearAt(const std::array<Vec3d, 4>& p, double u, double v) {
    return (p[0] * (1 - u) + p[1] * u) * (1 - v) + (p[2] * (1 - u) + p[3] * u) * v;
}

// kAreaLightSamples points over an area light's patches, a Hammersley set over the patches laid
// end to end by area: the first coordinate picks the patch (and u within it), the second is v.
void sampleArea(const std::vector<std::array<Vec3d, 4>>& patches, Light& l) {
    std::vector<double> cumulative;
    double total = 0;
    for (const std::array<Vec3d, 4>& p : patches) {
        total += 0.5 * (length(cross(p[1] - p[0], p[3] - p[0])) + length(cross(p[3] - p[0], p[2] - p[0])));
        cumulative.push_back(total);
    }
    if (!(total > 0)) return;
    for (int j = 0; j < kAreaLightSamples; ++j) {
        const double x = (j + 0.5) / kAreaLightSamples * total, v = radicalInverse2(uint32_t(j));
        const size_t k = size_t(std::lower_bound(cumulative.begin(), cumulative.end(), x) - cumulative.begin());
        const size_t f = std::min(k, patches.size() - 1);
        const double start = f == 0 ? 0 : cumulative[f - 1], width = cumulative[f] - start;
        const double u = width > 0 ? (x - start) / width : 0.5;
        const std::array<Vec3d, 4>& p = patches[f];
        Vec3d n = cross(bilinearAt(p, std::min(1.0, u + 1e-3), v) - bilinearAt(p, std::max(0.0, u - 1e-3), v),
                        bilinearAt(p, u, std::min(1.0, v + 1e-3)) - bilinearAt(p, u, std::max(0.0, v - 1e-3)));
        const double nl = length(n);
        l.areaP.push_back(bilinearAt(p, u, v));
        l.areaN.push_back(nl > 0 ? n / nl : Vec3d{0, 0, 1});
    }
}

}  // namespace

int coneShadowSamples(const CameraLight& l) { return l.coneTan > 0 ? kConeShadowSamples : 1; }

Vec3f coneShadowDirection(const CameraLight& l, int j) {
    if (!(l.coneTan > 0)) return l.direction;
    const Vec3f d = l.direction;
    const Vec3f u = normalize(std::fabs(d.y) < 0.9f ? cross(d, Vec3f{0, 1, 0}) : cross(d, Vec3f{1, 0, 0}));
    const Vec3f v = cross(d, u);
    const float r = l.coneTan * std::sqrt((float(j) + 0.5f) / float(kConeShadowSamples));
    const float phi = float(j) * 2.39996323f;  // the golden angle
    return normalize(d + u * (r * std::cos(phi)) + v * (r * std::sin(phi)));
}

LightSet::LightSet(const std::vector<LightDesc>& lights, const MotionTransform& worldToCamera)
    : worldToCamera_(worldToCamera) {
    static_ = worldToCamera.isStatic();
    for (const LightDesc& d : lights) {
        Light l;
        if (d.type == "distantlight") l.kind = LightKind::Distant;
        else if (d.type == "pointlight") l.kind = LightKind::Point;
        else if (d.type == "ambientlight") l.kind = LightKind::Ambient;
        else l.kind = LightKind::Shader;
        // A shader light's parameters are typed by its shader: read from and to only when RIB
        // typed them as points.
        const Param* from = d.params.find("from");
        const Param* to = d.params.find("to");
        if (!from || from->type == ParamType::Point) l.from = d.params.getPoint("from", {0, 0, 0});
        if (!to || to->type == ParamType::Point) l.to = d.params.getPoint("to", {0, 0, 1});
        l.color = l.kind == LightKind::Shader
                      ? Color{0, 0, 0}
                      : d.params.getColor("lightcolor", {1, 1, 1}) * float(d.params.getFloat("intensity", 1));
        l.lightToWorld = d.lightToWorld;
        if (d.area) {
            // Its shader runs at points of its shape, each with "shader" space moved there.
            l.kind = LightKind::Shader;
            sampleArea(d.areaPatches, l);
            l.lightToWorld = d.areaToWorld;
            Vec3d c{0, 0, 0};
            for (const Vec3d& p : l.areaP) c = c + p / double(std::max<size_t>(1, l.areaP.size()));
            l.from = c;  // the centre: where a light has one position (the ray tracer's bound)
        }
        areaLight_.push_back(d.area);
        // Attribute "light" "shadows" "on", or the light shader's "shadowname" "raytrace" (the
        // RenderMan convention: its shadow() calls read 0 and the renderer traces per sample).
        const Param* shadowName = d.params.find("shadowname");
        const bool raytraced = shadowName && shadowName->type == ParamType::String && !shadowName->strings.empty() &&
                               shadowName->strings[0] == "raytrace";
        l.castsShadows = (d.castsShadows || raytraced) && l.kind != LightKind::Ambient;
        slotOf_.push_back(l.castsShadows ? int(shadowLights_.size()) : -1);
        if (l.castsShadows) shadowLights_.push_back(int(lights_.size()));
        static_ = static_ && l.lightToWorld.isStatic();
        moves_.push_back(!worldToCamera.isStatic() || !l.lightToWorld.isStatic());
        lights_.push_back(l);
    }
    if (static_) at(0, staticLights_);
}

void LightSet::setDirectional(size_t light, const Vec3d& axis, double angle) {
    Light& l = lights_[light];
    if (l.kind != LightKind::Shader || areaLight_[light] || !(length(axis) > 0)) return;
    l.parallel = true;
    // 0 - axis, not -axis: a component of 0 stays +0, as from - to gives it, so a solar() light's
    // rays are bit for bit a distant light's (the hierarchy's slab test takes -0 as +0 anyway).
    l.towards = Vec3d{0, 0, 0} - axis;
    const double cone = std::clamp(std::isfinite(angle) ? angle : 0.0, 0.0, kMaxConeDegrees * M_PI / 180);
    l.coneTan = float(std::tan(cone));
    if (static_) {
        staticLights_.clear();  // else at() gives the cache back
        at(0, staticLights_);
    }
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
        CameraLight c{l.kind, l.color, {}, {}, l.castsShadows ? slot++ : -1, l.parallel, l.coneTan};
        Vec3d from = m.point(l.from);
        if (l.kind == LightKind::Point || l.kind == LightKind::Shader) c.position = Vec3f(from);
        if (l.kind == LightKind::Distant) c.direction = Vec3f(normalize(from - m.point(l.to)));
        if (l.parallel) c.direction = Vec3f(normalize(m.vector(l.towards)));
        out.push_back(c);
    }
}

}  // namespace streyes
