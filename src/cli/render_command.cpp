// `streyes render SCENE [options]`: parse, render, write one image per frame.
#include <sys/resource.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <new>
#include <set>
#include <thread>

#include "commands.h"
#include "io/exr_file.h"
#include "io/depth_map_file.h"
#include "io/frame_writer.h"
#include "pass_runner.h"
#include "raster/sample_kernels.h"
#include "render/dof_preview.h"
#include "streyes/textures.h"
#include "render_request.h"
#include "streyes/image_io.h"
#include "streyes/memory.h"
#include "streyes/renderer.h"
#include "streyes/rib.h"
#include "streyes/sequence.h"
#include "util/aov.h"

namespace streyes::cli {

namespace {

// --preview's samples per pixel (at most the scene's own).
constexpr int kPreviewSamples = 4;
constexpr int kPreviewDivisor = 2;  // --preview renders the Format's size divided by this

// A duration as m:ss, or h:mm:ss from an hour on.
std::string clockTime(int seconds) {
    char buf[32];
    if (seconds >= 3600)
        std::snprintf(buf, sizeof buf, "%d:%02d:%02d", seconds / 3600, seconds / 60 % 60, seconds % 60);
    else
        std::snprintf(buf, sizeof buf, "%d:%02d", seconds / 60, seconds % 60);
    return buf;
}

// Progress on stderr. On a terminal, a bar with an ETA redrawn in place. Elsewhere (a log file, a
// pipe, a render farm) one plain line at each 10% of buckets done, so that a long render shows
// signs of life where carriage returns would not: "streyes: 30% (412/1373 buckets), 1:05
// elapsed, ETA 2:31". Buckets finish on several threads and report out of order; a line is
// printed only for a tenth not reached before, so the percentages only rise, ending with 100%.
class ProgressBar {
  public:
    explicit ProgressBar(bool enabled) : enabled_(enabled), terminal_(isatty(STDERR_FILENO) != 0) {}
    void update(uint64_t done, uint64_t total) {
        if (!enabled_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        auto now = std::chrono::steady_clock::now();
        done = std::min(done, total);  // a second pass (grown procedurals) counts its buckets again
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        const double frac = total ? double(done) / double(total) : 1.0;
        const int eta = frac > 0 ? int(elapsed / frac - elapsed + 0.5) : 0;
        if (!terminal_) {
            const int tenth = total ? int(done * 10 / total) : 10;
            if (tenth <= lastTenth_) return;
            lastTenth_ = tenth;
            std::fprintf(stderr, "streyes: %d%% (%llu/%llu buckets), %s elapsed, ETA %s\n",
                         total ? int(done * 100 / total) : 100, (unsigned long long)done, (unsigned long long)total,
                         clockTime(int(elapsed)).c_str(), clockTime(eta).c_str());
            std::fflush(stderr);
            return;
        }
        if (done < total && now - last_ < std::chrono::milliseconds(100)) return;
        last_ = now;
        const int width = 30;
        int filled = int(frac * width);
        std::fprintf(stderr, "\r[%.*s%*s] %3d%%  %llu/%llu buckets  ETA %s ", filled,
                     "##############################", width - filled, "", int(frac * 100),
                     (unsigned long long)done, (unsigned long long)total, clockTime(eta).c_str());
        std::fflush(stderr);
        shown_ = true;
    }
    void finish() {
        if (shown_) std::fprintf(stderr, "\r%*s\r", 80, "");
    }

  private:
    bool enabled_, terminal_;
    bool shown_ = false;
    int lastTenth_ = 0;  // plain lines: the tenths of the buckets already reported
    std::mutex mutex_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
};

}  // namespace

std::vector<Output> chooseOutputs(const Scene& scene, const std::string& oPattern, const std::string& scenePath,
                                  int frames, Log& log) {
    std::vector<Output> outs, variables;
    std::string mode = "rgbaz";
    bool primary = true;
    for (const DisplayDesc& d : scene.settings.displays) {
        if (isDepthDisplay(d)) continue;  // depth maps: written by the passes (pass_runner.h)
        bool file = d.type == "openexr" || d.type == "file" || d.type == "tiff" || d.type == "exr";
        if (!file) {
            log.warn(d.loc, "Display type '" + d.type + "' is not supported: '" + d.name + "' skipped");
            continue;
        }
        // -o names the primary display's file; the other displays of output variables keep their
        // names ("+normals.####.exr"), and the colour-only ones give way to -o as always.
        const bool hasVariables = !modeVariables(d.mode).empty();
        if (hasVariables && primary) mode = d.mode;
        else if (hasVariables) variables.push_back({d.name, d.mode, d.quantize});
        else if (!d.mode.empty() && modeVariables(mode).empty()) mode = d.mode;
        // What the scene names is written (-o replaces only the primary display's name).
        if (oPattern.empty() || (hasVariables && !primary)) checkSceneWrite("Display", d.name, d.loc);
        primary = false;
        if (oPattern.empty()) outs.push_back({d.name, d.mode.empty() ? "rgbaz" : d.mode, d.quantize});
    }
    if (!oPattern.empty()) {
        outs.push_back({oPattern, mode, scene.settings.quantizeOf(mode)});
        outs.insert(outs.end(), variables.begin(), variables.end());
    }
    if (outs.empty()) {
        std::string stem = std::filesystem::path(scenePath).stem().string();
        outs.push_back({stem + ".####.exr", "rgbaz"});
        log.info("no output given (-o) and no file Display in the scene: writing " + outs.back().pattern);
    }
    for (Output& o : outs) {
        if (frames > 1 && !hasFrameField(o.pattern)) {
            std::string p = addFrameField(o.pattern);
            log.warn({}, "output '" + o.pattern + "' has no #### frame field and " + std::to_string(frames) +
                             " frames are rendered: writing '" + p + "'");
            o.pattern = p;
        }
    }
    return outs;
}

std::map<int, std::vector<Output>> sequenceOutputs(const Sequence& seq, const std::string& oPattern,
                                                   const std::string& scenePath, int first, int last, Log& log,
                                                   const std::set<int>* only) {
    std::map<int, std::vector<Output>> outs;
    auto skip = [&](int f) { return only && !only->count(f); };  // another pass's frame
    const int frames = last - first + 1;
    if (!oPattern.empty()) {
        Scene none;
        const std::vector<Output> o = chooseOutputs(none, oPattern, scenePath, frames, log);
        for (int f = first; f <= last; ++f)
            if (!skip(f)) outs[f] = o;
        return outs;
    }
    // Each frame's own Display names; a name without #### that several frames give gets one.
    std::map<std::string, int> uses;
    for (int f = first; f <= last; ++f) {
        auto it = seq.displays.find(f);
        if (it == seq.displays.end() || skip(f)) continue;
        for (const DisplayDesc& d : it->second) ++uses[d.name];
    }
    std::string stem = std::filesystem::path(scenePath).stem().string();
    stem.erase(std::remove(stem.begin(), stem.end(), '#'), stem.end());
    while (!stem.empty() && stem.back() == '.') stem.pop_back();
    std::set<std::string> checked;  // names a scene may write (--safe): each once
    for (int f = first; f <= last; ++f) {
        if (skip(f)) continue;
        std::vector<Output>& o = outs[f];
        auto it = seq.displays.find(f);
        if (it != seq.displays.end())
            for (const DisplayDesc& d : it->second) {
                if (isDepthDisplay(d)) continue;  // depth maps: written by the passes (pass_runner.h)
                const bool file = d.type == "openexr" || d.type == "file" || d.type == "tiff" || d.type == "exr";
                if (!file) {
                    log.warnOnce("display-type:" + d.type, d.loc,
                                 "Display type '" + d.type + "' is not supported: '" + d.name + "' skipped");
                    continue;
                }
                std::string name = d.name;
                if (checked.insert(name).second) checkSceneWrite("Display", name, d.loc);
                if (uses[name] > 1 && !hasFrameField(name)) {
                    const std::string p = addFrameField(name);
                    log.warnOnce("display-field:" + name, d.loc,
                                 "Display '" + name + "' is named by several frames: writing '" + p + "'");
                    name = p;
                }
                o.push_back({name, d.mode.empty() ? "rgbaz" : d.mode, d.quantize});
            }
        if (o.empty()) {
            o.push_back({(stem.empty() ? "frame" : stem) + ".####.exr", "rgbaz"});
            log.warnOnce("sequence-default-output", {},
                         "no output given (-o) and no file Display in frame " + std::to_string(f) + ": writing " +
                             o.back().pattern);
        }
    }
    return outs;
}

namespace {

void writeTextAtomically(const std::string& path, const std::string& text) {
    std::string tmp = path + ".tmp" + std::to_string(getpid());
    {
        std::ofstream f(tmp, std::ios::binary);
        f << text;
        f.close();
        if (!f) {
            std::remove(tmp.c_str());
            throw RenderError("cannot write '" + path + "': " + std::strerror(errno));
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        throw RenderError("cannot write '" + path + "': " + std::strerror(errno));
    }
}

// Frames first..last of an output pattern.
struct OutputFrames {
    std::string pattern;
    int first = 0, last = 0;
};

// The temporaries of the outputs' frames whose writers no longer run (image_io.h,
// removeStaleTemporaries), and only of those frames: on a render farm, tasks on other machines
// write the pattern's other frames into the same shared folder, and their process ids mean nothing
// here (a live writer there would look dead from here). Each folder is listed once, for whether
// any temporary is there at all: a sequence names its files frame by frame, and a listing a frame
// read a folder of N frames N times (a 5,000-frame shot spent 90% of its time there).
int removeStaleTemporariesOfFrames(const std::vector<OutputFrames>& outputs) {
    std::map<std::string, std::vector<std::string>> temporaries;  // by folder
    int removed = 0;
    for (const OutputFrames& o : outputs) {
        const std::filesystem::path dir = std::filesystem::path(o.pattern).has_parent_path()
                                              ? std::filesystem::path(o.pattern).parent_path()
                                              : std::filesystem::path(".");
        auto [listed, isNew] = temporaries.try_emplace(dir.string());
        if (isNew) {
            std::error_code ec;
            for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
                const std::string name = entry.path().filename().string();
                if (!name.empty() && name[0] == '.' && name.find(".tmp") != std::string::npos)
                    listed->second.push_back(name);
            }
        }
        if (listed->second.empty()) continue;
        for (int f = o.first; f <= o.last; ++f) {
            const std::string path = expandFramePattern(o.pattern, f);
            const std::string prefix = "." + std::filesystem::path(path).stem().string() + ".tmp";
            for (const std::string& t : listed->second)
                if (t.compare(0, prefix.size(), prefix) == 0) {
                    removed += removeStaleTemporaries(path);  // a pattern without #: this frame only
                    break;
                }
        }
    }
    return removed;
}

// The stats JSON with the process's CPU time (user + system, every thread, parse and writing
// included) as "cpu_seconds": what `streyes farm gather` sums over a shot's tasks.
std::string withProcessCpu(std::string json) {
    struct rusage ru {};
    if (getrusage(RUSAGE_SELF, &ru) != 0) return json;
    const double cpu = double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
                       1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(json);
    j["cpu_seconds"] = std::round(cpu * 1000) / 1000;  // milliseconds are all getrusage is good for
    return j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

// --resume: is this frame of the input written already? A depth frame: each depth map it writes
// reads back. A picture: each output (-o, else its file displays, else the default name) is a
// complete image of its size and channels. In doubt, not: then its depth maps are made again.
bool frameWritten(const Scene& frame, const RenderRequest& req, const std::string& scenePath) {
    const int f = frame.frameNumber;
    bool depth = false;
    std::vector<Output> outs;
    for (const DisplayDesc& d : frame.settings.displays) {
        if (isDepthDisplay(d)) {
            depth = true;
            DepthMap map;
            std::string error;
            if (!readDepthMapFile(frameFileName(d.name, f), &map, &error)) return false;
        } else if (d.type == "openexr" || d.type == "file" || d.type == "tiff" || d.type == "exr") {
            outs.push_back({d.name, d.mode.empty() ? "rgbaz" : d.mode, d.quantize});
        }
    }
    if (depth && outs.empty()) return true;
    if (!req.outPattern.empty()) {
        const std::string mode = outs.empty() ? "rgbaz" : outs.front().mode;
        const Quantize q = outs.empty() ? kColorQuantize : outs.front().quantize;
        outs = {Output{req.outPattern, mode, q}};
    }
    if (outs.empty()) {
        std::string stem = std::filesystem::path(scenePath).stem().string();
        stem.erase(std::remove(stem.begin(), stem.end(), '#'), stem.end());
        while (!stem.empty() && stem.back() == '.') stem.pop_back();
        outs.push_back({(stem.empty() ? "frame" : stem) + ".####.exr", "rgbaz"});
    }
    int w = req.opts.xres > 0 ? req.opts.xres : frame.camera.xres,
        h = req.opts.yres > 0 ? req.opts.yres : frame.camera.yres;
    if (req.preview && req.opts.xres <= 0) w = std::max(1, w / kPreviewDivisor), h = std::max(1, h / kPreviewDivisor);
    for (const Output& o : outs)
        if (!isCompleteFrame(expandFramePattern(o.pattern, f), w, h, o.mode) &&
            !isCompleteFrame(expandFramePattern(addFrameField(o.pattern), f), w, h, o.mode))
            return false;
    return true;
}

}  // namespace

SceneAccess sceneAccessFor(const RenderRequest& req) {
    SceneAccess access;
    if (!req.safe) return access;
    namespace fs = std::filesystem;
    access.programs = false;
    access.safe = true;
    std::string dir = req.safeDir;
    if (dir.empty()) dir = fs::path(req.outPattern).parent_path().string();
    if (dir.empty()) dir = ".";
    std::error_code ec;
    if (!req.safeDir.empty() && !fs::is_directory(dir, ec))
        throw InputError("--safe-dir " + dir + ": no such folder (the folder a scene may write in must exist)");
    access.writeFolder = fs::absolute(dir, ec).lexically_normal().string();
    if (access.writeFolder.size() > 1 && access.writeFolder.back() == '/') access.writeFolder.pop_back();
    return access;
}

void applyPreview(RenderRequest& req, const Scene& scene) {
    if (!req.preview) return;
    // Chosen from the speed-against-error measurements (docs/results/, docs/ARCHITECTURE.md):
    // fewer samples and half the resolution reach a given error fastest; the occlusion
    // tolerance never did, so it stays exact.
    RenderOptions& opts = req.opts;
    if (opts.xres <= 0) {
        opts.xres = std::max(1, scene.camera.xres / kPreviewDivisor);
        opts.yres = std::max(1, scene.camera.yres / kPreviewDivisor);
    }
    if (opts.samples == 0) opts.samples = std::min(kPreviewSamples, scene.settings.pixelSamplesX * scene.settings.pixelSamplesY);
}

int renderCommand(const std::vector<std::string>& args) {
    RenderRequest req;
    if (!parseRenderArgs(args, &req)) return 0;  // --help
    RenderOptions& opts = req.opts;
    const std::string &scenePath = req.scenePath, &outPattern = req.outPattern, &statsPath = req.statsPath;
    const bool quiet = req.quiet, resume = req.resume;
    if (scenePath.empty()) throw UsageError("no scene given");
    // On this machine (a farm's tasks may run on CPUs other than the one that submitted them).
    std::string simdError;
    if (!req.simd.empty() && !capSimd(req.simd, &simdError)) throw UsageError("--simd: " + simdError);

    setSceneAccess(sceneAccessFor(req));  // before the scene is read: --safe refuses at the request

    const auto start = std::chrono::steady_clock::now();
    const ExrChunkCounts chunksBefore = exrChunkCounts();
    Log log;
    log.setEcho(true);
    log.setQuiet(quiet);
    log.setStrict(req.strict);
    FrameRequest wanted;
    wanted.given = opts.hasFrames;
    wanted.first = opts.firstFrame, wanted.last = opts.lastFrame;

    // A file size limit kills a process that writes past it (SIGXFSZ); ignored, the write fails
    // with EFBIG instead, and the frame is reported and removed like any failed write.
    std::signal(SIGXFSZ, SIG_IGN);

    std::vector<std::string> written_;  // files, for the summary
    // Frames are encoded and written by a writer thread while the next block renders; OpenEXR
    // compresses each on as many threads as render (after the last block the writer is alone).
    setExrEncodeThreads(opts.threads > 0 ? opts.threads : int(std::max(1u, std::thread::hardware_concurrency())));
    FrameWriter writer;
    std::string outOfMemory;  // what an allocation that fails while rendering (or writing) says
    RenderStats total;
    ResolvedSettings first;
    int frames = 0, blocks = 0;
    double parseSeconds = 0;
    auto readFrom = std::chrono::steady_clock::now();
    PassRunner runner(log);
    RenderStats depthTotal;  // the depth passes', added to the pictures' at the end
    int depthRenders = 0;
    bool statsChecked = false;
    auto checkStatsFolder = [&] {  // before the first render, as the outputs' folders
        if (!statsPath.empty() && !statsChecked) checkWritableFolder(statsPath, "--stats");
        statsChecked = true;
    };
    auto addStats = [&](const RenderStats& stats, bool depth) {
        RenderStats& into = depth ? depthTotal : total;
        if ((depth ? depthRenders++ : blocks++) == 0) {
            into = stats;
        } else {  // several renders (a sequence's blocks, passes): summed, the largest memory theirs
            into.counters += stats.counters;
            into.lastFrame = std::max(into.lastFrame, stats.lastFrame);
            into.firstFrame = std::min(into.firstFrame, stats.firstFrame);
            into.timeBuild += stats.timeBuild;
            into.timeRender += stats.timeRender;
            into.timeWrite += stats.timeWrite;
            into.peakMemoryBytes = std::max(into.peakMemoryBytes, stats.peakMemoryBytes);
            into.memoryEstimateBytes = std::max(into.memoryEstimateBytes, stats.memoryEstimateBytes);
            into.memoryBodiesBytes = std::max(into.memoryBodiesBytes, stats.memoryBodiesBytes);
            into.framesSkipped += stats.framesSkipped;
            into.procedurals += stats.procedurals;
            into.bodiesGenerated += stats.bodiesGenerated;
            into.passes = std::max(into.passes, stats.passes);
            into.renders += stats.renders;
        }
    };
    // -o names the pictures' files: a frame number that two picture passes render (two shots
    // numbered alike) goes to the later pass's own name.
    std::map<int, int> oFrameOf;  // frame -> picture pass written under -o
    std::map<int, std::string> oPatternOf;
    auto outPatternFor = [&](const PassJob& job) -> std::string {
        if (outPattern.empty()) return outPattern;
        // Frames rendered for a texture's pictures (--frames left them out) write what the texture reads.
        if (!job.frames.empty() &&
            std::all_of(job.frames.begin(), job.frames.end(), [](const auto& f) { return f.second.madeFrom; }))
            return std::string();
        auto known = oPatternOf.find(job.pass);
        if (known != oPatternOf.end()) return known->second;
        bool clash = false;
        for (const auto& [f, frame] : job.frames) {
            auto it = oFrameOf.find(f);
            clash = clash || (it != oFrameOf.end() && it->second != job.pass);
        }
        std::string pattern = outPattern;
        if (clash) {
            const std::filesystem::path p(outPattern);
            pattern = (p.parent_path() /
                       (p.stem().string() + ".pass" + std::to_string(job.pass + 1) + p.extension().string()))
                          .string();
            log.warnOnce("o-pass:" + std::to_string(job.pass), job.frames.begin()->second.loc,
                         "frames of another pass have these frame numbers: this pass's pictures are written to '" +
                             pattern + "' (-o names the first)");
        }
        for (const auto& [f, frame] : job.frames) oFrameOf.emplace(f, job.pass);
        return oPatternOf[job.pass] = pattern;
    };
    // A picture job: its frames rendered as one scene (a sequence a block of frames at a time as it
    // is read: memory holds one block), with a renderer of its own: a frame's pixels do not depend
    // on the block (streyes/sequence.h). Frames of the block another pass has are not written.
    auto renderPicture = [&](PassJob& job) {
        Sequence& seq = job.sequence;
        Scene& scene = seq.scene;
        if (frames == 0) applyPreview(req, scene);
        RenderOptions blockOpts = opts;
        if (seq.isSequence) {  // this block's frames
            blockOpts.hasFrames = true;
            blockOpts.firstFrame = scene.settings.firstFrame;
            blockOpts.lastFrame = scene.settings.lastFrame;
        }
        const ResolvedSettings rs = resolveSettings(scene, blockOpts);
        if (frames == 0) first = rs;
        std::set<int> mine;  // the frames this job writes
        for (const auto& [f, frame] : job.frames) mine.insert(f);
        const int blockFrames = seq.isSequence ? int(mine.size()) : rs.lastFrame - rs.firstFrame + 1;
        frames += blockFrames;
        const std::string oPattern = outPatternFor(job);
        // Where each frame goes: -o, or the scene's displays (a sequence's frames each their own).
        std::vector<Output> outputs;
        std::map<int, std::vector<Output>> frameOutputs;
        if (seq.isSequence)
            frameOutputs = sequenceOutputs(seq, oPattern, scenePath, rs.firstFrame, rs.lastFrame, log, &mine);
        else outputs = chooseOutputs(scene, oPattern, scenePath, blockFrames, log);
        auto isMine = [&](int frame) { return !seq.isSequence || frameOutputs.count(frame) > 0; };
        auto outputsOf = [&](int frame) -> const std::vector<Output>& {
            return seq.isSequence ? frameOutputs.at(frame) : outputs;
        };
        std::vector<int> written;  // the frames of the block this job writes
        for (int f = rs.firstFrame; f <= rs.lastFrame; ++f)
            if (isMine(f)) written.push_back(f);
        // Depth is "midpoint" only in depth passes (they keep every surface); a picture's Z is the nearest.
        if (scene.settings.depthFilter == "midpoint" && !written.empty())
            for (const Output& o : outputsOf(written.front()))
                if (o.mode.find('z') != std::string::npos)
                    log.warnOnce(
                        "picture-midpoint", {},
                        "Hider \"hidden\" \"depthfilter\" \"midpoint\" applies to depth maps (Display \"zfile\" | "
                        "\"shadow\"): the picture's Z is the nearest depth");

        // Before anything is rendered, every output's folder and the --stats file's folder must
        // take a file: a missing or read-only folder would otherwise be found only when the first
        // frame block is done, perhaps minutes in (exit 1, as then). Writes failing later (a full
        // disk) are still caught, and the frame removed, by writeFrame.
        std::set<std::string> folders;  // each folder once (a sequence names a file a frame)
        for (int f : written) {
            for (const Output& o : outputsOf(f)) {
                const std::string file = expandFramePattern(o.pattern, f);
                if (folders.insert(std::filesystem::path(file).parent_path().string()).second)
                    checkWritableFolder(file, "-o");
            }
            if (!seq.isSequence) break;
        }
        checkStatsFolder();

        // Temporary files of renders of these frames that were killed mid-write go; with --resume,
        // frames whose every output is a complete image of the right size and channels (read
        // back) are not rendered.
        std::vector<OutputFrames> frameFiles;
        if (seq.isSequence) {
            for (const auto& [f, outs] : frameOutputs)
                for (const Output& o : outs) frameFiles.push_back({o.pattern, f, f});
        } else {
            for (const Output& o : outputs) frameFiles.push_back({o.pattern, rs.firstFrame, rs.lastFrame});
        }
        const int stale = removeStaleTemporariesOfFrames(frameFiles);
        if (stale > 0) log.info("removed " + std::to_string(stale) + " temporary file" + (stale == 1 ? "" : "s") +
                                " left by an interrupted render");
        blockOpts.frameDone = [&outputsOf, &rs, &isMine, resume](int frame) {
            if (!isMine(frame)) return true;  // another pass's frame: rendered with the block, not written
            if (!resume) return false;
            for (const Output& o : outputsOf(frame))
                if (!isCompleteFrame(expandFramePattern(o.pattern, frame), rs.cropX1 - rs.cropX0, rs.cropY1 - rs.cropY0,
                                     o.mode))  // a crop's file holds the crop (CropWindow)
                    return false;
            return true;
        };
        // The output variables the outputs write (a sequence's frames' own displays among them).
        for (int f : written) {
            for (const Output& o : outputsOf(f))
                for (const std::string& v : modeVariables(o.mode))
                    if (std::find(blockOpts.aovs.begin(), blockOpts.aovs.end(), v) == blockOpts.aovs.end())
                        blockOpts.aovs.push_back(v);
            if (!seq.isSequence) break;
        }
        if (blockOpts.dofPreviewLayers > 0 && !blockOpts.aovs.empty())
            throw UsageError("--dof-preview writes colour, alpha and Z only: drop the output variables (" +
                             blockOpts.aovs.front() + ", ...) from the displays, or render with lens samples");
        blockOpts.textureSource = openImageTextures;  // loads OpenImageIO only on a shader's first lookup
        blockOpts.shadowMaps = runner.binding(job);
        runner.cutBlobbies(job);
        const double open = scene.settings.shutterOpen;
        // A crop (CropWindow): the pixels are the crop's, written where they lie in the frame.
        const FrameWindow window = rs.cropped() ? FrameWindow{rs.cropX0, rs.cropY0, rs.width, rs.height} : FrameWindow{};
        auto sink = [&](FrameImage& img) {
            // A picture frame's own depth displays (Display "+x.z" "zfile" "z") are kept and written
            // before its pixels go to the writer.
            auto frame = job.frames.find(img.frame);
            if (frame != job.frames.end()) runner.keep(frame->second, img, open);
            std::vector<FrameOutput> files;
            for (const Output& o : outputsOf(img.frame)) {
                files.push_back({expandFramePattern(o.pattern, img.frame), o.mode, o.quantize, window});
                written_.push_back(files.back().path);
            }
            writer.handOver(img, std::move(files));  // no copy: the renderer gets a written frame's buffers
        };
        ProgressBar bar(!quiet);
        auto progress = [&](uint64_t done, uint64_t all) { bar.update(done, all); };
        outOfMemory = outOfMemoryMessage(rs.firstFrame, rs.lastFrame, rs.width, rs.height, blockOpts.maxFrameBlock,
                                         blockOpts.maxMemoryBytes ? blockOpts.maxMemoryBytes : defaultMemoryBudget());
        RenderStats stats;
        try {
            stats = blockOpts.dofPreviewLayers > 0
                        ? renderDofPreview(scene, blockOpts, blockOpts.dofPreviewLayers, log, sink, progress)
                        : Renderer(scene, blockOpts, log).render(sink, progress);
        } catch (const std::bad_alloc&) {
            throw RenderError(outOfMemory);
        }
        bar.finish();
        stats.framesSkipped -= (rs.lastFrame - rs.firstFrame + 1) - int(written.size());  // other passes' frames
        addStats(stats, false);
    };
    // Depth jobs render at their own Format and PixelSamples (--res, --samples and --preview are the
    // picture's), rasterized (depths need every surface a sample crosses).
    RenderOptions depthOpts = opts;
    depthOpts.xres = depthOpts.yres = depthOpts.samples = 0;
    depthOpts.dofPreviewLayers = 0;
    depthOpts.aovs.clear();
    depthOpts.textureSource = openImageTextures;
    if (depthOpts.algorithm == Algorithm::Raytrace) depthOpts.algorithm = Algorithm::SpacetimeOcclusion;
    if (depthOpts.algorithm == Algorithm::RaytraceFrames) depthOpts.algorithm = Algorithm::FramesOcclusion;
    auto onJob = [&](PassJob&& job) {
        parseSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - readFrom).count();
        switch (job.kind) {
            case PassJob::Kind::Render:
                if (job.depth) {
                    checkStatsFolder();
                    addStats(runner.renderDepth(job, depthOpts), true);
                }
                else renderPicture(job);
                break;
            case PassJob::Kind::MakeShadow: runner.makeShadow(job); break;
            case PassJob::Kind::MakeTexture: runner.makeTexture(job, writer); break;
        }
        runner.release(job.release);
        readFrom = std::chrono::steady_clock::now();
    };
    // What is sized while it is read (a Blobby's cells) is sized for the image rendered.
    ReadDetail detail;
    detail.xres = opts.xres, detail.yres = opts.yres;
    if (req.preview && opts.xres <= 0) detail.formatScale = 1.0 / kPreviewDivisor;  // applyPreview's size
    // A Blobby's repelling planes read their depth maps (named from the working folder) as they are read.
    detail.readDepthMap = [](const std::string& name, BlobbyDepthImage* out, std::string* error) {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(name, ec)) return false;
        DepthMap map;
        if (!readDepthMapFile(name, &map, error)) return false;
        out->width = map.width, out->height = map.height;
        out->z = std::move(map.z);
        out->worldToCamera = map.worldToCamera, out->worldToScreen = map.worldToScreen;
        return true;
    };
    // ...or, where their maps may be written by an earlier pass of this input, when their pass renders.
    detail.deferRepellingMaps = true;
    PassRequest passes;
    passes.frames = wanted;
    passes.blockFrames = opts.maxFrameBlock;
    checkRibDefaults(req.ribOptions);
    passes.defaults = req.ribOptions;
    // --resume: depth frames whose maps are on disk are rendered only for pictures still to render.
    if (resume) passes.done = [&](const Scene& frame) { return frameWritten(frame, req, scenePath); };
    readPasses(scenePath, passes, log, onJob, detail);
    const ResolvedSettings& rs = first;
    RenderStats& stats = total;
    if (depthRenders > 0) {  // the depth passes' work counts too; the figures describing the render are the pictures'
        if (blocks == 0) {
            total = depthTotal;
        } else {
            total.counters += depthTotal.counters;
            total.timeBuild += depthTotal.timeBuild;
            total.timeRender += depthTotal.timeRender;
            total.timeWrite += depthTotal.timeWrite;
            total.peakMemoryBytes = std::max(total.peakMemoryBytes, depthTotal.peakMemoryBytes);
            total.memoryEstimateBytes = std::max(total.memoryEstimateBytes, depthTotal.memoryEstimateBytes);
            total.memoryBodiesBytes = std::max(total.memoryBodiesBytes, depthTotal.memoryBodiesBytes);
            total.procedurals += depthTotal.procedurals;
            total.bodiesGenerated += depthTotal.bodiesGenerated;
            total.renders += depthTotal.renders;
        }
    }
    const auto waited = std::chrono::steady_clock::now();
    try {
        writer.finish();
    } catch (const std::bad_alloc&) {  // encoding the last frames
        if (outOfMemory.empty()) throw;
        throw RenderError(outOfMemory);
    }
    stats.timeWrite += std::chrono::duration<double>(std::chrono::steady_clock::now() - waited).count();
    stats.exrChunksCompressed = exrChunkCounts().compressed - chunksBefore.compressed;
    stats.exrChunksReused = exrChunkCounts().reused - chunksBefore.reused;
    stats.timeParse = parseSeconds;
    stats.timeTotal = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats.peakMemoryBytes = std::max(stats.peakMemoryBytes, peakResidentBytes());
    if (!statsPath.empty()) writeTextAtomically(statsPath, withProcessCpu(stats.toJson()));
    if (!quiet) {
        if (frames > 0 || runner.mapsWritten() == 0)
            std::fprintf(
                stderr, "streyes: %d frame%s %dx%d, %d samples/pixel, %s%s, %.2f s: %s%s\n", frames,
                frames == 1 ? "" : "s", rs.width, rs.height, rs.pattern.count(), algorithmName(opts.algorithm),
                opts.tolerance > 0 ? (" (tolerance " + std::to_string(opts.tolerance).substr(0, 6) + ")").c_str() : "",
                stats.timeTotal, written_.empty() ? "(nothing written)" : written_.front().c_str(),
                written_.size() > 1 ? (" ... " + written_.back()).c_str() : "");
        if (runner.mapsWritten() > 0)
            std::fprintf(stderr, "streyes: %d depth map file%s written\n", runner.mapsWritten(),
                         runner.mapsWritten() == 1 ? "" : "s");
        if (stats.framesSkipped > 0)
            std::fprintf(stderr, "streyes: %d frame%s already complete, not written again (--resume)\n",
                         stats.framesSkipped, stats.framesSkipped == 1 ? "" : "s");
    }
    return 0;
}

}  // namespace streyes::cli
