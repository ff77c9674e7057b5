#include <cmath>
#include <limits>
#include <stdexcept>

#include <tbb/task_arena.h>

#include "procedural/procedural.h"

namespace streyes {

ProceduralBody::ProceduralBody(ProceduralDesc desc, std::shared_ptr<const ProceduralGenerator> generator,
                               const Bounds3f& cameraBound, TimeSpan window, int depth)
    : desc_(std::move(desc)), generator_(std::move(generator)), bound_(cameraBound), depth_(depth) {
    time_ = window;
    moving_ = false;  // the bound covers the whole animation
}

LBBox3f ProceduralBody::bound() const {
    const Bounds3f& b = useGrown_ ? grown_ : bound_;
    return {b, b};
}

RasterMeasure ProceduralBody::measure(const Camera& camera) const {
    const Bounds3f& b = useGrown_ ? grown_ : bound_;
    RasterMeasure m;
    for (int i = 0; i < 8; ++i)
        m.bound.b0.extend(camera.toRaster({(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y,
                                           (i & 4) ? b.hi.z : b.lo.z}));
    m.bound.b1 = m.bound.b0;
    const Vec3f d = m.bound.b0.diagonal();
    m.extentU = d.x;
    m.extentV = d.y;
    return m;
}

CameraExtents ProceduralBody::cameraExtents() const {
    const Vec3f d = bound_.diagonal();
    return {d.x, d.y, 0};
}

void ProceduralBody::useGrownBound() {
    useGrown_ = true;
    for (ProceduralBody* p = const_cast<ProceduralBody*>(parent_); p; p = const_cast<ProceduralBody*>(p->parent_)) {
        if (!p->useGrown_) {
            p->useGrown_ = true;
            if (p->grown_.empty()) p->grown_ = p->bound_;
        }
        p->grown_.extend(grown_);
    }
}

void ProceduralBody::split(SplitAxis, std::unique_ptr<Body>[2]) const {
    throw std::logic_error("a procedural is expanded, not split");
}

std::unique_ptr<Body> ProceduralBody::restrictedTo(double, double) const {
    throw std::logic_error("a procedural spans the whole animation and is never restricted");
}

void ProceduralBody::dice(int, int, Grid&) const { throw std::logic_error("a procedural is expanded, not diced"); }

const std::vector<BodyPtr>& ProceduralBody::children(ChildBodyMaker& maker, const Camera& camera, Log& log,
                                                     bool* expandedHere) const {
    std::call_once(once_, [&] {
        if (expandedHere) *expandedHere = true;
        // Expansion may run parallel work (a subdivision mesh builds its faces with parallel_for).
        // A thread waiting for that work takes other tasks meanwhile; were it to take another
        // bucket that reaches this procedural, it would wait on the once-flag it holds itself,
        // for ever. Isolated, it takes only tasks of this expansion.
        tbb::this_task_arena::isolate([&] {
            try {
                expand(maker, camera, log);
            } catch (...) {
                error_ = std::current_exception();
            }
        });
        expanded_.store(true, std::memory_order_release);
    });
    if (error_) std::rethrow_exception(error_);
    return children_;
}

void ProceduralBody::expand(ChildBodyMaker& maker, const Camera& camera, Log& log) const {
    ExpandContext ctx;
    // RenderMan's detail: the raster area of the bound; unbounded when it reaches the eye plane.
    if (camera.perspective() && bound_.lo.z < camera.eyePlane()) {
        ctx.detail = std::numeric_limits<double>::infinity();
    } else {
        const Bounds3f r = measure(camera).bound.b0;
        ctx.detail = double(r.hi.x - r.lo.x) * double(r.hi.y - r.lo.y);
    }
    ctx.objectToWorld = desc_.objectToWorld;
    ctx.attributes = desc_.attributes;
    ctx.loc = desc_.loc;
    ctx.windowStart = maker.windowStart();
    ctx.windowEnd = maker.windowEnd();
    ctx.depth = depth_;
    ctx.log = &log;
    ProceduralOutput output;
    generator_->expand(ctx, output);
    maker.addChildren(output, primitiveId(), depth_ + 1, children_);
    for (const BodyPtr& c : children_)
        if (c->expands()) static_cast<const ProceduralBody&>(*c).parent_ = this;

    // Children reaching outside the declared bound are not lost: the renderer renders again
    // with the grown bound (see Renderer::render).
    grown_ = bound_;
    for (const BodyPtr& c : children_) grown_.extend(c->bound().swept());
    const float slack = 1e-4f * std::max({1.0f, std::fabs(bound_.lo.x), std::fabs(bound_.hi.x), std::fabs(bound_.lo.y),
                                          std::fabs(bound_.hi.y), std::fabs(bound_.lo.z), std::fabs(bound_.hi.z)});
    outgrew_ = grown_.lo.x < bound_.lo.x - slack || grown_.lo.y < bound_.lo.y - slack ||
               grown_.lo.z < bound_.lo.z - slack || grown_.hi.x > bound_.hi.x + slack ||
               grown_.hi.y > bound_.hi.y + slack || grown_.hi.z > bound_.hi.z + slack;
    if (outgrew_) {
        log.warnOnce("procedural-bound:" + desc_.loc.str(), desc_.loc,
                     generator_->describe() +
                         ": its children reach outside the declared bound; the frames are rendered again with "
                         "the bound they need (declare a larger bound to avoid the extra work)");
        maker.reportOutgrown(const_cast<ProceduralBody*>(this));
    }
}

}  // namespace streyes
