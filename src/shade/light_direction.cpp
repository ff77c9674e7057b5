#include "shade/light_direction.h"

#include <cmath>

#include "shade/sl/compiler.h"
#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes {

std::optional<SolarCone> solarCone(const sl::ShaderInstance& light, const Matrix4& lightToWorld) {
    const sl::ShaderProgram& p = light.program();
    if (p.type != sl::ShaderType::Light) return std::nullopt;
    bool solar = false;
    for (const sl::Instr& in : p.code) {
        if (in.fn == sl::ops::illuminate) return std::nullopt;
        solar = solar || in.fn == sl::ops::solar;
    }
    if (!solar) return std::nullopt;
    // A surface that asks every light for its light at one point: current space is the light's
    // "shader" space.
    static const sl::ProgramPtr probe =
        sl::compileShader("surface streyes_solar_probe() { Ci = 0; illuminance(P) { Ci += Cl; } }", "<solar probe>");
    const Vec3f origin{0, 0, 0}, normal{0, 0, 1}, white{1, 1, 1};
    sl::ShadingGrid g;
    g.n = 1;
    g.set(sl::Global::P, sl::ValueRef::uniform(origin));
    g.set(sl::Global::N, sl::ValueRef::uniform(normal));
    g.set(sl::Global::Ng, sl::ValueRef::uniform(normal));
    g.set(sl::Global::I, sl::ValueRef::uniform(normal));
    g.set(sl::Global::Cs, sl::ValueRef::uniform(white));
    g.set(sl::Global::Os, sl::ValueRef::uniform(white));
    Matrix4 worldToShader;
    if (!invert(lightToWorld, &worldToShader)) return std::nullopt;
    g.setSpace(sl::Space::World, worldToShader);
    const sl::ShaderInstance surface(probe);
    std::vector<sl::LightRef> lights{{&light, Matrix4()}};
    sl::ShadingVM vm;
    vm.setPrintSink([](const std::string&) {});  // the light's printf prints in the render, not here
    vm.run(surface, g, lights);
    const sl::SolarSeen& s = vm.solarSeen;
    const Vec3d axis(s.axis);
    if (!s.seen || !s.uniform || !(length(axis) > 0) || !std::isfinite(s.angle)) return std::nullopt;
    return SolarCone{axis, double(s.angle)};
}

}  // namespace streyes
