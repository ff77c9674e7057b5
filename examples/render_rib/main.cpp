// Renders a RIB scene's frames to EXR files through the streyes library, and prints each frame's
// mean alpha (the share of the image covered) and its centre pixel as read back from the file:
// the smallest complete use of the public API.
//   render_rib SCENE.rib OUT.####.exr [--threads N]
#include <cstdio>
#include <cstdlib>
#include <string>

#include <streyes/image_io.h>
#include <streyes/renderer.h>
#include <streyes/rib.h>
#include <streyes/textures.h>

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: render_rib SCENE.rib OUT.####.exr [--threads N]\n");
        return 2;
    }
    try {
        streyes::Log log;
        log.setEcho(true);
        const streyes::Scene scene = streyes::parseRibFile(argv[1], log);
        streyes::makeSceneTextures(scene);  // its MakeTexture requests, if any
        streyes::RenderOptions options;
        options.textureSource = streyes::openImageTextures;  // texture() and environment() in shaders
        if (argc == 5 && std::string(argv[3]) == "--threads") options.threads = std::atoi(argv[4]);
        streyes::Renderer renderer(scene, options, log);
        const streyes::RenderStats stats = renderer.render([&](const streyes::FrameImage& frame) {
            double alpha = 0;
            for (size_t i = 3; i < frame.rgba.size(); i += 4) alpha += frame.rgba[i];
            std::printf("frame %d: %dx%d mean alpha %.6f\n", frame.frame, frame.width, frame.height,
                        alpha / double(size_t(frame.width) * size_t(frame.height)));
            const std::string path = streyes::expandFramePattern(argv[2], frame.frame);
            streyes::writeFrame(path, frame, "rgbaz");
            const streyes::ImageData file = streyes::readImage(path);
            std::printf("%s: centre", path.c_str());
            for (size_t c = 0; c < file.channels.size(); ++c)
                std::printf(" %s=%g", file.channels[c].c_str(), file.at(file.width / 2, file.height / 2, int(c)));
            std::printf("\n");
        });
        std::printf("%llu micropolygons, %llu sample tests\n", (unsigned long long)stats.counters.micropolygons,
                    (unsigned long long)stats.counters.sampleTests);
        return 0;
    } catch (const streyes::InputError& e) {
        std::fprintf(stderr, "%s\n", e.report().c_str());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "render_rib: %s\n", e.what());
        return 1;
    }
}
