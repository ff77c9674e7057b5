// Scenes the pass planner reads or makes (scene/pass_scenes.h).
#include "scene/pass_scenes.h"

#include <algorithm>
#include <limits>
#include <set>
#include <vector>

#include "scene/blobby_cut.h"
#include "streyes/passes.h"

namespace streyes {

// Every string a shader parameter of the scene gives (lights, surfaces, displacements,
// atmospheres, the imager, in objects too), with where it is first given: the names a frame may
// read maps and textures by.
void stringsOf(const Scene& s, std::map<std::string, SourceLoc>& out) {
    auto params = [&](const ParamList& l) {
        for (const Param& p : l.params)
            for (const std::string& v : p.strings)
                if (!v.empty()) out.emplace(v, p.loc);
    };
    for (const LightDesc& l : s.lights) params(l.params);
    params(s.settings.imager.params);
    for (const ShaderDesc& d : s.settings.imagerLayers.layers) params(d.params);
    std::set<const Attributes*> seen;
    auto attributes = [&](const AttributesPtr& a) {
        if (!a || !seen.insert(a.get()).second) return;
        params(a->surface.params);
        for (const ShaderDesc& d : a->surfaceLayers.layers) params(d.params);
        params(a->displacement.params);
        for (const ShaderDesc& d : a->displacementLayers.layers) params(d.params);
        params(a->atmosphere.params);
        params(a->interior.params);
        params(a->exterior.params);
    };
    auto each = [&](const auto& v) {
        for (const auto& p : v) attributes(p.attributes);
    };
    each(s.patches), each(s.patchMeshes), each(s.subdivisionMeshes), each(s.quadrics), each(s.polygonMeshes);
    each(s.curves), each(s.points), each(s.nuPatches), each(s.procedurals);
    for (const ProceduralDesc& p : s.procedurals)
        if (p.object) stringsOf(*p.object, out);
    // A Blobby cut when its pass renders reads its repelling planes' maps then.
    for (const PolygonMeshDesc& m : s.polygonMeshes)
        if (m.deferred)
            for (const auto& [at, name] : m.deferred->key.planeMaps)
                if (m.deferred->key.field.ops[at].repel[0] > 0) out.emplace(name, m.deferred->loc);
}

namespace {

MotionTransform inverse(const MotionTransform& m) {
    std::vector<Matrix4> keys;
    for (const Matrix4& k : m.keys()) {
        Matrix4 inv;
        if (!invert(k, &inv)) inv = Matrix4();
        keys.push_back(inv);
    }
    return MotionTransform(m.times(), std::move(keys));
}

}  // namespace

// Attribute "autoshadows" on a light (Aqsis): the depth frame rendered from it before the frame, as
// Aqsis renders it: the light's space as the camera, the frame's projection over the screen
// window [-1, 1]^2, res x res pixels, one sample a pixel unjittered under a 1-pixel box, depths
// by "midpoint", written as a shadow map.
Scene autoShadowFrame(const Scene& picture, const LightDesc& light) {
    Scene s = picture;
    s.camera.worldToCamera = inverse(light.lightToWorld);
    s.camera.hasScreenWindow = true;
    const double window[4] = {-1, 1, -1, 1};
    std::copy(window, window + 4, s.camera.screenWindow);
    s.camera.frameAspect = 1;
    s.camera.xres = s.camera.yres = light.autoShadowRes;
    s.camera.pixelAspect = 1;
    s.camera.fstop = std::numeric_limits<double>::infinity();
    RenderSettings& r = s.settings;
    r.pixelSamplesX = r.pixelSamplesY = 1;
    r.filter = FilterDesc{"box", 1, 1};
    r.jitter = false;
    r.depthFilter = "midpoint";
    DisplayDesc map;
    map.name = light.autoShadowMap, map.type = "shadow", map.mode = "z", map.loc = light.autoShadowLoc;
    map.quantize = kDepthQuantize;
    r.displays = {map};
    r.imager = ShaderDesc{};
    r.imagerLayers = {};
    r.exposureGain = r.exposureGamma = 1;
    r.makeTextures.clear();
    r.makeShadows.clear();
    s.frameLoc = light.autoShadowLoc;
    return s;
}

}  // namespace streyes
