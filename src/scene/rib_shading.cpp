// Shading: the surface shader (Surface) and lights (LightSource, Illuminate). A light is on in the
// attribute block where it is declared and the blocks inside it, or as Illuminate turns it.
#include <algorithm>
#include <map>
#include <set>

#include "scene/rib_requests.h"

namespace streyes {

namespace {

// The built-in surfaces' parameters are checked here; any other name is a Shading Language
// shader found along the shader search path when the render binds it (shade/scene_shaders.h),
// which checks its parameters against the shader's declarations.
void surface(RibParser& reader, RibArgs& args) {
    static const std::map<std::string, std::vector<std::string>> builtins = {
        {"constant", {}},
        {"defaultsurface", {}},
        {"matte", {"Ka", "Kd"}},
        {"plastic", {"Ka", "Kd", "Ks", "roughness", "specularcolor"}}};
    std::string name = args.string("shader name");
    if (name.empty()) args.fail("the shader name is empty");
    // "null": no shader of its own, as depth passes write it. Aqsis shades such a surface with its
    // default surface, without a word; so does streyes (defaultsurface).
    if (name == "null") name = "defaultsurface";
    ParamList params = reader.readParams(args, true);
    auto builtin = builtins.find(name);
    if (builtin != builtins.end()) {
        // Check the values now, so that a bad one is reported here rather than while shading.
        for (const char* f : {"Ka", "Kd", "Ks"}) params.getFloat(f, 0);
        if (params.getFloat("roughness", 0.1) <= 0)
            throw InputError(params.find("roughness")->loc, "Surface: roughness must be positive");
        params.getColor("specularcolor", Color(1, 1, 1));
        reader.warnUnusedParams(params, builtin->second, "Surface \"" + name + "\"");
    }
    reader.state().mutableAttributes().surface = ShaderDesc{name, std::move(params), args.loc(), reader.state().ctm};
}

// A shader request's name and parameters, with the CTM as its "shader" space. "null" (the RI
// Spec's way to turn a displacement, atmosphere or imager off) gives no name.
ShaderDesc readShader(RibParser& reader, RibArgs& args) {
    std::string name = args.string("shader name");
    ParamList params = reader.readParams(args, true);
    if (name == "null") name.clear();
    return ShaderDesc{name, std::move(params), args.loc(), reader.state().ctm};
}

// Displacement: run on the diced grid before the surface; Atmosphere: a volume shader (fog,
// depthcue) run on every surface point after its surface, along I; Imager (an option): over each
// finished frame. All bound and checked when the render starts (shade/scene_shaders.h).
void displacement(RibParser& reader, RibArgs& args) {
    reader.state().mutableAttributes().displacement = readShader(reader, args);
}

void atmosphere(RibParser& reader, RibArgs& args) { reader.state().mutableAttributes().atmosphere = readShader(reader, args); }

void imager(RibParser& reader, RibArgs& args) { reader.scene().settings.imager = readShader(reader, args); }

// A light is on in the attribute block where it is declared (and the blocks inside it): its index
// goes into the current attributes' light list, which AttributeEnd restores.
// LightSource, or AreaLightSource (area: the geometry that follows in the attribute block shapes it).
void declareLight(RibParser& reader, RibArgs& args, bool area) {
    RibState& s = reader.state();
    static const std::set<std::string> builtins = {"ambientlight", "distantlight", "pointlight"};
    std::string name = args.string("shader name");
    if (name.empty()) args.fail("the shader name is empty");

    // The handle: a number (RIB 3.2) or a string (later versions). Parameters come in pairs, so a
    // string before an odd number of remaining values is a handle.
    std::string handle;
    if (const RibValue* v = args.peek()) {
        if (v->isNumber() || (v->isString() && args.remaining() % 2 == 1)) {
            handle = v->isNumber() ? std::to_string(args.integer("handle")) : args.string("handle");
        }
    }

    ParamList params = reader.readParams(args, true);
    auto builtin = area ? builtins.end() : builtins.find(name);
    if (builtin != builtins.end()) {
        // The built-in lights' values are checked now; a parameter they do not have is warned about
        // when the light's shader is bound (shade/scene_shaders.h), as for any light.
        params.getFloat("intensity", 1.0);
        params.getColor("lightcolor", Color(1, 1, 1));
        params.getPoint("from", Vec3d(0, 0, 0));
        params.getPoint("to", Vec3d(0, 0, 1));
    }

    if (s.world == RibState::World::After) args.fail(args.name() + " after WorldEnd: lights belong in the world");
    if (area && s.world != RibState::World::Inside)
        args.fail("AreaLightSource before WorldBegin: an area light is the geometry that follows it in the world");
    int index = int(reader.scene().lights.size());
    if (s.world == RibState::World::Before) s.cameraLights.push_back(index);
    const bool shadows = s.attributes->user.getString("light:shadows", "off") == "on";
    LightDesc light;
    light.type = name;
    light.params = std::move(params);
    light.lightToWorld = s.ctm;
    light.loc = args.loc();
    light.castsShadows = shadows;
    light.area = area;
    // Attribute "autoshadows" (Aqsis): a depth map rendered from the light before the frame.
    if (const Param* map = s.attributes->user.find("autoshadows:shadowmapname")) {
        if (map->type != ParamType::String || map->strings.size() != 1 || map->strings[0].empty())
            throw InputError(map->loc, "Attribute \"autoshadows\": shadowmapname is one file name, as in "
                                       "\"string shadowmapname\" [\"light.shad\"]");
        light.autoShadowMap = map->strings[0];
        light.autoShadowLoc = map->loc;
        if (const Param* res = s.attributes->user.find("autoshadows:res")) {
            if (res->nums.size() != 1 || !(res->nums[0] >= 1 && res->nums[0] <= 16384))
                throw InputError(res->loc, "Attribute \"autoshadows\": res is one size from 1 to 16384 pixels");
            light.autoShadowRes = int(res->nums[0]);
        }
    }
    reader.scene().lights.push_back(std::move(light));
    s.mutableAttributes().lights.push_back(index);
    if (area) s.mutableAttributes().areaLight = index;
    if (!handle.empty()) {
        s.lightHandles[handle] = index;
        s.skippedLightHandles.erase(handle);
    }
}

void lightSource(RibParser& reader, RibArgs& args) { declareLight(reader, args, false); }
void areaLightSource(RibParser& reader, RibArgs& args) { declareLight(reader, args, true); }

void illuminate(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    if (args.done()) args.fail("missing handle");
    std::string handle = args.peek()->isNumber() ? std::to_string(args.integer("handle")) : args.string("handle");
    int on = args.integer("onoff");
    args.expectEnd();
    if (s.skippedLightHandles.count(handle)) return;
    auto light = s.lightHandles.find(handle);
    if (light == s.lightHandles.end()) args.fail("no light has the handle '" + handle + "'");
    std::vector<int>& lights = s.mutableAttributes().lights;
    auto it = std::find(lights.begin(), lights.end(), light->second);
    if (on && it == lights.end()) lights.push_back(light->second);
    if (!on && it != lights.end()) lights.erase(it);
}

}  // namespace

void addShadingRequests(RibRequestTable& table) {
    table.add("Surface", {surface, "Surface \"name\" parameters..."});
    table.add("Displacement", {displacement, "Displacement \"name\" parameters..."});
    table.add("Atmosphere", {atmosphere, "Atmosphere \"name\" parameters..."});
    table.add("Imager", {imager, "Imager \"name\" parameters...", RibPhase::Options});
    table.add("LightSource", {lightSource, "LightSource \"name\" handle parameters..."});
    table.add("AreaLightSource", {areaLightSource, "AreaLightSource \"name\" handle parameters...", RibPhase::World});
    table.add("Illuminate", {illuminate, "Illuminate handle onoff", RibPhase::World});
}

}  // namespace streyes
