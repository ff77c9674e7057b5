#include "pass_runner.h"

#include <cfloat>
#include <climits>
#include <filesystem>
#include <map>

#include "geom/camera.h"
#include "scene/blobby_cut.h"
#include "io/depth_map_file.h"
#include "streyes/image_io.h"
#include "streyes/scene_access.h"
#include "streyes/textures.h"

namespace streyes::cli {

namespace {

constexpr int kAnyFrame = INT_MIN;  // a map read from a file: the same for every frame

// The folder of the RIB file a request came from: relative names are looked for there after the
// working folder.
std::string besideRequest(const SourceLoc& loc, const std::string& name) {
    namespace fs = std::filesystem;
    if (name.empty() || fs::path(name).is_absolute() || !loc.file) return name;
    const fs::path dir = fs::path(*loc.file).parent_path();
    return dir.empty() ? name : (dir / name).string();
}

}  // namespace

void PassRunner::writeMap(const std::string& path, FileVersion v, const DepthMap& map, bool shadow) {
    // The file holds what rendering the input frame by frame would leave: the last version written.
    auto it = fileVersion_.find(path);
    if (it != fileVersion_.end() && it->second > v) return;
    writeDepthMapFile(path, map, shadow);
    fileVersion_[path] = v;
    ++mapsWritten_;
}

void PassRunner::keep(const PassFrame& frame, const FrameImage& image, double shutterOpen) {
    if (frame.maps.empty()) return;
    CameraDesc desc = frame.camera;
    desc.xres = image.width;
    desc.yres = image.height;
    const Camera camera(desc);
    auto map = std::make_shared<DepthMap>();
    map->width = image.width;
    map->height = image.height;
    map->z.resize(image.z.size());
    for (size_t i = 0; i < image.z.size(); ++i)
        map->z[i] = image.z[i] < DepthMap::kNoDepth ? image.z[i] : DepthMap::kNoDepth;
    map->worldToCamera = frame.camera.worldToCamera.at(image.frame + shutterOpen);
    map->worldToScreen = map->worldToCamera * screenProjection(camera.perspective(), camera.ax(), camera.bx(),
                                                               camera.ay(), camera.by(), image.width, image.height);
    for (const auto& [display, version] : frame.maps) {
        const std::string path = frameFileName(display.name, image.frame);
        std::shared_ptr<const DepthMap> kept = map;
        auto appends = frame.appends.find(version);
        if (appends != frame.appends.end()) {
            // Display "append": the file as it stood (kept: a job keeps its frames in order) plus this map.
            auto appended = std::make_shared<DepthMap>(*map);
            appended->previous = mapOf(appends->second, image.frame);
            if (!appended->previous)
                throw RenderError("Display \"" + display.name + "\" \"append\": the maps written before frame " +
                                  std::to_string(image.frame) + "'s are not kept (an internal error)");
            kept = std::move(appended);
        }
        // A still light over a still set makes the same map every frame: one kept for all of them,
        // so that what reads it is still too.
        auto last = lastOfName_.find(path);
        if (last != lastOfName_.end() && last->second->sameAs(*kept)) kept = last->second;
        lastOfName_[path] = kept;
        maps_[version][image.frame] = kept;
        writeMap(path, version, *kept, display.type == "shadow");
    }
}

RenderStats PassRunner::renderDepth(PassJob& job, const RenderOptions& opts) {
    Scene& scene = job.sequence.scene;
    RenderOptions o = opts;
    o.depthPass = true;
    o.aovs.clear();
    o.dofPreviewLayers = 0;
    o.shadowMaps = binding(job);
    if (job.sequence.isSequence) {
        o.hasFrames = true;
        o.firstFrame = scene.settings.firstFrame;
        o.lastFrame = scene.settings.lastFrame;
    }
    // Frames between the job's that another pass has: rendered with it, not kept.
    const std::map<int, PassFrame>& frames = job.frames;
    o.frameDone = [&frames](int f) { return !frames.count(f); };
    for (const auto& [f, frame] : frames)
        for (const auto& [display, version] : frame.maps) {
            checkSceneWrite("Display", display.name, display.loc);  // --safe: inside its folder
            checkWritableFolder(frameFileName(display.name, f), "Display");
        }
    const double open = scene.settings.shutterOpen;
    auto sink = [&](FrameImage& image) {
        auto it = frames.find(image.frame);
        if (it != frames.end()) keep(it->second, image, open);
    };
    cutBlobbies(job);
    RenderStats stats = Renderer(scene, o, log_).render(sink);
    stats.framesSkipped = 0;  // the other passes' frames, not --resume's
    return stats;
}

void PassRunner::makeShadow(const PassJob& job) {
    const MakeShadowDesc& d = job.makeShadow;
    std::map<int, std::shared_ptr<const DepthMap>> in;
    auto made = job.input > 0 ? maps_.find(job.input) : maps_.end();
    if (made != maps_.end()) {
        in = made->second;
    } else {
        std::error_code ec;
        std::string path = d.input;
        if (!std::filesystem::is_regular_file(path, ec)) path = besideRequest(d.loc, d.input);
        if (!std::filesystem::is_regular_file(path, ec))
            throw InputError(d.loc, "MakeShadow: cannot read the depth map '" + d.input + "' to make '" + d.output +
                                        "' from: no frame of this input writes it (Display \"" + d.input +
                                        "\" \"zfile\" \"z\") and there is no such file");
        auto map = std::make_shared<DepthMap>();
        std::string error;
        if (!readDepthMapFile(path, map.get(), &error))
            throw InputError(d.loc, "MakeShadow '" + d.input + "' -> '" + d.output + "': '" + path + "': " + error);
        in[kAnyFrame] = std::move(map);
    }
    if (in.empty()) throw InputError(d.loc, "MakeShadow: the depth map '" + d.input + "' has no pixels");
    maps_[job.output] = in;
    writeMap(d.output, job.output, *in.rbegin()->second, true);
}

void PassRunner::makeTexture(const PassJob& job, FrameWriter& writer) {
    writer.finish();  // its picture may be a frame just rendered
    Scene one;
    one.settings.makeTextures = {job.makeTexture};  // (a missing picture: InputError at its line)
    makeSceneTextures(one);
}

std::shared_ptr<const DepthMap> PassRunner::mapOf(FileVersion v, int frame) const {
    auto it = maps_.find(v);
    if (it == maps_.end() || it->second.empty()) return nullptr;
    auto f = it->second.find(frame);
    if (f != it->second.end()) return f->second;
    f = it->second.find(kAnyFrame);
    if (f != it->second.end()) return f->second;
    return it->second.size() == 1 ? it->second.begin()->second : nullptr;
}

std::shared_ptr<const ShadowMapBinding> PassRunner::binding(const PassJob& job) const {
    auto b = std::make_shared<ShadowMapBinding>();
    for (const auto& [f, frame] : job.frames)
        for (const auto& [name, version] : frame.reads)
            if (std::shared_ptr<const DepthMap> m = mapOf(version, f)) b->frames[f][name] = std::move(m);
    b->readFile = readDepthMapFile;
    b->namedAt = job.namedAt;
    return b;
}

void PassRunner::cutBlobbies(PassJob& job) {
    Scene& scene = job.sequence.scene;
    const std::shared_ptr<const ShadowMapBinding> b = binding(job);
    // One image per map object: frames that share a map share their cut.
    std::map<const DepthMap*, std::shared_ptr<const BlobbyDepthImage>> images;
    std::map<std::string, std::pair<std::shared_ptr<const DepthMap>, std::string>> files;
    auto image = [&images](const std::shared_ptr<const DepthMap>& m) {
        std::shared_ptr<const BlobbyDepthImage>& i = images[m.get()];
        if (!i) {
            auto made = std::make_shared<BlobbyDepthImage>();
            made->width = m->width, made->height = m->height, made->z = m->z;
            made->worldToCamera = m->worldToCamera, made->worldToScreen = m->worldToScreen;
            i = std::move(made);
        }
        return i;
    };
    auto maps = [&](int frame, const std::string& name, std::string* error) -> std::shared_ptr<const BlobbyDepthImage> {
        auto f = b->frames.find(frame);
        if (f != b->frames.end()) {
            auto m = f->second.find(name);
            if (m != f->second.end() && m->second) return image(m->second);
        }
        auto [it, fresh] = files.try_emplace(name);
        if (fresh) {
            std::error_code ec;
            auto map = std::make_shared<DepthMap>();
            if (std::filesystem::is_regular_file(name, ec) && readDepthMapFile(name, map.get(), &it->second.second))
                it->second.first = std::move(map);
        }
        *error = it->second.second;
        return it->second.first ? image(it->second.first) : nullptr;
    };
    // The frames the job keeps (the others' pixels are not kept: the Blobby is not drawn there).
    std::vector<int> frames;
    for (const auto& [f, frame] : job.frames) frames.push_back(f);
    if (frames.empty())
        for (int f = scene.settings.firstFrame; f <= scene.settings.lastFrame; ++f) frames.push_back(f);
    cutDeferredBlobbies(scene, frames, maps, log_);
}

void PassRunner::release(const std::vector<FileVersion>& versions) {
    for (FileVersion v : versions) maps_.erase(v);
}

}  // namespace streyes::cli
