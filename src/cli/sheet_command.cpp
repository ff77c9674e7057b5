// `streyes sheet PATTERN -o FILE [options]`: the frames of an animation on one contact sheet.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.h"
#include "io/contact_sheet.h"
#include "streyes/image_io.h"
#include "streyes/error.h"

namespace streyes::cli {

const char* kSheetUsage = R"(usage: streyes sheet PATTERN -o FILE [options]

Lays the frames of PATTERN (e.g. out/demo.####.exr) out on one image, left to right and top to
bottom like the lines of a book, each labelled with its frame number.

options:
  -o FILE            the sheet: a .png or .jpg (8-bit sRGB; frames over black, on a white page)
  --frames A-B       frames to include (default: every frame of PATTERN on disk)
  --every N          every Nth frame, counting from the first (default 1)
  --columns N        frames per row (default: the square root of the count, rounded up)
  --cell-width W     scale each frame to W pixels wide, keeping its aspect (default: its width)
  --gap N            pixels between frames and around them (default 4)
  --no-labels        leave out the frame numbers

exit codes: 0 written, 1 the sheet could not be written, 2 bad input or usage
)";

int sheetCommand(const std::vector<std::string>& args) {
    SheetOptions opts;
    std::string pattern, out;
    bool hasRange = false;
    int first = 0, last = 0, every = 1;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
            return args[++i];
        };
        if (a == "-o" || a == "--output") out = value();
        else if (a == "--frames") {
            parseFrameRange(a, value(), &first, &last);
            hasRange = true;
        } else if (a == "--every") every = int(parseInt(a, value(), 1, 1000000));
        else if (a == "--columns") opts.columns = int(parseInt(a, value(), 1, 10000));
        else if (a == "--cell-width") opts.cellWidth = int(parseInt(a, value(), 1, 65536));
        else if (a == "--gap") opts.gap = int(parseInt(a, value(), 0, 1000));
        else if (a == "--no-labels") opts.labels = false;
        else if (a.size() > 1 && a[0] == '-') throw UsageError("unknown option '" + a + "'");
        else if (pattern.empty()) pattern = a;
        else throw UsageError("more than one frame pattern given ('" + pattern + "' and '" + a + "')");
    }
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
