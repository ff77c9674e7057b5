// Bodies still in world space under a moving camera (Body::stillInWorld): the camera's motion
// moves them in camera space, where the renderer works, but nothing about them changes. Such a
// root is cut into longer chunks of frames (geom/root_chunks.h: up to kMaxWorldChunkFrames,
// aligned in absolute frame numbers as every chunk is), each piece split and diced once for its
// chunk. Motion is linear in camera space over a piece (it lies within one motion segment), so
// the piece's grid at any time is the linear interpolation of its grid's two ends, as the piece
// restricted to that time would dice it. Its shading is shared by the chunk's frames only where
// it provably reads nothing of the view (shadesOnceForFrames); otherwise each of the bucket's
// frames gets its exposure's grid cut from the diced one, shaded at the exposure's ends (in that
// frame's camera space) and sampled alone, as a one-frame piece is. Everything here is a function
// of the piece, never of the bucket's frames, so a frame rendered alone and in a block gets the
// same grids, colours and pixels (docs/ARCHITECTURE.md, "The split loop").
#include <algorithm>
#include <chrono>
#include <cmath>

#include "cull/view_cull.h"
#include "render/bucket.h"
#include "render/bucket_bounds.h"
#include "render/bucket_grid_ops.h"
#include "render/grid_cache.h"
#include "shade/aov_fill.h"

namespace streyes {

using namespace bucket;

namespace {
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

int facingSign(Vec3f n, Vec3f p, bool perspective) {
    const float d = perspective ? dot(n, p) : n.z;  // the eye's direction to p (orthographic: +z)
    return d > 0 ? 1 : d < 0 ? -1 : 0;
}

// The fractions of a piece's span at the ends of each frame's exposure within it: the times
// shading per frame would shade at. All of the piece's frames, whatever the bucket renders.
void exposureEnds(const TimeSpan& span, double open, double close, std::vector<float>& out) {
    out.clear();
    const double len = span.t1 - span.t0;
    for (double f = std::ceil(span.t0 - close); f <= std::floor(span.t1 - open); f += 1) {
        const double a = std::max(span.t0, f + open), b = std::min(span.t1, f + close);
        if (a > b) continue;
        out.push_back(a == span.t0 ? 0.0f : float((a - span.t0) / len));
        out.push_back(b == span.t1 ? 1.0f : float((b - span.t0) / len));
    }
}
}  // namespace

bool BucketWorker::worldChunks(const Body& root) const {
    if (!root.stillInWorld || !root.moving() || !root.diceableInTime() || root.dicesAtKeys() || root.expands())
        return false;
    const Material* m = root.material();
    // What reads maps made frame by frame, or casts rays, is shaded at each exposure's start,
    // unlike a moving grid (BucketWorker::shadingVaries, chunkFrames): kept to the chunks of every mover.
    return m && !(m->readsMaps && shaders_ && shaders_->mapsPerFrame()) && !m->tracesRays && m->dissolveLo == 0 &&
           m->dissolveHi == 1;
}

bool BucketWorker::dicedForFrames(const Body& body) const {
    const TimeSpan& span = body.time();
    return worldChunks(body) && span.t1 - span.t0 > scene_.shutter.close - scene_.shutter.open;
}

void BucketWorker::diceOnly(const Body& body, int nu, int nv, Grid& grid) {
    auto t = Clock::now();
    grid.shadowSlots = shadowSlots_;
    grid.aovCount = aovs_.count;
    body.dice(nu, nv, grid);
    ++counters.gridsDiced;
    const Material* mat = body.material();
    grid.flatShading = mat && !mat->smoothShading;
    grid.dissolveLo = mat ? mat->dissolveLo : 0;
    grid.dissolveHi = mat ? mat->dissolveHi : 1;
    for (int k = 0; k < (grid.moving ? 2 : 1); ++k) orientNormals(grid, k, mat);
    counters.timeDice += secondsSince(t);
}

// Shaded once for every frame of the piece when its colour cannot change with the camera: what
// its shading reads does not move in the world (lights, time, maps, rays), and it reads the view
// not at all, or only through the side facing the eye while no vertex turns its other side to
// the eye at any exposure's end in the piece. A per-grid check, the same for every bucket.
bool BucketWorker::shadesOnceForFrames(const Body& body, const Grid& diced) const {
    const Material* m = body.material();
    if (!m || m->readsTime || (m->readsMaps && shaders_ && shaders_->mapsVary()) || m->tracesRays || aovs_.count)
        return false;
    // Material::viewUse: the compiler's analysis of its shaders and lights (shade/sl/view_use.h).
    const ViewUse use = m->viewUse;
    if (use == ViewUse::Reads || scene_.lights.anyMovesInWorld(m->lights)) return false;
    if (use == ViewUse::None) return true;
    // Facing only: the side the grid's normals turn to the eye. A displacement (which replaces
    // N before the surface runs) or a primitive variable "N" (the shading normal) could turn
    // another normal to the eye than the grid's: per frame.
    if (m->displacement || m->primvars.find("N")) return false;
    if (!diced.moving) return true;
    std::vector<float> ends;
    exposureEnds(body.time(), scene_.shutter.open, scene_.shutter.close, ends);
    const bool persp = scene_.camera.perspective();
    const size_t n = size_t(diced.vertexCount());
    for (size_t i = 0; i < n; ++i) {
        const Vec3f p0 = diced.P[0][i], p1 = diced.P[1][i], n0 = diced.N[0][i], n1 = diced.N[1][i];
        const int s0 = facingSign(n0, p0, persp);
        if (s0 == 0 || facingSign(n1, p1, persp) != s0) return false;
        for (float s : ends)
            if (facingSign(lerp(n0, n1, s), lerp(p0, p1, s), persp) != s0) return false;
    }
    return true;
}

void BucketWorker::diceShadeSampleFrames(const Body& body, int nu, int nv, const Bounds3f& raster) {
    auto finish = [&](const Grid& diced, bool dicedHere) {
        if (shadesOnceForFrames(body, diced)) shadeSampleOnce(diced, dicedHere);
        else shadeSampleFrames(body, diced, dicedHere);
    };
    // Shared between buckets as other grids are (bucket.cpp, diceShadeSample), but unshaded:
    // each bucket shades what its frames need. From two buckets on: the chunk's sweep puts most
    // such pieces across a bucket's border, and each bucket dicing its own doubled them.
    constexpr int kMinBucketsShared = 2;
    const int reached = gridCache_ && gridCache_->enabled() ? gridCache_->layout().bucketsReached(raster) : 0;
    const GridKey key{body.pieceKey, body.uv, body.time().t0, body.time().t1, nu, nv, bucket_.firstFrame, bucket_.frameCount};
    GridCache::Lease lease;
    if (reached >= kMinBucketsShared) lease = gridCache_->acquire(key);
    if (lease.grid) {
        ++counters.gridsShared;
        finish(*lease.grid, false);
        gridCache_->recycle(std::move(lease.grid));
        return;
    }
    if (!lease.make) {
        diceOnly(body, nu, nv, diced_);
        finish(diced_, true);
        return;
    }
    struct Abandon {
        GridCache* cache;
        const GridKey& key;
        bool armed = true;
        ~Abandon() {
            if (armed) cache->abandon(key);
        }
    } abandon{gridCache_, key};
    std::shared_ptr<Grid> made = gridCache_->spare();
    diceOnly(body, nu, nv, *made);
    gridCache_->publish(key, made, reached - 1);
    abandon.armed = false;
    finish(*made, true);
    gridCache_->recycle(std::move(made));
}

// The micropolygons counter counts what was diced: a grid sampled several times, or diced by
// another bucket, is counted once, where it was diced (micropolygons_shared: taken from another).
void BucketWorker::shadeSampleOnce(const Grid& diced, bool dicedHere) {
    auto t = Clock::now();
    grid_ = diced;
    const Material* mat = grid_.material;
    setSolid(grid_, mat, gridCamera(grid_));
    if (mat && mat->oneSided && !cullBackFacing(grid_, gridCamera(grid_)) && !mat->shadeBackFacing) {
        counters.timeDice += secondsSince(t);
        return;
    }
    auto t1 = Clock::now();
    counters.timeDice += std::chrono::duration<double>(t1 - t).count();
    shader_.shade(grid_);
    if (aovs_.count) fillAovs(grid_, aovs_, gridCamera(grid_));
    counters.timeShade += secondsSince(t1);
    testStillShadows(grid_);
    sample(grid_);
    if (!dicedHere) {
        const uint64_t n = uint64_t(grid_.nu) * uint64_t(grid_.nv);
        rasterCounters_.micropolygons -= n;
        counters.micropolygonsShared += n;
    }
}

// A vertex moving linearly in camera space, in front of the eye plane throughout, stays on the
// raster segment between its projections at the exposure's ends (a line projects to a line), and
// so does a quad's sample-time corner (exact or raster-interpolated): a quad whose box over those
// eight corners, grown by two pixels for rounding, misses the block is never sampled here
// (GridRasterizer's boundQuad drops it). Without a lens, which widens what a quad reaches; a
// non-finite corner (its quad's bound would be NaN) shades all.
bool BucketWorker::markSeenHere(const Camera& cam) {
    const Material* m = grid_.material;  // a shader or a displacement shades the whole grid anyway
    if (cam.depthOfField() || !m || m->surface || m->displacement || m->atmosphere) return false;
    const int nu = grid_.nu, nv = grid_.nv, stride = nu + 1;
    const size_t n = size_t(grid_.vertexCount());
    const bool moving = grid_.moving, persp = cam.perspective();
    const float eye = cam.eyePlane();
    seenBox_.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const Vec3f p0 = grid_.P[0][i], p1 = moving ? grid_.P[1][i] : p0;
        if (persp && !(p0.z >= eye && p1.z >= eye)) return false;  // NaN too
        const Vec3f a = cam.toRaster(p0), b = cam.toRaster(p1);
        if (!(std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(b.x) && std::isfinite(b.y))) return false;
        seenBox_[i] = {std::min(a.x, b.x), std::max(a.x, b.x), std::min(a.y, b.y), std::max(a.y, b.y)};
    }
    const PixelRect& R = block_.rect();
    constexpr float kMargin = 2;
    const float x0 = float(R.x0) - kMargin, x1 = float(R.x1 + 1) + kMargin;
    const float y0 = float(R.y0) - kMargin, y1 = float(R.y1 + 1) + kMargin;
    seenHere_.assign(n, 0);
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const size_t idx[4] = {size_t(j * stride + i), size_t(j * stride + i + 1), size_t((j + 1) * stride + i + 1),
                                   size_t((j + 1) * stride + i)};
            float lx = seenBox_[idx[0]][0], hx = seenBox_[idx[0]][1], ly = seenBox_[idx[0]][2], hy = seenBox_[idx[0]][3];
            for (size_t c : idx) {
                lx = std::min(lx, seenBox_[c][0]), hx = std::max(hx, seenBox_[c][1]);
                ly = std::min(ly, seenBox_[c][2]), hy = std::max(hy, seenBox_[c][3]);
            }
            if (!(hx >= x0 && lx < x1 && hy >= y0 && ly < y1)) continue;
            for (size_t c : idx) seenHere_[c] = 1;
        }
    return true;
}

void BucketWorker::shadeSampleFrames(const Body& body, const Grid& diced, bool dicedHere) {
    const TimeSpan& span = body.time();
    const double open = scene_.shutter.open, close = scene_.shutter.close, len = span.t1 - span.t0;
    const Material* mat = body.material();
    const PixelRect& R = bucket_.rect;
    const uint64_t n = uint64_t(diced.nu) * uint64_t(diced.nv);
    uint64_t sampled = 0;
    const size_t count = size_t(diced.vertexCount());
    for (int fi = 0; fi < bucket_.frameCount; ++fi) {
        const double f = bucket_.firstFrame + fi;
        if (!reachesSamples(span, f + open, f + close, open == close)) continue;
        const Camera& cam = scene_.cameras.ofFrame(int(f));  // a zoom's frame's
        const double a = std::max(span.t0, f + open), b = std::min(span.t1, f + close);
        // The frame's part of the piece misses the bucket (the cut's own bound, as pushChunks culls).
        if (boxOutside(cam, displaced(body, body.boundDuring(a, b)), {R.x0 - 1, R.y0 - 1, R.x1 + 1, R.y1 + 1})) continue;
        auto t = Clock::now();
        // As TrilinearBody::restrictedTo cuts a piece: exact at the span's ends, closed at a cut.
        const float sa = a == span.t0 ? 0.0f : float((a - span.t0) / len);
        const float sb = b == span.t1 ? 1.0f : float((b - span.t0) / len);
        grid_ = diced;
        grid_.t0 = a;
        grid_.t1 = b;
        grid_.openEnd = b == span.t1 ? span.openEnd : false;
        grid_.moving = a < b;
        grid_.stillShadows = 0;  // shaded frame by frame: its samples test every occluder
        grid_.frameShadows.clear();
        for (size_t i = 0; i < count; ++i) {
            const Vec3f p0 = diced.P[0][i], p1 = diced.P[1][i], n0 = diced.N[0][i], n1 = diced.N[1][i];
            grid_.P[0][i] = lerp(p0, p1, sa);
            grid_.N[0][i] = lerp(n0, n1, sa);
            if (grid_.moving) {
                grid_.P[1][i] = lerp(p0, p1, sb);
                grid_.N[1][i] = lerp(n0, n1, sb);
            }
        }
        setSolid(grid_, mat, cam);
        if (mat && mat->oneSided && !cullBackFacing(grid_, cam) && !mat->shadeBackFacing) {
            counters.timeDice += secondsSince(t);
            continue;
        }
        auto t1 = Clock::now();
        counters.timeDice += std::chrono::duration<double>(t1 - t).count();
        // A swept piece reaches several buckets, and each shaded all of every frame's grid: the
        // built-in surfaces (each vertex shaded on its own) shade only what this bucket samples.
        if (!aovs_.count && markSeenHere(gridCamera(grid_))) shader_.shade(grid_, seenHere_.data());
        else shader_.shade(grid_);
        if (aovs_.count) fillAovs(grid_, aovs_, cam);
        counters.timeShade += secondsSince(t1);
        sample(grid_);
        ++sampled;
    }
    rasterCounters_.micropolygons -= n * sampled;
    if (dicedHere) rasterCounters_.micropolygons += n;
    else counters.micropolygonsShared += n;
}

}  // namespace streyes
