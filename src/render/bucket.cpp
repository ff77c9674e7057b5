#include "bucket.h"

#include <chrono>
#include <cmath>

#include "streyes/view_cull.h"

namespace streyes {

namespace {
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

BucketWorker::BucketWorker(const RenderScene& scene, const RenderOptions& options, const PixelFilter& filter,
                           const SamplePattern& pattern, Log& log)
    : scene_(scene), options_(options), filter_(filter), pattern_(pattern), log_(log) {}

void BucketWorker::setTrace(const TraceScene* trace) {
    trace_ = trace;
    const Algorithm a = options_.algorithm;
    traceEyeRays_ = trace && (a == Algorithm::Raytrace || a == Algorithm::RaytraceFrames);
    shadowSlots_ = trace && !traceEyeRays_ ? scene_.lights.shadowSlots() : 0;
    grid_.shadowSlots = shadowSlots_;
}

void BucketWorker::render(const BucketSpec& bucket, std::vector<FrameImage>& frames, int framesFirst) {
    bucket_ = bucket;
    ++counters.buckets;
    auto t = Clock::now();
    block_.reset(bucket.rect, bucket.firstFrame, bucket.frameCount, pattern_, shadowSlots_);
    counters.timeSampleGen += secondsSince(t);

    // The bucket's block of spacetime: its frames' exposures.
    const double wa = bucket.firstFrame + scene_.shutter.open;
    const double wb = bucket.firstFrame + bucket.frameCount - 1 + scene_.shutter.close;
    t = Clock::now();
    const double diceShadeSampleBefore = counters.timeDice + counters.timeShade + counters.timeSample;
    static const std::vector<BodyPtr> kNothingToSplit;  // the ray tracer traces the samples instead
    for (const BodyPtr& root : traceEyeRays_ ? kNothingToSplit : scene_.roots) {
        const TimeSpan& span = root->time();
        if (!span.overlaps(wa, wb)) continue;
        if (root->moving() && (span.t0 < wa || span.t1 > wb)) {
            // Only the part of the motion inside this bucket's frames matters here.
            stack_.push_back(root->restrictedTo(std::max(span.t0, wa), std::min(span.t1, wb)));
        } else {
            process(*root);
        }
        while (!stack_.empty()) {
            BodyPtr b = std::move(stack_.back());
            stack_.pop_back();
            process(*b);
        }
    }
    counters.timeSplit +=
        secondsSince(t) - (counters.timeDice + counters.timeShade + counters.timeSample - diceShadeSampleBefore);

    if (trace_) {  // eye rays (raytrace*), or the shadow rays of the rasterizer's hits
        t = Clock::now();
        if (traceEyeRays_) tracer_.traceSamples(block_, *trace_, counters);
        else if (shadowSlots_) tracer_.shadeShadows(block_, *trace_, counters);
        counters.timeTrace += secondsSince(t);
    }
    if (options_.sampleObserver) options_.sampleObserver(block_, bucket.tile);

    t = Clock::now();
    resolveTile(block_, bucket.tile, filter_, &frames[size_t(bucket.firstFrame - framesFirst)], resolveScratch_);
    counters.timeResolve += secondsSince(t);
    counters.micropolygons += rasterCounters_.micropolygons;
    counters.sampleTests += rasterCounters_.sampleTests;
    counters.sampleHits += rasterCounters_.sampleHits;
    rasterCounters_ = {};
}

// Algorithm S, one body: cull against the bucket's spacetime block, then dice it if it is
// small enough or split it along its longest direction in raster spacetime (u, v or t).
void BucketWorker::process(const Body& body) {
    const Camera& cam = scene_.camera;
    const Bounds3f swept = body.bound().swept();
    if (!(swept.hi.z >= cam.nearClip() && swept.lo.z <= cam.farClip())) {
        ++counters.culledClip;  // wholly in front of the near plane or beyond the far plane (or NaN)
        return;
    }

    // Bodies reaching the eye plane cannot be projected: cull them against the frustum in camera
    // space, or split them until the pieces lie in front of the plane or behind the near plane.
    if (cam.perspective() && swept.lo.z < cam.eyePlane()) {
        if (outsideFrustum(cam, swept, bucket_.rect)) {
            ++counters.culledView;
            return;
        }
        if (body.eyeSplitDepth >= options_.maxEyeSplits) {
            ++counters.culledEyeLimit;
            log_.warnOnce("eyesplit", body.source() ? *body.source() : SourceLoc{},
                          "geometry crossing the eye plane still straddles it after " +
                              std::to_string(options_.maxEyeSplits) +
                              " eye splits: a piece was dropped (move the near clipping plane out, see Clipping)");
            return;
        }
        CameraExtents e = body.cameraExtents();
        SplitAxis axis = e.u >= e.v ? SplitAxis::U : SplitAxis::V;
        if (body.moving() && e.t > std::max(e.u, e.v)) axis = SplitAxis::T;
        ++counters.eyeSplits;
        pushSplit(body, axis, true);
        return;
    }

    const RasterMeasure m = body.measure(cam);
    if (rasterOutside(m.bound.swept(), bucket_.rect)) {
        ++counters.culledView;
        return;
    }

    const float side = std::sqrt(std::max(body.material()->shadingRate, 1e-4f));
    const float size = std::max(m.extentU, m.extentV);
    SplitAxis axis;
    if (body.moving() && m.motion > std::max(options_.timeSplitRatio * size, options_.timeSplitMinMotion)) {
        axis = SplitAxis::T;  // the swept bound is much larger than the body: split its time span
    } else {
        const double nu = std::max(1.0, std::ceil(double(m.extentU) / side));
        const double nv = std::max(1.0, std::ceil(double(m.extentV) / side));
        if (nu * nv <= double(options_.maxGridSize)) {
            diceShadeSample(body, int(nu), int(nv));
            return;
        }
        axis = m.extentU >= m.extentV ? SplitAxis::U : SplitAxis::V;
    }
    if (body.splitDepth >= options_.maxSplitDepth) {
        ++counters.culledSplitLimit;
        log_.warnOnce("splitlimit", body.source() ? *body.source() : SourceLoc{},
                      "a body is still too large to dice after " + std::to_string(options_.maxSplitDepth) +
                          " splits (degenerate or huge geometry): dropped");
        return;
    }
    (axis == SplitAxis::U ? counters.splitsU : axis == SplitAxis::V ? counters.splitsV : counters.splitsT)++;
    pushSplit(body, axis, false);
}

void BucketWorker::pushSplit(const Body& body, SplitAxis axis, bool eyeSplit) {
    BodyPtr halves[2];
    body.split(axis, halves);
    // Second half below the first: the first half is processed next (depth first).
    for (int i = 1; i >= 0; --i) {
        if (eyeSplit) halves[i]->eyeSplitDepth = static_cast<unsigned char>(body.eyeSplitDepth + 1);
        else halves[i]->splitDepth = static_cast<unsigned char>(body.splitDepth + 1);
        stack_.push_back(std::move(halves[i]));
    }
}

void BucketWorker::diceShadeSample(const Body& body, int nu, int nv) {
    auto t = Clock::now();
    body.dice(nu, nv, grid_);
    ++counters.gridsDiced;
    auto t1 = Clock::now();
    counters.timeDice += std::chrono::duration<double>(t1 - t).count();
    shadeGrid(grid_, scene_.lights, !scene_.camera.perspective(), lightScratch_);
    auto t2 = Clock::now();
    counters.timeShade += std::chrono::duration<double>(t2 - t1).count();
    rasterizer_.rasterize(grid_, scene_.camera, scene_.shutter, block_, rasterCounters_);
    counters.timeSample += secondsSince(t2);
}

}  // namespace streyes
