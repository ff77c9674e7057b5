// RiBegin and RiEnd (include/ri.h): a program's session. The calls between them go to a RIB
// stream (scene/ri_stream.h) on the thread that called RiBegin; RiEnd writes it to the file
// RiBegin named, or renders it to its Display files. They live here, not with the other Ri calls,
// because rendering to files is this stage's; a program using them links streyes::io.
#include <cstdio>
#include <fstream>
#include <memory>

#include "ri.h"
#include "streyes/textures.h"
#include "scene/ri_stream.h"
#include "streyes/image_io.h"
#include "streyes/renderer.h"
#include "streyes/rib.h"

namespace {

struct Session {
    std::unique_ptr<streyes::RiStream> stream;
    std::unique_ptr<streyes::RiStreamScope> scope;
    std::string file;  // "" renders
};
thread_local std::unique_ptr<Session> session;

// The scene the stream describes, rendered; each frame written to the scene's file displays
// ("ri.exr" when it names none). Problems are reported on standard error: RiEnd returns nothing.
void render(const std::string& rib) {
    streyes::Log log;
    log.setEcho(true);
    try {
        const streyes::Scene scene = streyes::parseRibString(rib, "RiBegin", log);
        std::vector<streyes::FrameOutput> outputs;
        for (const streyes::DisplayDesc& d : scene.settings.displays) {
            if (d.type == "openexr" || d.type == "file" || d.type == "tiff" || d.type == "exr")
                outputs.push_back({d.name, d.mode, d.quantize, {}});
            else
                log.warn(d.loc, "Display type '" + d.type + "' is not supported: '" + d.name + "' skipped");
        }
        if (outputs.empty()) outputs.push_back({"ri.exr", "rgba", {}, {}});
        streyes::makeSceneTextures(scene);
        streyes::RenderOptions options;
        options.textureSource = streyes::openImageTextures;
        streyes::Renderer renderer(scene, options, log);
        renderer.render([&](const streyes::FrameImage& frame) {
            for (const streyes::FrameOutput& o : outputs)
                streyes::writeFrame(streyes::expandFramePattern(o.path, frame.frame), frame, o.mode, o.quantize);
        });
    } catch (const streyes::InputError& e) {
        std::fprintf(stderr, "%s\n", e.report().c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "streyes: RiEnd: %s\n", e.what());
    }
}

}  // namespace

extern "C" {

RtVoid RiBegin(RtToken name) {
    if (session) {
        std::fprintf(stderr, "streyes: RiBegin inside RiBegin/RiEnd: ignored\n");
        return;
    }
    session = std::make_unique<Session>();
    session->file = name ? name : "";
    session->stream = std::make_unique<streyes::RiStream>("RiBegin");
    session->stream->encoding = streyes::pendingRibEncoding();  // Option "rib" before RiBegin
    session->scope = std::make_unique<streyes::RiStreamScope>(session->stream.get());
}

RtVoid RiEnd(void) {
    if (!session) {
        std::fprintf(stderr, "streyes: RiEnd without RiBegin: ignored\n");
        return;
    }
    std::unique_ptr<Session> s = std::move(session);
    s->scope.reset();
    streyes::RiStream& stream = *s->stream;
    if (!stream.error().empty()) {
        std::fprintf(stderr, "streyes: RiEnd: %s; nothing %s\n", stream.error().c_str(),
                     s->file.empty() ? "rendered" : "written");
        return;
    }
    const std::string rib = stream.text() + "\n";
    if (s->file.empty()) {
        render(rib);  // the stream keeps its function procedurals until the render is done
        return;
    }
    // A function cannot be written as RIB: its procedural would be unreadable.
    if (!stream.functions().empty())
        std::fprintf(stderr,
                     "streyes: RiEnd: '%s' names %zu procedural(s) of the program's own functions, which a RIB file "
                     "cannot hold: they are written as Procedural \"RiFunction\" and will not read back\n",
                     s->file.c_str(), stream.functions().size());
    // In the encoding Option "rib" asked for: ASCII as the stream has it, or binary, or gzip.
    const streyes::RibEncoding& encoding = stream.encoding;
    std::string bytes;
    try {
        bytes = encoding.binary || encoding.gzip ? streyes::encodeRib(rib, "RiBegin", encoding) : rib;
    } catch (const streyes::InputError& e) {
        std::fprintf(stderr, "%s; nothing written\n", e.report().c_str());
        return;
    }
    if (s->file == "-") {
        std::fwrite(bytes.data(), 1, bytes.size(), stdout);
        std::fflush(stdout);
    } else {
        std::ofstream out(s->file, std::ios::binary);
        out << bytes;
        if (!out.flush()) std::fprintf(stderr, "streyes: RiEnd: cannot write '%s'\n", s->file.c_str());
    }
}

}  // extern "C"
