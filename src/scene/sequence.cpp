// Frame sequences into one spacetime scene (streyes/sequence.h): matching a frame's primitives
// with the previous frame's, runs of still primitives, and reading patterns and frame files.
#include "streyes/sequence.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "scene/sequence_equal.h"
#include "streyes/rib.h"

namespace streyes {

namespace {

std::string shutter(const RenderSettings& s) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "Shutter %g %g", s.shutterOpen, s.shutterClose);
    return buf;
}

// Where a frame's message points: its FrameBegin, or its file.
SourceLoc frameLoc(const Scene& s) { return s.frameLoc; }

}  // namespace

// ---- Matching ---------------------------------------------------------------------------------------------
AttributesPtr SequenceBuilder::remap(const AttributesPtr& a) {
    if (!a) return a;
    auto it = remapped_.find(a.get());
    if (it != remapped_.end()) return it->second;
    auto copy = std::make_shared<Attributes>(*a);
    for (int& l : copy->lights) l = lightIndex_[size_t(l)];
    if (copy->detail && copy->detail->hasBound) {
        // The Detail box is measured in the render camera's space, into which the frame's
        // primitives are baked: its transform is baked with them.
        auto lod = std::make_shared<LevelOfDetail>(*copy->detail);
        lod->boundToWorld = lod->boundToWorld.then(worldToCamera_);
        copy->detail = std::move(lod);
    }
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
                                   int frame, int previous) {
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
    if (it != tracks_.end() && it->second.lastFrame == previous && !zoomed_) {
        Desc& run = merged[it->second.run];
        // With the input's runs known, a block's run goes on only within its run there and its
        // epoch (its life is theirs already).
        const std::pair<int, int>* inInput = table_ ? tableRun(key, frame) : nullptr;
        const bool sameRun = !table_ || (inInput && inInput->first <= it->second.firstFrame &&
                                         runEpoch(frame) == runEpoch(it->second.firstFrame));
        if (sameRun && stillWithinFrame(p) && stillWithinFrame(run) && sameData(run, p)) {
            if (!table_) run.life.t1 = frame + close_;
            if (!scan_) {
                SequenceRun& r = out_.runs[it->second.runIndex];
                if (r.lastFrame == r.firstFrame) ++out_.stats.stillRuns;
                r.lastFrame = frame;
            }
            it->second.lastFrame = frame;
            return;
        }
        if (scan_) closeRun(key, it->second);
    }
    p.life = lifeOf(key, frame);
    Track t;
    t.run = merged.size();
    t.firstFrame = t.lastFrame = frame;
    t.runIndex = out_.runs.size();
    if (!scan_) out_.runs.push_back({name, frame, frame});
    merged.push_back(std::move(p));
    tracks_[key] = t;
}

// ---- Runs over the whole input ----------------------------------------------------------------------------
// The input's run of `key` that holds `frame`, or null (a run of that frame alone).
const std::pair<int, int>* SequenceBuilder::tableRun(const std::string& key, int frame) const {
    auto it = table_->runs.find(key);
    if (it == table_->runs.end()) return nullptr;
    const std::vector<std::pair<int, int>>& runs = it->second;
    auto r = std::upper_bound(runs.begin(), runs.end(), frame, [](int f, const auto& run) { return f < run.first; });
    if (r == runs.begin()) return nullptr;
    --r;
    return frame <= r->second ? &*r : nullptr;
}

// A run starting at `frame` in the block lives over its frames in the input within the frame's
// epoch (the block's own frames when the input's runs are not known).
Lifetime SequenceBuilder::lifeOf(const std::string& key, int frame) {
    int a = frame, b = frame;
    if (table_) {
        if (const std::pair<int, int>* run = tableRun(key, frame)) {
            const auto [first, last] = runEpochFrames(frame);
            a = std::max(run->first, first);
            b = std::min(run->second, last);
        }
        shotFirst_ = std::min(shotFirst_, a);
        shotLast_ = std::max(shotLast_, b);
    }
    return Lifetime{a + open_, b + close_, false};
}

void SequenceBuilder::closeRun(const std::string& key, const Track& t) {
    if (t.lastFrame > t.firstFrame) found_.runs[key].emplace_back(t.firstFrame, t.lastFrame);
}

template <typename Desc>
void SequenceBuilder::keepAlive(std::vector<Desc>& v, std::vector<std::pair<size_t, Track*>>& alive) {
    std::vector<Desc> kept;
    kept.reserve(alive.size());
    for (auto& [i, t] : alive) {
        t->run = kept.size();
        kept.push_back(std::move(v[i]));
    }
    v = std::move(kept);
}

// A scan keeps the primitives of runs that reached this frame only: a run that did not can never
// go on (a run goes on from the frame before).
void SequenceBuilder::dropEnded(int frame) {
    std::map<char, std::vector<std::pair<size_t, Track*>>> alive;
    for (auto it = tracks_.begin(); it != tracks_.end();) {
        if (it->second.lastFrame != frame) {
            closeRun(it->first, it->second);
            it = tracks_.erase(it);
        } else {
            alive[it->first[0]].emplace_back(it->second.run, &it->second);
            ++it;
        }
    }
    Scene& m = out_.scene;
    keepAlive(m.patches, alive['b']), keepAlive(m.procedurals, alive['r']), keepAlive(m.patchMeshes, alive['p']);
    keepAlive(m.subdivisionMeshes, alive['s']), keepAlive(m.quadrics, alive['q']), keepAlive(m.curves, alive['c']);
    keepAlive(m.points, alive['o']), keepAlive(m.polygonMeshes, alive['g']), keepAlive(m.nuPatches, alive['n']);
}

RunTable SequenceBuilder::runTable() {
    for (const auto& [key, t] : tracks_) closeRun(key, t);
    tracks_.clear();
    for (auto& [key, runs] : found_.runs) std::sort(runs.begin(), runs.end());
    found_.lastFrame = lastFrame_;
    return std::move(found_);
}

namespace {
bool sameSolids(const std::vector<SolidNode>& a, const std::vector<SolidNode>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].op != b[i].op || a[i].parent != b[i].parent || a[i].children != b[i].children) return false;
    return true;
}
}  // namespace

void SequenceBuilder::add(Scene&& frame) {
    const int f = frame.frameNumber;
    if (out_.stats.frames > 0) {
        // The passes (streyes/passes.h) give a builder frames of one pass in increasing order.
        if (f <= lastFrame_)
            throw InputError(frameLoc(frame), "frame " + std::to_string(f) + " comes after frame " +
                                                  std::to_string(lastFrame_) + ": frames must be in increasing order");
        if (frame.settings.shutterOpen != open_ || frame.settings.shutterClose != close_)
            throw InputError(frameLoc(frame), "frame " + std::to_string(f) + " has " + shutter(frame.settings) +
                                                  ", not the other frames' " + shutter(out_.scene.settings) +
                                                  ": a pass's frames share one shutter");
        if (close_ - open_ > 1)
            throw InputError(frameLoc(frame), shutter(frame.settings) +
                                                  ": the exposures of consecutive frames overlap, so frames cannot "
                                                  "be merged (each renders alone)");
    }
    if (out_.stats.frames == 0) {  // the block's first frame
        blockFirst_ = f;
        shotFirst_ = shotLast_ = f;
        open_ = frame.settings.shutterOpen;
        close_ = frame.settings.shutterClose;
        out_.scene.camera = frame.camera;
        out_.scene.camera.worldToCamera = MotionTransform();
        out_.scene.settings = frame.settings;
        out_.scene.sourceName = frame.sourceName;
    }
    const int previous = out_.stats.frames == 0 ? f - 1 : lastFrame_;
    lastFrame_ = f;
    ++out_.stats.frames;
    if (!scan_) {  // a scan keeps nothing per frame: its memory is the last frame's, however long the input
        out_.displays[f] = frame.settings.displays;
        out_.scene.frameWorldToCamera[f] = frame.camera.worldToCamera;
    }
    // A zoom: frames of one pass may differ in projection (streyes/passes.h). A still primitive's
    // run ends where it changes, so that each body lives under one projection and is split and
    // diced as its frames alone would (docs/ARCHITECTURE.md, "Zooms").
    zoomed_ = out_.stats.frames > 1 && !sameZoom(frame.camera, previousCamera_);
    if (!scan_ && !sameZoom(frame.camera, out_.scene.camera)) {
        CameraDesc& c = out_.scene.frameCamera[f] = out_.scene.camera;  // camera space: the merged one
        c.fov = frame.camera.fov;
        c.hasScreenWindow = frame.camera.hasScreenWindow;
        std::copy(frame.camera.screenWindow, frame.camera.screenWindow + 4, c.screenWindow);
        c.frameAspect = frame.camera.frameAspect;
    }
    previousCamera_ = frame.camera;

    // Lights in camera space, shared with earlier frames where equal.
    worldToCamera_ = frame.camera.worldToCamera;
    lightIndex_.clear();
    remapped_.clear();
    declared_.clear();
    for (LightDesc& l : frame.lights) {
        l.lightToWorld = l.lightToWorld.then(worldToCamera_);
        if (l.area) l.areaToWorld = l.areaToWorld.then(worldToCamera_);  // its shape, in the frame's world
        std::vector<LightDesc>& lights = out_.scene.lights;
        size_t i = 0;
        while (i < lights.size() && !sameLight(lights[i], l)) ++i;
        if (i == lights.size()) lights.push_back(std::move(l));
        lightIndex_.push_back(int(i));
    }

    Scene& m = out_.scene;
    // Primitives point at their solid's leaves by index (Attributes::solid): frames merge when they
    // declare the same solids (the usual animation of one CSG model), with one tree for all.
    if (m.solids.empty()) {
        m.solids = std::move(frame.solids);
    } else if (!frame.solids.empty() && !sameSolids(m.solids, frame.solids)) {
        throw InputError(frame.solids.front().loc, "frame " + std::to_string(f) +
                                                       " declares other solids (SolidBegin) than an earlier frame of "
                                                       "its pass: render such frames one at a time (--frames)");
    }
    std::map<std::string, int> seen;
    for (BilinearPatchDesc& p : frame.patches) addPrimitive('b', std::move(p), m.patches, seen, f, previous);
    seen.clear();
    for (ProceduralDesc& p : frame.procedurals) addPrimitive('r', std::move(p), m.procedurals, seen, f, previous);
    seen.clear();
    for (PatchMeshDesc& p : frame.patchMeshes) addPrimitive('p', std::move(p), m.patchMeshes, seen, f, previous);
    seen.clear();
    for (SubdivisionMeshDesc& p : frame.subdivisionMeshes)
        addPrimitive('s', std::move(p), m.subdivisionMeshes, seen, f, previous);
    seen.clear();
    for (QuadricDesc& p : frame.quadrics) addPrimitive('q', std::move(p), m.quadrics, seen, f, previous);
    seen.clear();
    for (CurvesDesc& p : frame.curves) addPrimitive('c', std::move(p), m.curves, seen, f, previous);
    seen.clear();
    for (PointsDesc& p : frame.points) addPrimitive('o', std::move(p), m.points, seen, f, previous);
    seen.clear();
    for (PolygonMeshDesc& p : frame.polygonMeshes) {
        // Ids follow the merged order: a Polygon that is one patch takes its place after the
        // patches merged so far.
        p.patchesBefore = m.patches.size();
        addPrimitive('g', std::move(p), m.polygonMeshes, seen, f, previous);
    }
    seen.clear();
    for (NuPatchDesc& p : frame.nuPatches) addPrimitive('n', std::move(p), m.nuPatches, seen, f, previous);
    if (scan_) dropEnded(f);
}

Sequence SequenceBuilder::finish() {
    if (out_.stats.frames == 0) throw InputError("the sequence has no frames");
    RenderSettings& s = out_.scene.settings;
    s.hasFrames = true;
    s.firstFrame = blockFirst_;
    s.lastFrame = lastFrame_;
    s.displays.clear();
    // Exposures that touch (close - open == 1): a run that ends before the last frame (of the
    // input, when its runs are known) ends open, so that the instant the next frame's exposure
    // begins is the next frame's.
    const double end = (table_ ? std::max(table_->lastFrame, lastFrame_) : lastFrame_) + close_;
    if (table_) {
        s.hasShot = true;
        s.shotFirst = shotFirst_;  // from the block's first frame on, lowered by its runs
        s.shotLast = std::max(shotLast_, lastFrame_);
    }
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

}  // namespace streyes
