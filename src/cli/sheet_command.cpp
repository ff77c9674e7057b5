// `streyes sheet PATTERN -o FILE [options]`: the frames of an animation on one contact sheet.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "command_line.h"
#include "commands.h"
#include "io/contact_sheet.h"
#include "streyes/image_io.h"
#include "streyes/error.h"

namespace streyes::cli {

int sheetCommand(const std::vector<std::string>& args) {
    CommandLine cl("sheet", "usage: streyes sheet PATTERN -o FILE [options]",
                   "\nLays the frames of PATTERN (e.g. out/demo.####.exr) out on one image, left to right and top "
                   "to\nbottom like the lines of a book, each labelled with its frame number.");
    SheetOptions opts;
    std::string out;
    std::vector<std::string> patterns;
    bool hasRange = false, noLabels = false;
    int first = 0, last = 0, every = 1;
    cl.positionals("pattern", "the frames, #### for the frame number", &patterns)->type_name("PATTERN");
    cl.value("-o,--output", "FILE", "the sheet: a .png or .jpg (8-bit sRGB; frames over black, on a white page)", &out);
    cl.value("--frames", "A-B", "frames to include (default: every frame of PATTERN on disk)", [&](const std::string& v) {
        parseFrameRange("--frames", v, &first, &last);
        hasRange = true;
    });
    cl.value("--every", "N", "every Nth frame, counting from the first (default 1)",
             [&](const std::string& v) { every = int(parseInt("--every", v, 1, 1000000)); });
    cl.value("--columns", "N", "frames per row (default: the square root of the count, rounded up)",
             [&](const std::string& v) { opts.columns = int(parseInt("--columns", v, 1, 10000)); });
    cl.value("--cell-width", "W", "scale each frame to W pixels wide, keeping its aspect (default: its width)",
             [&](const std::string& v) { opts.cellWidth = int(parseInt("--cell-width", v, 1, 65536)); });
    cl.value("--gap", "N", "pixels between frames and around them (default 4)",
             [&](const std::string& v) { opts.gap = int(parseInt("--gap", v, 0, 1000)); });
    cl.flag("--no-labels", "leave out the frame numbers", &noLabels);
    cl.app().footer("exit codes: 0 written, 1 the sheet could not be written, 2 bad input or usage");
    if (!cl.parse(args)) return 0;
    opts.labels = !noLabels;
    if (patterns.size() > 1)
        throw UsageError("more than one frame pattern given ('" + patterns[0] + "' and '" + patterns[1] + "')");
    const std::string pattern = patterns.empty() ? std::string() : patterns[0];
    if (pattern.empty()) throw UsageError("no frame pattern given");
    if (out.empty()) throw UsageError("no output given: -o sheet.png");
    if (!hasFrameField(pattern)) throw UsageError("'" + pattern + "' is not a frame pattern: use #### for the frame number");

    const std::vector<int> found = selectFrames(pattern, hasRange, first, last);
    std::vector<SheetFrame> frames;
    for (int f : found) {
        if ((f - found.front()) % every != 0) continue;
        SheetFrame sf{f, expandFramePattern(pattern, f)};
        if (!std::filesystem::exists(sf.path))
            throw InputError("frame " + std::to_string(f) + ": '" + sf.path + "' does not exist");
        frames.push_back(sf);
    }
    writeContactSheet(frames, out, opts);
    return 0;
}

}  // namespace streyes::cli
