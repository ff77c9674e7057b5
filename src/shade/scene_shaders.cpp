#include "shade/scene_shaders.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "shade/layer_network.h"
#include "shade/vm/ops.h"
#include "scene/bound_spaces.h"
#include "scene/search_path.h"
#include "shade/vm/vm.h"

namespace streyes {

namespace {

bool isBuiltinSurface(const std::string& name) {
    return name == "constant" || name == "matte" || name == "plastic" || name == "defaultsurface";
}

// Does the shader read `time`? Then a still grid it shades is shaded per exposure.
bool readsTime(const sl::ShaderInstance& s) { return s.program().globalReg[size_t(sl::Global::time)] >= 0; }

bool isBuiltinLight(const LightDesc& d) {
    if (d.type != "ambientlight" && d.type != "distantlight" && d.type != "pointlight") return false;
    // A shadow map's name: the shader reads it (the built-in light does not), "raytrace" is traced.
    const Param* map = d.params.find("shadowname");
    return !map || map->type != ParamType::String || map->strings.empty() || map->strings[0].empty() ||
           map->strings[0] == "raytrace";
}

// Does the shader call shadow() (a depth map, unless the name is "raytrace")?
bool readsMaps(const sl::ShaderInstance* s) {
    if (!s) return false;
    for (const sl::Instr& in : s->program().code)
        if (in.fn == sl::ops::shadow || in.fn == sl::ops::occlusionmap) return true;
    return false;
}

// Can the shader name "object" space? Only through a string constant or a string parameter's
// value (a name built at run time by concat() or format() is not seen).
bool namesObjectSpace(const sl::ShaderInstance* s) {
    if (!s) return false;
    const sl::ShaderProgram& p = s->program();
    for (const std::string& c : p.constStrings)
        if (c == "object") return true;
    for (size_t i = 0; i < p.params.size(); ++i) {
        const sl::ShaderInstance::Value* v = s->value(int(i));
        for (const std::string& str : v ? v->strings : p.params[i].defaultStrings)
            if (str == "object") return true;
    }
    return false;
}

// Does the shader cast rays (occlusion, indirectdiffuse, trace, transmission, gather)?
bool castsRays(const sl::ShaderInstance* s) {
    if (!s) return false;
    for (const sl::Instr& in : s->program().code)
        if (in.fn == sl::ops::occlusion || in.fn == sl::ops::occlusionmap || in.fn == sl::ops::indirectdiffuse ||
            in.fn == sl::ops::trace || in.fn == sl::ops::transmission || in.fn == sl::ops::gather)
            return true;
    // environment("raytrace", ...): the name is a string constant, or a parameter set to it.
    const sl::ShaderProgram& p = s->program();
    bool environment = false;
    for (const sl::Instr& in : p.code) environment = environment || in.fn == sl::ops::environment;
    if (!environment) return false;
    for (const std::string& c : p.constStrings)
        if (c == "raytrace") return true;
    for (size_t i = 0; i < p.params.size(); ++i) {
        const sl::ShaderInstance::Value* v = s->value(int(i));
        for (const std::string& str : v ? v->strings : p.params[i].defaultStrings)
            if (str == "raytrace") return true;
    }
    return false;
}

sl::BaseType baseTypeOf(const Param& p) {
    switch (p.type) {
        case ParamType::Float:
        case ParamType::Integer: return sl::BaseType::Float;
        case ParamType::Color: return sl::BaseType::Color;
        case ParamType::Point: return sl::BaseType::Point;
        case ParamType::Vector: return sl::BaseType::Vector;
        case ParamType::Normal: return sl::BaseType::Normal;
        case ParamType::Matrix: return sl::BaseType::Matrix;
        case ParamType::String: return sl::BaseType::String;
        case ParamType::HPoint: break;
    }
    throw InputError(p.loc, "parameter '" + p.name + "': the Shading Language has no hpoint type");
}

// Does the camera move rigidly: is every key of world -> camera the first key's up to a rotation
// and translation (key_k = key_0 * R, R orthogonal)? The view-use analysis's metric rules (dot
// products, lengths, distances of current-space vectors) hold only then. Within 1e-6: keys written
// with six digits pass, a scale of 1.001 does not.
bool movesRigidly(const MotionTransform& worldToCamera) {
    const std::vector<Matrix4>& keys = worldToCamera.keys();
    Matrix4 inv0;
    if (keys.empty() || !invert(keys[0], &inv0)) return false;
    for (size_t k = 1; k < keys.size(); ++k) {
        const Matrix4 rel = inv0 * keys[k];  // camera space at key 0 -> at key k
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
                double d = 0;
                for (int i = 0; i < 3; ++i) d += rel(r, i) * rel(c, i);
                if (std::fabs(d - (r == c ? 1.0 : 0.0)) > 1e-6) return false;
            }
    }
    return true;
}

ViewUse fromProgram(const sl::ShaderInstance* s) {
    if (!s) return ViewUse::None;  // a shader not found: nothing runs
    switch (s->program().viewUse) {
        case sl::ViewUse::None: return ViewUse::None;
        case sl::ViewUse::FacingOnly: return ViewUse::FacingOnly;
        case sl::ViewUse::Reads: break;
    }
    return ViewUse::Reads;
}

// The camera-space length of one unit of "screen", "NDC" and "raster" space across an
// orthographic image (the larger of the x and y scales): screen x and y are camera x and y, NDC
// spans the screen window, raster a pixel of it. (Under a perspective projection a length in
// them grows with depth: the reader takes such bounds in object space.)
void imageUnits(const CameraDesc& cam, int xres, int yres, double* screen, double* ndc, double* raster) {
    xres = std::max(xres, 1), yres = std::max(yres, 1);
    const double aspect = cam.frameAspect > 0 ? cam.frameAspect : cam.pixelAspect * xres / yres;
    double w = 2, h = 2;  // RenderMan's default screen window: the shorter side spans [-1, 1]
    if (cam.hasScreenWindow) {
        w = std::fabs(cam.screenWindow[1] - cam.screenWindow[0]);
        h = std::fabs(cam.screenWindow[3] - cam.screenWindow[2]);
    } else if (aspect >= 1) {
        w = 2 * aspect;
    } else {
        h = 2 / aspect;
    }
    *screen = std::max(*screen, 1.0);
    *ndc = std::max({*ndc, w, h});
    *raster = std::max({*raster, w / xres, h / yres});
}

}  // namespace

std::string standardShaderDir() {
    std::error_code ec;
    for (const char* dir : {STREYES_SHADERS_SOURCE_DIR, STREYES_SHADERS_INSTALL_DIR})
        if (std::filesystem::is_directory(dir, ec)) return dir;
    return STREYES_SHADERS_INSTALL_DIR;
}

void setShaderParams(sl::ShaderInstance& shader, const ParamList& params, Log& log) {
    const sl::ShaderProgram& program = shader.program();
    for (const Param& p : params.params) {
        if (!program.findParam(p.name)) {
            log.lenient("shader-param:" + program.path + ":" + p.name, p.loc,
                        "shader \"" + program.name + "\" (" + program.path + ") has no parameter \"" + p.name +
                            "\": ignored");
            continue;
        }
        if (p.type == ParamType::String) {
            shader.setStrings(p.name, p.strings, p.loc);
            continue;
        }
        const sl::BaseType base = p.declared ? baseTypeOf(p) : sl::BaseType::Void;
        const sl::SlType type(base, p.declared && p.arraySize > 1 ? p.arraySize : 0);
        shader.set(p.name, type, std::vector<float>(p.nums.begin(), p.nums.end()), p.loc);
    }
}

sl::TextureSource* LazyTextureSource::source() {
    std::call_once(once_, [this] {
        if (!factory_) return;
        try {
            source_ = factory_(searchPath_, log_);
        } catch (const std::exception& e) {
            log_.warnOnce("textures", {}, std::string(e.what()) + ": texture lookups give their fill value");
        }
    });
    return source_.get();
}

bool LazyTextureSource::texture(const std::string& name, const sl::TextureOptions& o, const sl::TextureQuery& q,
                                float* const* out) {
    sl::TextureSource* s = source();
    return s && s->texture(name, o, q, out);
}

bool LazyTextureSource::environment(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q,
                                    float* const* out) {
    if (environments_ && environments_->lookup(name, o.channels, q, out)) return true;
    sl::TextureSource* s = source();
    return s && s->environment(name, o, q, out);
}

bool LazyTextureSource::shadow(const std::string& name, const sl::TextureOptions& o, const sl::DirectionQuery& q,
                               float* const* out) {
    return maps_ && maps_->shadow(name, o, q, out[0]);
}

bool LazyTextureSource::occlusionMap(const std::string& name, const sl::TextureOptions& o,
                                     const sl::DirectionQuery& q, const float* const* normal, float* out) {
    return maps_ && maps_->occlusion(name, o, q, normal, out);
}

bool LazyTextureSource::textureInfo(const std::string& name, const std::string& field, sl::QueryValue& out) {
    sl::TextureSource* s = source();
    return s && s->textureInfo(name, field, out);
}

SceneShaders::SceneShaders(const Scene& scene, Log& log, TextureSourceFactory textures,
                           std::shared_ptr<const ShadowMapBinding> maps)
    : worldToCamera_(scene.camera.worldToCamera), options_(scene), builtinShading_(scene.settings.builtinShading),
      specularExponent_(float(scene.settings.specularExponent)), log_(log) {
    // Maps named without a folder: along Option "searchpath" "texture", else beside the scene.
    std::vector<std::string> texturePath = scene.settings.textureSearchPath;
    if (texturePath.empty()) {
        const std::string dir = std::filesystem::path(scene.sourceName).parent_path().string();
        texturePath.push_back(dir.empty() ? "." : dir);
    }
    // The environment's folders after the scene's own (search_path.h).
    for (const std::string& f : environmentSearchPath(kTexturePathVariable)) texturePath.push_back(f);
    maps_ = std::make_unique<ShadowMaps>(std::move(maps), scene, texturePath, log);
    perspective_ = scene.camera.projection == ProjectionKind::Perspective;
    imageCameras_.push_back(scene.camera);
    for (const auto& frame : scene.frameCamera) imageCameras_.push_back(frame.second);
    setResolution(scene.camera.xres, scene.camera.yres);
    cameraRigid_ = movesRigidly(scene.camera.worldToCamera);
    for (const auto& frame : scene.frameWorldToCamera) cameraRigid_ = cameraRigid_ && movesRigidly(frame.second);
    textures_ = std::make_unique<LazyTextureSource>(std::move(textures), std::move(texturePath), maps_.get(), log);
    clouds_ = std::make_unique<PointClouds>(log);
    cache_ = std::make_unique<sl::ShaderCache>(std::vector<std::string>{standardShaderDir()});
    searchPathSet_ = !scene.settings.shaderSearchPath.empty();
    if (searchPathSet_) cache_->setSearchPath(scene.settings.shaderSearchPath);
    cache_->appendSearchPath(environmentSearchPath(kShaderPathVariable));
    // CoordinateSystem names, as the RIB reader keeps them ("CoordinateSystem:name", a matrix).
    const std::string prefix = "CoordinateSystem:";
    for (const Param& p : scene.settings.options.params)
        if (p.name.compare(0, prefix.size(), prefix) == 0 && p.type == ParamType::Matrix && p.nums.size() == 16)
            coordinateSystems_.push_back({p.name.substr(prefix.size()), Matrix4::fromRowMajor(p.nums.data())});

    if (!scene.settings.imagerLayers.layers.empty()) {
        BoundLayers im = bindLayers(scene.settings.imagerLayers, sl::ShaderType::Imager);
        if (!im.shaders.empty()) imager_ = im.shaders.back();
        imagerLayers_ = std::move(im.network);
    } else if (!scene.settings.imager.name.empty()) {
        imager_ = instance(scene.settings.imager.name, scene.settings.imager.params, scene.settings.imager.loc,
                           sl::ShaderType::Imager);
    }
    addShaderEnvironments(scene);
    textures_->setShaderEnvironments(&environments_);
    for (const LightDesc& d : scene.lights) {
        builtinLight_.push_back(isBuiltinLight(d));
        lights_.push_back(instance(d.type, d.params, d.loc, sl::ShaderType::Light));
        // What its code does decides whether it is a distant light, not its name.
        solar_.push_back(lights_.back() && !d.area
                             ? streyes::solarCone(*lights_.back(), d.lightToWorld.at(d.lightToWorld.times().front()))
                             : std::nullopt);
        lightReadsMaps_.push_back(readsMaps(lights_.back().get()));
        lightTracesRays_.push_back(castsRays(lights_.back().get()));
        if (lightTracesRays_.back()) tracesRays_ = true;
        // Still in world: its own transform (and an area light's shape) has one key, and the
        // scene's world is the world (a frame sequence's is each frame's camera space, where a
        // light still in world differs from frame to frame).
        lightStillInWorld_.push_back(d.lightToWorld.isStatic() && (!d.area || d.areaToWorld.isStatic()) &&
                                     !maps_->worldVaries());
    }
}

void SceneShaders::setResolution(int width, int height) {
    screenUnit_ = ndcUnit_ = rasterUnit_ = 0;
    for (const CameraDesc& c : imageCameras_) imageUnits(c, width, height, &screenUnit_, &ndcUnit_, &rasterUnit_);
}

// Option "environment:NAME" "string shader" [name] params...: the options keep each value as
// "environment:NAME:param" (rib_options.cpp); the shader is a surface, its parameters the rest.
void SceneShaders::addShaderEnvironments(const Scene& scene) {
    const std::string prefix = "environment:";
    std::vector<std::string> names;
    for (const Param& p : scene.settings.options.params) {
        if (p.name.compare(0, prefix.size(), prefix) != 0) continue;
        const size_t colon = p.name.rfind(':');
        const std::string name = p.name.substr(prefix.size(), colon - prefix.size());
        if (colon > prefix.size() && std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
    for (const std::string& name : names) {
        const std::string category = prefix + name + ":";
        ParamList params;
        const Param* shaderName = nullptr;
        for (const Param& p : scene.settings.options.params) {
            if (p.name.compare(0, category.size(), category) != 0) continue;
            Param q = p;
            q.name = p.name.substr(category.size());
            if (q.name == "shader") shaderName = &p;
            else params.params.push_back(std::move(q));
        }
        if (!shaderName || shaderName->type != ParamType::String || shaderName->strings.size() != 1)
            throw InputError(shaderName ? shaderName->loc : params.params.front().loc,
                             "Option \"environment:" + name + "\" needs \"string shader\" [\"name\"]: the surface shader "
                             "that gives the environment's colour along each direction (docs/SCENE-FORMAT.md, \"Sun and sky\")");
        if (std::shared_ptr<sl::ShaderInstance> s =
                instance(shaderName->strings[0], params, shaderName->loc, sl::ShaderType::Surface))
            environments_.add(name, std::move(s));
    }
}

// What a render does without a shader it cannot find, for the warning.
static const char* missingShaderFallback(sl::ShaderType type) {
    switch (type) {
    case sl::ShaderType::Surface: return "using defaultsurface";
    case sl::ShaderType::Light: return "the light is dark";
    case sl::ShaderType::Displacement: return "the surface is not displaced";
    case sl::ShaderType::Volume: return "no atmosphere";
    case sl::ShaderType::Imager: return "no imager runs";
    }
    return "skipped";
}

std::shared_ptr<sl::ShaderInstance> SceneShaders::instance(const std::string& name, const ParamList& params,
                                                           const SourceLoc& loc, sl::ShaderType type) const {
    // Without a search path, the folder of the RIB file that names the shader comes first.
    std::string file = name;
    if (!searchPathSet_ && loc.file && name.find('/') == std::string::npos) {
        std::filesystem::path dir = std::filesystem::path(*loc.file).parent_path();
        if (dir.empty()) dir = ".";
        const std::string here = (dir / name).string();
        if (!cache_->find(here).empty()) file = here;
    }
    if (cache_->find(file).empty()) {
        std::string dirs = searchPathSet_ ? "" : "the RIB file's folder";
        for (const std::string& d : cache_->searchPath()) dirs += (dirs.empty() ? "" : ":") + d;
        log_.warnOnce(std::string(sl::shaderTypeName(type)) + ":" + name, loc,
                      std::string(sl::shaderTypeName(type)) + " shader \"" + name + "\" not found (searchpath " + dirs +
                          "; see Option \"searchpath\" \"shader\"): " + missingShaderFallback(type));
        return nullptr;
    }
    sl::ProgramPtr program = cache_->get(file, loc);
    for (const sl::ShaderProgram::Warning& w : program->warnings)
        log_.warnOnce("shader-compile:" + w.str(), w.loc, w.what);
    if (program->type != type) {
        // A displacement shader named by Surface, say: the peers warn and go without it.
        log_.lenient(std::string(sl::shaderTypeName(type)) + "-type:" + name, loc,
                     "\"" + name + "\" (" + program->path + ") is a " + sl::shaderTypeName(program->type) +
                         " shader, not a " + sl::shaderTypeName(type) + " shader: " + missingShaderFallback(type));
        return nullptr;
    }
    auto shader = std::make_shared<sl::ShaderInstance>(program);
    setShaderParams(*shader, params, log_);
    return shader;
}

SceneShaders::BoundLayers SceneShaders::bindLayers(const ShaderNetwork& net, sl::ShaderType type) const {
    BoundLayers out;
    ShaderNetwork found;
    std::vector<int> index;
    for (size_t i = 0; i < net.layers.size(); ++i) {
        const ShaderDesc& d = net.layers[i];
        std::shared_ptr<sl::ShaderInstance> s = instance(d.name, d.params, d.loc, type);
        index.push_back(s ? int(out.shaders.size()) : -1);
        if (!s) continue;
        out.shaders.push_back(std::move(s));
        out.descs.push_back(&d);
        found.layers.push_back(d);
        found.names.push_back(net.names[i]);
    }
    for (ShaderConnection c : net.connections) {
        c.from = index[size_t(c.from)];
        c.to = index[size_t(c.to)];
        if (c.from >= 0 && c.to >= 0) found.connections.push_back(std::move(c));
    }
    if (out.shaders.size() > 1) out.network = bindLayerNetwork(found, type, out.shaders, log_);
    return out;
}

void SceneShaders::runImager(FrameImage& frame) const {
    if (!imager_ || frame.width == 0 || frame.height == 0) return;
    const int n = frame.width * frame.height;
    std::vector<float> px(static_cast<size_t>(n)), py(static_cast<size_t>(n));
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            px[size_t(y * frame.width + x)] = float(x) + 0.5f;
            py[size_t(y * frame.width + x)] = float(y) + 0.5f;
        }
    float* rgba = frame.rgba.data();
    sl::ShadingGrid g;
    g.setShape(frame.width - 1, frame.height - 1);
    g.set(sl::Global::Ci, sl::ValueRef{{rgba, rgba + 1, rgba + 2}, 4});
    g.set(sl::Global::Oi, sl::ValueRef{{rgba + 3, rgba + 3, rgba + 3}, 4});
    g.set(sl::Global::alpha, sl::ValueRef{{rgba + 3, nullptr, nullptr}, 4});
    g.set(sl::Global::P, sl::ValueRef::soa(px.data(), py.data(), frame.z.data()));
    const SceneQueries state = queries(nullptr);
    g.state = &state;
    sl::ShadingVM vm;
    vm.setTextureSource(textures());
    vm.setLog(&log_);
    LayerNetworkRunner layers;  // its results stay valid until it goes
    if (imagerLayers_) layers.run(vm, *imagerLayers_, g, {});
    else vm.run(*imager_, g);
    auto result = [&](sl::Global v) { return imagerLayers_ ? layers.result(vm, v) : vm.result(v); };
    const sl::ValueRef ci = result(sl::Global::Ci), alpha = result(sl::Global::alpha);
    // The pixel's alpha: the imager's alpha when it (a layer of it) names it, else the mean of its
    // Oi (as Aqsis takes it: an imager that draws over an empty world, a fisheye's disc, sets Oi).
    auto names = [&](sl::Global v) {
        if (!imagerLayers_) return imager_->program().globalReg[size_t(v)] >= 0;
        for (const auto& l : imagerLayers_->layers)
            if (l->program().globalReg[size_t(v)] >= 0) return true;
        return false;
    };
    const bool ownAlpha = names(sl::Global::alpha);
    const sl::ValueRef oi = result(sl::Global::Oi);
    const bool fromOi = !ownAlpha && names(sl::Global::Oi) && oi.valid();
    std::vector<float> out(size_t(n) * 4);
    for (int i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) out[size_t(i) * 4 + size_t(c)] = ci.valid() ? ci.at(c, i) : rgba[size_t(i) * 4 + size_t(c)];
        out[size_t(i) * 4 + 3] = fromOi ? (oi.at(0, i) + oi.at(1, i) + oi.at(2, i)) / 3
                                 : alpha.valid() ? alpha.at(0, i) : rgba[size_t(i) * 4 + 3];
    }
    frame.rgba = std::move(out);
}

void SceneShaders::bind(Material& m, const Attributes& a) const {
    // Material::viewUse's parts. The analysis (shade/sl/view_use.h) assumes a rigid camera: a
    // scaling or shearing one changes lengths and angles in current space, and a frame
    // sequence's "world" is each frame's camera space.
    const ViewUse rigid = cameraRigid_ && !maps_->worldVaries() ? ViewUse::None : ViewUse::Reads;
    // A shader's: the compiler's class, its "shader" and "object" spaces still in world.
    auto shaderUse = [&](const sl::ShaderInstance& s, const ShaderDesc& desc) {
        if (!desc.shaderToWorld.isStatic()) return ViewUse::Reads;
        return std::max(fromProgram(&s), rigid);
    };
    if (!a.atmosphere.name.empty()) {
        m.atmosphere = instance(a.atmosphere.name, a.atmosphere.params, a.atmosphere.loc, sl::ShaderType::Volume);
        if (m.atmosphere) m.readsTime = readsTime(*m.atmosphere);
        m.readsObjectSpace = namesObjectSpace(m.atmosphere.get());
        m.tracesRays = castsRays(m.atmosphere.get());
        if (m.atmosphere) m.viewUse = std::max(m.viewUse, shaderUse(*m.atmosphere, a.atmosphere));
    }
    // Interior and Exterior run over rays' segments (trace/shader_rays.h), not over this
    // surface's grids: they do not change how it is shaded, but rays they cast are its rays.
    for (auto [desc, out] : {std::pair{&a.interior, &m.interior}, std::pair{&a.exterior, &m.exterior}}) {
        if (desc->name.empty()) continue;
        *out = instance(desc->name, desc->params, desc->loc, sl::ShaderType::Volume);
        m.tracesRays = m.tracesRays || castsRays(out->get());
        const ShaderDesc* none = nullptr;
        if (*out) firstVolume_.compare_exchange_strong(none, desc, std::memory_order_relaxed);
    }
    // The displacement: its shader, or each layer of a layered one (the last is
    // Material::displacement, whose "shader" space every layer runs in).
    BoundLayers displacement;
    if (!a.displacementLayers.layers.empty()) {
        displacement = bindLayers(a.displacementLayers, sl::ShaderType::Displacement);
    } else if (!a.displacement.name.empty()) {
        if (auto s = instance(a.displacement.name, a.displacement.params, a.displacement.loc, sl::ShaderType::Displacement)) {
            displacement.shaders.push_back(std::move(s));
            displacement.descs.push_back(&a.displacement);
        }
    }
    if (!displacement.shaders.empty()) {
        m.displacement = displacement.shaders.back();
        m.displacementLayers = displacement.network;
        // The bound's radius in camera space: "camera" and "current" are camera space; "object"
        // is the primitive's (taken here as the shader's; the factory corrects a primitive whose
        // transform stretches otherwise: Material::displacementBoundInObject); "surface" the
        // surface shader's (the CTM at Surface or its last layer's, else the displacement's); the image's spaces a
        // length across an orthographic image (the reader takes them under no other projection).
        std::string space = a.displacementBoundSpace;
        if (isImageBoundSpace(space) && perspective_) {
            // Given before the Projection request: the reader took the projection as orthographic.
            log_.lenient("displacementbound:perspective-" + space, a.displacement.loc, perspectiveImageBoundMessage(space));
            space = "object";
        }
        double scale = 1;
        if (space == "object" || space == "shader")
            scale = largestStretch(a.displacement.shaderToWorld) * largestStretch(worldToCamera_);
        else if (space == "surface")
            scale = largestStretch(!a.surfaceLayers.layers.empty() ? a.surfaceLayers.layers.back().shaderToWorld
                                   : !a.surface.name.empty()       ? a.surface.shaderToWorld
                                                                   : a.displacement.shaderToWorld) *
                    largestStretch(worldToCamera_);
        else if (space == "world")
            scale = largestStretch(worldToCamera_);
        else if (isImageBoundSpace(space))
            scale = space == "screen" ? screenUnit_ : space == "NDC" ? ndcUnit_ : rasterUnit_;
        else if (space != "camera" && space != "current")  // a CoordinateSystem's, or PRMan's "null"
            scale = largestStretch(a.displacementBoundToWorld) * largestStretch(worldToCamera_);
        m.displacementBound = float(a.displacementBound * scale);
        if (space == "object") m.displacementBoundInObject = float(a.displacementBound);
        for (size_t i = 0; i < displacement.shaders.size(); ++i) {
            const sl::ShaderInstance& s = *displacement.shaders[i];
            m.readsTime = m.readsTime || readsTime(s);
            m.readsObjectSpace = m.readsObjectSpace || namesObjectSpace(&s);
            m.tracesRays = m.tracesRays || castsRays(&s);
            m.viewUse = std::max(m.viewUse, shaderUse(s, *displacement.descs[i]));
        }
        if (m.displacementLayers && connectsViewValues(*m.displacementLayers)) m.viewUse = ViewUse::Reads;
    }
    struct NoteRays {  // however bind returns
        const Material& m;
        std::atomic<bool>& any;
        ~NoteRays() {
            if (m.tracesRays) any = true;
        }
    } noteRays{m, tracesRays_};
    m.specularExponent = specularExponent_;  // the built-in plastic's highlight, as specular()'s
    bool builtinLights = true;
    for (int i : m.lights) {
        builtinLights = builtinLights && builtinLight_[size_t(i)];
        m.readsMaps = m.readsMaps || lightReadsMaps_[size_t(i)];
        m.tracesRays = m.tracesRays || lightTracesRays_[size_t(i)];
    }
    // A light moving in world (or with the camera) lights a world-still point differently from
    // frame to frame; a light's shader may read the view. The built-in constant reads no light
    // (nor does a shader that calls neither illuminance nor ambient, diffuse, specular, phong).
    ViewUse lightsUse = ViewUse::None;
    for (int i : m.lights)
        lightsUse = std::max(lightsUse, lightStillInWorld_[size_t(i)]
                                            ? std::max(fromProgram(lights_[size_t(i)].get()), rigid)
                                            : ViewUse::Reads);
    const std::string& name = a.surface.name;
    // A layered surface: each layer's shader (one not found is warned about and left out, with
    // its connections), the last one Material::surface.
    std::vector<std::shared_ptr<const sl::ShaderInstance>> layers;
    std::vector<const ShaderDesc*> layerDescs;
    if (!a.surfaceLayers.layers.empty()) {
        BoundLayers surface = bindLayers(a.surfaceLayers, sl::ShaderType::Surface);
        layers = std::move(surface.shaders);
        layerDescs = std::move(surface.descs);
        m.layers = std::move(surface.network);
    }
    // The built-in shading reads no primitive variables: a primitive with some runs the shader.
    if (layers.empty() && builtinShading_ && builtinLights && isBuiltinSurface(name) && m.primvars.params.empty()) {
        // makeMaterial set the built-in's own use; a scaling camera changes its N.L too.
        if (m.kind != SurfaceKind::Constant) m.viewUse = std::max({m.viewUse, lightsUse, rigid});
        if (m.tracesRays) m.viewUse = ViewUse::Reads;
        return;
    }
    std::shared_ptr<const sl::ShaderInstance> shader =
        !layers.empty() ? layers.back()
                        : !a.surfaceLayers.layers.empty()
                              ? nullptr  // every layer's shader is missing (warned)
                              : instance(name, a.surface.params, a.surface.loc, sl::ShaderType::Surface);
    if (!shader) {
        m.kind = SurfaceKind::Default;
        if (builtinShading_) {  // defaultsurface reads no light: the built-in serves
            m.viewUse = ViewUse::Reads;  // |N.I|
            return;
        }
        shader = instance("defaultsurface", {}, a.surface.loc, sl::ShaderType::Surface);
        if (!shader) return;
    }
    if (layers.empty()) {
        layers.push_back(shader);
        layerDescs.push_back(&a.surface);
    }
    // What the compiler proved of the surface (each layer), its displacement and atmosphere, with
    // its lights when it reads them; rays see what moves (and are cast per exposure anyway).
    m.viewUse = ViewUse::None;
    bool usesLights = false;
    for (size_t i = 0; i < layers.size(); ++i) {
        const sl::ShaderInstance& s = *layers[i];
        m.readsTime = m.readsTime || readsTime(s);
        m.readsMaps = m.readsMaps || readsMaps(&s);
        m.readsObjectSpace = m.readsObjectSpace || namesObjectSpace(&s);
        m.tracesRays = m.tracesRays || castsRays(&s);
        m.viewUse = std::max(m.viewUse, shaderUse(s, *layerDescs[i]));
        usesLights = usesLights || s.program().usesLights;
    }
    if (m.atmosphere) m.viewUse = std::max(m.viewUse, shaderUse(*m.atmosphere, a.atmosphere));
    for (size_t i = 0; i < displacement.shaders.size(); ++i)
        m.viewUse = std::max(m.viewUse, shaderUse(*displacement.shaders[i], *displacement.descs[i]));
    if (usesLights) m.viewUse = std::max(m.viewUse, lightsUse);
    if (m.tracesRays) m.viewUse = ViewUse::Reads;
    for (const LayerNetwork* net : {m.layers.get(), m.displacementLayers.get()})
        if (net && connectsViewValues(*net)) m.viewUse = ViewUse::Reads;
    m.surface = std::move(shader);
}

}  // namespace streyes
