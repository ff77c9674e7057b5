// Options: the camera (Format, Projection, ScreenWindow, FrameAspectRatio, Clipping), the exposure
// (Shutter), sampling and filtering (PixelSamples, PixelFilter), output (Display) and Option.
// Valid only before WorldBegin.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "scene/rib_requests.h"

namespace streyes {

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
    static const char* kFilters[] = {"box", "triangle", "gaussian", "catmull-rom", "sinc", "mitchell", "disk"};
    if (std::find(std::begin(kFilters), std::end(kFilters), type) == std::end(kFilters)) {
        reader.log().warnOnce("pixelfilter:" + type, args.loc(),
                              "pixel filter \"" + type +
                                  "\" is not supported (box, triangle, gaussian, catmull-rom, sinc, mitchell, disk): "
                                  "using gaussian 2 2");
        settings.filter = FilterDesc{};
        return;
    }
    settings.filter = FilterDesc{type, w[0], w[1]};
}

// A name starting with '+' adds a display; any other name replaces the displays given so far.
void display(RibParser& reader, RibArgs& args) {
    RenderSettings& settings = reader.scene().settings;
    const RibValue* nameValue = args.peek();
    std::string name = args.string("name");
    std::string type = args.string("type");
    const RibValue* modeValue = args.peek();
    std::string mode = args.string("mode");
    args.skipRest();  // display parameters (compression, quantization, ...) are not used
    if (mode != "rgb" && mode != "rgba" && mode != "rgbaz")
        args.fail(*modeValue, "display mode \"" + mode + "\" is not supported: use rgb, rgba or rgbaz");
    bool additional = !name.empty() && name[0] == '+';
    if (additional) name.erase(0, 1);
    if (name.empty()) args.fail(*nameValue, "the display name is empty");
    if (!additional) settings.displays.clear();
    settings.displays.push_back(DisplayDesc{name, type, mode, args.loc()});
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

void shadingOption(RibParser& reader, RibArgs& args) {
    ParamList params = reader.readParams(args);
    if (const Param* p = params.find("builtin")) {
        const std::string v = params.getString("builtin", "on");
        if (v != "on" && v != "off") throw InputError(p->loc, "Option \"shading\": builtin is \"on\" or \"off\"");
        reader.scene().settings.builtinShading = v == "on";
    }
    reader.warnUnusedParams(params, {"builtin"}, "Option \"shading\"");
}

void option(RibParser& reader, RibArgs& args) {
    RenderSettings& settings = reader.scene().settings;
    std::string category = args.string("option name");
    if (category == "searchpath") {
        searchPathOption(reader, args);
        return;
    }
    if (category == "shading") {
        shadingOption(reader, args);
        return;
    }
    if (category != "streyes") {
        reader.log().warnOnce("option:" + category, args.loc(), "Option \"" + category + "\" is not supported: ignored");
        args.skipRest();
        return;
    }
    ParamList params = reader.readParams(args);
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

}  // namespace

void addOptionRequests(RibRequestTable& table) {
    const RibPhase options = RibPhase::Options;
    table.add("Format", {format, "Format xres yres pixelaspect", options});
    table.add("Projection",
              {projection, "Projection \"perspective\" \"fov\" degrees | Projection \"orthographic\"", options});
    table.add("ScreenWindow", {screenWindow, "ScreenWindow left right bottom top", options});
    table.add("FrameAspectRatio", {frameAspectRatio, "FrameAspectRatio ratio", options});
    table.add("Clipping", {clipping, "Clipping near far", options});
    table.add("Shutter", {shutter, "Shutter open close", options});
    table.add("PixelSamples", {pixelSamples, "PixelSamples xsamples ysamples", options});
    table.add("PixelFilter", {pixelFilter, "PixelFilter \"gaussian\" xwidth ywidth", options});
    table.add("Display", {display, "Display \"name\" \"type\" \"mode\"", options});
    table.add("Option", {option, "Option \"streyes\" \"int frames\" [first last]", options});
}

}  // namespace streyes
