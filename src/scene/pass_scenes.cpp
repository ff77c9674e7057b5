// Scenes the pass planner reads or makes (scene/pass_scenes.h).
#include "scene/pass_scenes.h"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <set>
#include <vector>

#include "scene/blobby_cut.h"
#include "streyes/passes.h"
#include "streyes/rib.h"

namespace streyes {

namespace {

bool isPictureDisplay(const DisplayDesc& d) {
    return d.type == "openexr" || d.type == "file" || d.type == "tiff" || d.type == "exr";
}

}  // namespace

bool depthFrame(const Scene& s) {
    bool depth = false;
    for (const DisplayDesc& d : s.settings.displays) {
        if (isPictureDisplay(d)) return false;
        depth = depth || isDepthDisplay(d);
    }
    return depth;
}

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

// ---- Reading ----------------------------------------------------------------------------------
std::vector<int> framesOnDisk(const std::string& pattern) {
    const std::filesystem::path p(pattern);
    const std::filesystem::path dir = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
    const std::string name = p.filename().string();
    const size_t a = name.find('#');
    size_t b = a;
    while (b < name.size() && name[b] == '#') ++b;
    const std::string prefix = name.substr(0, a), suffix = name.substr(b);
    std::vector<int> frames;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
        const std::string n = entry.path().filename().string();
        if (n.size() < prefix.size() + suffix.size() + (b - a) || n.compare(0, prefix.size(), prefix) != 0 ||
            n.compare(n.size() - suffix.size(), suffix.size(), suffix) != 0)
            continue;
        const std::string digits = n.substr(prefix.size(), n.size() - prefix.size() - suffix.size());
        if (digits.empty() || digits.size() > 9 ||
            !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
            continue;
        const int f = std::stoi(digits);
        if (frameFileName(pattern, f) == (dir / n).string() || frameFileName(pattern, f) == n) frames.push_back(f);
    }
    std::sort(frames.begin(), frames.end());
    return frames;
}

FrameFile readFrameFile(const std::string& file, int f, Log& log, const ReadDetail& detail,
                        const RibDefaults& defaults) {
    FrameFile out;
    parseRibFrames(
        file, log,
        [&](Scene&& s) {
            const bool block = s.frameLoc.line > 0;
            if (block && s.frameNumber != f)
                log.warnOnce("sequence-number:" + file, s.frameLoc,
                             "FrameBegin " + std::to_string(s.frameNumber) + " in the file of frame " +
                                 std::to_string(f) + ": the file name's number is used");
            if (!block) s.frameLoc = SourceLoc{std::make_shared<const std::string>(file), 1, 0};
            s.frameNumber = f;
            out.scenes.push_back(std::move(s));
        },
        detail, [&](Scene&& s) { out.after = std::move(s); }, defaults);
    return out;
}

// ---- Runs over the input ----------------------------------------------------------------------
std::map<std::string, std::shared_ptr<const RunTable>> scanRuns(const std::string& path, const PassRequest& req,
                                                                 const ReadDetail& detail) {
    Log quiet;  // the reading proper gives the input's warnings
    quiet.setQuiet(true);
    std::map<std::string, std::unique_ptr<SequenceBuilder>> scans;
    auto add = [&](Scene&& f) {
        std::unique_ptr<SequenceBuilder>& b = scans[passKey(f)];
        if (!b) b = std::make_unique<SequenceBuilder>(quiet, true);
        b->add(std::move(f));
    };
    // As the planner takes them: a picture's autoshadow depth frames, then the picture.
    auto frame = [&](Scene&& s) {
        if (s.frameLoc.line == 0) return;  // an ordinary scene: one render, no blocks
        if (!depthFrame(s))
            for (const LightDesc& l : s.lights)
                if (!l.autoShadowMap.empty()) add(autoShadowFrame(s, l));
        add(std::move(s));
    };
    try {
        if (isFramePattern(path)) {
            std::vector<int> files = framesOnDisk(path);
            if (req.frames.given) {
                // The wanted frames' epochs, and the first frame after them.
                const int first = runEpochFrames(req.frames.first).first;
                const int last = runEpochFrames(req.frames.last).second;
                auto after = std::upper_bound(files.begin(), files.end(), last);
                files.erase(after == files.end() ? after : after + 1, files.end());
                files.erase(files.begin(), std::lower_bound(files.begin(), files.end(), first));
            }
            for (int f : files)
                for (Scene& s : readFrameFile(frameFileName(path, f), f, quiet, detail, req.defaults).scenes)
                    frame(std::move(s));
        } else {
            parseRibFrames(path, quiet, frame, detail, [](Scene&&) {}, req.defaults);
        }
    } catch (const std::exception&) {
        return {};
    }
    std::map<std::string, std::shared_ptr<const RunTable>> out;
    for (auto& [key, b] : scans) out[key] = std::make_shared<const RunTable>(b->runTable());
    return out;
}

}  // namespace streyes
