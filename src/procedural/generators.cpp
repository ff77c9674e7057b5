// The procedurals a RIB file can name: archives, helper programs and the built-in generators.
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "procedural/dynamic_load.h"
#include "procedural/forest.h"
#include "procedural/grass.h"
#include "procedural/run_program.h"
#include "procedural/procedural.h"
#include "scene/object_st.h"
#include "scene/ri_stream.h"
#include "scene/search_path.h"

namespace streyes {

namespace {

// A procedural's RIB output, parsed under its transform and attributes.
void parseFragment(const std::string& text, const std::string& name, const ExpandContext& ctx, ProceduralOutput& output) {
    Scene& out = output.scene;
    out = parseRibFragment(text, name, ctx.objectToWorld, ctx.attributes, *ctx.log, ctx.read);
    if (!out.lights.empty()) {
        ctx.log->warnOnce("procedural-lights", ctx.loc, "lights declared by a procedural are ignored");
        out.lights.clear();
    }
}

// Procedural "DelayedReadArchive" ["file.rib"]: the file's requests, when the bound is seen.
class ArchiveGenerator final : public ProceduralGenerator {
  public:
    explicit ArchiveGenerator(std::string path) : path_(std::move(path)) {}
    std::string describe() const override { return "DelayedReadArchive '" + path_ + "'"; }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        std::ifstream in(path_, std::ios::binary);
        if (!in) throw InputError(ctx.loc, "DelayedReadArchive: cannot open '" + path_ + "': " + std::strerror(errno));
        std::ostringstream text;
        text << in.rdbuf();
        parseFragment(text.str(), path_, ctx, out);
    }

  private:
    std::string path_;
};

// Procedural "RunProgram" ["program args" "datablock"]: the program's answer to the detail and
// the datablock (run_program.h).
class ProgramGenerator final : public ProceduralGenerator {
  public:
    ProgramGenerator(std::string command, std::string datablock)
        : command_(std::move(command)), datablock_(std::move(datablock)) {}
    std::string describe() const override { return "RunProgram '" + command_ + "'"; }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        const std::string rib = runProgramRequest(command_, ctx.detail, datablock_, ctx.loc);
        parseFragment(rib, "RunProgram '" + command_ + "' output", ctx, out);
    }

  private:
    std::string command_, datablock_;
};

// ObjectInstance: the object's primitives under the instance's transform (after their own) and
// its attributes, with those set inside the object's definition over them (the scene stage made
// them: ProceduralDesc::objectAttributes).
class InstanceGenerator final : public ProceduralGenerator {
  public:
    using AttributeMap = std::vector<std::pair<AttributesPtr, AttributesPtr>>;
    InstanceGenerator(std::string handle, std::shared_ptr<const Scene> object, AttributeMap attributes)
        : handle_(std::move(handle)), object_(std::move(object)), attributes_(std::move(attributes)) {}
    std::string describe() const override { return "ObjectInstance " + handle_; }
    // A copy of what the scene holds is cheap to make again: buckets expand it for themselves.
    // An object holding procedurals keeps its children (they report outgrown bounds by address).
    bool keepsChildren() const override { return !object_->procedurals.empty(); }
    void expand(const ExpandContext& ctx, ProceduralOutput& out) const override {
        Scene& s = out.scene;
        s = *object_;
        auto place = [&](auto& prims) {
            for (auto& p : prims) {
                p.objectToWorld = p.objectToWorld.then(ctx.objectToWorld);
                auto own = std::find_if(attributes_.begin(), attributes_.end(),
                                        [&](const auto& m) { return m.first == p.attributes; });
                p.attributes = own != attributes_.end() ? own->second : ctx.attributes;
            }
        };
        place(s.patches);
        place(s.procedurals);
        place(s.patchMeshes);
        place(s.subdivisionMeshes);
        place(s.quadrics);
        place(s.polygonMeshes);
        // A polygon's s and t default to its object x and y where a shader may read them: the
        // instance's shader, which the definition's primitives did not know.
        for (PolygonMeshDesc& m : s.polygonMeshes)
            if (!m.P.empty()) addObjectSt(m.P.front(), m);
        place(s.curves);
        place(s.points);
        place(s.nuPatches);
    }

  private:
    std::string handle_;
    std::shared_ptr<const Scene> object_;
    AttributeMap attributes_;
};

}  // namespace

std::shared_ptr<const ProceduralGenerator> makeProceduralGenerator(const ProceduralDesc& desc) {
    namespace fs = std::filesystem;
    const std::string& kind = desc.kind;
    const std::vector<std::string>& args = desc.args;
    const std::string& directory = desc.directory;
    const SourceLoc& loc = desc.loc;
    const SceneAccess access = sceneAccess();
    if (kind == "ObjectInstance") {
        if (!desc.object || args.size() != 1) throw InputError(loc, "ObjectInstance without its object");
        return std::make_shared<InstanceGenerator>(args[0], desc.object, desc.objectAttributes);
    }
    if (kind == "DelayedReadArchive" && !access.files)
        throw InputError(loc, "Procedural \"DelayedReadArchive\" is not allowed here (no other files are read)");
    if (kind == "RunProgram" && !access.programs)
        throw InputError(loc, access.safe ? "Procedural \"RunProgram\" is refused by --safe: it would run a program. "
                                            "Render without --safe only if you trust the scene"
                                          : "Procedural \"RunProgram\" is not allowed here (no programs are run)");
    if (kind == "DelayedReadArchive") {
        if (args.size() != 1) throw InputError(loc, "Procedural \"DelayedReadArchive\" takes one file name: [\"file.rib\"]");
        // Relative to the folder of the declaring file, else to the current folder. A missing
        // archive is reported now, where the mistake is, not when (or if) it is first seen.
        std::string path = args[0];
        std::error_code ec;
        if (fs::path(path).is_relative() && !directory.empty() && fs::exists(fs::path(directory) / path, ec))
            path = (fs::path(directory) / path).string();
        // A name without a folder found in neither place: along Option "searchpath" "archive".
        if (path.find('/') == std::string::npos && !fs::exists(path, ec)) {
            const std::string found = findOnSearchPath(path, desc.archivePath, directory, {".rib"});
            if (!found.empty()) path = found;
        }
        if (!fs::is_regular_file(path, ec))
            throw InputError(loc, "DelayedReadArchive: no archive '" + args[0] + "' (looked beside this file, in the current folder and along Option \"searchpath\" \"archive\")");
        return std::make_shared<ArchiveGenerator>(path);
    }
    if (kind == "RunProgram") {
        if (args.empty() || args.size() > 2)
            throw InputError(loc, "Procedural \"RunProgram\" takes [\"program arguments\" \"datablock\"]");
        std::vector<std::string> words = splitCommandLine(args[0]);
        if (words.empty()) throw InputError(loc, "RunProgram: no program given");
        // A relative program path is looked up beside the declaring file first.
        if (words[0].find('/') != std::string::npos && fs::path(words[0]).is_relative() && !directory.empty()) {
            std::error_code ec;
            fs::path beside = fs::path(directory) / words[0];
            if (fs::exists(beside, ec)) words[0] = beside.string();
        }
        if (findProgram(words[0]).empty())
            throw InputError(loc, "RunProgram: cannot run '" + words[0] + "': no such program (give a path, or put it on PATH)");
        std::string command;
        for (const std::string& w : words) command += (command.empty() ? "" : " ") + w;
        return std::make_shared<ProgramGenerator>(command, args.size() > 1 ? args[1] : "");
    }
    if (kind == "DynamicLoad") {
        if (args.empty() || args.size() > 2)
            throw InputError(loc, "Procedural \"DynamicLoad\" takes [\"name\" \"parameters\"]");
        const std::string block = args.size() > 1 ? args[1] : "";
        if (args[0] == "forest") return makeForestGenerator(block, loc);
        if (args[0] == "tree") return makeTreeGenerator(block, loc);
        if (args[0] == "grass") return makeGrassGenerator(block, loc);
        // A plug-in runs code, as a program does: allowed where programs are.
        if (!access.programs)
            throw InputError(loc, access.safe ? "Procedural \"DynamicLoad\" \"" + args[0] +
                                                    "\" is refused by --safe: it would load a plug-in, which runs code "
                                                    "(the built-in generators, \"forest\", \"tree\" and \"grass\", are allowed). "
                                                    "Render without --safe only if you trust the scene"
                                              : "Procedural \"DynamicLoad\" with a plug-in is not allowed here (no "
                                                "plug-ins are loaded)");
        return makePluginGenerator(desc);
    }
    if (kind == kRiFunctionKind) return makeFunctionGenerator(desc);
    throw InputError(loc, "unknown procedural '" + kind + "': use DelayedReadArchive, RunProgram or DynamicLoad");
}

}  // namespace streyes
