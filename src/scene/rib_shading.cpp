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
    Attributes& a = reader.state().mutableAttributes();
    a.surface = ShaderDesc{name, std::move(params), args.loc(), reader.state().ctm};
    a.surfaceLayers = {};  // a Surface replaces a layered surface
}

// The layered shader a ShaderLayer or ConnectShaderLayers of `type` ("surface", "displacement",
// "imager") adds to, and the description of it that stands for the whole (the last layer's, what
// the render falls back on): the attribute state's, or the options' for an imager. Null (warned
// about and ignored) for another type, or for an imager inside the world (an option, as Imager).
struct LayerTarget {
    ShaderNetwork* net = nullptr;
    ShaderDesc* last = nullptr;
};
LayerTarget layerTarget(RibParser& reader, RibArgs& args, const std::string& type, const std::string& request) {
    LayerTarget t;
    if (type == "imager") {
        if (reader.state().world != RibState::World::Before) {
            reader.log().lenient("phase:" + request + ":imager", args.loc(),
                                 request + " \"imager\" makes an option: it belongs before WorldBegin; ignored here");
            return t;
        }
        RenderSettings& s = reader.scene().settings;
        t.net = &s.imagerLayers;
        t.last = &s.imager;
        return t;
    }
    if (type != "surface" && type != "displacement") {
        reader.log().lenient("shaderlayer:" + type, args.loc(),
                             request + " \"" + type +
                                 "\": only surface, displacement and imager shaders are layered; ignored");
        return t;
    }
    Attributes& a = reader.state().mutableAttributes();
    t.net = type == "surface" ? &a.surfaceLayers : &a.displacementLayers;
    t.last = type == "surface" ? &a.surface : &a.displacement;
    return t;
}

// ShaderLayer "type" "name" "layername" parameters...: a layer of the current surface,
// displacement or imager when it is layered, else the first layer of a new one (as Aqsis and
// PRMan 16 read it). The built-in surfaces run as their shipped .sl files here.
void shaderLayer(RibParser& reader, RibArgs& args) {
    const std::string type = args.string("shader type");
    std::string name = args.string("shader name");
    const std::string layer = args.string("layer name");
    if (name.empty()) args.fail("the shader name is empty");
    if (layer.empty()) args.fail("the layer name is empty");
    ParamList params = reader.readParams(args, true);
    const LayerTarget t = layerTarget(reader, args, type, "ShaderLayer");
    if (!t.net) return;
    if (name == "null" && type == "surface") name = "defaultsurface";
    ShaderNetwork& net = *t.net;
    for (const std::string& n : net.names)
        if (n == layer)
            reader.log().lenient("shaderlayer-name:" + layer, args.loc(),
                                 "the " + type + " already has a layer named '" + layer +
                                     "': later connections name the new one");
    net.layers.push_back(ShaderDesc{name, std::move(params), args.loc(), reader.state().ctm});
    net.names.push_back(layer);
    *t.last = net.layers.back();  // what the shader is when the network cannot run: its last layer
}

// ConnectShaderLayers "type" "layer1" "variable1" "layer2" "variable2": after layer1 runs,
// layer2's variable2 takes layer1's variable1. Layers must be declared (in this attribute state,
// or the options for an imager) before, and layer1 before layer2, as they run in order; else
// warned and skipped, as the peers skip what they cannot connect. The variables are checked
// against the shaders when the render binds them (shade/scene_shaders.cpp).
void connectShaderLayers(RibParser& reader, RibArgs& args) {
    const std::string type = args.string("shader type");
    ShaderConnection c;
    const std::string layer1 = args.string("layer1");
    c.fromVar = args.string("variable1");
    const std::string layer2 = args.string("layer2");
    c.toVar = args.string("variable2");
    args.expectEnd();
    c.loc = args.loc();
    ShaderNetwork* const net = layerTarget(reader, args, type, "ConnectShaderLayers").net;
    if (!net) return;
    auto find = [&](const std::string& n) {
        for (size_t i = net->names.size(); i-- > 0;)  // the latest of that name
            if (net->names[i] == n) return int(i);
        return -1;
    };
    c.from = find(layer1);
    c.to = find(layer2);
    const std::string what = "ConnectShaderLayers " + layer1 + "." + c.fromVar + " -> " + layer2 + "." + c.toVar;
    for (const auto& [index, n] : {std::pair<int, std::string>{c.from, layer1}, {c.to, layer2}})
        if (index < 0) {
            reader.log().lenient("connect:" + what, args.loc(),
                                 what + ": the " + type + " has no layer named '" + n + "' (ShaderLayer \"" + type +
                                     "\" declares layers first): not connected");
            return;
        }
    if (c.from >= c.to) {
        reader.log().lenient("connect:" + what, args.loc(),
                             what + ": layers run in the order they are declared, and '" + layer2 +
                                 "' does not come after '" + layer1 + "': not connected");
        return;
    }
    net->connections.push_back(std::move(c));
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
    Attributes& a = reader.state().mutableAttributes();
    a.displacement = readShader(reader, args);
    a.displacementLayers = {};  // a Displacement replaces a layered one
}

void atmosphere(RibParser& reader, RibArgs& args) { reader.state().mutableAttributes().atmosphere = readShader(reader, args); }

// Interior, Exterior: volume shaders over the segments of shaders' rays inside and outside the
// surfaces that follow (trace/shader_rays.h).
void interior(RibParser& reader, RibArgs& args) { reader.state().mutableAttributes().interior = readShader(reader, args); }
void exterior(RibParser& reader, RibArgs& args) { reader.state().mutableAttributes().exterior = readShader(reader, args); }

void imager(RibParser& reader, RibArgs& args) {
    reader.scene().settings.imager = readShader(reader, args);
    reader.scene().settings.imagerLayers = {};  // an Imager replaces a layered one
}

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
    table.add("ShaderLayer", {shaderLayer, "ShaderLayer \"type\" \"name\" \"layername\" parameters..."});
    table.add("ConnectShaderLayers",
              {connectShaderLayers, "ConnectShaderLayers \"type\" \"layer1\" \"variable1\" \"layer2\" \"variable2\""});
    table.add("Displacement", {displacement, "Displacement \"name\" parameters..."});
    table.add("Atmosphere", {atmosphere, "Atmosphere \"name\" parameters..."});
    table.add("Interior", {interior, "Interior \"name\" parameters..."});
    table.add("Exterior", {exterior, "Exterior \"name\" parameters..."});
    table.add("Imager", {imager, "Imager \"name\" parameters...", RibPhase::Options});
    table.add("LightSource", {lightSource, "LightSource \"name\" handle parameters..."});
    table.add("AreaLightSource", {areaLightSource, "AreaLightSource \"name\" handle parameters...", RibPhase::World});
    table.add("Illuminate", {illuminate, "Illuminate handle onoff", RibPhase::World});
}

}  // namespace streyes
