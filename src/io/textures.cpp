#include "streyes/textures.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "io/bake_file.h"
#include "io/exr_file.h"
#include "io/image_library.h"
#include "shade/vm/texture_source.h"

namespace streyes {

std::shared_ptr<sl::TextureSource> openImageTextures(const std::vector<std::string>& searchPath, Log& log) {
    const ImageLibrary& library = imageLibrary();
    // Lookups warn from any thread: Log is thread-safe, and the key keeps it to once a map.
    TextureWarning warn = [&log](const std::string& key, const std::string& message) { log.warnOnce(key, {}, message); };
    return std::shared_ptr<sl::TextureSource>(library.makeTextureSource(searchPath, std::move(warn)));
}

namespace {

const char* requestName(const MakeTextureDesc& d) {
    if (!d.cubeFaces.empty()) return "MakeCubeFaceEnvironment";
    return d.latLongEnvironment ? "MakeLatLongEnvironment" : "MakeTexture";
}

}  // namespace

void makeSceneTextures(const Scene& scene, std::vector<std::string>* done) {
    for (const MakeTextureDesc& d : scene.settings.makeTextures) {
        if (done && std::find(done->begin(), done->end(), d.output) != done->end()) continue;
        const std::vector<std::string> pictures = d.cubeFaces.empty() ? std::vector<std::string>{d.input} : d.cubeFaces;
        for (const std::string& picture : pictures) {
            std::error_code ec;
            if (!std::filesystem::is_regular_file(picture, ec))
                throw InputError(d.loc, std::string(requestName(d)) + ": cannot read the picture '" + picture +
                                            "' to make '" + d.output + "' from");
        }
        std::string error;
        const ImageLibrary* library = nullptr;
        try {
            library = &imageLibrary();
        } catch (const RenderError& e) {
            throw InputError(d.loc, std::string(requestName(d)) + ": " + e.what());
        }
        MakeTextureDesc made = d;
        std::string picture;  // a bake file's picture, made beside the output and removed after
        if (!d.latLongEnvironment && d.cubeFaces.empty() && isBakeFile(d.input)) {
            std::vector<float> rgb;
            int size = 0;
            if (!bakeToPicture(d.input, &size, &rgb, &error))
                throw InputError(d.loc, "MakeTexture: bake file '" + d.input + "': " + error);
            picture = d.output + ".bake.exr";
            const std::vector<unsigned char> bytes = encodeExrChannels(size, size, {"R", "G", "B"}, rgb);
            std::ofstream out(picture, std::ios::binary | std::ios::trunc);
            out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
            if (!out) throw InputError(d.loc, "MakeTexture: cannot write '" + picture + "' (the bake file's picture)");
            made.input = picture;
        }
        const bool ok = library->makeTexture(made, &error);
        if (!picture.empty()) {
            std::error_code ec;
            std::filesystem::remove(picture, ec);
        }
        if (!ok)
            throw InputError(d.loc, std::string(requestName(d)) + (d.cubeFaces.empty() ? " '" + d.input + "'" : "") +
                                        " -> '" + d.output + "': " + error);
        if (done) done->push_back(d.output);
    }
}

}  // namespace streyes
