#include "io/depth_map_file.h"

#include <filesystem>

#include "io/image_library.h"
#include "streyes/image_io.h"

namespace streyes {

void writeDepthMapFile(const std::string& path, const DepthMap& map, bool shadow) {
    std::vector<unsigned char> bytes;
    std::string error;
    if (!imageLibrary().encodeDepthMap(path, map, shadow, &bytes, &error))
        throw RenderError("cannot write the depth map '" + path + "': " + error);
    writeFileAtomically(path, bytes);
}

bool readDepthMapFile(const std::string& path, DepthMap* out, std::string* error) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        *error = "no such file";
        return false;
    }
    const ImageLibrary* library = nullptr;
    try {
        library = &imageLibrary();
    } catch (const RenderError& e) {
        *error = e.what();
        return false;
    }
    return library->readDepthMap(path, out, error);
}

}  // namespace streyes
