// streyes_dicestats: how many micropolygons dicing makes for the area it covers.
//
//   build/streyes_dicestats SCENE.rib [--frame F] [--bucket N] [--grid-size N] [--csv FILE]
//                           [--time-split-min-motion PX]   (1e9: no time splits)
//
// Runs the split loop's decision (src/render/bucket.cpp: cull, time split, dice when
// nu x nv <= grid size, else split the longer raster direction) over the scene's root bodies for
// one frame, without shading, sampling or occlusion culling, and measures each diced grid: the
// micropolygons it has (NU x NV), what the split loop asked for (nu x nv), how many are
// degenerate (zero raster area: repeated side vertices), and the raster area of each at the
// grid's t0 (front and back faces alike). With --bucket N the image is cut into N x N tiles (plus
// the renderer's one-pixel guard band for its default filter) and every tile runs its own loop,
// so the count includes grids diced again in every bucket they reach, as the renderer did before
// it shared grids reaching three buckets or more (src/render/grid_cache.h; `streyes render
// --stats` counts what it dices now); without it the whole image is one bucket.
//
// Prints the totals, micropolygons per (area / shading rate), the mean raster area of a
// micropolygon, a histogram of micropolygon areas and of grid sizes, and per kind of body.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "bodies/material.h"
#include "bodies/render_scene.h"
#include "cull/view_cull.h"
#include "geom/curved_body.h"
#include "geom/grid.h"
#include "streyes/render_options.h"
#include "streyes/rib.h"

using namespace streyes;

namespace {

struct Totals {
    uint64_t grids = 0, mp = 0, requested = 0, degenerate = 0, splits = 0, timeSplits = 0;
    uint64_t tilesByBound = 0, tilesByGrid = 0;  // 32-px buckets each grid's bound / its vertices reach
    uint64_t bySideCounts = 0;   // max(nu, segments on the top and bottom sides) x likewise for v
    uint64_t byMeanLengths = 0;  // ceil(mean row length / side) x ceil(mean column length / side), from the grid
    double area = 0, areaOverRate = 0, diceSeconds = 0;
    double edgeProduct = 0;  // per micropolygon, mean u-edge length x mean v-edge length: area when not skewed
    std::map<int, uint64_t> areaHist;  // 2 log2 of the area
};

float quadArea(Vec3f a, Vec3f b, Vec3f c, Vec3f d) {
    // Half the cross product of the diagonals: the area of a planar quad, a mean for a twisted one.
    const float x1 = d.x - a.x, y1 = d.y - a.y, x2 = c.x - b.x, y2 = c.y - b.y;
    return 0.5f * std::fabs(x1 * y2 - x2 * y1);
}

const char* kindOf(const Body& b) {
    if (auto* c = dynamic_cast<const CurvedBody*>(&b)) return c->hasBezier() ? "bezier" : "curved-box";
    if (dynamic_cast<const TrilinearBody*>(&b)) return "trilinear";
    return "other";
}

std::string rectOf(const Body& b) {
    auto* c = dynamic_cast<const CurvedBody*>(&b);
    if (!c) return ",,,,";
    const ParamRect& r = c->rect();
    return std::to_string(c->face()) + "," + std::to_string(r.u0) + "," + std::to_string(r.u1) + "," + std::to_string(r.v0) + "," +
           std::to_string(r.v1);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: streyes_dicestats SCENE.rib [--frame F] [--bucket N] [--grid-size N] [--csv FILE]\n");
        return 2;
    }
    std::string path = argv[1], csvPath;
    RenderOptions options;
    int frame = -1, bucket = 0, gridSize = 256;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--frame")) frame = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--bucket")) bucket = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--grid-size")) gridSize = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--csv")) csvPath = argv[i + 1];
        else if (!std::strcmp(argv[i], "--time-split-min-motion")) options.timeSplitMinMotion = float(std::atof(argv[i + 1]));
    }
    Log log;
    Scene scene = parseRibFile(path, log);
    if (frame < 0) frame = scene.settings.firstFrame;
    auto rs = buildRenderScene(scene, frame, frame, 0, 0, log);
    const Camera& cam = rs->camera;
    const int W = cam.width(), H = cam.height();
    std::vector<PixelRect> tiles;
    if (bucket <= 0) {
        tiles.push_back({0, 0, W - 1, H - 1});
    } else {
        for (int y = 0; y < H; y += bucket)
            for (int x = 0; x < W; x += bucket)
                tiles.push_back({std::max(0, x - 1), std::max(0, y - 1), std::min(W - 1, x + bucket), std::min(H - 1, y + bucket)});
    }
    std::ofstream csv;
    if (!csvPath.empty()) {
        csv.open(csvPath);
        csv << "kind,prim,nu,nv,NU,NV,degenerate,area,bw,bh,gw,gh,face,u0,u1,v0,v1\n";
    }

    std::map<std::string, Totals> byKind;
    Totals all;
    std::map<int, uint64_t> gridHist;  // micropolygons per grid, in steps of 16
    const double wa = frame + rs->shutter.open, wb = frame + rs->shutter.close;
    Grid grid;
    std::vector<BodyPtr> stack;
    for (const PixelRect& tile : tiles) {
        for (const BodyPtr& root : rs->roots) {
            if (!root->time().overlaps(wa, wb)) continue;
            stack.push_back(root->restrictedTo(std::max(root->time().t0, wa), std::min(root->time().t1, wb)));
            while (!stack.empty()) {
                BodyPtr b = std::move(stack.back());
                stack.pop_back();
                const Bounds3f swept = b->bound().swept();
                if (!(swept.hi.z >= cam.nearClip() && swept.lo.z <= cam.farClip())) continue;
                SplitAxis axis;
                if (cam.perspective() && swept.lo.z < cam.eyePlane()) {
                    if (outsideFrustum(cam, swept, tile) || b->eyeSplitDepth >= options.maxEyeSplits) continue;
                    const CameraExtents e = b->cameraExtents();
                    axis = e.u >= e.v ? SplitAxis::U : SplitAxis::V;
                    if ((b->moving() && e.t > std::max(e.u, e.v)) || !b->diceableInTime()) axis = SplitAxis::T;
                    BodyPtr h[2];
                    b->split(axis, h);
                    for (int i = 1; i >= 0; --i) {
                        h[i]->eyeSplitDepth = static_cast<unsigned char>(b->eyeSplitDepth + 1);
                        stack.push_back(std::move(h[i]));
                    }
                    continue;
                }
                const RasterMeasure m = b->measure(cam);
                if (rasterOutside(m.bound.swept(), tile)) continue;
                const float rate = std::max(b->material()->shadingRate, 1e-4f);
                const float side = std::sqrt(rate), size = std::max(m.extentU, m.extentV);
                Totals& k = byKind[kindOf(*b)];
                if (!b->diceableInTime()) {
                    axis = SplitAxis::T;
                } else if (b->moving() && m.motion > std::max(options.timeSplitRatio * size, options.timeSplitMinMotion)) {
                    axis = SplitAxis::T;
                } else {
                    const double nu = std::max(1.0, std::ceil(double(m.extentU) / side));
                    const double nv = std::max(1.0, std::ceil(double(m.extentV) / side));
                    if (nu * nv <= gridSize || b->splitDepth >= options.maxSplitDepth) {
                        const auto t0 = std::chrono::steady_clock::now();
                        b->dice(int(nu), int(nv), grid);
                        const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                        std::vector<Vec3f> r(grid.P[0].size());
                        for (size_t i = 0; i < r.size(); ++i) r[i] = cam.toRaster(grid.P[0][i]);
                        uint64_t degenerate = 0;
                        double area = 0, edgeProduct = 0;
                        for (int j = 0; j < grid.nv; ++j)
                            for (int i = 0; i < grid.nu; ++i) {
                                const float a = quadArea(r[size_t(grid.index(i, j))], r[size_t(grid.index(i + 1, j))],
                                                         r[size_t(grid.index(i, j + 1))], r[size_t(grid.index(i + 1, j + 1))]);
                                auto len = [](Vec3f p, Vec3f q) { return std::hypot(p.x - q.x, p.y - q.y); };
                                const Vec3f& p00 = r[size_t(grid.index(i, j))];
                                const Vec3f& p10 = r[size_t(grid.index(i + 1, j))];
                                const Vec3f& p01 = r[size_t(grid.index(i, j + 1))];
                                const Vec3f& p11 = r[size_t(grid.index(i + 1, j + 1))];
                                edgeProduct += 0.25 * (len(p00, p10) + len(p01, p11)) * (len(p00, p01) + len(p10, p11));
                                if (a <= 0) ++degenerate;
                                else ++all.areaHist[int(std::floor(std::log2(a) * 2))];
                                area += a;
                            }
                        const uint64_t mp = uint64_t(grid.nu) * uint64_t(grid.nv);
                        // Buckets (32 px tiles and a one-pixel guard band) that the bound reaches, and
                        // that the grid's own vertices reach.
                        Bounds3f gb;
                        for (const Vec3f& p : r) gb.extend(p);
                        if (grid.moving)
                            for (const Vec3f& p : grid.P[1]) gb.extend(cam.toRaster(p));
                        auto tilesOf = [&](const Bounds3f& rb) {
                            uint64_t n = 0;
                            for (int y = 0; y < H; y += 32)
                                for (int x = 0; x < W; x += 32)
                                    n += !rasterOutside(rb, {std::max(0, x - 1), std::max(0, y - 1), std::min(W - 1, x + 32),
                                                             std::min(H - 1, y + 32)});
                            return n;
                        };
                        // Distinct vertices along each side (0: row 0, 1: column NU, 2: row NV, 3: column 0).
                        auto segments = [&](int side) {
                            const int n = side == 0 || side == 2 ? grid.nu : grid.nv;
                            int count = 0;
                            Vec3f last{};
                            for (int q = 0; q <= n; ++q) {
                                const int i = side == 0 || side == 2 ? q : (side == 1 ? grid.nu : 0);
                                const int j = side == 1 || side == 3 ? q : (side == 2 ? grid.nv : 0);
                                const Vec3f p = grid.P[0][size_t(grid.index(i, j))];
                                if (q == 0 || p != last) ++count;
                                last = p;
                            }
                            return uint64_t(count - 1);
                        };
                        const uint64_t sideCounts = std::max({uint64_t(nu), segments(0), segments(2)}) *
                                                    std::max({uint64_t(nv), segments(1), segments(3)});
                        // What nu x nv would be from the mean raster length of the grid's rows and
                        // columns instead of the longest edges of the piece.
                        double rowLength = 0, columnLength = 0;
                        for (int j = 0; j <= grid.nv; ++j)
                            for (int i = 0; i < grid.nu; ++i)
                                rowLength += std::hypot(r[size_t(grid.index(i + 1, j))].x - r[size_t(grid.index(i, j))].x,
                                                        r[size_t(grid.index(i + 1, j))].y - r[size_t(grid.index(i, j))].y);
                        for (int i = 0; i <= grid.nu; ++i)
                            for (int j = 0; j < grid.nv; ++j)
                                columnLength += std::hypot(r[size_t(grid.index(i, j + 1))].x - r[size_t(grid.index(i, j))].x,
                                                           r[size_t(grid.index(i, j + 1))].y - r[size_t(grid.index(i, j))].y);
                        const uint64_t byMean = uint64_t(std::max(1.0, std::ceil(rowLength / (grid.nv + 1) / side))) *
                                                uint64_t(std::max(1.0, std::ceil(columnLength / (grid.nu + 1) / side)));
                        const uint64_t tb = tilesOf(m.bound.swept()), tg = tilesOf(gb);
                        for (Totals* t : {&k, &all}) {
                            ++t->grids;
                            t->mp += mp;
                            t->requested += uint64_t(nu * nv);
                            t->degenerate += degenerate;
                            t->area += area;
                            t->edgeProduct += edgeProduct;
                            t->areaOverRate += area / rate;
                            t->diceSeconds += sec;
                            t->tilesByBound += tb;
                            t->tilesByGrid += tg;
                            t->bySideCounts += sideCounts;
                            t->byMeanLengths += byMean;
                        }
                        ++gridHist[int(mp / 32)];
                        if (csv) csv << kindOf(*b) << ',' << b->primitiveId() << ',' << nu << ',' << nv << ',' << grid.nu << ',' << grid.nv << ','
                                     << degenerate << ',' << area << ',' << m.bound.swept().hi.x - m.bound.swept().lo.x << ','
                                     << m.bound.swept().hi.y - m.bound.swept().lo.y << ',' << gb.hi.x - gb.lo.x << ','
                                     << gb.hi.y - gb.lo.y << ',' << rectOf(*b) << '\n';
                        continue;
                    }
                    axis = m.extentU >= m.extentV ? SplitAxis::U : SplitAxis::V;
                }
                ++(axis == SplitAxis::T ? k.timeSplits : k.splits);
                ++(axis == SplitAxis::T ? all.timeSplits : all.splits);
                BodyPtr h[2];
                b->split(axis, h);
                for (int i = 1; i >= 0; --i) {
                    h[i]->splitDepth = static_cast<unsigned char>(b->splitDepth + 1);
                    stack.push_back(std::move(h[i]));
                }
            }
        }
    }
    auto report = [](const char* name, const Totals& t) {
        std::printf("%-10s grids %7llu  micropolygons %9llu (asked %9llu, by side counts %9llu, by mean lengths %9llu, degenerate %8llu)  area %10.0f px  "
                    "mp per area/rate %.2f  mean mp area %.3f px (non-degenerate %.3f)  splits %llu t %llu  dice %.3f s  "
                    "32-px buckets per grid: by bound %.2f, by vertices %.2f  edge products / area %.2f\n",
                    name, (unsigned long long)t.grids, (unsigned long long)t.mp, (unsigned long long)t.requested, (unsigned long long)t.bySideCounts, (unsigned long long)t.byMeanLengths,
                    (unsigned long long)t.degenerate, t.area, t.mp / std::max(t.areaOverRate, 1e-9),
                    t.area / std::max<double>(double(t.mp), 1), t.area / std::max<double>(double(t.mp - t.degenerate), 1),
                    (unsigned long long)t.splits, (unsigned long long)t.timeSplits, t.diceSeconds,
                    double(t.tilesByBound) / std::max<double>(double(t.grids), 1),
                    double(t.tilesByGrid) / std::max<double>(double(t.grids), 1), t.edgeProduct / std::max(t.area, 1e-9));
    };
    std::printf("%s frame %d, %zu bucket(s)%s\n", path.c_str(), frame, tiles.size(),
                bucket > 0 ? (" of " + std::to_string(bucket) + " px").c_str() : " (the whole image)");
    for (const auto& [name, t] : byKind) report(name.c_str(), t);
    report("all", all);
    std::printf("micropolygon area (px), non-degenerate:\n");
    for (const auto& [bin, n] : all.areaHist)
        std::printf("  [%7.3f, %7.3f) %9llu  %5.1f%%\n", std::pow(2.0, bin / 2.0), std::pow(2.0, (bin + 1) / 2.0),
                    (unsigned long long)n, 100.0 * double(n) / double(std::max<uint64_t>(all.mp, 1)));
    std::printf("micropolygons per grid:\n");
    for (const auto& [bin, n] : gridHist)
        std::printf("  [%4d, %4d) %7llu\n", bin * 32, bin * 32 + 32, (unsigned long long)n);
    return 0;
}
