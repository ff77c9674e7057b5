// Checking a render sample by sample against an analytic answer (hard-case tests).
//
// The scenes use a one-pixel box filter, so a pixel is exactly the mean of its own samples and
// no sample is shared between buckets. The test gives `layers(x, y, t)`: how many surfaces lie
// over raster (x, y) at time t (frames); 0 where the sample sees the background. The oracle
// regenerates every sample the renderer used (PatternTable::pixelSamples: a pure function) and checks
//   - a pixel whose samples are all clearly covered has alpha exactly 1 (no cracks);
//   - a pixel whose samples are all clearly uncovered has alpha exactly 0 (nothing stray);
//   - the renderer's hit count (every micropolygon a sample falls in, before the depth test) is
//     the sum of the layers over the samples: a crack hidden by a surface behind, or a double
//     hit on a shared edge, shows here;
// where "clearly" means that points `hair` pixels away agree: samples that close to an outline
// may go either way, and are allowed any count up to the most layers around them. `layers` may
// also answer -n: "either way, up to n layers" (where the renderer only approximates the shape).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <type_traits>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bodies/polygons.h"
#include "raster/image_block.h"
#include "streyes/rib.h"
#include "test_util.h"

namespace streyes::test {

struct OracleReport {
    uint64_t samplesCovered = 0, samplesUncovered = 0, samplesOnOutline = 0;
    uint64_t layers = 0;         // summed over the clear samples: the hits expected
    uint64_t outlineLayers = 0;  // the most layers around each outline sample, summed
    uint64_t hits = 0;           // what the renderer counted
    uint64_t behind = 0;         // samples the renderer did not test: a micropolygon lay behind their hit
    int pixelsCovered = 0, pixelsUncovered = 0;  // pixels whose samples are all clearly (un)covered
    int crackedPixels = 0;                       // ... of which alpha is not 1
    int strayPixels = 0;                         // ... of which alpha is not 0
    int alphaAboveOne = 0;
    // Per frame and pixel (in the render's order): 1 all samples covered, 0 none, -1 neither.
    std::vector<signed char> pixelClass;
};

// Checks another render of the same scene and samples against the pixel classes of `rep`:
// cracked and stray pixels, counted into a copy of it (its hits are the other render's).
inline OracleReport recheckPixels(const OracleReport& rep, const RenderResult& r) {
    OracleReport again = rep;
    again.crackedPixels = again.strayPixels = again.alphaAboveOne = 0;
    again.hits = r.stats.counters.sampleHits;
    size_t i = 0;
    for (const FrameImage& img : r.frames)
        for (size_t p = 0; p < size_t(img.width) * size_t(img.height); ++p, ++i) {
            const float a = img.rgba[p * 4 + 3];
            again.alphaAboveOne += a > 1.0f;
            again.crackedPixels += rep.pixelClass[i] == 1 && a != 1.0f;
            again.strayPixels += rep.pixelClass[i] == 0 && a != 0.0f;
        }
    return again;
}

template <typename Layers>
OracleReport checkSamples(const Scene& scene, const RenderResult& r, Layers layers, double hair = 1e-4) {
    const ResolvedSettings s = resolveSettings(scene, RenderOptions{});
    const double open = scene.settings.shutterOpen, close = scene.settings.shutterClose;
    EXPECT_EQ(scene.settings.filter.type, "box");
    EXPECT_EQ(scene.settings.filter.xwidth, 1.0);
    OracleReport rep;
    rep.hits = r.stats.counters.sampleHits;
    rep.behind = r.stats.counters.samplesBehind;
    std::vector<SamplePosition> pos(static_cast<size_t>(s.pattern.count()));
    const PatternTable table(s.pattern);
    for (const FrameImage& img : r.frames) {
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                table.pixelSamples(x, y, img.frame, pos.data());
                const float* lens = table.lens(table.patternOf(x, y));
                int covered = 0, uncovered = 0;
                for (size_t j = 0; j < pos.size(); ++j) {
                    const SamplePosition& p = pos[j];
                    const double t = img.frame + open + (close - open) * double(p.tf);
                    // With depth of field `layers` may take the sample's lens position too.
                    auto at = [&](double sx, double sy) {
                        if constexpr (std::is_invocable_v<Layers, double, double, double, double, double>)
                            return layers(sx, sy, t, double(lens[2 * j]), double(lens[2 * j + 1]));
                        else
                            return layers(sx, sy, t);
                    };
                    // A negative answer means "either way, up to -n layers".
                    const int n = int(at(double(p.x), double(p.y)));
                    int most = std::abs(n);
                    bool clear = n >= 0;
                    for (auto [dx, dy] : {std::pair{hair, 0.0}, {-hair, 0.0}, {0.0, hair}, {0.0, -hair}}) {
                        const int m = int(at(p.x + dx, p.y + dy));
                        clear = clear && m == n;
                        most = std::max(most, std::abs(m));
                    }
                    if (!clear) {
                        ++rep.samplesOnOutline;
                        rep.outlineLayers += uint64_t(most);
                    } else if (n > 0) {
                        ++rep.samplesCovered, ++covered;
                        rep.layers += uint64_t(n);
                    } else {
                        ++rep.samplesUncovered, ++uncovered;
                    }
                }
                const float a = img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4 + 3];
                rep.alphaAboveOne += a > 1.0f;
                if (covered == int(pos.size())) {
                    ++rep.pixelsCovered;
                    rep.crackedPixels += a != 1.0f;
                    rep.pixelClass.push_back(1);
                } else if (uncovered == int(pos.size())) {
                    ++rep.pixelsUncovered;
                    rep.strayPixels += a != 0.0f;
                    rep.pixelClass.push_back(0);
                } else {
                    rep.pixelClass.push_back(-1);
                }
            }
    }
    return rep;
}

// A primitive's corners in camera space at time t, from the scene description in double
// precision: its own keys and its transform's, linear between keys and held outside them.
inline std::array<Vec3d, 4> cameraCorners(const BilinearPatchDesc& p, const MotionTransform& objectToCamera, double t) {
    std::array<Vec3d, 4> obj = p.P.front();
    if (p.P.size() > 1 && t >= p.times.back()) obj = p.P.back();
    for (size_t i = 1; i < p.P.size(); ++i)
        if (t > p.times[i - 1] && t < p.times[i]) {
            const double s = (t - p.times[i - 1]) / (p.times[i] - p.times[i - 1]);
            for (size_t c = 0; c < 4; ++c) obj[c] = lerp(p.P[i - 1][c], p.P[i][c], s);
        }
    const Matrix4 m = objectToCamera.at(t);
    std::array<Vec3d, 4> r;
    for (size_t c = 0; c < 4; ++c) r[c] = m.point(obj[c]);
    return r;
}
inline std::array<Vec3d, 4> cameraCorners(const Scene& scene, const BilinearPatchDesc& p, double t) {
    return cameraCorners(p, p.objectToWorld.then(scene.camera.worldToCamera), t);
}

// How many times the bilinear patch with these corners (x and y only: seen along z) covers the
// point (x, y): the (u, v) in [0, 1]^2 it maps there. 0 or 1, or 2 where a folded patch lies
// over itself; 0 for a patch of zero area, which the renderer also never hits.
inline int bilinearLayers(const std::array<Vec3d, 4>& c, double x, double y) {
    auto cross2 = [](Vec3d a, Vec3d b) { return a.x * b.y - a.y * b.x; };
    const Vec3d e = c[1] - c[0], f = c[2] - c[0], g = c[0] - c[1] - c[2] + c[3], h = Vec3d{x, y, 0} - c[0];
    // h = e u + f v + g u v; crossing with (e + g v) leaves k2 v^2 + k1 v + k0 = 0.
    const double k2 = cross2(g, f), k1 = cross2(e, f) + cross2(h, g), k0 = cross2(h, e);
    double roots[2];
    int n = 0;
    if (std::fabs(k2) <= 1e-12 * (std::fabs(k1) + std::fabs(k0))) {
        if (k1 != 0) roots[n++] = -k0 / k1;
    } else {
        const double disc = k1 * k1 - 4 * k2 * k0;
        if (disc < 0) return 0;
        const double q = -0.5 * (k1 + std::copysign(std::sqrt(disc), k1));  // stable roots
        roots[n++] = q / k2;
        if (disc > 0 && q != 0) roots[n++] = k0 / q;
    }
    int layers = 0;
    for (int i = 0; i < n; ++i) {
        const double v = roots[i];
        if (!(v >= 0 && v <= 1)) continue;
        const double dx = e.x + g.x * v, dy = e.y + g.y * v;
        const double u = std::fabs(dx) >= std::fabs(dy) ? (h.x - f.x * v) / dx : (h.y - f.y * v) / dy;
        layers += u >= 0 && u <= 1;
    }
    return layers;
}

// A scene's bilinear patches as the renderer makes them: its patches and the Polygons that are
// one (bodies/polygons.h).
inline std::vector<BilinearPatchDesc> bilinearPatches(const Scene& scene) {
    std::vector<BilinearPatchDesc> patches = scene.patches;
    for (const PolygonMeshDesc& mesh : scene.polygonMeshes)
        if (std::optional<BilinearPatchDesc> patch = polygonAsPatch(mesh)) patches.push_back(std::move(*patch));
    return patches;
}

// The layers of every patch of an orthographic scene (seen along z) over a point, with the
// corners of all patches evaluated once per time (or once, when nothing moves), and a uniform
// grid over their bounds so that a point is tested against the patches near it only.
class PatchLayers {
  public:
    explicit PatchLayers(const Scene& scene) : patches_(bilinearPatches(scene)) {
        still_ = scene.camera.worldToCamera.isStatic();
        for (const BilinearPatchDesc& p : patches_) {
            still_ = still_ && p.P.size() == 1 && p.objectToWorld.isStatic();
            objectToCamera_.push_back(p.objectToWorld.then(scene.camera.worldToCamera));
        }
    }
    int operator()(double x, double y, double t) {
        if (corners_.empty() || (!still_ && t != time_)) update(t);
        int n = 0;
        if (!still_) {  // corners change with every sample time: not worth an index
            for (size_t i = 0; i < corners_.size(); ++i)
                if (bounds_[i].contains({x, y, 0})) n += bilinearLayers(corners_[i], x, y);
            return n;
        }
        const int cx = int(std::floor((x - all_.lo.x) / cell_)), cy = int(std::floor((y - all_.lo.y) / cell_));
        if (cx < 0 || cy < 0 || cx >= kCells || cy >= kCells) return 0;
        for (size_t i : cells_[size_t(cy * kCells + cx)])
            if (bounds_[i].contains({x, y, 0})) n += bilinearLayers(corners_[i], x, y);
        return n;
    }

  private:
    static constexpr int kCells = 64;
    void update(double t);
    std::vector<BilinearPatchDesc> patches_;
    bool still_ = false;
    double time_ = 0, cell_ = 1;
    std::vector<MotionTransform> objectToCamera_;
    std::vector<std::array<Vec3d, 4>> corners_;
    std::vector<Bounds3d> bounds_;  // in x and y (z spans everything)
    Bounds3d all_;
    std::vector<std::vector<size_t>> cells_;
};

inline void PatchLayers::update(double t) {
    time_ = t;
    corners_.clear();
    bounds_.clear();
    all_ = Bounds3d();
    for (size_t i = 0; i < patches_.size(); ++i) {
        corners_.push_back(cameraCorners(patches_[i], objectToCamera_[i], t));
        Bounds3d b;
        for (const Vec3d& c : corners_.back()) b.extend(c);
        b.lo.z = -1e300, b.hi.z = 1e300;
        bounds_.push_back(b);
        all_.extend(b);
    }
    if (!still_) return;
    cell_ = std::max(all_.hi.x - all_.lo.x, all_.hi.y - all_.lo.y) / kCells * (1 + 1e-9) + 1e-300;
    cells_.assign(size_t(kCells) * kCells, {});
    auto cellOf = [&](double v, double lo) { return std::clamp(int(std::floor((v - lo) / cell_)), 0, kCells - 1); };
    for (size_t i = 0; i < bounds_.size(); ++i)
        for (int cy = cellOf(bounds_[i].lo.y, all_.lo.y); cy <= cellOf(bounds_[i].hi.y, all_.lo.y); ++cy)
            for (int cx = cellOf(bounds_[i].lo.x, all_.lo.x); cx <= cellOf(bounds_[i].hi.x, all_.lo.x); ++cx)
                cells_[size_t(cy * kCells + cx)].push_back(i);
}

// A scene of scenes/hard/, rendered and checked: its values are finite, it reached no split
// limit and gave no warning, and its samples match the oracle `makeLayers(scene)` builds (by
// default the layers of its patches, for orthographic scenes).
struct CheckedCase {
    Scene scene;
    RenderResult render;
    OracleReport oracle;
};

inline void expectMatchesOracle(const OracleReport& rep);

template <typename MakeLayers>
CheckedCase checkHardCase(const std::string& name, MakeLayers makeLayers, double hair = 1e-4) {
    CheckedCase c;
    Log log;
    c.scene = parseRibFile(sourcePath("scenes/hard/" + name), log);
    c.render = renderFile(sourcePath("scenes/hard/" + name));
    for (const FrameImage& f : c.render.frames) {
        for (float v : f.rgba) EXPECT_TRUE(std::isfinite(v)) << name;
        for (float z : f.z) EXPECT_FALSE(std::isnan(z)) << name;
    }
    EXPECT_EQ(c.render.stats.counters.culledSplitLimit, 0u);
    EXPECT_EQ(c.render.stats.counters.culledEyeLimit, 0u);
    EXPECT_TRUE(c.render.warnings.empty()) << c.render.warnings.front();
    auto layers = makeLayers(c.scene);
    c.oracle = checkSamples(c.scene, c.render, layers, hair);
    expectMatchesOracle(c.oracle);
    return c;
}
inline CheckedCase checkHardCase(const std::string& name, double hair = 1e-4) {
    return checkHardCase(name, [](const Scene& s) { return PatchLayers(s); }, hair);
}

// The assertions every hard case shares.
inline void expectMatchesOracle(const OracleReport& rep) {
    EXPECT_EQ(rep.crackedPixels, 0);
    EXPECT_EQ(rep.strayPixels, 0);
    EXPECT_EQ(rep.alphaAboveOne, 0);
    // Every layer of a clear sample was hit, unless the micropolygon lay behind what the sample
    // already saw (not tested); and no more hits than layers.
    EXPECT_GE(rep.hits + rep.behind, rep.layers);
    EXPECT_LE(rep.hits, rep.layers + rep.outlineLayers);
    ::testing::Test::RecordProperty("samples_covered", std::to_string(rep.samplesCovered));
    ::testing::Test::RecordProperty("samples_on_outline", std::to_string(rep.samplesOnOutline));
    ::testing::Test::RecordProperty("hits", std::to_string(rep.hits));
}

}  // namespace streyes::test
