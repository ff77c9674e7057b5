// TraceScene (trace/trace.h): the bodies rays can meet and their spacetime hierarchies, built
// once a render (still ones) or a frame block (movers); SampleTracer is in sample_tracer.cpp.
#include "trace/trace.h"

#include <sys/resource.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "procedural/procedural.h"
#include "shade/shading.h"

namespace streyes {

namespace {
// CPU seconds of the whole process. Hierarchies are built (in parallel) while nothing else
// runs, so the difference around a build is its CPU time, comparable between the two modes.
double processCpuSeconds() {
    struct rusage ru {};
    getrusage(RUSAGE_SELF, &ru);
    auto sec = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return sec(ru.ru_utime) + sec(ru.ru_stime);
}
}  // namespace



TraceScene::TraceScene(const RenderScene& scene, const RenderOptions& options, Log& log, const SceneShaders* shaders)
    : scene_(scene), shaders_(shaders), windowStart_(scene.renderedStart), windowEnd_(scene.renderedEnd) {
    for (const BodyPtr& root : scene.roots) collect(*root, log);
    // Curved bodies are tessellated in parallel (splitting and dicing are const and thread-safe,
    // as the buckets use them), each into its own deque, then placed where collect met them: the
    // body order, and so the hierarchy, does not depend on threads.
    micropolygons_.resize(curved_.size());
    std::vector<const TrilinearBody*> traceUndisplaced(curved_.size(), nullptr);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, curved_.size()), [&](const tbb::blocked_range<size_t>& r) {
        Tessellator tessellator(scene.cameras, options, scene.shutter.close - scene.shutter.open, log);
        std::unique_ptr<GridShader> displacer;  // this task's, for displacement shaders (no rays)
        if (shaders_) {
            displacer = std::make_unique<GridShader>(shaders_, scene.camera, scene.lights);
            tessellator.setDisplacer(displacer.get());
        }
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const Body& body = *curved_[i].body;
            if (tessellator.tessellate(body, micropolygons_[i])) continue;
            const SourceLoc at = body.source() ? *body.source() : SourceLoc{};
            const std::string many = std::to_string(Tessellator::kMaxMicropolygonsPerBody);
            if (const auto* patch = dynamic_cast<const TrilinearBody*>(&body)) {
                // A displaced patch too large to dice (a ground plane to the horizon): traced as
                // the exact patch, as before displacement was traced.
                traceUndisplaced[i] = patch;
                log.warnOnce("trace:displacedtessellation", at,
                             "a displaced surface would make more than " + many +
                                 " micropolygons for the ray tracer: it is traced undisplaced");
            } else {
                log.warnOnce("trace:tessellation", at,
                             "a surface would make more than " + many +
                                 " micropolygons for the ray tracer: it is left out of ray tracing and shadows");
            }
        }
    });
    if (!curved_.empty()) {
        std::vector<const TrilinearBody*> all;
        size_t n = bodies_.size();
        for (const std::deque<TrilinearBody>& d : micropolygons_) micropolygonCount_ += d.size();
        n += micropolygonCount_;
        all.reserve(n);
        size_t next = 0;  // of bodies_
        for (size_t i = 0; i < curved_.size(); ++i) {
            for (; next < curved_[i].at; ++next) all.push_back(bodies_[next]);
            for (const TrilinearBody& mp : micropolygons_[i]) all.push_back(&mp);
            if (traceUndisplaced[i]) all.push_back(traceUndisplaced[i]);
        }
        for (; next < bodies_.size(); ++next) all.push_back(bodies_[next]);
        bodies_ = std::move(all);
    }
    curved_ = {};
    include_.extend(Vec3f{0, 0, 0});  // the eye
    const float lens = scene.camera.lensRadius();  // and the lens, where eye rays start with depth of field
    include_.extend(Vec3f{-lens, -lens, 0});
    include_.extend(Vec3f{lens, lens, 0});
    std::vector<CameraLight> lights;
    for (double t : {scene.renderedStart, scene.renderedEnd}) {
        scene.lights.at(t, lights);
        for (const CameraLight& l : lights)
            if (shadowsTowardsPoint(l) && isFinite(l.position)) include_.extend(l.position);
    }
}

void TraceScene::collect(const Body& body, Log& log) {
    if (!body.time().overlaps(scene_.renderedStart, scene_.renderedEnd)) return;  // no ray is cast while it exists
    const auto* patch = dynamic_cast<const TrilinearBody*>(&body);
    if (patch && !displaced(body)) {
        bodies_.push_back(patch);
    } else if (body.expands()) {
        const auto* p = static_cast<const ProceduralBody*>(&body);
        bool expandedHere = false;
        leases_.push_back(p->children(*scene_.factory, scene_.cameras.during(p->time().t0, p->time().t1), log, &expandedHere));  // held as long as the scene
        const std::vector<BodyPtr>& children = leases_.back()->bodies;
        if (expandedHere) {
            const size_t d = size_t(p->depth());
            if (proceduralsExpandedByDepth.size() <= d) proceduralsExpandedByDepth.resize(d + 1, 0);
            ++proceduralsExpandedByDepth[d];
        }
        for (const BodyPtr& child : children) collect(*child, log);
    } else if (!body.diceableInTime()) {  // several motion keys: cut at the middle key
        BodyPtr halves[2];
        body.split(SplitAxis::T, halves);
        for (BodyPtr& h : halves) {
            collect(*h, log);
            pieces_.push_back(std::move(h));
        }
    } else if (displaced(body) && displacementReadsTime(*body.material())) {
        // Its surface changes with time even where it stands still: the micropolygons of each
        // frame's exposure apart (the rasterizer shades such a body per exposure), each frame's
        // cut from the body itself, so a frame's traced surface is the same in any frame block.
        const double open = scene_.shutter.open, close = scene_.shutter.close;
        const TimeSpan& span = body.time();
        const double a0 = std::max(span.t0, scene_.renderedStart), b0 = std::min(span.t1, scene_.renderedEnd);
        for (double f = std::ceil(a0 - close); f <= std::floor(b0 - open); f += 1) {
            const double a = std::max(span.t0, f + open), b = std::min(span.t1, f + close);
            if (a > b || !span.overlaps(a, b)) continue;
            pieces_.push_back(body.restrictedTo(a, b));
            curved_.push_back({pieces_.back().get(), bodies_.size()});
        }
    } else {  // a curved or displaced body: its micropolygons, made after collecting (see the constructor)
        curved_.push_back({&body, bodies_.size()});
    }
}

bool TraceScene::displaced(const Body& body) const {
    return shaders_ && body.material() && body.material()->displacement;
}

void TraceScene::setFrames(int first, int count) {
    windowStart_ = std::max(scene_.renderedStart, first + scene_.shutter.open);
    windowEnd_ = std::min(scene_.renderedEnd, first + count - 1 + scene_.shutter.close);
}

bool TraceScene::changesOverFrames() const {
    return std::any_of(bodies_.begin(), bodies_.end(), [&](const TrilinearBody* b) {
        return b->moving() || b->time().t0 > scene_.renderedStart || b->time().t1 < scene_.renderedEnd;
    });
}

void TraceScene::buildSpacetime(const HierarchyOptions& options) {
    const double cpu = processCpuSeconds();
    frames_.clear();
    spacetime_ = SpacetimeBVH{};  // the previous block's first
    spacetime_.build(bodies_, windowStart_, windowEnd_, include_, options, &scene_.solids);
    boundingVolumes += spacetime_.nodeCount();
    buildSeconds += processCpuSeconds() - cpu;
}

void TraceScene::buildShadowHierarchies(const HierarchyOptions& options) {
    const double cpu = processCpuSeconds();
    if (!shadowSplit_) {
        // windowStart and windowEnd are the shot's (RenderScene): the parting is the same whatever
        // frames are rendered, and so is every still vertex's test.
        markMovingSolids();
        for (const TrilinearBody* b : bodies_) {
            const bool still = !b->moving() && b->time().t0 <= scene_.windowStart &&
                               b->time().t1 >= scene_.windowEnd && !inMovingSolid(*b);
            (still ? stillBodies_ : movingBodies_).push_back(b);
        }
        collectShotMovers();
        // Shadow rays start on surfaces: the root cells need not hold the eye and the lights.
        // Still bodies are never cut in time: their hierarchy is the same over any frames.
        still_.build(stillBodies_, scene_.renderedStart, scene_.renderedEnd, Bounds3f{}, options, &scene_.solids);
        boundingVolumes += still_.nodeCount();
        shadowSplit_ = true;
    }
    movingBound_ = Bounds3f{};
    for (const TrilinearBody* b : movingBodies_)
        if (b->time().overlaps(windowStart_, windowEnd_))
            movingBound_.extend(
                b->boundDuring(std::max(windowStart_, b->time().t0), std::min(windowEnd_, b->time().t1)));
    moving_ = SpacetimeBVH{};  // the previous block's first
    moving_.build(movingBodies_, windowStart_, windowEnd_, Bounds3f{}, options, &scene_.solids);
    boundingVolumes += moving_.nodeCount();
    buildSeconds += processCpuSeconds() - cpu;
}

// A shadow ray resolves a solid from all the crossings of its tree, so a solid's members share
// one hierarchy: the moving one when any of them does not stand still through the shot (judged
// as collectShotMovers judges roots, and as buildShadowHierarchies judges the traced pieces).
void TraceScene::markMovingSolids() {
    movingSolids_.assign(scene_.solids.size(), 0);
    if (scene_.solids.empty()) return;
    auto mark = [&](const Body& b, bool still) {
        if (!still && b.material() && b.material()->solid >= 0)
            movingSolids_[size_t(scene_.solids.rootOf(b.material()->solid))] = 1;
    };
    for (const BodyPtr& root : scene_.roots) mark(*root, standsStillThroughShot(*root));
    for (const TrilinearBody* b : bodies_)
        mark(*b, !b->moving() && b->time().t0 <= scene_.windowStart && b->time().t1 >= scene_.windowEnd);
}

bool TraceScene::inMovingSolid(const Body& b) const {
    const Material* m = b.material();
    return m && m->solid >= 0 && !movingSolids_.empty() && movingSolids_[size_t(scene_.solids.rootOf(m->solid))];
}

bool TraceScene::standsStillThroughShot(const Body& b) const {
    return !b.moving() && !b.expands() && !(b.material() && b.material()->displacement) &&
           b.time().t0 <= scene_.windowStart && b.time().t1 >= scene_.windowEnd;
}

void TraceScene::collectShotMovers() {
    shotMoverBoxes_.clear();
    const double open = scene_.shutter.open, close = scene_.shutter.close;
    // A root stands still through the shot as buildShadowHierarchies' bodies do; a procedural may
    // hold moving children, and a displaced body may be displaced by time: both count as moving.
    std::vector<const Body*> movers;
    for (const BodyPtr& root : scene_.roots) {
        const Body& b = *root;
        const bool still = standsStillThroughShot(b) && !inMovingSolid(b);
        if (!still && b.time().overlaps(scene_.windowStart, scene_.windowEnd)) movers.push_back(&b);
    }
    shotMoverRoots_ = movers.size();
    if (movers.empty()) return;
    const double first = std::round(scene_.windowStart - open), last = std::round(scene_.windowEnd - close);
    const size_t frames = size_t(std::max(0.0, last - first) + 1);
    // Frames a box covers: one where the boxes fit, more (consecutive frames) where they would not.
    const size_t group = std::max<size_t>(1, (frames * movers.size() + kShotMoverBoxes - 1) / kShotMoverBoxes);
    shotFirstFrame_ = long(first);
    shotMoverGroup_ = group;
    shotMoverGroups_ = (frames + group - 1) / group;
    for (const Body* b : movers) {
        const TimeSpan& span = b->time();
        for (size_t f0 = 0; f0 < frames; f0 += group) {
            const double a = std::max(span.t0, first + double(f0) + open);
            const double e = std::min(span.t1, first + double(std::min(frames, f0 + group) - 1) + close);
            if (a > e || !span.overlaps(a, e)) {
                shotMoverBoxes_.push_back(Bounds3f{});  // not there in these frames
                continue;
            }
            Bounds3f box = b->boundDuring(a, e);
            if (const float r = b->material() ? b->material()->displacementBound : 0.0f; r > 0) {
                box.lo = box.lo - Vec3f{r, r, r};
                box.hi = box.hi + Vec3f{r, r, r};
            }
            shotMoverBoxes_.push_back(box);
        }
    }
}

void TraceScene::buildFrames(int first, int count, const HierarchyOptions& options) {
    HierarchyOptions o = options;
    o.splitTime = false;
    frames_.clear();  // release the previous block's hierarchies first
    frames_.resize(size_t(count));
    framesFirst_ = first;
    const double cpu = processCpuSeconds();
    tbb::parallel_for(0, count, [&](int i) {
        const double e0 = first + i + scene_.shutter.open, e1 = first + i + scene_.shutter.close;
        frames_[size_t(i)].build(bodies_, e0, e1, include_, o, &scene_.solids);
    });
    for (int i = 0; i < count; ++i) boundingVolumes += frames_[size_t(i)].nodeCount();
    buildSeconds += processCpuSeconds() - cpu;
}

size_t TraceScene::hierarchyBytes() const {
    size_t b = spacetime_.bytes() + still_.bytes() + moving_.bytes() +
               (stillBodies_.capacity() + movingBodies_.capacity()) * sizeof(const TrilinearBody*);
    for (const SpacetimeBVH& h : frames_) b += h.bytes();
    return b;
}

size_t TraceScene::buildBytes() const {
    size_t b = std::max({spacetime_.buildBytes(), still_.buildBytes(), moving_.buildBytes()});
    for (const SpacetimeBVH& h : frames_) b = std::max(b, h.buildBytes());
    return b;
}

size_t TraceScene::bytes() const {
    return bodies_.capacity() * sizeof(bodies_[0]) + pieces_.size() * (sizeof(TrilinearBody) + 16) +
           micropolygonCount_ * sizeof(TrilinearBody) + hierarchyBytes();
}

float TraceScene::shadowBias(float z, double time) const {
    const Camera& cam = scene_.cameras.during(time, time);  // a zoom's frame's pixel
    const float pixel = 1.0f / std::min(std::fabs(cam.ax()), std::fabs(cam.ay()));  // screen units
    return cam.perspective() ? pixel * std::fabs(z) : pixel;
}

}  // namespace streyes
