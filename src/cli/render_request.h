// `streyes render`'s command line as data, shared with `streyes farm submit`, which checks a shot's
// render options with the same code its tasks will run (render_command.cpp).
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "streyes/renderer.h"
#include "streyes/scene.h"
#include "streyes/passes.h"
#include "streyes/sequence.h"
#include "streyes/error.h"

namespace streyes::cli {

struct RenderRequest {
    RenderOptions opts;
    std::string scenePath, outPattern, statsPath;
    bool quiet = false, resume = false, preview = false;
    bool strict = false;  // --strict: what the peers warn about and render without is an error (exit 2)
    std::string simd;  // --simd: the kernels' instruction set cap, applied on the machine that renders
    // --safe (or --safe-dir DIR): no programs or plug-ins, and the files the scene asks to write
    // only inside DIR (default: -o's folder, else the current folder).
    bool safe = false;
    std::string safeDir;
    RibDefaults ribOptions;  // --option 'RIB request' (any number): read before the scene, which may override them
};

class CommandLine;

// A request with the command's defaults (before any option).
RenderRequest newRenderRequest();
// Parses `streyes render` arguments (without the command word) into `req`; UsageError on bad
// ones. False when --help was asked for (and printed).
bool parseRenderArgs(const std::vector<std::string>& args, RenderRequest* req);
// Registers render's options on `cl`, filling `req` as they are parsed, but those named in
// `leaveOut` ("--frames", "-o" ...: the caller has its own); in the help's `group` when given
// (render_options.cpp).
void addRenderOptions(CommandLine& cl, RenderRequest& req, const std::set<std::string>& leaveOut,
                      const std::string& group);
// --preview's half resolution and samples, from the scene's (options given explicitly win).
void applyPreview(RenderRequest& req, const Scene& scene);
// What the scene may reach (streyes/scene_access.h): everything, or --safe's limits, its write
// folder made absolute (InputError when --safe-dir is not a folder).
SceneAccess sceneAccessFor(const RenderRequest& req);

// An output: a #### pattern and its channels ("rgbaz", "rgba", "rgb").
struct Output {
    std::string pattern, mode;
    Quantize quantize{};  // of a file that is not EXR (streyes/quantize.h); floats unless a Display says
};
// Where frames go: -o, else the scene's file displays, else SCENE-NAME.####.exr.
std::vector<Output> chooseOutputs(const Scene& scene, const std::string& oPattern, const std::string& scenePath,
                                  int frames, Log& log);
// A frame sequence's outputs, frame by frame: -o for all, else each frame's own file displays (a
// name without #### that several frames give gets one), else SCENE-NAME.####.exr.
// `only`: the frames to give outputs (a pass's; the others of first..last are another pass's).
std::map<int, std::vector<Output>> sequenceOutputs(const Sequence& seq, const std::string& oPattern,
                                                   const std::string& scenePath, int first, int last, Log& log,
                                                   const std::set<int>* only = nullptr);

}  // namespace streyes::cli
