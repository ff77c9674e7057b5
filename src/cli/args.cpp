#include <cerrno>
#include <cstdlib>

#include "commands.h"
#include "streyes/image_io.h"
#include "streyes/error.h"

namespace streyes::cli {

long parseInt(const std::string& opt, const std::string& v, long lo, long hi) {
    char* end = nullptr;
    errno = 0;
    long n = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || errno != 0 || n < lo || n > hi)
        throw UsageError(opt + " expects a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                         ", not '" + v + "'");
    return n;
}

double parseReal(const std::string& opt, const std::string& v, double lo, double hi) {
    char* end = nullptr;
    errno = 0;
    double x = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || errno != 0 || !(x >= lo && x <= hi))
        throw UsageError(opt + " expects a number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                         ", not '" + v + "'");
    return x;
}

void parseFrameRange(const std::string& opt, const std::string& v, int* first, int* last) {
    // "A-B" or "A"; A may be negative ("-3-5").
    size_t dash = v.find('-', 1);
    std::string a = v.substr(0, dash), b = dash == std::string::npos ? a : v.substr(dash + 1);
    *first = int(parseInt(opt, a, -1000000, 1000000));
    *last = int(parseInt(opt, b, -1000000, 1000000));
    if (*last < *first) throw UsageError(opt + " " + v + ": the last frame comes before the first");
}

std::vector<int> selectFrames(const std::string& pattern, bool hasRange, int first, int last) {
    std::vector<int> frames;
    if (hasRange) {
        for (int f = first; f <= last; ++f) frames.push_back(f);
    } else {
        frames = findFrames(pattern);
        if (frames.empty()) throw InputError("no frames found for '" + pattern + "'");
    }
    return frames;
}

const char* kUsage = R"(usage: streyes render SCENE.rib | SHOT.####.rib [options]
       streyes compare A B [options]        (streyes compare --help)
       streyes sheet PATTERN -o FILE [options]   (streyes sheet --help)
       streyes shader FILE.sl ...           check shaders and print their parameters
       streyes catrib FILE.rib ... [-o OUT] RIB as ASCII, binary or gzip (streyes catrib --help)
       streyes farm submit|status|gather ...     (streyes farm --help: a shot on a Slurm cluster)
       streyes --help | --version

Renders an animation described in RIB as one spacetime scene, one EXR per frame. A frame
pattern (shot.####.rib: a file per frame) or a file of FrameBegin blocks is read as a frame
sequence, each frame a complete scene (docs/SCENE-FORMAT.md, "Frame sequences").

render options:
  --frames A-B        frames to render (or a single frame A); default: the scene's
                      Option "streyes" "int frames", else frame 0; of a sequence, every
                      frame it has (a pattern: every file there is, which must be consecutive)
  --shot A-B          the whole animation these frames belong to: motion segments and procedurals'
                      level of detail are decided over it, so that a frame renders the same
                      whatever other frames are rendered with it (render farms pass it);
                      it must hold them; default: the scene's frames joined with those rendered
  --res WxH           image size in pixels; default: the scene's Format
  --samples N         samples per pixel per frame; default: the scene's PixelSamples
  --algorithm NAME    spacetime-occlusion (default): Algorithm S with occlusion culling
                      spacetime:          Algorithm S, split once per block of frames
                      frames-occlusion:   Algorithm C', Catmull per frame with occlusion culling
                      frames:             Algorithm C, Catmull per frame (the baseline)
                      raytrace:           ray tracing through one spacetime hierarchy
                                          (Glassner's; the reference for the rasterizer's error)
                      raytrace-frames:    ray tracing with a 3D hierarchy per frame
  --tolerance EPS     occlusion tolerance: drop a body when at most EPS of its pixel-frame
                      block is uncovered (default 0: the image does not change by a bit)
  --layers N|adaptive depth layers between occlusion tables (default adaptive)
  --preview           quick look: half resolution and at most 4 samples per pixel
                      (options given explicitly win)
  --dof-preview N     DepthOfField as N pinhole depth layers blurred by their circles of
                      confusion and composited (quick; lens samples by default)
  -o PATTERN          output files, #### = frame number (e.g. out/shot.####.exr);
                      default: the scene's Display, else SCENE-NAME.####.exr
  --stats FILE        write render statistics as JSON
  --threads N         worker threads (default: every core); images do not depend on it
  --seed N            sample pattern seed (default 0)
  --bucket N          bucket tile size in pixels (default 64); images do not depend on it
  --simd NAME         the widest instruction set the SIMD kernels use (sampling, shader
                      noise): AVX512, AVX2, SSE4, SSSE3 ... (default: the best this CPU
                      runs; --stats says which ran); images do not depend on it
  --frame-block N     frames rendered together (default 64; memory grows with it)
  --max-memory SIZE   memory budget, e.g. 8G or 512M (default: 3/4 of the machine's);
                      frame blocks and workers shrink to fit it, and a render that
                      cannot fit one frame at a time is refused (exit 2)
  --grid-cache SIZE   room for grids shared between buckets (default 128M; less when
                      the memory budget is short; 0: each bucket dices its own);
                      images do not depend on it
  --resume            skip frames whose files are already complete (read back and
                      checked), render the rest
  --option 'REQUEST'  a RIB request read before the scene, as a default the scene may
                      override (Aqsis's -option), e.g. --option 'Option "searchpath"
                      "shader" ["/studio/shaders:&"]'; any number, read in order
  --safe              for scenes from others (docs/SCENE-FORMAT.md, "What a scene can do"):
                      no Procedural "RunProgram", no "DynamicLoad" of a plug-in (the built-in
                      generators stay), and every file the scene asks to write (Display,
                      MakeTexture ...) only inside -o's folder, else the current one, named
                      without an absolute path or ".."; refused with exit 2 at file:line
  --safe-dir DIR      --safe, with DIR as the folder the scene may write in
  --quiet             no progress (a bar on a terminal, else a line per 10%), no summary,
                      no warnings on stderr
  --strict            what PRMan and Aqsis warn about and render without (an unknown
                      request, one in the wrong block, a parameter a shader does not
                      have, an option or attribute that changes another renderer's
                      picture, an unknown Blobby opcode, an empty primitive) is an error
                      naming file:line (exit 2), not a warning

environment: STREYES_SHADERPATH, STREYES_TEXTUREPATH, STREYES_PROCEDURALPATH: folders separated by
             ':' where shaders, texture maps and plug-ins are looked for after the scene's own
             search paths (Option "searchpath")

exit codes: 0 done, 1 render failed (e.g. an output folder missing or not writable, found
            before rendering; a full disk), 2 bad input or usage (or more memory than the budget)
)";

}  // namespace streyes::cli
