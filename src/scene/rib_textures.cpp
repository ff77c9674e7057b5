// MakeTexture and MakeLatLongEnvironment: recorded in RenderSettings::makeTextures, made before
// the render by the io stage (streyes/textures.h): the scene stage reads no images. A missing
// input is an error here, at the request's line, before anything is made or rendered.
#include <filesystem>

#include "scene/rib_requests.h"
#include "streyes/scene_access.h"

namespace streyes {

namespace {

// The folder of the RIB file that gives the request: relative names are taken from it.
std::string fileFolder(const RibArgs& args) {
    return args.loc().file ? std::filesystem::path(*args.loc().file).parent_path().string() : "";
}

std::string besideFile(const RibArgs& args, const std::string& name) {
    namespace fs = std::filesystem;
    if (name.empty() || fs::path(name).is_absolute()) return name;
    const std::string dir = fileFolder(args);
    return dir.empty() ? name : (fs::path(dir) / name).string();
}

void checkWrap(RibArgs& args, const RibValue& at, const std::string& wrap) {
    if (wrap != "black" && wrap != "clamp" && wrap != "periodic")
        args.fail(at, "wrap mode must be \"black\", \"clamp\" or \"periodic\", not \"" + wrap + "\"");
}

void readFiles(RibArgs& args, MakeTextureDesc& d) {
    const RibValue* in = args.peek();
    d.input = besideFile(args, args.string("picture name"));
    const std::string output = args.string("texture name");
    d.output = besideFile(args, output);
    if (d.output.empty()) args.fail("the texture name is empty");
    checkSceneWrite(args.name(), output, args.loc(), fileFolder(args));  // --safe: inside its folder
    std::error_code ec;
    if (!std::filesystem::is_regular_file(d.input, ec))
        args.fail(*in, "cannot read the picture '" + d.input + "' to make '" + d.output + "' from");
}

void readFilter(RibParser& reader, RibArgs& args, MakeTextureDesc& d) {
    d.filter = args.string("filter name");
    d.swidth = args.number("swidth");
    d.twidth = args.number("twidth");
    // Parameters ("fov", "compression", ...) are not used.
    const ParamList params = reader.readParams(args);
    reader.warnUnusedParams(params, {}, args.name());
}

void makeTexture(RibParser& reader, RibArgs& args) {
    MakeTextureDesc d;
    d.loc = args.loc();
    readFiles(args, d);
    const RibValue* sw = args.peek();
    d.swrap = args.string("swrap");
    checkWrap(args, *sw, d.swrap);
    const RibValue* tw = args.peek();
    d.twrap = args.string("twrap");
    checkWrap(args, *tw, d.twrap);
    readFilter(reader, args, d);
    reader.scene().settings.makeTextures.push_back(std::move(d));
}

void makeLatLongEnvironment(RibParser& reader, RibArgs& args) {
    MakeTextureDesc d;
    d.loc = args.loc();
    d.latLongEnvironment = true;
    readFiles(args, d);
    d.swrap = "periodic";
    d.twrap = "clamp";
    readFilter(reader, args, d);
    reader.scene().settings.makeTextures.push_back(std::move(d));
}

}  // namespace

void addTextureRequests(RibRequestTable& table) {
    table.add("MakeTexture",
              {makeTexture, "MakeTexture \"picture\" \"texture\" \"swrap\" \"twrap\" \"filter\" swidth twidth"});
    table.add("MakeLatLongEnvironment",
              {makeLatLongEnvironment, "MakeLatLongEnvironment \"picture\" \"texture\" \"filter\" swidth twidth"});
}

}  // namespace streyes
