#include "geom/lights.h"

namespace streyes {

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
        if (l.kind == LightKind::Point || l.kind == LightKind::Shader) c.position = Vec3f(from);
        if (l.kind == LightKind::Distant) c.direction = Vec3f(normalize(from - m.point(l.to)));
        out.push_back(c);
    }
}

}  // namespace streyes
