// MakeTexture and MakeLatLongEnvironment: recorded in RenderSettings::makeTextures, made before
// the render by the io stage (streyes/textures.h): the scene stage reads no images. A missing
// input is an error here, at the request's line, before anything is made or rendered.
#include <filesystem>

#include "scene/rib_requests.h"

namespace streyes {

namespace {

// A relative name is the folder's of the RIB file that gives the request.
std::string besideFile(const RibArgs& args, const std::string& name) {
    namespace fs = std::filesystem;
    if (name.empty() || fs::path(name).is_absolute() || !args.loc().file) return name;
    const fs::path dir = fs::path(*args.loc().file).parent_path();
    return dir.empty() ? name : (dir / name).string();
}

void checkWrap(RibArgs& args, const RibValue& at, const std::string& wrap) {
    if (wrap != "black" && wrap != "clamp" && wrap != "periodic")
        args.fail(at, "wrap mode must be \"black\", \"clamp\" or \"periodic\", not \"" + wrap + "\"");
}

void readFiles(RibArgs& args, MakeTextureDesc& d) {
    const RibValue* in = args.peek();
    d.input = besideFile(args, args.string("picture name"));
    d.output = besideFile(args, args.string("texture name"));
    std::error_code ec;
    if (!std::filesystem::is_regular_file(d.input, ec))
        args.fail(*in, "cannot read the picture '" + d.input + "' to make '" + d.output + "' from");
    if (d.output.empty()) args.fail("the texture name is empty");
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
