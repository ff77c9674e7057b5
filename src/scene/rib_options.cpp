// Options: the camera (Format, Projection, ScreenWindow, FrameAspectRatio, Clipping, DepthOfField), the exposure
// (Shutter), sampling and filtering (PixelSamples, PixelFilter), output (Display) and Option.
// Valid only before WorldBegin.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "scene/rib_categories.h"
#include "scene/rib_requests.h"
#include "util/aov.h"

namespace streyes {

Quantize RenderSettings::quantizeOf(const std::string& mode) const {
    const bool depth = mode == "z";
    auto it = quantize.find(mode);
    if (it == quantize.end()) it = quantize.find(depth ? "z" : "rgba");
    return it != quantize.end() ? it->second : depth ? kDepthQuantize : kColorQuantize;
}

namespace {

void format(RibParser& reader, RibArgs& args) {
    CameraDesc& camera = reader.scene().camera;
    const RibValue* xv = args.peek();
    int xres = args.integer("xres");
    const RibValue* yv = args.peek();
    int yres = args.integer("yres");
    const RibValue* av = args.peek();
    double aspect = args.done() ? 1.0 : args.number("pixelaspect");
    args.expectEnd();
    constexpr int kMaxRes = 65536;
    if (xres < 1 || xres > kMaxRes)
        args.fail(*xv, "xres must be between 1 and 65536, got " + std::to_string(xres));
    if (yres < 1 || yres > kMaxRes)
        args.fail(*yv, "yres must be between 1 and 65536, got " + std::to_string(yres));
    if (!(aspect > 0)) args.fail(*av, "pixelaspect must be positive, got " + formatNumber(aspect));
    camera.xres = xres;
    camera.yres = yres;
    camera.pixelAspect = aspect;
}

// Projection also makes the current coordinate system the camera's: the CTM restarts at identity.
void projection(RibParser& reader, RibArgs& args) {
    CameraDesc& camera = reader.scene().camera;
    RibState& s = reader.state();
    const RibValue* nameValue = args.peek();
    std::string name = args.string("projection name");
    if (name != "perspective" && name != "orthographic")
        args.fail(*nameValue,
                  "projection \"" + name + "\" is not supported: use \"perspective\" or \"orthographic\"");
    ParamList params = reader.readParams(args);
    if (name == "perspective") {
        double fov = params.getFloat("fov", 90.0);
        if (!(fov > 0 && fov < 180))
            throw InputError(params.find("fov")->loc,
                             "Projection: fov must be between 0 and 180 degrees, got " + formatNumber(fov));
        camera.projection = ProjectionKind::Perspective;
        camera.fov = fov;
        reader.warnUnusedParams(params, {"fov"}, "Projection \"perspective\"");
    } else {
        camera.projection = ProjectionKind::Orthographic;
        reader.warnUnusedParams(params, {}, "Projection \"orthographic\"");
    }
    if (!s.ctm.isStatic() || s.ctm.keys()[0] != Matrix4::identity())
        reader.log().warnOnce("projection:ctm", args.loc(),
                              "transforms before Projection are ignored: put camera transforms after Projection");
    s.ctm = MotionTransform();
}

void screenWindow(RibParser& reader, RibArgs& args) {
    CameraDesc& camera = reader.scene().camera;
    std::vector<double> w = args.numbers(4, "left right bottom top");
    args.expectEnd();
    if (w[0] == w[1] || w[2] == w[3]) args.fail("the window is empty (left = right or bottom = top)");
    std::copy(w.begin(), w.end(), camera.screenWindow);
    camera.hasScreenWindow = true;
}

void frameAspectRatio(RibParser& reader, RibArgs& args) {
    double ratio = args.number("ratio");
    args.expectEnd();
    if (!(ratio > 0)) args.fail("the ratio must be positive, got " + formatNumber(ratio));
    reader.scene().camera.frameAspect = ratio;
}

void clipping(RibParser& reader, RibArgs& args) {
    CameraDesc& camera = reader.scene().camera;
    std::vector<double> c = args.numbers(2, "near far");
    args.expectEnd();
    if (!(c[0] > 0)) args.fail("near must be positive, got " + formatNumber(c[0]));
    if (!(c[1] > c[0]))
        args.fail("far must be greater than near, got near " + formatNumber(c[0]) + " and far " +
                  formatNumber(c[1]));
    camera.nearClip = c[0];
    camera.farClip = c[1];
}

// DepthOfField fstop focallength focaldistance; with no arguments, or an fstop of RI_INFINITY
// (RIB writers give 1e38: any fstop from 1e30 up), a pinhole camera.
void depthOfField(RibParser& reader, RibArgs& args) {
    CameraDesc& camera = reader.scene().camera;
    camera.depthOfFieldLoc = args.loc();
    if (args.done()) {
        camera.fstop = std::numeric_limits<double>::infinity();
        return;
    }
    const RibValue* fv = args.peek();
    const double fstop = args.number("fstop");
    const RibValue* lv = args.peek();
    const double focalLength = args.number("focallength");
    const RibValue* dv = args.peek();
    const double focalDistance = args.number("focaldistance");
    args.expectEnd();
    if (!(fstop > 0)) args.fail(*fv, "fstop must be positive, got " + formatNumber(fstop));
    if (!(focalLength > 0)) args.fail(*lv, "focallength must be positive, got " + formatNumber(focalLength));
    if (!(focalDistance > 0)) args.fail(*dv, "focaldistance must be positive, got " + formatNumber(focalDistance));
    constexpr double kInfiniteFstop = 1e30;
    camera.fstop = fstop >= kInfiniteFstop ? std::numeric_limits<double>::infinity() : fstop;
    camera.focalLength = focalLength;
    camera.focalDistance = focalDistance;
}

void shutter(RibParser& reader, RibArgs& args) {
    RenderSettings& settings = reader.scene().settings;
    std::vector<double> s = args.numbers(2, "open close");
    args.expectEnd();
    if (s[1] < s[0])
        args.fail("close must not come before open, got open " + formatNumber(s[0]) + " and close " +
                  formatNumber(s[1]));
    settings.shutterOpen = s[0];
    settings.shutterClose = s[1];
}

void pixelSamples(RibParser& reader, RibArgs& args) {
    RenderSettings& settings = reader.scene().settings;
    std::vector<double> s = args.numbers(2, "xsamples ysamples");
    args.expectEnd();
    constexpr int kMaxSamples = 64;
    for (double v : s) {
        if (!(v >= 1)) args.fail("samples must be at least 1, got " + formatNumber(v));
        if (v > kMaxSamples) args.fail("at most 64 samples per axis are supported, got " + formatNumber(v));
    }
    settings.pixelSamplesX = int(std::ceil(s[0]));
    settings.pixelSamplesY = int(std::ceil(s[1]));
}

void pixelFilter(RibParser& reader, RibArgs& args) {
    RenderSettings& settings = reader.scene().settings;
    std::string type = args.string("filter name");
    std::vector<double> w = args.numbers(2, "xwidth ywidth");
    args.expectEnd();
    if (!(w[0] > 0 && w[1] > 0))
        args.fail("filter widths must be positive, got " + formatNumber(w[0]) + " " + formatNumber(w[1]));
    // The resolver keeps 64 taps a side, and each bucket renders a guard band of half the width.
    constexpr double kMaxFilterWidth = 32;
    if (w[0] > kMaxFilterWidth || w[1] > kMaxFilterWidth)
        args.fail("filter widths must be at most 32 pixels, got " + formatNumber(w[0]) + " " + formatNumber(w[1]));
    // PRMan's "separable-" names are the separable forms these filters already are.
    if (type.rfind("separable-", 0) == 0) type = type.substr(10);
    if (type == "catmullrom") type = "catmull-rom";
    if (type == "blackmanharris") type = "blackman-harris";
    static const char* kFilters[] = {"box",  "triangle", "gaussian",       "catmull-rom",
                                     "sinc", "mitchell", "blackman-harris", "disk"};
    if (std::find(std::begin(kFilters), std::end(kFilters), type) == std::end(kFilters)) {
        reader.log().warnOnce("pixelfilter:" + type, args.loc(),
                              "pixel filter \"" + type +
                                  "\" is not supported (box, triangle, gaussian, catmull-rom, sinc, mitchell, "
                                  "blackman-harris, disk): "
                                  "using gaussian 2 2");
        settings.filter = FilterDesc{};
        return;
    }
    settings.filter = FilterDesc{type, w[0], w[1]};
}

// A name starting with '+' adds a display; any other name replaces the displays given so far.
void checkQuantize(const SourceLoc& loc, const std::string& what, const Quantize& q) {
    for (double x : {q.zero, q.one, q.min, q.max, q.dither})
        if (!std::isfinite(x)) throw InputError(loc, what + ": every value must be a finite number");
    if (q.one < 0) throw InputError(loc, what + ": one must be at least 0 (0 writes floats), got " + formatNumber(q.one));
    if (q.dither < 0)
        throw InputError(loc, what + ": the dither amplitude must be at least 0, got " + formatNumber(q.dither));
    if (q.min > q.max)
        throw InputError(loc, what + ": min " + formatNumber(q.min) + " is above max " + formatNumber(q.max));
}

void display(RibParser& reader, RibArgs& args) {
    RenderSettings& settings = reader.scene().settings;
    const RibValue* nameValue = args.peek();
    std::string name = args.string("name");
    std::string type = args.string("type");
    const RibValue* modeValue = args.peek();
    std::string mode = args.string("mode");
    // Display parameters: "quantize" and "dither" are read (as Aqsis and PRMan read them); the
    // display driver's own ones ("compression", ...) are not used.
    ParamList params = reader.readParams(args, true);  // a driver's parameters need no declaration
    std::vector<double> quantizeParam, ditherParam;
    if (const Param* q = params.find("quantize")) {
        if (q->nums.size() != 4) throw InputError(q->loc, "Display: \"quantize\" takes four numbers: zero one min max");
        quantizeParam = q->nums;
        checkQuantize(q->loc, "Display \"quantize\"", Quantize{q->nums[1], q->nums[2], q->nums[3], 0, q->nums[0]});
    }
    if (const Param* d = params.find("dither")) {
        if (d->nums.size() != 1 || !(d->nums[0] >= 0) || !std::isfinite(d->nums[0]))
            throw InputError(d->loc, "Display: \"dither\" takes one amplitude of at least 0");
        ditherParam = d->nums;
    }
    bool append = false;
    if (const Param* a = params.find("append")) {
        if (a->nums.size() != 1 || !std::isfinite(a->nums[0]))
            throw InputError(a->loc, "Display: \"append\" takes one number (1: add this frame's map to the file's)");
        append = a->nums[0] != 0;
    }
    // A mode that declares its variable inline, "float myval" or "varying color paint" (PRMan's
    // and Aqsis's form): declared as DisplayChannel declares it, the mode its name.
    if (mode.find(' ') != std::string::npos && mode.find(',') == std::string::npos) {
        std::vector<std::string> words;
        for (size_t a = 0; a < mode.size();) {
            const size_t b = std::min(mode.find(' ', a), mode.size());
            if (b > a) words.push_back(mode.substr(a, b - a));
            a = b + 1;
        }
        const std::string type = words.size() >= 2 ? words[words.size() - 2] : "";
        const std::string var = words.empty() ? "" : words.back();
        if (words.size() >= 2 && aovTypeWidth(type) > 0 && !findAovVariable(var) && !modeOutputs(var, nullptr).empty()) {
            bool known = false;
            for (const RenderSettings::ShaderOutput& o : settings.shaderOutputs) {
                if (o.name != var) continue;
                if (o.type != type) args.fail(*modeValue, "display mode \"" + mode + "\": " + var + " was declared a " + o.type);
                known = true;
            }
            if (!known) settings.shaderOutputs.push_back({type, var, args.loc()});
            mode = var;
        }
    }
    std::vector<std::string> declared;
    for (const RenderSettings::ShaderOutput& o : settings.shaderOutputs) declared.push_back(o.name);
    std::string why;
    if (modeOutputs(mode, &why, &declared).empty()) args.fail(*modeValue, "display mode \"" + mode + "\": " + why);
    bool additional = !name.empty() && name[0] == '+';
    if (additional) name.erase(0, 1);
    if (name.empty()) args.fail(*nameValue, "the display name is empty");
    if (!additional) settings.displays.clear();
    DisplayDesc desc;
    desc.name = name, desc.type = type, desc.mode = mode, desc.loc = args.loc();
    desc.quantizeParam = std::move(quantizeParam);
    desc.ditherParam = std::move(ditherParam);
    desc.append = append;
    settings.displays.push_back(std::move(desc));
}

// CropWindow xmin xmax ymin ymax (fractions of the frame, y from the top): only the pixels inside
// are rendered and written (ResolvedSettings::cropX0...); 0 1 0 1, what exporters write by
// default, is the whole frame.
void cropWindow(RibParser& reader, RibArgs& args) {
    std::vector<double> w;
    for (const char* what : {"xmin", "xmax", "ymin", "ymax"}) w.push_back(args.number(what));
    args.expectEnd();
    for (double x : w)
        if (!(x >= 0 && x <= 1)) args.fail("CropWindow takes fractions of the frame from 0 to 1, got " + formatNumber(x));
    if (!(w[0] < w[1]) || !(w[2] < w[3])) args.fail("CropWindow: xmin must be below xmax and ymin below ymax");
    // Kept among the options as "CropWindow" (what shaders' option("CropWindow") reads, and what
    // tells passes apart); resolveSettings turns it into pixels.
    Param p;
    p.name = "CropWindow", p.arraySize = 4, p.nums = w, p.loc = args.loc();
    std::vector<Param>& options = reader.scene().settings.options.params;
    auto same = std::find_if(options.begin(), options.end(), [](const Param& q) { return q.name == "CropWindow"; });
    if (same != options.end()) *same = std::move(p);
    else options.push_back(std::move(p));
}

// Quantize "type" one min max ditheramplitude: one, min, max and the amplitude finite, one and the
// amplitude at least 0, min <= max.
void quantize(RibParser& reader, RibArgs& args) {
    const std::string type = args.string("type");
    std::vector<double> v;
    for (const char* what : {"one", "min", "max", "ditheramplitude"}) v.push_back(args.number(what));
    args.expectEnd();
    if (type.empty()) args.fail("the quantized type is empty (\"rgba\", \"z\", or a display mode)");
    const Quantize q{v[0], v[1], v[2], v[3]};
    checkQuantize(args.loc(), "Quantize", q);
    reader.scene().settings.quantize[type] = q;
}

// Exposure gain gamma: both positive and finite.
void exposure(RibParser& reader, RibArgs& args) {
    const RibValue* gv = args.peek();
    const double gain = args.number("gain");
    const RibValue* yv = args.peek();
    const double gamma = args.number("gamma");
    args.expectEnd();
    if (!(gain >= 0) || !std::isfinite(gain)) args.fail(*gv, "gain must be a finite number >= 0, got " + formatNumber(gain));
    if (!(gamma > 0) || !std::isfinite(gamma)) args.fail(*yv, "gamma must be positive, got " + formatNumber(gamma));
    reader.scene().settings.exposureGain = gain;
    reader.scene().settings.exposureGamma = gamma;
}

// Hider "hidden" (or "stochastic", its old name) with "jitter" and "depthfilter". Another hider
// warns once and renders with the hidden one.
void hider(RibParser& reader, RibArgs& args) {
    RenderSettings& settings = reader.scene().settings;
    const std::string type = args.string("hider type");
    ParamList params = reader.readParams(args);
    if (type != "hidden" && type != "stochastic") {
        reader.log().warnOnce("hider:" + type, args.loc(),
                              "Hider \"" + type + "\" is not supported: rendering with \"hidden\"");
        return;
    }
    if (const Param* p = params.find("jitter")) {
        if (p->nums.size() != 1 || (p->nums[0] != 0 && p->nums[0] != 1))
            throw InputError(p->loc, "Hider \"hidden\": jitter is 0 or 1");
        settings.jitter = p->nums[0] != 0;
    }
    if (const Param* p = params.find("depthfilter")) {
        const std::string f = params.getString("depthfilter", "min");
        if (f == "min" || f == "max" || f == "average" || f == "midpoint") {
            settings.depthFilter = f;
        } else {
            throw InputError(p->loc, "Hider \"hidden\": depthfilter \"" + f + "\" is not min, max, average or midpoint");
        }
    }
    reader.warnUnusedParams(params, {"jitter", "depthfilter"}, "Hider \"hidden\"");
}

// Option "limits" "bucketsize" [w h] "gridsize" n: buckets are square here, so the larger side.
// The other limits tune another renderer's memory and splitting (rib_categories.cpp).
void limitsOption(RibParser& reader, const ParamList& params) {
    RenderSettings& settings = reader.scene().settings;
    if (const Param* p = params.find("bucketsize")) {
        if (p->nums.size() != 2 || !(p->nums[0] >= 1 && p->nums[1] >= 1 && p->nums[0] <= 1024 && p->nums[1] <= 1024))
            throw InputError(p->loc, "Option \"limits\": bucketsize is two sizes [w h] from 1 to 1024 pixels");
        if (p->nums[0] != p->nums[1])
            reader.log().warnOnce("limits:bucketsize", p->loc,
                                  "Option \"limits\": buckets are square here: using the larger side of bucketsize");
        settings.bucketSize = std::max(4, int(std::max(p->nums[0], p->nums[1])));
    }
    if (const Param* p = params.find("gridsize")) {
        if (p->nums.size() != 1 || !(p->nums[0] >= 1 && p->nums[0] <= 65536))
            throw InputError(p->loc, "Option \"limits\": gridsize is one count from 1 to 65536 micropolygons");
        settings.gridSize = int(p->nums[0]);
    }
}

// DisplayChannel "type name": declares an output variable a Display mode may name. Only the
// variables streyes carries (util/aov.h) can be declared, with their own type; the declaration's
// parameters (filter, quantize, ...) are not used.
void displayChannel(RibParser& reader, RibArgs& args) {
    const RibValue* declValue = args.peek();
    const std::string decl = args.string("declaration");
    if (args.remaining() > 0)
        reader.log().warnOnce("displaychannel-params", args.loc(), "DisplayChannel parameters are ignored");
    args.skipRest();
    // "[varying|vertex|uniform] type name", or a bare name.
    std::vector<std::string> words;
    for (size_t a = 0; a < decl.size();) {
        const size_t b = std::min(decl.find(' ', a), decl.size());
        if (b > a) words.push_back(decl.substr(a, b - a));
        a = b + 1;
    }
    if (words.empty()) args.fail(*declValue, "the DisplayChannel declaration is empty");
    const std::string& name = words.back();
    const AovVariable* v = findAovVariable(name);
    if (!v && (name == "z" || name == "Z" || name == "a")) return;  // the samples' own depth and alpha
    if (!v) {
        // A surface shader's output parameter: its type says how many channels it has.
        const std::string type = words.size() >= 2 ? words[words.size() - 2] : "";
        if (aovTypeWidth(type) == 0 || modeOutputs(name, nullptr).empty())
            args.fail(*declValue, "DisplayChannel \"" + decl + "\": \"" + name + "\" is not a variable streyes knows (" +
                                      aovVariableList() +
                                      ", z, a); a surface shader's output is declared with its type: "
                                      "float, color, point, vector or normal");
        RenderSettings& settings = reader.scene().settings;
        for (const RenderSettings::ShaderOutput& o : settings.shaderOutputs)
            if (o.name == name) {
                if (o.type != type) args.fail(*declValue, "DisplayChannel \"" + decl + "\": " + name + " was declared a " + o.type);
                return;
            }
        settings.shaderOutputs.push_back({type, name, args.loc()});
        return;
    }
    const std::string type = words.size() >= 2 ? words[words.size() - 2] : v->type;
    if (type != v->type)
        args.fail(*declValue, "DisplayChannel \"" + decl + "\": " + name + " is a " + v->type + ", not a " + type);
}

// Option "searchpath" "procedural" ["dir:&"] "archive" [...] "shader" [...]: the names are
// strings whatever declarations say (RenderMan declares them so). Procedural and archive paths
// and texture paths are expanded here ('@' of a texture path is the folder of the file giving
// it); the shader path is kept as written for the render's shader cache ('@' there is the
// shipped shaders). Other paths are not used.
void searchPathOption(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    RenderSettings& settings = reader.scene().settings;
    while (!args.done()) {
        const std::string name = args.string("search path name (\"procedural\", \"archive\", \"shader\" or \"texture\")");
        if (args.done()) args.fail("Option \"searchpath\" \"" + name + "\" needs a value: [\"dir1:dir2:&\"]");
        const std::string value = args.string("search path");
        if (name == "procedural" || name == "string procedural") {
            s.proceduralPath = expandSearchPath(value, s.proceduralPath);
        } else if (name == "archive" || name == "string archive") {
            s.archivePath = expandSearchPath(value, s.archivePath);
        } else if (name == "shader" || name == "string shader") {
            // '&' is the path given before (the default when none was).
            std::string v = value, before = settings.shaderSearchPath.empty() ? "@" : settings.shaderSearchPath;
            for (size_t at = v.find('&'); at != std::string::npos; at = v.find('&', at + before.size()))
                v.replace(at, 1, before);
            settings.shaderSearchPath = v;
            settings.shaderSearchPathLoc = args.loc();
        } else if (name == "texture" || name == "string texture") {
            std::string before;
            for (const std::string& f : settings.textureSearchPath) before += (before.empty() ? "" : ":") + f;
            const std::string dir = args.loc().file ? std::filesystem::path(*args.loc().file).parent_path().string() : "";
            settings.textureSearchPath = searchPathFolders(expandSearchPath(value, before.empty() ? "@" : before), dir);
        } else {
            reader.log().warnOnce("searchpath:" + name, args.loc(),
                                  "Option \"searchpath\" \"" + name + "\" is not used: ignored");
        }
    }
}

void shadingOption(RibParser& reader, const ParamList& params) {
    if (const Param* p = params.find("builtin")) {
        const std::string v = params.getString("builtin", "on");
        if (v != "on" && v != "off") throw InputError(p->loc, "Option \"shading\": builtin is \"on\" or \"off\"");
        reader.scene().settings.builtinShading = v == "on";
    }
    // specular()'s highlight: PRMan's (the default) or the RI Spec's (docs/SCENE-FORMAT.md).
    if (const Param* p = params.find("specular")) {
        const std::string v = params.getString("specular", "prman");
        if (v != "prman" && v != "rispec")
            throw InputError(p->loc, "Option \"shading\": specular is \"prman\" (exponent 8 / roughness, PRMan's and "
                                     "Aqsis's highlight) or \"rispec\" (1 / roughness, the RI Spec's), not \"" + v + "\"");
        reader.scene().settings.specularExponent = v == "prman" ? 8.0 : 1.0;
    }
    reader.warnUnusedParams(params, {"builtin", "specular"}, "Option \"shading\"");
}

// Option "shadow" "bias" b: how far behind a shadow map's depth a point must be to be in shadow
// (shade/shadow_map.h). PRMan's and Aqsis's "bias0" and "bias1" give a range over which shadow
// fades in; streyes takes one bias, their mean.
void shadowOption(RibParser& reader, const ParamList& params) {
    RenderSettings& settings = reader.scene().settings;
    auto value = [&](const char* name, double fallback) {
        const Param* p = params.find(name);
        if (!p) return fallback;
        if (p->nums.size() != 1 || !std::isfinite(p->nums[0]) || p->nums[0] < 0)
            throw InputError(p->loc, std::string("Option \"shadow\": ") + name + " is one distance >= 0");
        return p->nums[0];
    };
    const double b0 = value("bias0", -1), b1 = value("bias1", -1);
    if (b0 >= 0 || b1 >= 0) settings.shadowBias = b0 >= 0 && b1 >= 0 ? 0.5 * (b0 + b1) : std::max(b0, b1);
    settings.shadowBias = value("bias", settings.shadowBias);
    reader.warnUnusedParams(params, {"bias", "bias0", "bias1"}, "Option \"shadow\"");
}

void streyesOption(RibParser& reader, const ParamList& params) {
    RenderSettings& settings = reader.scene().settings;
    if (const Param* frames = params.find("frames")) {
        if (frames->type != ParamType::Integer || frames->nums.size() != 2)
            throw InputError(frames->loc,
                             "Option \"streyes\": frames must be two integers [first last], as in "
                             "Option \"streyes\" \"int frames\" [1 24]");
        int first = int(frames->nums[0]), last = int(frames->nums[1]);
        if (first > last)
            throw InputError(frames->loc, "Option \"streyes\": the first frame (" + std::to_string(first) +
                                              ") comes after the last (" + std::to_string(last) + ")");
        settings.hasFrames = true;
        settings.firstFrame = first;
        settings.lastFrame = last;
    }
    reader.warnUnusedParams(params, {"frames"}, "Option \"streyes\"");
}

// Every value is kept as "category:name" in RenderSettings::options (the Shading Language's
// option() reads them there); a name nobody declared takes its type from its value.
void option(RibParser& reader, RibArgs& args) {
    const std::string category = args.string("option name");
    if (category == "searchpath") {
        searchPathOption(reader, args);
        return;
    }
    const ParamList params = reader.readParams(args, true);
    keepCategoryValues(category, params, reader.scene().settings.options);
    if (category == "shading") shadingOption(reader, params);
    else if (category == "limits") limitsOption(reader, params);
    else if (category == "streyes") streyesOption(reader, params);
    else if (category == "shadow") shadowOption(reader, params);
    else reviewOption(reader, category, params, args.loc());
}

}  // namespace

void addOptionRequests(RibRequestTable& table) {
    const RibPhase options = RibPhase::Options;
    table.add("Format", {format, "Format xres yres pixelaspect", options});
    table.add("Projection",
              {projection, "Projection \"perspective\" \"fov\" degrees | Projection \"orthographic\"", options});
    table.add("ScreenWindow", {screenWindow, "ScreenWindow left right bottom top", options});
    table.add("FrameAspectRatio", {frameAspectRatio, "FrameAspectRatio ratio", options});
    table.add("Clipping", {clipping, "Clipping near far", options});
    table.add("DepthOfField", {depthOfField, "DepthOfField fstop focallength focaldistance | DepthOfField", options});
    table.add("Shutter", {shutter, "Shutter open close", options});
    table.add("PixelSamples", {pixelSamples, "PixelSamples xsamples ysamples", options});
    table.add("PixelFilter", {pixelFilter, "PixelFilter \"gaussian\" xwidth ywidth", options});
    table.add("Display", {display, "Display \"name\" \"type\" \"mode\"", options});
    table.add("CropWindow", {cropWindow, "CropWindow xmin xmax ymin ymax", options});
    table.add("Quantize", {quantize, "Quantize \"rgba\" one min max ditheramplitude", options});
    table.add("Exposure", {exposure, "Exposure gain gamma", options});
    table.add("Hider", {hider, "Hider \"hidden\" \"jitter\" [1] \"depthfilter\" \"min\"", options});
    table.add("DisplayChannel", {displayChannel, "DisplayChannel \"type name\"", options});
    table.add("Option", {option, "Option \"streyes\" \"int frames\" [first last]", options});
}

}  // namespace streyes
