#include <cerrno>
#include <cstdlib>

#include "commands.h"
#include "streyes/image_io.h"
#include "streyes/error.h"

namespace streyes::cli {

UsageContext& usageContext() {
    static UsageContext context;
    return context;
}

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

const char* kUsage = R"(usage: streyes render SCENE.rib | SHOT.####.rib [options]   render frames (streyes render --help)
       streyes compare A B [options]        error of B against A (streyes compare --help)
       streyes sheet PATTERN -o FILE [options]   frames on a contact sheet (streyes sheet --help)
       streyes shader FILE.sl ...           check shaders and print their parameters
       streyes catrib FILE.rib ... [-o OUT] RIB as ASCII, binary or gzip (streyes catrib --help)
       streyes farm submit|status|gather ...     a shot on a Slurm cluster (streyes farm --help)
       streyes --help | --version

Renders an animation described in RIB as one spacetime scene, one EXR per frame. Each command
lists its options with --help (streyes render --help, streyes farm submit --help ...).

exit codes: 0 done, 1 the command failed, 2 bad input or usage
)";

}  // namespace streyes::cli
