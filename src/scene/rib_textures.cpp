// MakeTexture, MakeLatLongEnvironment, MakeCubeFaceEnvironment and MakeShadow: recorded in
// RenderSettings::makeTextures and makeShadows, made by the io stage (streyes/textures.h) when the
// frames before them are done: the scene stage reads no images. A missing input is an error at the
// request's line when it is made (a frame of the same input may write it).
#include <cmath>
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

// The picture may be one a frame of the same input writes: whether it exists is checked when the
// map is made (streyes/textures.h), after the frames before it are rendered.
void readFiles(RibParser& reader, RibArgs& args, MakeTextureDesc& d) {
    d.input = besideFile(args, args.string("picture name"));
    const std::string output = args.string("texture name");
    d.output = besideFile(args, output);
    if (d.input.empty()) args.fail("the picture name is empty");
    if (d.output.empty()) args.fail("the texture name is empty");
    checkSceneWrite(args.name(), output, args.loc(), fileFolder(args));  // --safe: inside its folder
    d.serial = reader.nextMakeSerial();
    d.afterWorld = reader.afterWorld();
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
    readFiles(reader, args, d);
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
    readFiles(reader, args, d);
    d.swrap = "periodic";
    d.twrap = "clamp";
    readFilter(reader, args, d);
    reader.scene().settings.makeTextures.push_back(std::move(d));
}

// MakeCubeFaceEnvironment "px" "nx" "py" "ny" "pz" "nz" "texture" fov "filter" swidth twidth: six
// perspective views from the cube's centre, rendered with field of view `fov` (90: the faces meet
// edge to edge; more: they overlap, as PRMan's users render them to hide the seams).
void makeCubeFaceEnvironment(RibParser& reader, RibArgs& args) {
    MakeTextureDesc d;
    d.loc = args.loc();
    d.latLongEnvironment = true;  // what it makes (io/oiio_cube_faces.cpp)
    static const char* const kFaces[6] = {"+x face", "-x face", "+y face", "-y face", "+z face", "-z face"};
    for (const char* face : kFaces) {
        const std::string name = args.string(face);
        if (name.empty()) args.fail(std::string("the ") + face + " picture name is empty");
        d.cubeFaces.push_back(besideFile(args, name));
    }
    d.input = d.cubeFaces.front();
    const std::string output = args.string("texture name");
    d.output = besideFile(args, output);
    if (d.output.empty()) args.fail("the texture name is empty");
    checkSceneWrite(args.name(), output, args.loc(), fileFolder(args));  // --safe: inside its folder
    d.serial = reader.nextMakeSerial();
    d.afterWorld = reader.afterWorld();
    const RibValue* at = args.peek();
    d.cubeFov = args.number("fov");
    if (!std::isfinite(d.cubeFov) || d.cubeFov <= 0 || d.cubeFov >= 180)
        args.fail(*at, "the field of view of the faces must be more than 0 and less than 180 degrees (90: faces that "
                       "meet edge to edge), not " + formatNumber(d.cubeFov));
    if (d.cubeFov < 90)
        reader.log().warnOnce("cubeface-fov", args.loc(),
                              "MakeCubeFaceEnvironment: faces of field of view " + formatNumber(d.cubeFov) +
                                  " degrees (under 90) leave gaps between them: directions there take the nearest "
                                  "edge of their face");
    d.swrap = "periodic";
    d.twrap = "clamp";
    readFilter(reader, args, d);
    reader.scene().settings.makeTextures.push_back(std::move(d));
}

// MakeShadow "picture" "shadow map" [params]: the picture is a depth map (Display "zfile"), of
// this input's frames or on disk, checked when it is made.
void makeShadow(RibParser& reader, RibArgs& args) {
    MakeShadowDesc d;
    d.loc = args.loc();
    // Names as written: the frames that write depth maps and the shaders that read them name them
    // so (relative names are the working folder's, as Display names are; a file on disk is looked
    // for beside the RIB file too).
    d.input = args.string("picture name");
    d.output = args.string("shadow map name");
    if (d.input.empty()) args.fail("the picture name is empty");
    if (d.output.empty()) args.fail("the shadow map name is empty");
    checkSceneWrite(args.name(), d.output, args.loc());  // --safe: inside its folder
    // Parameters ("compression", ...) are not used.
    const ParamList params = reader.readParams(args);
    reader.warnUnusedParams(params, {}, args.name());
    d.serial = reader.nextMakeSerial();
    d.afterWorld = reader.afterWorld();
    reader.scene().settings.makeShadows.push_back(std::move(d));
}

}  // namespace

void addTextureRequests(RibRequestTable& table) {
    table.add("MakeTexture",
              {makeTexture, "MakeTexture \"picture\" \"texture\" \"swrap\" \"twrap\" \"filter\" swidth twidth"});
    table.add("MakeLatLongEnvironment",
              {makeLatLongEnvironment, "MakeLatLongEnvironment \"picture\" \"texture\" \"filter\" swidth twidth"});
    table.add("MakeCubeFaceEnvironment",
              {makeCubeFaceEnvironment, "MakeCubeFaceEnvironment \"px\" \"nx\" \"py\" \"ny\" \"pz\" \"nz\" \"texture\" "
                                        "fov \"filter\" swidth twidth"});
    table.add("MakeShadow", {makeShadow, "MakeShadow \"picture\" \"shadow map\""});
}

}  // namespace streyes
