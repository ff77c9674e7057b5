// `streyes render`'s options (CLI11, command_line.h), shared with `streyes farm submit`, which
// passes them to its tasks.
#include <filesystem>

#include "command_line.h"
#include "commands.h"
#include "raster/sample_kernels.h"
#include "render_request.h"
#include "streyes/memory.h"

namespace streyes::cli {

namespace {

void parseRes(const std::string& v, RenderOptions& o) {
    size_t x = v.find('x');
    if (x == std::string::npos) throw UsageError("--res expects WIDTHxHEIGHT, e.g. 640x360, not '" + v + "'");
    o.xres = int(parseInt("--res", v.substr(0, x), 1, 65536));
    o.yres = int(parseInt("--res", v.substr(x + 1), 1, 65536));
}

}  // namespace

const char* kRenderSynopsis = "usage: streyes render SCENE.rib | SHOT.####.rib [options]";

const char* kRenderDescription = R"(
Renders an animation described in RIB as one spacetime scene, one EXR per frame. A frame
pattern (shot.####.rib: a file per frame) or a file of FrameBegin blocks is read as a frame
sequence, each frame a complete scene (docs/SCENE-FORMAT.md, "Frame sequences").)";

const char* kRenderFooter = R"(environment: STREYES_SHADERPATH, STREYES_TEXTUREPATH, STREYES_PROCEDURALPATH: folders separated by
             ':' where shaders, texture maps and plug-ins are looked for after the scene's own
             search paths (Option "searchpath")

exit codes: 0 done, 1 render failed (e.g. an output folder missing or not writable, found
            before rendering; a full disk), 2 bad input or usage (or more memory than the budget))";

void addRenderOptions(CommandLine& cl, RenderRequest& req, const std::set<std::string>& leaveOut,
                      const std::string& group) {
    RenderOptions& opts = req.opts;
    std::vector<CLI::Option*> added;
    auto keep = [&](const std::string& name) { return leaveOut.count(name) == 0; };
    auto add = [&](CLI::Option* o) { added.push_back(o); };
    if (keep("--frames"))
        add(cl.value("--frames", "A-B",
                     "frames to render (or a single frame A); default: the scene's\n"
                     "Option \"streyes\" \"int frames\", else frame 0; of a sequence, every\n"
                     "frame it has (a pattern: every file there is, which must be consecutive)",
                     [&](const std::string& v) {
                         parseFrameRange("--frames", v, &opts.firstFrame, &opts.lastFrame);
                         opts.hasFrames = true;
                     }));
    if (keep("--shot"))
        add(cl.value("--shot", "A-B",
                     "the whole animation these frames belong to: motion segments and procedurals'\n"
                     "level of detail are decided over it, so that a frame renders the same\n"
                     "whatever other frames are rendered with it (render farms pass it);\n"
                     "it must hold them; default: the scene's frames joined with those rendered",
                     [&](const std::string& v) {
                         parseFrameRange("--shot", v, &opts.shotFirst, &opts.shotLast);
                         opts.hasShot = true;
                     }));
    add(cl.value("--res", "WxH", "image size in pixels; default: the scene's Format",
                 [&](const std::string& v) { parseRes(v, opts); }));
    add(cl.value("--samples", "N", "samples per pixel per frame; default: the scene's PixelSamples",
                 [&](const std::string& v) { opts.samples = int(parseInt("--samples", v, 1, 4096)); }));
    add(cl.value("--algorithm", "NAME",
                 "spacetime-occlusion (default): Algorithm S with occlusion culling\n"
                 "spacetime:          Algorithm S, split once per block of frames\n"
                 "frames-occlusion:   Algorithm C', Catmull per frame with occlusion culling\n"
                 "frames:             Algorithm C, Catmull per frame (the baseline)\n"
                 "raytrace:           ray tracing through one spacetime hierarchy\n"
                 "                    (Glassner's; the reference for the rasterizer's error)\n"
                 "raytrace-frames:    ray tracing with a 3D hierarchy per frame",
                 [&](const std::string& v) {
                     if (!parseAlgorithm(v, &opts.algorithm))
                         throw UsageError("--algorithm expects spacetime-occlusion, spacetime, frames-occlusion, "
                                          "frames, raytrace or raytrace-frames, not '" + v + "'");
                 }));
    add(cl.value("--tolerance", "EPS",
                 "occlusion tolerance: drop a body when at most EPS of its pixel-frame\n"
                 "block is uncovered (default 0: the image does not change by a bit)",
                 [&](const std::string& v) { opts.tolerance = parseReal("--tolerance", v, 0.0, 1.0); }));
    add(cl.value("--layers", "N|adaptive", "depth layers between occlusion tables (default adaptive)",
                 [&](const std::string& v) { opts.layers = v == "adaptive" ? 0 : int(parseInt("--layers", v, 1, 1024)); }));
    add(cl.flag("--preview",
                "quick look: half resolution and at most 4 samples per pixel\n"
                "(options given explicitly win)",
                &req.preview));
    add(cl.value("--dof-preview", "N",
                 "DepthOfField as N pinhole depth layers blurred by their circles of\n"
                 "confusion and composited (quick; lens samples by default)",
                 [&](const std::string& v) { opts.dofPreviewLayers = int(parseInt("--dof-preview", v, 1, 256)); }));
    if (keep("-o"))
        add(cl.value("-o,--output", "PATTERN",
                     "output files, #### = frame number (e.g. out/shot.####.exr);\n"
                     "default: the scene's Display, else SCENE-NAME.####.exr",
                     &req.outPattern));
    if (keep("--stats")) add(cl.value("--stats", "FILE", "write render statistics as JSON", &req.statsPath));
    if (keep("--threads"))
        add(cl.value("--threads", "N", "worker threads (default: every core); images do not depend on it",
                     [&](const std::string& v) { opts.threads = int(parseInt("--threads", v, 0, 1024)); }));
    if (keep("--seed"))
        add(cl.value("--seed", "N", "sample pattern seed (default 0)",
                     [&](const std::string& v) { opts.seed = uint64_t(parseInt("--seed", v, 0, 0x7fffffffL)); }));
    add(cl.value("--bucket", "N", "bucket tile size in pixels (default 64); images do not depend on it",
                 [&](const std::string& v) { opts.bucketSize = int(parseInt("--bucket", v, 4, 1024)); }));
    add(cl.value("--simd", "NAME",
                 "the widest instruction set the SIMD kernels use (sampling, shader\n"
                 "noise): AVX512, AVX2, SSE4, SSSE3 ... (default: the best this CPU\n"
                 "runs; --stats says which ran); images do not depend on it",
                 [&](const std::string& v) {
                     req.simd = v;
                     std::string error;
                     if (!simdNameKnown(v, &error)) throw UsageError("--simd: " + error);
                 }));
    add(cl.value("--frame-block", "N", "frames rendered together (default 64; memory grows with it)",
                 [&](const std::string& v) { opts.maxFrameBlock = int(parseInt("--frame-block", v, 1, 100000)); }));
    add(cl.value("--max-memory", "SIZE",
                 "memory budget, e.g. 8G or 512M (default: 3/4 of the machine's);\n"
                 "frame blocks and workers shrink to fit it, and a render that\n"
                 "cannot fit one frame at a time is refused (exit 2)",
                 [&](const std::string& v) {
                     if (!parseByteSize(v, &opts.maxMemoryBytes))
                         throw UsageError("--max-memory expects a size such as 512M, 8G or 1.5GiB, not '" + v + "'");
                 }));
    add(cl.value("--grid-cache", "SIZE",
                 "room for grids shared between buckets (default 128M; less when\n"
                 "the memory budget is short; 0: each bucket dices its own);\n"
                 "images do not depend on it",
                 [&](const std::string& v) {
                     if (v == "0") opts.gridCacheBytes = 0;
                     else if (!parseByteSize(v, &opts.gridCacheBytes))
                         throw UsageError("--grid-cache expects a size such as 128M or 1G, or 0 (off), not '" + v + "'");
                 }));
    if (keep("--resume"))
        add(cl.flag("--resume",
                    "skip frames whose files are already complete (read back and\n"
                    "checked), render the rest",
                    &req.resume));
    add(cl.values("--option", "'REQUEST'",
                  "a RIB request read before the scene, as a default the scene may\n"
                  "override (Aqsis's -option), e.g. --option 'Option \"searchpath\"\n"
                  "\"shader\" [\"/studio/shaders:&\"]'; any number, read in order",
                  &req.ribOptions));
    add(cl.flag("--safe",
                "for scenes from others (docs/SCENE-FORMAT.md, \"What a scene can do\"):\n"
                "no Procedural \"RunProgram\", no \"DynamicLoad\" of a plug-in (the built-in\n"
                "generators stay), and every file the scene asks to write (Display,\n"
                "MakeTexture ...) only inside -o's folder, else the current one, named\n"
                "without an absolute path or \"..\"; refused with exit 2 at file:line",
                &req.safe));
    add(cl.value("--safe-dir", "DIR", "--safe, with DIR as the folder the scene may write in",
                 [&](const std::string& v) {
                     req.safe = true;
                     req.safeDir = v;
                     if (v.empty()) throw UsageError("--safe-dir needs a folder");
                 }));
    add(cl.flag("-q,--quiet",
                "no progress (a bar on a terminal, else a line per 10%), no summary,\n"
                "no warnings on stderr",
                &req.quiet));
    add(cl.flag("--strict",
                "what PRMan and Aqsis warn about and render without (an unknown\n"
                "request, one in the wrong block, a parameter a shader does not\n"
                "have, an option or attribute that changes another renderer's\n"
                "picture, an unknown Blobby opcode, an empty primitive) is an error\n"
                "naming file:line (exit 2), not a warning",
                &req.strict));
    if (!group.empty())
        for (CLI::Option* o : added) o->group(group);
}

RenderRequest newRenderRequest() {
    RenderRequest req;
#ifdef STREYES_JEMALLOC
    // What procedurals expand into goes as soon as no bucket left can reach it, not only under
    // memory pressure: under jemalloc freeing costs no time (glibc's malloc took 4-7% more), and
    // the forests peak at a third to three fifths less memory (docs/ARCHITECTURE.md, Procedurals).
    req.opts.freeExpansions = RenderOptions::FreeExpansions::Always;
#endif
    return req;
}

bool parseRenderArgs(const std::vector<std::string>& args, RenderRequest* req) {
    *req = newRenderRequest();
    CommandLine cl("render", kRenderSynopsis, kRenderDescription);
    std::vector<std::string> scenes;
    cl.positionals("scene", "the scene: a RIB file, or a #### pattern of frame files", &scenes)->type_name("SCENE");
    addRenderOptions(cl, *req, {}, "");
    cl.app().footer(kRenderFooter);
    if (!cl.parse(args)) return false;
    if (scenes.size() > 1) throw UsageError("more than one scene given ('" + scenes[0] + "' and '" + scenes[1] + "')");
    if (!scenes.empty()) req->scenePath = scenes[0];
    return true;
}

}  // namespace streyes::cli
