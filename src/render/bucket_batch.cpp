// Keyed bodies' small grids shaded in batches (BucketWorker::batchKeys, flushPending).
//
// A swaying leaf is diced at each of its keys, shaded there, and sampled one key interval at a
// time (diceShadeSampleKeys). The forest has hundreds of thousands of such grids of a dozen
// points, and an interpreter run over a dozen points is almost all fixed cost. So a small keyed
// body under a batchable material (GridShader::batchable) is diced at its keys into grids of its
// own and waits; when the batch is flushed, every waiting key grid is shaded through
// GridShader::shadeSlots (one run for the grids of one material and key time) and the bodies are
// sampled in the order they came, each key interval exactly as diceShadeSampleKeys samples it.
//
// Pixels: the shading of each grid is its own bit for bit (shadeSlots), and what is sampled is
// sampled in the same order as without batching, only later. Later matters only to what reads
// the samples before the flush: the occlusion tables (a flush comes first: endLayer) and the
// hidden-body test (a flush first when the body's bound meets the waiting ones'). The adaptive
// layer rule counts first hits, which arrive later: tables may be built at other depths, which
// exact culling (tolerance 0, the only case batched) does not show in the image.
#include <chrono>

#include "render/bucket.h"
#include "render/bucket_grid_ops.h"
#include "render/grid_cache.h"

namespace streyes {

using namespace bucket;

namespace {
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

Grid& BucketWorker::spareGrid() {
    if (keyGridsUsed_ == keyGrids_.size()) keyGrids_.push_back(std::make_unique<Grid>());
    return *keyGrids_[keyGridsUsed_++];
}

bool BucketWorker::pendingMeets(const Bounds3f& r, const uint64_t* primitive) const {
    for (const PendingBody& p : pending_) {
        if (primitive && p.primitive != *primitive) continue;
        if (r.lo.x <= p.raster.hi.x + 1 && r.hi.x >= p.raster.lo.x - 1 && r.lo.y <= p.raster.hi.y + 1 &&
            r.hi.y >= p.raster.lo.y - 1)
            return true;
    }
    return false;
}

bool BucketWorker::batchGrid(const Body& body, int nu, int nv, const Bounds3f& raster) {
    if (!batching_ || !shader_.batchable(body.material(), (nu + 1) * (nv + 1), grid_.aovCount)) return false;
    // Shared with other buckets (diceShadeSample's rule): made and published now, not batched.
    if (gridCache_ && gridCache_->enabled() && gridCache_->layout().bucketsReached(raster) >= kMinBucketsShared) return false;
    if (!diceForShading(body, nu, nv)) return true;  // nothing faces the eye: nothing to shade or sample
    PendingBody p;
    p.firstKey = keyGridsUsed_;
    p.keys = 1;
    p.material = body.material();
    Grid& g = spareGrid();
    std::swap(g, grid_);
    grid_.shadowSlots = shadowSlots_;  // what every grid of this worker is set up with
    grid_.aovCount = aovs_.count;
    for (int k = 0; k < (g.moving ? 2 : 1); ++k) pendingSlots_.push_back({&g, k, k == 0 ? g.t0 : g.t1});
    pendingPoints_ += g.vertexCount();
    p.raster = raster;
    p.primitive = body.primitiveId();
    pending_.push_back(p);
    if (pendingPoints_ >= 4 * GridShader::kBatchPoints) flushPending();
    return true;
}

bool BucketWorker::batchKeys(const KeyedPatchBody& body, int nu, int nv, const Bounds3f& raster) {
    const Material* mat = body.material();
    if (!batching_ || !shader_.batchable(mat, (nu + 1) * (nv + 1), grid_.aovCount)) return false;
    auto t = Clock::now();
    ++counters.gridsDiced;
    // The key intervals that meet the bucket's frames, as diceShadeSampleKeys takes them.
    const double a = bucket_.firstFrame + scene_.shutter.open, b = bucket_.firstFrame + bucket_.frameCount - 1 + scene_.shutter.close;
    size_t k0 = 0, keys = body.keyCount();
    while (k0 + 2 < keys && body.keyTime(k0 + 1) <= a) ++k0;
    while (keys > k0 + 2 && body.keyTime(keys - 2) >= b) --keys;
    PendingBody p;
    p.keyed = true;
    p.firstKey = keyGridsUsed_;
    p.keys = keys - k0;
    p.camera = &cameraOf(body);
    p.material = mat;
    p.firstInterval = pendingIntervals_.size();
    for (size_t k = k0; k < keys; ++k) {
        Grid& g = spareGrid();
        pendingSlots_.push_back({&g, 0, body.keyTime(k)});
        g.shadowSlots = shadowSlots_;
        g.aovCount = grid_.aovCount;
        body.startKeyGrid(nu, nv, g);
        g.stillShadows = 0;
        body.diceKey(k, g, 0);
        g.flatShading = mat && !mat->smoothShading;
        g.matte = mat && mat->matte;
        g.dissolveLo = mat ? mat->dissolveLo : 0;
        g.dissolveHi = mat ? mat->dissolveHi : 1;
        orientNormals(g, 0, mat);
        if (k == k0) setSolid(g, mat, *p.camera);
        pendingPoints_ += g.vertexCount();
        if (k + 1 < keys) {
            PendingInterval in;
            in.t0 = body.keyTime(k);
            in.t1 = body.keyTime(k + 1);
            in.openEnd = k + 2 < body.keyCount() || body.time().openEnd;
            in.moving = body.keyMoves(k) || shadingMovesWithin(body, 0.5 * (in.t0 + in.t1));
            pendingIntervals_.push_back(in);
        }
    }
    p.raster = raster;
    p.primitive = body.primitiveId();
    pending_.push_back(p);
    counters.timeDice += secondsSince(t);
    if (pendingPoints_ >= 4 * GridShader::kBatchPoints) flushPending();
    return true;
}

void BucketWorker::flushPending() {
    if (pending_.empty()) return;
    auto t = Clock::now();
    shader_.shadeSlots(pendingSlots_.data(), pendingSlots_.size());
    auto ts = Clock::now();
    counters.timeShade += std::chrono::duration<double>(ts - t).count();
    // Each body's key intervals as diceShadeSampleKeys samples them: slot 0 key k, slot 1 key k + 1.
    for (const PendingBody& p : pending_) {
        if (!p.keyed) {  // as diceShade and sample do after shading
            Grid& g = *keyGrids_[p.firstKey];
            testStillShadows(g);
            rasterizer_.rasterize(g, gridCamera(g), scene_.shutter, block_, rasterCounters_);
            continue;
        }
        const Grid& first = *keyGrids_[p.firstKey];
        for (size_t i = 0; i + 1 < p.keys; ++i) {
            const Grid& k0 = *keyGrids_[p.firstKey + i];
            const Grid& k1 = *keyGrids_[p.firstKey + i + 1];
            grid_ = k0;
            grid_.P[1] = k1.P[0];
            grid_.N[1] = k1.N[0];
            grid_.Ci[1] = k1.Ci[0];
            grid_.Oi[1] = k1.Oi[0];
            grid_.Cl[1] = k1.Cl[0];
            grid_.solid = first.solid;
            grid_.frontWinding = first.frontWinding;
            const PendingInterval& in = pendingIntervals_[p.firstInterval + i];
            grid_.t0 = in.t0;
            grid_.t1 = in.t1;
            grid_.openEnd = in.openEnd;
            grid_.moving = in.moving;
            grid_.hole.clear();
            if (!p.material || !p.material->oneSided || cullBackFacing(grid_, *p.camera))
                rasterizer_.rasterize(grid_, *p.camera, scene_.shutter, block_, rasterCounters_);
        }
    }
    counters.timeSample += secondsSince(ts);
    pending_.clear();
    pendingSlots_.clear();
    pendingIntervals_.clear();
    keyGridsUsed_ = 0;
    pendingPoints_ = 0;
}

}  // namespace streyes
