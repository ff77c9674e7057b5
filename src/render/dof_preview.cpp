#include "render/dof_preview.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "bodies/render_scene.h"

namespace streyes {

std::vector<double> dofLayerDepths(double zmin, double zmax, int layers) {
    std::vector<double> z;
    const double w0 = 1 / zmin, w1 = 1 / zmax;
    for (int i = 0; i <= layers; ++i) z.push_back(1 / (w0 + (w1 - w0) * i / layers));
    z.front() = zmin, z.back() = zmax;
    return z;
}

void blurDisc(const FrameImage& in, float rx, float ry, FrameImage& out) {
    const int W = in.width, H = in.height;
    out.resize(W, H);
    out.frame = in.frame;
    out.z = in.z;
    if (!(rx > 0.5f || ry > 0.5f)) {  // under a pixel: the pixel filter has done it
        out.rgba = in.rgba;
        return;
    }
    rx = std::max(rx, 0.5f), ry = std::max(ry, 0.5f);
    // Taps: the share of each pixel offset's square inside the ellipse, from 4 x 4 points.
    struct Tap {
        int dx, dy;
        float w;
    };
    std::vector<Tap> taps;
    const int kx = int(std::ceil(rx + 0.5f)), ky = int(std::ceil(ry + 0.5f));
    for (int dy = -ky; dy <= ky; ++dy)
        for (int dx = -kx; dx <= kx; ++dx) {
            int inside = 0;
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) {
                    const float u = (dx - 0.5f + (i + 0.5f) / 4) / rx, v = (dy - 0.5f + (j + 0.5f) / 4) / ry;
                    inside += u * u + v * v <= 1;
                }
            if (inside) taps.push_back({dx, dy, inside / 16.0f});
        }
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            float acc[4] = {0, 0, 0, 0}, wsum = 0;
            for (const Tap& t : taps) {
                const int sx = x + t.dx, sy = y + t.dy;
                if (sx < 0 || sy < 0 || sx >= W || sy >= H) continue;
                const float* p = &in.rgba[(size_t(sy) * size_t(W) + size_t(sx)) * 4];
                for (int c = 0; c < 4; ++c) acc[c] += t.w * p[c];
                wsum += t.w;
            }
            float* o = &out.rgba[(size_t(y) * size_t(W) + size_t(x)) * 4];
            for (int c = 0; c < 4; ++c) o[c] = wsum > 0 ? acc[c] / wsum : 0.0f;
        }
}

void compositeOver(const FrameImage& front, FrameImage& back) {
    const size_t n = size_t(front.width) * size_t(front.height);
    for (size_t i = 0; i < n; ++i) {
        const float* f = &front.rgba[i * 4];
        float* b = &back.rgba[i * 4];
        const float keep = 1 - f[3];
        for (int c = 0; c < 4; ++c) b[c] = f[c] + keep * b[c];
        back.z[i] = std::min(back.z[i], front.z[i]);
    }
}

RenderStats renderDofPreview(const Scene& scene, const RenderOptions& options, int layers, Log& log,
                             const Renderer::FrameSink& sink, const Renderer::Progress& progress) {
    if (!scene.camera.depthOfField() || layers < 1) return Renderer(scene, options, log).render(sink, progress);
    // The lens and the depth range: from the scene as made for rendering (its camera's
    // resolution, its bodies' camera-space bounds over the whole shot: Renderer::shotDepthRange).
    float radius[2] = {0, 0};  // per unit |1/d - 1/z|: raster x and y
    Camera camera;
    float zmin = 0, zmax = 0;
    {
        Renderer probe(scene, options, log);
        camera = probe.renderScene().camera;
        std::tie(zmin, zmax) = probe.shotDepthRange();
    }
    if (!(zmax > zmin)) return Renderer(scene, options, log).render(sink, progress);
    const float invD = 1.0f / camera.focalDistance();
    radius[0] = camera.lensRadius() * std::fabs(camera.ax());
    radius[1] = camera.lensRadius() * std::fabs(camera.ay());

    const std::vector<double> depths = dofLayerDepths(zmin, zmax, layers);
    std::map<int, FrameImage> composite;
    RenderStats total;
    FrameImage blurred;
    // Far to near, each layer composited under the ones before it were: over the composite so far.
    for (int l = layers - 1; l >= 0; --l) {
        Scene slab = scene;
        slab.camera.fstop = std::numeric_limits<double>::infinity();
        slab.camera.nearClip = depths[size_t(l)];
        slab.camera.farClip = depths[size_t(l) + 1];
        const float w = float(0.5 * (1 / depths[size_t(l)] + 1 / depths[size_t(l) + 1]));
        const float rx = radius[0] * std::fabs(invD - w), ry = radius[1] * std::fabs(invD - w);
        Renderer renderer(slab, options, log);
        std::map<int, FrameImage> frames;  // a frame may come again (procedurals' second pass): the last
        const RenderStats stats = renderer.render([&](const FrameImage& img) { frames[img.frame] = img; }, progress);
        for (const auto& [frame, img] : frames) {
            blurDisc(img, rx, ry, blurred);
            auto it = composite.find(frame);
            if (it == composite.end()) composite.emplace(frame, blurred);
            else compositeOver(blurred, it->second);
        }
        if (l == layers - 1) {
            total = stats;
        } else {
            total.counters += stats.counters;
            total.timeBuild += stats.timeBuild;
            total.timeRender += stats.timeRender;
            total.peakMemoryBytes = std::max(total.peakMemoryBytes, stats.peakMemoryBytes);
        }
    }
    for (auto& [frame, img] : composite) sink(img);
    return total;
}

}  // namespace streyes
