// Frame sequences into one spacetime scene (streyes/sequence.h): matching a frame's primitives
// with the previous frame's, runs of still primitives, and reading patterns and frame files.
#include "streyes/sequence.h"

#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <set>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "scene/sequence_equal.h"
#include "streyes/rib.h"

namespace streyes {

namespace {

std::string describeFrame(const SourceLoc& loc, int frame) {
    return "frame " + std::to_string(frame) + (loc.str().empty() ? "" : " (" + loc.str() + ")");
}

std::string resolution(const CameraDesc& c) { return std::to_string(c.xres) + "x" + std::to_string(c.yres); }

std::string shutter(const RenderSettings& s) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "Shutter %g %g", s.shutterOpen, s.shutterClose);
    return buf;
}

// Where a frame's message points: its FrameBegin, or its file.
SourceLoc frameLoc(const Scene& s) { return s.frameLoc; }

}  // namespace

// ---- Checks between frames ----------------------------------------------------------------------------
// What one render of all frames shares: the image, the shutter, the projection and sampling.
void SequenceBuilder::check(const Scene& frame) {
    const Reference& r = *first_;
    const CameraDesc &a = r.camera, &b = frame.camera;
    const RenderSettings &s = r.settings, &t = frame.settings;
    const std::string against = " against " + describeFrame(r.loc, r.frame);
    auto fail = [&](const std::string& what) {
        throw InputError(frameLoc(frame), "frame " + std::to_string(frame.frameNumber) + " " + what);
    };
    if (a.xres != b.xres || a.yres != b.yres || a.pixelAspect != b.pixelAspect)
        fail("has resolution " + resolution(b) + ", " + resolution(a) + against +
             ": every frame of a sequence needs the same Format");
    if (s.shutterOpen != t.shutterOpen || s.shutterClose != t.shutterClose)
        fail("has " + shutter(t) + ", " + shutter(s) + against + ": every frame of a sequence needs the same shutter");
    if (a.projection != b.projection || a.fov != b.fov || a.hasScreenWindow != b.hasScreenWindow ||
        !std::equal(a.screenWindow, a.screenWindow + 4, b.screenWindow) || a.frameAspect != b.frameAspect)
        fail("has another projection or screen window than" + against.substr(8) +
             ": a sequence is rendered through one projection (the camera may move)");
    if (a.nearClip != b.nearClip || a.farClip != b.farClip)
        fail("has other Clipping planes than" + against.substr(8) + ": every frame of a sequence needs the same");
    if (a.depthOfField() != b.depthOfField() ||
        (a.depthOfField() && (a.fstop != b.fstop || a.focalLength != b.focalLength || a.focalDistance != b.focalDistance)))
        fail("has another DepthOfField than" + against.substr(8) + ": every frame of a sequence needs the same lens");
    if (!sameParams(s.options, t.options))  // shaders read them (option()): one value for the whole render
        fail("has other Option \"user\" values than" + against.substr(8) + ": every frame of a sequence needs the same");
    if (s.pixelSamplesX != t.pixelSamplesX || s.pixelSamplesY != t.pixelSamplesY || s.filter.type != t.filter.type ||
        s.filter.xwidth != t.filter.xwidth || s.filter.ywidth != t.filter.ywidth)
        fail("has other PixelSamples or PixelFilter than" + against.substr(8) +
             ": every frame of a sequence needs the same");
}

// ---- Matching ---------------------------------------------------------------------------------------------
AttributesPtr SequenceBuilder::remap(const AttributesPtr& a) {
    if (!a) return a;
    auto it = remapped_.find(a.get());
    if (it != remapped_.end()) return it->second;
    auto copy = std::make_shared<Attributes>(*a);
    for (int& l : copy->lights) l = lightIndex_[size_t(l)];
    return remapped_.emplace(a.get(), std::move(copy)).first->second;
}

namespace {

template <typename Desc>
void bake(Desc& p, const MotionTransform& worldToCamera) {
    p.objectToWorld = p.objectToWorld.then(worldToCamera);
}

}  // namespace

// A primitive of this frame: its run goes on when the previous frame had it, the same and still;
// otherwise it starts a run of its own over this frame's exposure.
template <typename Desc>
void SequenceBuilder::addPrimitive(char kind, Desc&& p, std::vector<Desc>& merged, std::map<std::string, int>& seen,
                                   int frame) {
    const Param* id = p.attributes ? p.attributes->user.find("identifier:name") : nullptr;
    const std::string name = id && !id->strings.empty() ? id->strings.front() : "";
    const int index = seen[name]++;
    if (id && !name.empty()) {
        // Primitives of one Attribute "identifier" are one object; the same name given again
        // elsewhere in the frame is most likely a mistake of the exporter's.
        auto [first, isNew] = declared_.emplace(name, id->loc);
        if (!isNew && (first->second.line != id->loc.line || first->second.file != id->loc.file))
            log_.warnOnce("sequence-duplicate:" + name, id->loc,
                          "identifier \"" + name + "\" is given again in frame " + std::to_string(frame) +
                              " (first at " + (first->second.file == id->loc.file ? "line " + std::to_string(first->second.line)
                                                                                  : first->second.str()) +
                              "): its primitives are matched with other frames' in the order they come");
    }
    std::string key;
    key.reserve(name.size() + 16);
    key += kind;
    key += std::to_string(index);
    key += ':';
    key += name;
    bake(p, worldToCamera_);
    p.attributes = remap(p.attributes);
    ++out_.stats.primitivesRead;
    auto it = tracks_.find(key);
    if (it != tracks_.end() && it->second.lastFrame == frame - 1) {
        Desc& run = merged[it->second.run];
        if (stillWithinFrame(p) && stillWithinFrame(run) && sameData(run, p)) {
            run.life.t1 = frame + close_;
            SequenceRun& r = out_.runs[it->second.runIndex];
            if (r.lastFrame == r.firstFrame) ++out_.stats.stillRuns;
            r.lastFrame = frame;
            it->second.lastFrame = frame;
            return;
        }
    }
    p.life = Lifetime{frame + open_, frame + close_, false};
    Track t;
    t.run = merged.size();
    t.lastFrame = frame;
    t.runIndex = out_.runs.size();
    out_.runs.push_back({name, frame, frame});
    merged.push_back(std::move(p));
    tracks_[key] = t;
}

void SequenceBuilder::add(Scene&& frame) {
    const int f = frame.frameNumber;
    if (!first_) {
        first_ = std::make_unique<Reference>(Reference{f, frame.frameLoc, frame.camera, frame.settings});
        open_ = frame.settings.shutterOpen;
        close_ = frame.settings.shutterClose;
        if (close_ - open_ > 1)
            throw InputError(frameLoc(frame), shutter(frame.settings) +
                                                  ": the exposures of consecutive frames overlap, so a sequence "
                                                  "cannot say what is seen when (a frame sequence needs close - "
                                                  "open <= 1)");
    } else {
        if (f <= lastFrame_)
            throw InputError(frameLoc(frame), "frame " + std::to_string(f) + " comes after frame " +
                                                  std::to_string(lastFrame_) + ": frames must be in increasing order");
        if (f != lastFrame_ + 1) {
            const std::string missing = f - 1 > lastFrame_ + 1 ? "frames " + std::to_string(lastFrame_ + 1) + "-" +
                                                                     std::to_string(f - 1) + " are missing"
                                                               : "frame " + std::to_string(lastFrame_ + 1) + " is missing";
            throw InputError(frameLoc(frame), "frame " + std::to_string(f) + " follows frame " +
                                                  std::to_string(lastFrame_) + ": " + missing +
                                                  " (a sequence's frames must be consecutive)");
        }
        check(frame);
    }
    if (out_.stats.frames == 0) {  // the block's first frame
        blockFirst_ = f;
        out_.scene.camera = frame.camera;
        out_.scene.camera.worldToCamera = MotionTransform();
        out_.scene.settings = frame.settings;
        out_.scene.sourceName = frame.sourceName;
    }
    lastFrame_ = f;
    ++out_.stats.frames;
    out_.displays[f] = frame.settings.displays;

    // Lights in camera space, shared with earlier frames where equal.
    worldToCamera_ = frame.camera.worldToCamera;
    lightIndex_.clear();
    remapped_.clear();
    declared_.clear();
    for (LightDesc& l : frame.lights) {
        l.lightToWorld = l.lightToWorld.then(worldToCamera_);
        std::vector<LightDesc>& lights = out_.scene.lights;
        size_t i = 0;
        while (i < lights.size() && !sameLight(lights[i], l)) ++i;
        if (i == lights.size()) lights.push_back(std::move(l));
        lightIndex_.push_back(int(i));
    }

    Scene& m = out_.scene;
    std::map<std::string, int> seen;
    for (BilinearPatchDesc& p : frame.patches) addPrimitive('b', std::move(p), m.patches, seen, f);
    seen.clear();
    for (ProceduralDesc& p : frame.procedurals) addPrimitive('r', std::move(p), m.procedurals, seen, f);
    seen.clear();
    for (PatchMeshDesc& p : frame.patchMeshes) addPrimitive('p', std::move(p), m.patchMeshes, seen, f);
    seen.clear();
    for (SubdivisionMeshDesc& p : frame.subdivisionMeshes) addPrimitive('s', std::move(p), m.subdivisionMeshes, seen, f);
    seen.clear();
    for (QuadricDesc& p : frame.quadrics) addPrimitive('q', std::move(p), m.quadrics, seen, f);
    seen.clear();
    for (CurvesDesc& p : frame.curves) addPrimitive('c', std::move(p), m.curves, seen, f);
    seen.clear();
    for (PointsDesc& p : frame.points) addPrimitive('o', std::move(p), m.points, seen, f);
    seen.clear();
    for (PolygonMeshDesc& p : frame.polygonMeshes) {
        // Ids follow the merged order: a Polygon that is one patch takes its place after the
        // patches merged so far.
        p.patchesBefore = m.patches.size();
        addPrimitive('g', std::move(p), m.polygonMeshes, seen, f);
    }
    seen.clear();
    for (NuPatchDesc& p : frame.nuPatches) addPrimitive('n', std::move(p), m.nuPatches, seen, f);
}

Sequence SequenceBuilder::finish() {
    if (out_.stats.frames == 0) throw InputError("the sequence has no frames");
    RenderSettings& s = out_.scene.settings;
    s.hasFrames = true;
    s.firstFrame = blockFirst_;
    s.lastFrame = lastFrame_;
    s.displays.clear();
    // Exposures that touch (close - open == 1): a run that ends before the last frame ends open,
    // so that the instant the next frame's exposure begins is the next frame's.
    const double end = lastFrame_ + close_;
    const bool touching = close_ - open_ >= 1;
    auto close = [&](auto& v) {
        for (auto& p : v) p.life.openEnd = touching && p.life.t1 < end;
    };
    Scene& m = out_.scene;
    close(m.patches), close(m.procedurals), close(m.patchMeshes), close(m.subdivisionMeshes), close(m.quadrics);
    close(m.polygonMeshes), close(m.curves), close(m.points), close(m.nuPatches);
    out_.stats.runs = out_.runs.size();
    out_.isSequence = true;
    tracks_.clear();
    Sequence done = std::move(out_);
    out_ = Sequence();
    return done;
}

// ---- Reading --------------------------------------------------------------------------------------------
bool isFramePattern(const std::string& path) {
    return std::filesystem::path(path).filename().string().find('#') != std::string::npos;
}

std::string frameFileName(const std::string& pattern, int frame) {
    const size_t slash = pattern.find_last_of('/');
    const size_t a = pattern.find('#', slash == std::string::npos ? 0 : slash + 1);
    if (a == std::string::npos) return pattern;
    size_t b = a;
    while (b < pattern.size() && pattern[b] == '#') ++b;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%0*d", int(b - a), frame);
    return pattern.substr(0, a) + buf + pattern.substr(b);
}

namespace {

// The frame numbers of the files a pattern matches, in order.
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

uint64_t fileSize(const std::string& path) {
    struct stat st {};
    return stat(path.c_str(), &st) == 0 ? uint64_t(st.st_size) : 0;
}

// One frame's file: a scene, or one FrameBegin block (whose number should be the file's).
Scene readFrameFile(const std::string& file, int f, Log& log, const ReadDetail& detail) {
    Scene frame;
    int blocks = 0;
    parseRibFrames(
        file, log,
        [&](Scene&& s) {
            const bool block = s.frameLoc.line > 0;
            if (block && ++blocks > 1)
                throw InputError(s.frameLoc, "a second FrameBegin in the frame file of frame " + std::to_string(f) +
                                                 ": a pattern's file holds one frame");
            if (block && s.frameNumber != f)
                log.warnOnce("sequence-number:" + file, s.frameLoc,
                             "FrameBegin " + std::to_string(s.frameNumber) + " in the file of frame " + std::to_string(f) +
                                 ": the file name's number is used");
            if (!block) s.frameLoc = SourceLoc{std::make_shared<const std::string>(file), 1, 0};
            s.frameNumber = f;
            frame = std::move(s);
        },
        detail);
    return frame;
}

}  // namespace

Sequence readScene(const std::string& path, const FrameRequest& req, Log& log, const ReadDetail& detail) {
    Sequence all;
    readSceneBlocks(
        path, req, std::numeric_limits<int>::max(), log, [&](Sequence&& s) { all = std::move(s); }, detail);
    return all;
}

void readSceneBlocks(const std::string& path, const FrameRequest& req, int blockFrames, Log& log,
                     const std::function<void(Sequence&&)>& block, const ReadDetail& detail) {
    SequenceBuilder builder(log);
    uint64_t bytes = 0;
    blockFrames = std::max(1, blockFrames);
    auto add = [&](Scene&& s) {
        builder.add(std::move(s));
        if (builder.frames() < blockFrames) return;
        Sequence done = builder.finish();
        done.stats.bytesRead = std::exchange(bytes, 0);
        block(std::move(done));
    };
    if (isFramePattern(path)) {
        std::vector<int> frames;
        if (req.given) {
            for (int f = req.first; f <= req.last; ++f) frames.push_back(f);
        } else {
            frames = framesOnDisk(path);
            if (frames.empty()) throw InputError("no frame file matches the pattern '" + path + "'");
        }
        for (size_t i = 0; i < frames.size(); ++i) {
            const int f = frames[i];
            const std::string file = frameFileName(path, f);
            std::error_code ec;
            if (!std::filesystem::exists(file, ec)) {
                std::string why = req.given ? "--frames " + std::to_string(req.first) + "-" + std::to_string(req.last) +
                                                  " asks for it"
                                            : "the pattern's files run from " + std::to_string(frames.front()) +
                                                  " to " + std::to_string(frames.back());
                throw InputError("missing frame file '" + file + "' (frame " + std::to_string(f) + "): " + why);
            }
            if (!req.given && i > 0 && f != frames[i - 1] + 1)
                throw InputError("missing frame file '" + frameFileName(path, frames[i - 1] + 1) + "' (frame " +
                                 std::to_string(frames[i - 1] + 1) + "): the pattern's files run from " +
                                 std::to_string(frames.front()) + " to " + std::to_string(frames.back()) +
                                 " with a gap; give --frames to render a part");
        }
        // Frames are parsed in parallel, a batch at a time (memory holds a batch), and merged in
        // order; the first frame's error in order is the one reported, whatever thread found it.
        const size_t batch = size_t(std::max(2, 2 * tbb::this_task_arena::max_concurrency()));
        for (size_t b = 0; b < frames.size(); b += batch) {
            const size_t n = std::min(batch, frames.size() - b);
            std::vector<Scene> scenes(n);
            std::vector<std::exception_ptr> errors(n);
            tbb::parallel_for(size_t(0), n, [&](size_t i) {
                try {
                    scenes[i] = readFrameFile(frameFileName(path, frames[b + i]), frames[b + i], log, detail);
                } catch (...) {
                    errors[i] = std::current_exception();
                }
            });
            for (size_t i = 0; i < n; ++i) {
                if (errors[i]) std::rethrow_exception(errors[i]);
                bytes += fileSize(frameFileName(path, frames[b + i]));
                add(std::move(scenes[i]));
            }
        }
        if (builder.frames() > 0) {
            Sequence done = builder.finish();
            done.stats.bytesRead = bytes;
            block(std::move(done));
        }
        return;
    }
    Sequence single;
    bool frames = false;
    std::set<int> read;
    parseRibFrames(path, log, [&](Scene&& s) {
        if (s.frameLoc.line == 0) {  // no frame blocks: an ordinary scene
            single.scene = std::move(s);
            return;
        }
        frames = true;
        read.insert(s.frameNumber);
        if (req.given && (s.frameNumber < req.first || s.frameNumber > req.last)) return;
        add(std::move(s));
    }, detail);
    if (!frames) {
        single.stats.bytesRead = fileSize(path);
        block(std::move(single));
        return;
    }
    if (req.given)
        for (int f = req.first; f <= req.last; ++f)
            if (!read.count(f))
                throw InputError("'" + path + "' has no FrameBegin " + std::to_string(f) + ", which --frames " +
                                 std::to_string(req.first) + "-" + std::to_string(req.last) + " asks for");
    if (builder.frames() > 0) block(builder.finish());
}

}  // namespace streyes
