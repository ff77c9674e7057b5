// Archives and procedurals: ReadArchive reads a file here and now, under the current state;
// Procedural declares geometry made later, when its bound is seen (procedural.h).
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene/rib_requests.h"
#include "scene/search_path.h"
#include "streyes/rib.h"

namespace streyes {

namespace {

// Procedural "kind" [args] [xmin xmax ymin ymax zmin zmax]: a bound now, children when the
// bound is seen (procedural.h).
void procedural(RibParser& reader, RibArgs& args) {
    ProceduralDesc p;
    const std::string kind = args.string("procedural kind");
    if (args.done()) args.fail("missing the argument array");
    const RibValue& a = args.take();
    std::vector<std::string> strings;
    if (a.isString()) strings = a.strings;
    else if (a.isStringArray()) strings = a.strings;
    else args.fail(a, "the arguments must be an array of strings, got " + describeValue(a));
    std::vector<double> b = args.numbers(6, "bound: xmin xmax ymin ymax zmin zmax");
    args.expectEnd();
    if (b[0] > b[1] || b[2] > b[3] || b[4] > b[5])
        args.fail("the bound must be xmin xmax ymin ymax zmin zmax with each min <= max");
    p.bound = Bounds3d({b[0], b[2], b[4]}, {b[1], b[3], b[5]});
    p.kind = kind;
    p.args = std::move(strings);
    if (args.loc().file) p.directory = std::filesystem::path(*args.loc().file).parent_path().string();
    p.proceduralPath = reader.state().proceduralPath;
    p.archivePath = reader.state().archivePath;
    p.objectToWorld = reader.state().ctm;
    p.attributes = reader.state().attributes;
    p.loc = args.loc();
    reader.scene().procedurals.push_back(std::move(p));
}

// An archive path: relative to the folder of the file that names it, else as given; a name
// without a folder that is in neither place, along Option "searchpath" "archive".
std::string resolveArchive(const std::string& name, const SourceLoc& loc, const std::string& searchPath) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const std::string directory = loc.file ? fs::path(*loc.file).parent_path().string() : "";
    if (fs::path(name).is_relative() && loc.file) {
        fs::path beside = fs::path(directory) / name;
        if (fs::exists(beside, ec)) return beside.string();
    }
    if (name.find('/') == std::string::npos && !fs::exists(name, ec)) {
        const std::string found = findOnSearchPath(name, searchPath, directory, {".rib"});
        if (!found.empty()) return found;
    }
    return name;
}

// ReadArchive "file": the file's requests, here and now, under the current state.
void readArchive(RibParser& reader, RibArgs& args) {
    const std::string name = args.string("archive file name");
    args.expectEnd();
    if (!sceneAccess().files) args.fail("reading other files is not allowed here");
    const std::string path = resolveArchive(name, args.loc(), reader.state().archivePath);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(args.loc(), "ReadArchive: cannot open '" + name + "': " + std::strerror(errno));
    std::ostringstream text;
    text << in.rdbuf();
    reader.parseString(text.str(), path);
}

}  // namespace

void addArchiveRequests(RibRequestTable& table) {
    table.add("Procedural", {procedural,
                             "Procedural \"DelayedReadArchive\" [\"file\"] [xmin xmax ymin ymax zmin zmax]",
                             RibPhase::World});
    table.add("ReadArchive", {readArchive, "ReadArchive \"file\""});
}

}  // namespace streyes
