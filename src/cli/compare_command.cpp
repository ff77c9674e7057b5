// `streyes compare A B [options]`: the error of B against the reference A, for two image files
// or two frame patterns, per frame and over all frames; a table or JSON; exit 1 above --fail.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "command_line.h"
#include "commands.h"
#include "streyes/compare.h"
#include "streyes/image_io.h"
#include "streyes/error.h"

namespace streyes::cli {

namespace {

struct FramePair {
    bool hasFrame = false;
    int frame = 0;
    std::string a, b;
};

// The files to compare, frame by frame for patterns.
std::vector<FramePair> pairFrames(const std::string& a, const std::string& b, bool hasRange, int first, int last) {
    if (hasFrameField(a) != hasFrameField(b))
        throw UsageError("A and B must both be frame patterns (with ####) or both single files: '" + a + "', '" + b +
                         "'");
    if (!hasFrameField(a)) {
        if (hasRange) throw UsageError("--frames needs frame patterns (with ####) for A and B");
        return {{false, 0, a, b}};
    }
    std::vector<FramePair> pairs;
    for (int f : selectFrames(a, hasRange, first, last)) {
        FramePair p{true, f, expandFramePattern(a, f), expandFramePattern(b, f)};
        for (const std::string& path : {p.a, p.b})
            if (!std::filesystem::exists(path))
                throw InputError("frame " + std::to_string(f) + ": '" + path +
                                 "' does not exist (choose the frames to compare with --frames)");
        pairs.push_back(p);
    }
    return pairs;
}

// An image named on the command line is input: an unreadable one is bad input (exit 2).
ImageData readInput(const std::string& path) {
    if (!std::filesystem::exists(path)) throw InputError("'" + path + "' does not exist");
    try {
        return readImage(path);
    } catch (const RenderError& e) {
        throw InputError(e.what());
    }
}

using Json = nlohmann::ordered_json;  // PSNR of identical images is infinite: written as null

Json nonFiniteJson(const NonFiniteCounts& n) {
    return {{"color_nan", n.colorNaN}, {"color_inf", n.colorInf}, {"z_nan", n.zNaN}, {"z_neg_inf", n.zNegInf}};
}

// The error figures, added to `o`.
void addErrors(Json& o, const ImageErrors& e) {
    o["pixels"] = e.pixels;
    o["pixels_skipped"] = e.pixelsSkipped;
    o["rmse_rgb"] = e.rmseRGB();
    o["rmse_a"] = e.rmseA();
    o["psnr"] = e.psnr();
    o["mean_abs"] = e.meanAbsRGB();
    o["max_abs"] = e.maxAbsRGB;
    o["max_abs_a"] = e.maxAbsA;
    o["share_differing"] = e.shareDiffering();
    o["share_over_threshold"] = e.shareOverThreshold();
    o["z"] = {{"compared", e.zCompared},
              {"coverage_mismatch", e.zCoverageMismatch},
              {"depth_mismatch", e.zDepthMismatch},
              {"max_rel_diff", e.zMaxRelDiff}};
    o["nonfinite"] = {{"a", nonFiniteJson(e.nonFiniteA)}, {"b", nonFiniteJson(e.nonFiniteB)}};
}

void printRow(const char* label, const ImageErrors& e) {
    const std::string z = e.zCompared ? std::to_string(e.zCoverageMismatch) + "/" + std::to_string(e.zDepthMismatch)
                                      : std::string("-");
    std::printf("%-8s %10.6f %10.6f %8.2f %10.6f %9.5f %7.3f%% %7.3f%% %12s %8llu\n", label, e.rmseRGB(), e.rmseA(),
                e.psnr(), e.meanAbsRGB(), e.maxAbsRGB, 100 * e.shareDiffering(), 100 * e.shareOverThreshold(),
                z.c_str(), (unsigned long long)(e.nonFiniteA.total() + e.nonFiniteB.total()));
}

void warnNonFinite(const FramePair& p, const ImageErrors& e) {
    auto say = [](const std::string& path, const NonFiniteCounts& n) {
        if (n.total())
            std::fprintf(stderr,
                         "streyes compare: '%s' holds %llu NaN and %llu infinite values in R G B A, %llu NaN and "
                         "%llu -inf in Z\n",
                         path.c_str(), (unsigned long long)n.colorNaN, (unsigned long long)n.colorInf,
                         (unsigned long long)n.zNaN, (unsigned long long)n.zNegInf);
    };
    say(p.a, e.nonFiniteA);
    say(p.b, e.nonFiniteB);
}

}  // namespace

int compareCommand(const std::vector<std::string>& args) {
    CommandLine cl("compare", "usage: streyes compare A B [options]",
                   "\nMeasures the error of B against the reference A: two image files, or two frame patterns\n"
                   "(ref.####.exr test.####.exr) compared frame by frame and over all frames.");
    CompareOptions opts;
    std::vector<std::string> files;
    bool hasRange = false, hasFail = false, json = false;
    int first = 0, last = 0;
    double fail = 0;
    cl.positionals("images", "A (the reference) and B: image files, or frame patterns with ####", &files)
        ->type_name("A B");
    cl.value("--frames", "A-B",
             "frames to compare (patterns only); default: every frame of A's pattern on\n"
             "disk, each of which must exist for B too",
             [&](const std::string& v) {
                 parseFrameRange("--frames", v, &first, &last);
                 hasRange = true;
             });
    cl.value("--threshold", "X", "a pixel is \"over\" when any of R G B A differs by more than X (default 0.01)",
             [&](const std::string& v) { opts.threshold = parseReal("--threshold", v, 0, 1e30); });
    cl.value("--z-tolerance", "X", "relative depth difference that counts as a Z disagreement (default 0.001)",
             [&](const std::string& v) { opts.zTolerance = parseReal("--z-tolerance", v, 0, 1e30); });
    cl.flag("--resize",
            "resample B bilinearly to A's size first (a preview rendered at a lower\n"
            "--res); Z is then not compared",
            &opts.resize);
    cl.value("--fail", "X",
             "exit 1 when a frame's RMSE of RGB or of A exceeds X, or when any value is\n"
             "NaN or infinite (Z = +inf is background and allowed)",
             [&](const std::string& v) {
                 fail = parseReal("--fail", v, 0, 1e30);
                 hasFail = true;
             });
    cl.flag("--json", "print the figures as JSON on stdout instead of a table", &json);
    cl.app().footer(
        "figures: RMSE of RGB and of A; PSNR in dB (peak 1); mean and max absolute RGB error; share of\n"
        "pixels that differ at all and by more than the threshold; Z disagreement (surface against\n"
        "background, and depth beyond the tolerance); NaN and Inf counts in each image.\n\n"
        "exit codes: 0 compared (within --fail), 1 above --fail, 2 bad input or usage (a missing or\n"
        "unreadable file, images of different sizes or channels)");
    if (!cl.parse(args)) return 0;
    if (files.size() != 2) throw UsageError("compare needs two images or frame patterns, A (the reference) and B");

    const std::vector<FramePair> pairs = pairFrames(files[0], files[1], hasRange, first, last);
    std::vector<ImageErrors> perFrame;
    ImageErrors overall;
    std::string failure;
    for (const FramePair& p : pairs) {
        ImageErrors e = compareImages(readInput(p.a), readInput(p.b), opts, p.a, p.b);
        warnNonFinite(p, e);
        const std::string which = p.hasFrame ? "frame " + std::to_string(p.frame) : "'" + p.b + "'";
        if (hasFail && failure.empty()) {
            char buf[160];
            if (e.rmseRGB() > fail || e.rmseA() > fail)
                std::snprintf(buf, sizeof buf, "%s: RMSE of RGB %.6g, of A %.6g, above --fail %.6g", which.c_str(),
                              e.rmseRGB(), e.rmseA(), fail);
            else if (e.hasNonFinite())
                std::snprintf(buf, sizeof buf, "%s: NaN or infinite values", which.c_str());
            else
                buf[0] = '\0';
            failure = buf;
        }
        overall += e;
        perFrame.push_back(e);
    }

    if (json) {
        Json o = {{"a", files[0]},
                  {"b", files[1]},
                  {"threshold", opts.threshold},
                  {"z_tolerance", opts.zTolerance},
                  {"resized", opts.resize}};
        Json& frames = o["frames"] = Json::array();
        for (size_t i = 0; i < pairs.size(); ++i) {
            Json f = {{"frame", pairs[i].hasFrame ? Json(pairs[i].frame) : Json()}, {"a", pairs[i].a}, {"b", pairs[i].b}};
            addErrors(f, perFrame[i]);
            frames.push_back(std::move(f));
        }
        Json& all = o["overall"] = {{"frames", pairs.size()}};
        addErrors(all, overall);
        o["fail"] = {{"threshold", hasFail ? Json(fail) : Json()}, {"failed", !failure.empty()}, {"reason", failure}};
        // File names that are not UTF-8 are written with U+FFFD, not refused.
        const std::string text = o.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
        std::fputs(text.c_str(), stdout);
    } else {
        std::printf("%-8s %10s %10s %8s %10s %9s %8s %8s %12s %8s\n", "frame", "rmse_rgb", "rmse_a", "psnr_dB",
                    "mean_abs", "max_abs", "differ", "over", "z_cover/depth", "nan_inf");
        if (pairs.size() > 1 || pairs[0].hasFrame)
            for (size_t i = 0; i < pairs.size(); ++i) printRow(std::to_string(pairs[i].frame).c_str(), perFrame[i]);
        printRow("all", overall);
        std::printf("(over: a channel differs by more than %g; z: surface against background / depth beyond %g)\n",
                    opts.threshold, opts.zTolerance);
    }
    if (!failure.empty()) {
        std::fprintf(stderr, "streyes compare: FAIL: %s\n", failure.c_str());
        return 1;
    }
    return 0;
}

}  // namespace streyes::cli
