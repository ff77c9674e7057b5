// Passes (streyes/passes.h): an input's frames grouped into jobs, make requests among them, each
// name's versions, and the order that makes every version before it is read.
#include "streyes/passes.h"

#include "scene/pass_scenes.h"

#include <sys/stat.h>

#include <algorithm>
#include <climits>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <memory>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace streyes {

bool isDepthDisplay(const DisplayDesc& d) { return d.type == "zfile" || d.type == "shadow"; }

namespace {

void put(std::string& k, double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g,", v);
    k += buf;
}

void put(std::string& k, const std::string& v) {
    k += std::to_string(v.size());
    k += ':';
    k += v;
    k += ',';
}

void put(std::string& k, const ParamList& params) {
    for (const Param& p : params.params) {
        put(k, p.name);
        put(k, double(int(p.type)));
        for (double v : p.nums) put(k, v);
        for (const std::string& v : p.strings) put(k, v);
        k += ';';
    }
}

}  // namespace

std::string passKey(const Scene& f) {
    std::string k;
    const CameraDesc& c = f.camera;
    const RenderSettings& s = f.settings;
    k += depthFrame(f) ? "depth|" : "picture|";
    // A picture's field of view, screen window and frame aspect ratio are not: a zoom is one pass,
    // each frame with its own projection (Scene::frameCamera). Perspective and orthographic
    // frames are other passes. A depth frame's projection is its light's cone: the frames of one
    // light are a pass, another light's (numbered alike) another, so that each light's maps
    // stay one still spacetime render.
    put(k, double(int(c.projection)));
    if (depthFrame(f)) {
        put(k, c.fov), put(k, double(c.hasScreenWindow)), put(k, c.frameAspect);
        for (double v : c.screenWindow) put(k, v);
    }
    put(k, double(c.xres)), put(k, double(c.yres)), put(k, c.pixelAspect);
    put(k, c.nearClip), put(k, c.farClip), put(k, c.fstop), put(k, c.focalLength), put(k, c.focalDistance);
    k += '|';
    put(k, s.shutterOpen), put(k, s.shutterClose), put(k, double(s.pixelSamplesX)), put(k, double(s.pixelSamplesY));
    put(k, s.filter.type), put(k, s.filter.xwidth), put(k, s.filter.ywidth);
    put(k, s.shaderSearchPath), put(k, double(s.builtinShading));
    put(k, s.imager.name), put(k, s.imager.params);
    for (size_t i = 0; i < s.imagerLayers.layers.size(); ++i)
        put(k, s.imagerLayers.names[i]), put(k, s.imagerLayers.layers[i].name), put(k, s.imagerLayers.layers[i].params);
    for (const ShaderConnection& c : s.imagerLayers.connections)
        put(k, double(c.from)), put(k, double(c.to)), put(k, c.fromVar), put(k, c.toVar);
    put(k, s.exposureGain), put(k, s.exposureGamma), put(k, double(s.jitter)), put(k, s.depthFilter);
    put(k, double(s.bucketSize)), put(k, double(s.gridSize)), put(k, s.shadowBias);
    put(k, s.options), put(k, s.specularExponent);  // what shaders' option() and specular() read
    for (const std::string& t : s.textureSearchPath) put(k, t);
    k += '|';
    for (const RenderSettings::ShaderOutput& o : s.shaderOutputs) put(k, o.type), put(k, o.name);
    // Exposures that overlap (close - open > 1) cannot share a spacetime render: each frame alone.
    if (s.shutterClose - s.shutterOpen > 1) put(k, double(f.frameNumber)), put(k, f.frameLoc.str());
    return k;
}

namespace {

class Planner {
  public:
    Planner(const PassRequest& req, Log& log, const std::function<void(PassJob&&)>& emit,
            std::map<std::string, std::shared_ptr<const RunTable>> runs)
        : req_(req), log_(log), emit_(emit), block_(std::max(1, req.blockFrames)), runs_(std::move(runs)) {}

    void beginFile() { serials_.clear(); }

    // A frame (frameLoc set) or an ordinary scene, with the make requests around it.
    void scene(Scene&& s) {
        const bool ordinary = s.frameLoc.line == 0;  // a scene without frames (a frame file's has its file's place)
        makes(s, false);
        const std::vector<MakeShadowDesc> shadows = s.settings.makeShadows;
        const std::vector<MakeTextureDesc> textures = s.settings.makeTextures;
        if (!depthFrame(s))
            for (const LightDesc& l : s.lights)
                if (!l.autoShadowMap.empty()) place(autoShadowFrame(s, l), ordinary);
        place(std::move(s), ordinary);
        Scene rest;
        rest.settings.makeShadows = shadows;
        rest.settings.makeTextures = textures;
        makes(rest, true);
    }
    // What follows a file's last frame.
    void trailing(const Scene& s) { makes(s, true, true); }
    const std::set<int>& numbers() const { return numbers_; }

    void finish() {
        flush();
        candidates_.clear();
    }

  private:
    struct Make {
        PassJob::Kind kind = PassJob::Kind::MakeShadow;
        MakeShadowDesc shadow;
        MakeTextureDesc texture;
    };
    struct Node {
        bool job = true;
        std::string key;
        bool depth = false, ordinary = false;
        int pass = 0, count = 0, last = INT_MIN;
        std::unique_ptr<SequenceBuilder> builder;
        Sequence ordinaryScene;
        std::map<int, PassFrame> frames;
        std::map<std::string, SourceLoc> namedAt;
        Make make;
        FileVersion input = 0, output = 0;
        std::set<int> deps;
        std::vector<FileVersion> reads, writes;
        int order = 0;
    };
    struct Version {
        std::string name;
        int node = -1;       // the node that writes it (pending, or done once not pending)
        int candidate = -1;  // or the candidate that would
        bool superseded = false, emitted = false, released = false;
        int readers = 0;  // placed nodes reading it, not yet emitted
    };
    // A frame or request kept until it is known whether a wanted frame reads what it writes.
    struct Candidate {
        bool isMake = false;
        Scene scene;
        bool ordinary = false;
        PassFrame frame;
        std::map<std::string, SourceLoc> strings;
        Make make;
        FileVersion input = 0;
        std::vector<FileVersion> textureInputs;  // a texture make's pictures kept in case
        std::vector<FileVersion> writes;
        bool needy = true;  // what it reads is made for it (not for a picture --resume found written)
        int order = 0;      // its place in the input
    };

    bool inRange(const Scene& s) const {
        return !req_.frames.given || (s.frameNumber >= req_.frames.first && s.frameNumber <= req_.frames.last);
    }

    // The frames an ordinary scene renders (the renderer's rule: --frames, else its own option).
    std::pair<int, int> ordinaryFrames(const Scene& s) const {
        if (req_.frames.given) return {req_.frames.first, req_.frames.last};
        if (s.settings.hasFrames) return {s.settings.firstFrame, s.settings.lastFrame};
        return {0, 0};
    }

    // A new version of `name`, made the latest (what readers after it read) by publish(): between
    // the two, the one who writes it can be registered, so that the versions it supersedes are let
    // go knowing of it.
    FileVersion newVersion(const std::string& name) {
        const FileVersion v = nextVersion_++;
        versions_[v].name = name;
        return v;
    }
    void publish(FileVersion v) {
        const std::string& name = versions_[v].name;
        auto it = latest_.find(name);
        const FileVersion old = it == latest_.end() ? 0 : it->second;
        latest_[name] = v;
        if (old > 0) supersede(old);
    }
    void supersede(FileVersion v) {
        Version& ver = versions_[v];
        ver.superseded = true;
        if (ver.emitted && ver.readers == 0 && !ver.released) {
            ver.released = true;
            releaseSoon_.push_back(v);
        }
        dropDeadCandidates();
    }

    // A candidate none of whose versions can be read any more (each written again since, and no
    // candidate reading it) goes; the oldest go too when too many are kept.
    void dropDeadCandidates() {
        for (bool again = true; again;) {
            again = false;
            for (auto it = candidates_.begin(); it != candidates_.end();) {
                bool dead = true;
                for (FileVersion v : it->second.writes) {
                    if (!versions_[v].superseded) dead = false;
                    for (const auto& [id, c] : candidates_) {
                        if (c.isMake && (c.input == v || std::count(c.textureInputs.begin(), c.textureInputs.end(), v)))
                            dead = false;
                        for (const auto& [w, prior] : c.frame.appends) dead = dead && prior != v;
                    }
                }
                if (dead) {
                    for (FileVersion v : it->second.writes) versions_[v].candidate = -1;
                    it = candidates_.erase(it);
                    again = true;
                } else {
                    ++it;
                }
            }
        }
        while (candidates_.size() > size_t(2 * block_ + 16)) {
            for (FileVersion v : candidates_.begin()->second.writes) versions_[v].candidate = -1;
            candidates_.erase(candidates_.begin());
        }
    }

    // New make requests of a scene (by serial: a frame's scene carries those before it too):
    // those before its world, or after it.
    void makes(const Scene& s, bool after, bool all = false) {
        std::vector<std::pair<int, Make>> found;
        for (const MakeShadowDesc& d : s.settings.makeShadows)
            if ((all || d.afterWorld == after) && !serials_.count(d.serial))
                found.push_back({d.serial, {PassJob::Kind::MakeShadow, d, {}}});
        for (const MakeTextureDesc& d : s.settings.makeTextures)
            if ((all || d.afterWorld == after) && !serials_.count(d.serial))
                found.push_back({d.serial, {PassJob::Kind::MakeTexture, {}, d}});
        std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        for (auto& [serial, m] : found) {
            serials_.insert(serial);
            addMake(std::move(m));
        }
    }

    void addMake(Make&& m) {
        ++order_;
        if (m.kind == PassJob::Kind::MakeShadow) {
            auto it = latest_.find(m.shadow.input);
            const FileVersion input = it == latest_.end() ? 0 : it->second;
            const FileVersion output = newVersion(m.shadow.output);
            if (input > 0 && versions_[input].candidate >= 0) {  // made from a frame kept in case: kept too
                Candidate c;
                c.isMake = true;
                c.make = std::move(m);
                c.input = input;
                c.writes = {output};
                c.order = order_;
                versions_[output].candidate = order_;
                candidates_.emplace(order_, std::move(c));
                publish(output);  // (in place, "a.z" -> "a.z": the frame stays, as the request reads it)
                return;
            }
            placeMake(std::move(m), input, output, order_);
            publish(output);
            return;
        }
        // A texture made from pictures a frame kept in case writes (a frame --frames leaves out):
        // kept too, until a wanted frame reads the texture (then the frames are rendered for it).
        std::vector<FileVersion> kept;
        for (const std::string& name : textureInputs(m.texture)) {
            auto it = latest_.find(pictureKey(name));
            if (it != latest_.end() && versions_[it->second].candidate >= 0) kept.push_back(it->second);
        }
        const FileVersion made = newVersion(textureKey(m.texture.output));
        if (!kept.empty()) {
            Candidate c;
            c.isMake = true;
            c.make = std::move(m);
            c.textureInputs = std::move(kept);
            c.writes = {made};
            c.order = order_;
            versions_[made].candidate = order_;
            candidates_.emplace(order_, std::move(c));
        }
        publish(made);
        if (versions_[made].candidate < 0) placeMake(std::move(m), 0, 0, order_);
    }

    // Names under which the versions of pictures (a frame's picture displays) and textures (a
    // make request's output) are kept: apart from the depth maps' (what frames read by name).
    static std::string pictureKey(const std::string& name) { return std::string("\x01picture:") + name; }
    static std::string textureKey(const std::string& name) { return std::string("\x01texture:") + name; }
    static std::vector<std::string> textureInputs(const MakeTextureDesc& d) {
        return d.cubeFaces.empty() ? std::vector<std::string>{d.input} : d.cubeFaces;
    }
    static std::string frameList(const std::set<int>& frames) {
        std::string out;
        for (int f : frames) out += (out.empty() ? "" : ", ") + std::to_string(f);
        return out;
    }

    // The texture makes kept in case that a wanted frame reads (by a shader string naming the
    // texture, or its file name), placed with the frames whose pictures they read; says which.
    void promoteTextures(const Candidate& reader) {
        std::set<int> frames;
        std::vector<int> makes;
        std::string where;
        for (const auto& [id, c] : candidates_) {
            if (!c.isMake || c.make.kind != PassJob::Kind::MakeTexture || versions_[c.writes.front()].superseded)
                continue;
            const std::string& out = c.make.texture.output;
            if (!reader.strings.count(out) && !reader.strings.count(std::filesystem::path(out).filename().string()))
                continue;
            makes.push_back(id);
            if (where.empty()) where = c.make.texture.loc.str();
            for (FileVersion v : c.textureInputs) {
                auto f = versions_[v].candidate >= 0 ? candidates_.find(versions_[v].candidate) : candidates_.end();
                if (f == candidates_.end() || f->second.isMake) continue;
                f->second.frame.madeFrom = true;
                frames.insert(f->second.frame.number);
            }
        }
        for (int id : makes) promote(id);
        if (!frames.empty())
            log_.info("frame" + std::string(frames.size() > 1 ? "s " : " ") + frameList(frames) +
                      " rendered for frame " + std::to_string(reader.frame.number) +
                      ": the texture it reads is made from " + (frames.size() > 1 ? "their pictures" : "its picture") +
                      " (" + where + ")");
    }

    void placeMake(Make&& m, FileVersion input, FileVersion output, int order) {
        const int id = nextNode_++;
        Node& n = pending_[id];
        n.job = false;
        n.order = order;
        n.make = std::move(m);
        n.input = input;
        n.output = output;
        if (input > 0) {
            n.reads = {input};
            ++versions_[input].readers;
            if (pending_.count(versions_[input].node)) n.deps.insert(versions_[input].node);
        }
        if (output > 0) {
            n.writes = {output};
            versions_[output].node = id;
            versions_[output].candidate = -1;
        }
        if (n.make.kind == PassJob::Kind::MakeTexture) {
            // Its picture may be any file a frame before it writes, and frames before it may read
            // the texture it replaces: it runs after everything before it.
            for (const auto& [other, node] : pending_)
                if (other != id) n.deps.insert(other);
            textures_.push_back({n.make.texture.output, id});
        }
    }

    void place(Scene&& s, bool ordinary) {
        ++order_;
        if (!ordinary) numbers_.insert(s.frameNumber);
        Candidate c;
        c.ordinary = ordinary;
        c.order = order_;
        PassFrame& f = c.frame;
        f.number = s.frameNumber;
        f.loc = s.frameLoc;
        f.camera = s.camera;
        stringsOf(s, c.strings);
        for (const auto& [name, loc] : c.strings) {
            auto it = latest_.find(name);
            if (it != latest_.end()) f.reads[name] = it->second;
        }
        // Wanted: in --frames; a depth frame not if --resume finds it written (then only if a
        // picture still to render reads from it). A picture written already reads from nothing.
        const bool done = !ordinary && inRange(s) && req_.done && req_.done(s);
        const bool want = ordinary || (inRange(s) && !(done && depthFrame(s)));
        c.needy = !done;
        // The versions it writes, in display order: a frame's depth display named with a frame
        // field writes that frame's name (an ordinary scene's, one version holding every frame's).
        for (const DisplayDesc& d : s.settings.displays)
            if (isDepthDisplay(d)) {
                const std::string file = ordinary ? d.name : frameFileName(d.name, s.frameNumber);
                auto prior = d.append ? latest_.find(file) : latest_.end();
                const FileVersion v = newVersion(file);
                if (prior != latest_.end()) f.appends[v] = prior->second;
                f.maps.push_back({d, v});
                c.writes.push_back(v);
                if (!want) versions_[v].candidate = order_;
            }
        // Its pictures, versioned apart: a texture made from one that --frames leaves out keeps
        // this frame in case a wanted frame reads the texture.
        for (const DisplayDesc& d : s.settings.displays)
            if (!isDepthDisplay(d) && !d.name.empty()) {
                const FileVersion v = newVersion(pictureKey(ordinary ? d.name : frameFileName(d.name, s.frameNumber)));
                c.writes.push_back(v);
                if (!want) versions_[v].candidate = order_;
            }
        const std::vector<FileVersion> writes = c.writes;
        c.scene = std::move(s);
        if (want) {
            placeFrame(std::move(c));
        } else if (!c.writes.empty()) {
            const bool picturesOnly = c.frame.maps.empty();
            candidates_.emplace(order_, std::move(c));
            // Frames kept only because a texture might be made from their pictures: the latest few
            // (a cube face environment's six and more), not a whole shot's.
            if (picturesOnly) {
                pictureCandidates_.push_back(order_);
                if (pictureCandidates_.size() > kPictureCandidates) {
                    auto old = candidates_.find(pictureCandidates_.front());
                    pictureCandidates_.pop_front();
                    if (old != candidates_.end() && !old->second.isMake) {
                        for (FileVersion v : old->second.writes) versions_[v].candidate = -1;
                        candidates_.erase(old);
                    }
                }
            }
        }
        for (FileVersion v : writes) publish(v);
    }

    // A candidate a wanted frame reads from: placed now, with what it reads from.
    void promote(int id) {
        auto it = candidates_.find(id);
        if (it == candidates_.end()) return;
        Candidate c = std::move(it->second);
        candidates_.erase(it);
        if (c.isMake) {
            if (c.input > 0 && versions_[c.input].candidate >= 0) promote(versions_[c.input].candidate);
            for (FileVersion v : c.textureInputs)
                if (versions_[v].candidate >= 0) promote(versions_[v].candidate);
            if (c.make.kind == PassJob::Kind::MakeTexture) {
                versions_[c.writes.front()].candidate = -1;
                placeMake(std::move(c.make), 0, 0, c.order);
            } else {
                placeMake(std::move(c.make), c.input, c.writes.front(), c.order);
            }
            return;
        }
        placeFrame(std::move(c));
    }

    // Does `from` run after `to` (through the pending nodes' dependencies)?
    bool reaches(int from, int to) const {
        std::vector<int> stack{from};
        std::set<int> seen;
        while (!stack.empty()) {
            const int n = stack.back();
            stack.pop_back();
            if (n == to) return true;
            if (!seen.insert(n).second) continue;
            auto it = pending_.find(n);
            if (it != pending_.end()) stack.insert(stack.end(), it->second.deps.begin(), it->second.deps.end());
        }
        return false;
    }

    void placeFrame(Candidate&& c) {
        PassFrame& f = c.frame;
        if (c.needy) {
            for (const auto& [name, v] : f.reads)
                if (versions_[v].candidate >= 0) promote(versions_[v].candidate);
            for (const auto& [w, prior] : f.appends)
                if (versions_[prior].candidate >= 0) promote(versions_[prior].candidate);
            promoteTextures(c);
        }
        // Frames rendered only for a texture's pictures are jobs of their own (never under -o).
        const std::string key = c.ordinary ? std::string() : passKey(c.scene) + (f.madeFrom ? "|made-from" : "");
        // A full job, or two blocks' worth of frames held: render what is held first.
        auto open = openJob_.find(key);
        if (!c.ordinary && ((open != openJob_.end() && pending_.count(open->second) &&
                             pending_.at(open->second).count >= block_) ||
                            pendingFrames_ >= 2 * block_)) {
            flush();
            open = openJob_.end();
        }
        std::set<int> deps;
        for (const auto& [name, v] : f.reads)
            if (pending_.count(versions_[v].node)) deps.insert(versions_[v].node);
        for (const auto& [name, node] : textures_)
            if (pending_.count(node) &&
                (c.strings.count(name) || c.strings.count(std::filesystem::path(name).filename().string())))
                deps.insert(node);
        // A file it appends to: made before it, by an earlier job or earlier in its own (a job keeps
        // its frames' maps in frame order).
        std::set<int> appendDeps;
        for (const auto& [w, prior] : f.appends)
            if (pending_.count(versions_[prior].node)) appendDeps.insert(versions_[prior].node);
        int id = -1;
        if (!c.ordinary && open != openJob_.end() && pending_.count(open->second)) {
            const int j = open->second;
            const Node& n = pending_.at(j);
            bool fits = n.last < f.number && n.count < block_;
            for (int d : deps) fits = fits && d != j && !reaches(d, j);
            for (int d : appendDeps) fits = fits && (d == j || !reaches(d, j));
            if (fits) id = j;
        }
        if (id < 0) {
            id = nextNode_++;
            Node& n = pending_[id];
            n.key = key;
            n.ordinary = c.ordinary;
            n.depth = depthFrame(c.scene);
            n.order = c.order;
            auto p = passOfKey_.find(key);
            n.pass = c.ordinary ? nextPass_++ : p != passOfKey_.end() ? p->second : (passOfKey_[key] = nextPass_++);
            if (!c.ordinary) {
                n.builder = std::make_unique<SequenceBuilder>(log_);
                auto runs = runs_.find(key);
                if (runs != runs_.end()) n.builder->setRuns(runs->second);
                openJob_[key] = id;
            }
        }
        Node& n = pending_.at(id);
        n.deps.insert(deps.begin(), deps.end());
        for (int d : appendDeps)
            if (d != id) n.deps.insert(d);
        for (const auto& [name, v] : f.reads) {
            n.reads.push_back(v);
            ++versions_[v].readers;
        }
        for (const auto& [w, prior] : f.appends) {
            n.reads.push_back(prior);
            ++versions_[prior].readers;
        }
        for (const auto& [d, v] : f.maps) {
            n.writes.push_back(v);
            versions_[v].node = id;
            versions_[v].candidate = -1;
        }
        for (FileVersion v : c.writes) versions_[v].candidate = -1;  // its pictures too: made now
        n.namedAt.insert(c.strings.begin(), c.strings.end());
        ++n.count;
        ++pendingFrames_;
        if (c.ordinary) {
            const auto [first, last] = ordinaryFrames(c.scene);
            for (int k = first; k <= last; ++k) {
                PassFrame one = f;
                one.number = k;
                n.frames[k] = std::move(one);
            }
            n.ordinaryScene.scene = std::move(c.scene);
        } else {
            n.last = f.number;
            n.frames[f.number] = std::move(f);
            n.builder->add(std::move(c.scene));
        }
    }

    // Every pending node, in an order that runs each after what it reads (the input's order
    // where either would do).
    void flush() {
        std::map<int, Node> nodes = std::move(pending_);
        pending_.clear();
        openJob_.clear();
        textures_.clear();
        pendingFrames_ = 0;
        std::set<int> left;
        for (const auto& [id, n] : nodes) left.insert(id);
        while (!left.empty()) {
            int next = -1;
            for (int id : left) {
                bool ready = true;
                for (int d : nodes.at(id).deps) ready = ready && !left.count(d);
                if (ready && (next < 0 || nodes.at(id).order < nodes.at(next).order)) next = id;
            }
            if (next < 0) throw std::logic_error("passes: a cycle among the jobs");  // joining rules prevent it
            left.erase(next);
            emit(nodes.at(next));
        }
    }

    void emit(Node& n) {
        PassJob job;
        if (n.job) {
            job.kind = PassJob::Kind::Render;
            job.depth = n.depth;
            job.pass = n.pass;
            job.frames = std::move(n.frames);
            job.namedAt = std::move(n.namedAt);
            job.sequence = n.ordinary ? std::move(n.ordinaryScene) : n.builder->finish();
        } else {
            job.kind = n.make.kind;
            job.makeShadow = std::move(n.make.shadow);
            job.makeTexture = std::move(n.make.texture);
            job.input = n.input;
            job.output = n.output;
        }
        for (FileVersion v : n.writes) versions_[v].emitted = true;
        for (FileVersion v : n.reads) --versions_[v].readers;
        job.release = std::move(releaseSoon_);
        releaseSoon_.clear();
        for (const std::vector<FileVersion>* list : {&n.reads, &n.writes})
            for (FileVersion v : *list) {
                Version& ver = versions_[v];
                if (ver.superseded && ver.emitted && ver.readers == 0 && !ver.released) {
                    ver.released = true;
                    job.release.push_back(v);
                }
            }
        emit_(std::move(job));
    }

    const PassRequest& req_;
    Log& log_;
    const std::function<void(PassJob&&)>& emit_;
    const int block_;
    const std::map<std::string, std::shared_ptr<const RunTable>> runs_;  // each pass's runs over the input
    std::set<int> serials_;  // the current file's make requests handed over
    std::set<int> numbers_;  // frame numbers read
    int order_ = 0, nextNode_ = 0, nextPass_ = 0, pendingFrames_ = 0;
    FileVersion nextVersion_ = 1;
    std::map<int, Node> pending_;
    std::map<std::string, int> openJob_;
    std::map<std::string, int> passOfKey_;
    std::vector<std::pair<std::string, int>> textures_;  // pending MakeTexture outputs and nodes
    std::map<FileVersion, Version> versions_;
    std::map<std::string, FileVersion> latest_;
    std::map<int, Candidate> candidates_;
    std::vector<FileVersion> releaseSoon_;
    static constexpr size_t kPictureCandidates = 12;
    std::deque<int> pictureCandidates_;  // candidates kept for their pictures alone, oldest first
};

}  // namespace

void readPasses(const std::string& path, const PassRequest& req, Log& log, const std::function<void(PassJob&&)>& job,
                const ReadDetail& detail) {
    Planner planner(req, log, job, scanRuns(path, req, detail));
    if (isFramePattern(path)) {
        std::vector<int> frames;
        if (req.frames.given) {
            for (int f = req.frames.first; f <= req.frames.last; ++f) frames.push_back(f);
        } else {
            frames = framesOnDisk(path);
            if (frames.empty()) throw InputError("no frame file matches the pattern '" + path + "'");
        }
        for (size_t i = 0; i < frames.size(); ++i) {
            const int f = frames[i];
            const std::string file = frameFileName(path, f);
            std::error_code ec;
            if (!std::filesystem::exists(file, ec)) {
                std::string why = req.frames.given ? "--frames " + std::to_string(req.frames.first) + "-" +
                                                         std::to_string(req.frames.last) + " asks for it"
                                                   : "the pattern's files run from " + std::to_string(frames.front()) +
                                                         " to " + std::to_string(frames.back());
                throw InputError("missing frame file '" + file + "' (frame " + std::to_string(f) + "): " + why);
            }
            if (!req.frames.given && i > 0 && f != frames[i - 1] + 1)
                throw InputError("missing frame file '" + frameFileName(path, frames[i - 1] + 1) + "' (frame " +
                                 std::to_string(frames[i - 1] + 1) + "): the pattern's files run from " +
                                 std::to_string(frames.front()) + " to " + std::to_string(frames.back()) +
                                 " with a gap; give --frames to render a part");
        }
        // Frames are parsed in parallel, a batch at a time (memory holds a batch), and planned in
        // order; the first frame's error in order is the one reported, whatever thread found it.
        const size_t batch = size_t(std::max(2, 2 * tbb::this_task_arena::max_concurrency()));
        for (size_t b = 0; b < frames.size(); b += batch) {
            const size_t n = std::min(batch, frames.size() - b);
            std::vector<FrameFile> files(n);
            std::vector<std::exception_ptr> errors(n);
            tbb::parallel_for(size_t(0), n, [&](size_t i) {
                try {
                    files[i] = readFrameFile(frameFileName(path, frames[b + i]), frames[b + i], log, detail,
                                             req.defaults);
                } catch (...) {
                    errors[i] = std::current_exception();
                }
            });
            for (size_t i = 0; i < n; ++i) {
                if (errors[i]) std::rethrow_exception(errors[i]);
                planner.beginFile();
                for (Scene& s : files[i].scenes) planner.scene(std::move(s));
                planner.trailing(files[i].after);
            }
        }
        planner.finish();
        return;
    }
    bool frames = false;
    planner.beginFile();
    parseRibFrames(
        path, log,
        [&](Scene&& s) {
            frames = frames || s.frameLoc.line > 0;
            planner.scene(std::move(s));
        },
        detail, [&](Scene&& s) { planner.trailing(s); }, req.defaults);
    if (frames && req.frames.given)
        for (int f = req.frames.first; f <= req.frames.last; ++f)
            if (!planner.numbers().count(f))
                throw InputError("'" + path + "' has no FrameBegin " + std::to_string(f) + ", which --frames " +
                                 std::to_string(req.frames.first) + "-" + std::to_string(req.frames.last) +
                                 " asks for");
    planner.finish();
}

Sequence readScene(const std::string& path, const FrameRequest& frames, Log& log, const ReadDetail& detail,
                   const RibDefaults& defaults) {
    PassRequest req;
    req.frames = frames;
    req.defaults = defaults;
    req.blockFrames = INT_MAX / 4;
    std::vector<Sequence> renders;
    readPasses(path, req, log, [&](PassJob&& j) {
        if (j.kind == PassJob::Kind::Render) renders.push_back(std::move(j.sequence));
    }, detail);
    if (renders.size() != 1)
        throw InputError("'" + path + "' holds " + std::to_string(renders.size()) +
                         " passes (frames with other settings): read it with readPasses");
    return std::move(renders.front());
}

}  // namespace streyes
