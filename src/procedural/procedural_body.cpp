#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <tbb/task_arena.h>

#include "procedural/procedural.h"

namespace streyes {

int detailLevel(double area) {
    if (!(area < 1e300)) return kDetailUnbounded;  // infinite or NaN: the bound reaches the eye plane
    if (area <= 1) return 0;
    return std::min(kDetailUnbounded - 1, int(std::ceil(std::log2(area))));
}

double detailOfLevel(int level) {
    return level >= kDetailUnbounded ? std::numeric_limits<double>::infinity() : std::ldexp(1.0, level);
}

// How many pixels a world unit spans near a procedural seen at `detail`: the side of a square
// of its raster area over its bound's longest side in world space (its transform's first key; the
// world its frame was written in, `sceneToWorld` from the scene's space), for what its output
// decides while it is read (a Blobby's cells, a Weber-Penn tree's range). Block-invariant, as the
// level is, and the same for a frame of a sequence as for that frame written as one world.
static double pixelsPerUnit(const ProceduralDesc& d, double detail, const Matrix4& sceneToWorld) {
    const Vec3d size = (d.objectToWorld.keys().front() * sceneToWorld).box(d.bound).diagonal();
    const double side = std::max({size.x, size.y, size.z});
    if (!(detail < std::numeric_limits<double>::infinity())) return detail;  // reaches the eye plane: the most
    return side > 0 && std::isfinite(side) ? std::sqrt(detail) / side : std::sqrt(detail);  // a point: per unit
}

ProceduralBody::ProceduralBody(ProceduralDesc desc, std::shared_ptr<const ProceduralGenerator> generator,
                               const Bounds3f& cameraBound, TimeSpan window, int depth, bool moving,
                               const ChildBodyMaker* maker)
    : desc_(std::move(desc)), generator_(std::move(generator)), maker_(maker), depth_(depth), bound_(cameraBound) {
    time_ = window;
    moving_ = moving;  // in camera space: its level of detail and bound change from frame to frame
}

std::unique_ptr<ProceduralBody> ProceduralBody::view(double a, double b, int level) const {
    const ProceduralBody& r = root();
    auto v = std::unique_ptr<ProceduralBody>(
        new ProceduralBody(ProceduralDesc{}, nullptr, boundDuring(a, b), TimeSpan{a, b, false}, r.depth_, false, r.maker_));
    v->root_ = &r;
    v->level_ = level;
    v->inheritFrom(*this);
    return v;
}

std::unique_ptr<Body> ProceduralBody::restrictedTo(double a, double b) const { return view(a, b, level_); }

Bounds3f ProceduralBody::boundDuring(double a, double b) const {
    const ProceduralBody& r = root();
    if (r.useGrown_) return r.grown_;  // the declared bound was too small: the union of what came out
    if (!moving_ || !r.maker_) return bound_;
    return r.maker_->cameraBound(r.desc_.bound, r.desc_.objectToWorld, a, b);
}

int ProceduralBody::level(const Camera& camera) const {
    if (level_ >= 0) return level_;
    if (camera.perspective() && bound().b0.lo.z < camera.eyePlane()) return kDetailUnbounded;
    const Bounds3f r = measure(camera).bound.b0;
    return detailLevel(double(r.hi.x - r.lo.x) * double(r.hi.y - r.lo.y));
}

LBBox3f ProceduralBody::bound() const {
    const Bounds3f& b = root().useGrown_ ? root().grown_ : bound_;
    return {b, b};
}

RasterMeasure ProceduralBody::measure(const Camera& camera) const {
    const Bounds3f b = bound().b0;
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
    ProceduralBody& r = const_cast<ProceduralBody&>(root());
    r.useGrown_ = true;
    for (ProceduralBody* p = const_cast<ProceduralBody*>(r.parent_); p; p = const_cast<ProceduralBody*>(p->parent_)) {
        if (!p->useGrown_) {
            p->useGrown_ = true;
            if (p->grown_.empty()) p->grown_ = p->bound_;
        }
        p->grown_.extend(r.grown_);
    }
}

void ProceduralBody::split(SplitAxis, std::unique_ptr<Body>[2]) const {
    throw std::logic_error("a procedural is expanded, not split");
}

size_t ProceduralBody::memoryBytes() const {
    size_t bytes = heapBlockBytes(sizeof(*this));
    if (root_) return bytes;  // a view: the description is its root's
    auto text = [](const std::string& s) { return s.capacity() > 15 ? heapBlockBytes(s.capacity() + 1) : 0; };
    bytes += text(desc_.kind) + text(desc_.directory) + text(desc_.proceduralPath) + text(desc_.archivePath);
    bytes += heapBlockBytes(desc_.args.capacity() * sizeof(std::string));
    for (const std::string& a : desc_.args) bytes += text(a);
    return bytes;
}

void ProceduralBody::dice(int, int, Grid&) const { throw std::logic_error("a procedural is expanded, not diced"); }

ChildrenLease ProceduralBody::children(ChildBodyMaker& maker, const Camera& camera, Log& log, bool* madeHere,
                                       bool* madeAgain) const {
    const ProceduralBody& r = root();
    const int lv = level(camera);
    for (;;) {
        std::shared_ptr<Expansion> e;
        bool again = false;  // made before and released: made again, not counted again
        {
            std::lock_guard<std::mutex> lock(r.mutex_);
            Level& slot = r.expansions_[lv];
            if (!slot.current) slot.current = std::make_shared<Expansion>();
            e = slot.current;
            again = slot.madeBefore;
        }
        std::call_once(e->once, [&] {
            if (madeHere) *madeHere = true;
            if (madeAgain) *madeAgain = again;
            auto made = std::make_shared<ProceduralChildren>();
            // Expansion may run parallel work (a subdivision mesh builds its faces with
            // parallel_for). A thread waiting for that work takes other tasks meanwhile; were it
            // to take another bucket that reaches this procedural, it would wait on the once-flag
            // it holds itself, for ever. Isolated, it takes only tasks of this expansion.
            tbb::this_task_arena::isolate([&] {
                try {
                    r.expand(*made, lv, maker, log, false, !again);
                } catch (...) {
                    e->error = std::current_exception();
                }
            });
            for (const BodyPtr& c : made->bodies)
                if (c->expands()) static_cast<const ProceduralBody&>(*c).heldBy_ = made;
            std::lock_guard<std::mutex> lock(r.mutex_);
            e->children = std::move(made);
        });
        if (e->error) std::rethrow_exception(e->error);
        std::lock_guard<std::mutex> lock(r.mutex_);
        if (e->children) return e->children;
        // Released between its making and this hold (by a release that did not expect this
        // caller): make it again.
    }
}

void ProceduralBody::release(int level) const {
    const ProceduralBody& r = root();
    std::shared_ptr<ProceduralChildren> freed;  // freed after the lock, when no hold is left
    std::lock_guard<std::mutex> lock(r.mutex_);
    auto it = r.expansions_.find(level);
    if (it == r.expansions_.end() || !it->second.current) return;
    freed = std::move(it->second.current->children);
    it->second.current.reset();
    it->second.madeBefore = true;
}

void ProceduralBody::expandInto(ProceduralChildren& out, ChildBodyMaker& maker, const Camera& camera, Log& log) const {
    const int lv = level(camera);
    tbb::this_task_arena::isolate([&] { root().expand(out, lv, maker, log, true, true); });  // as children() does
}

// `own`: the meshes go with the children (out.keep), not to the maker. `count`: the maker counts
// the bodies (not when they are made again after release()).
void ProceduralBody::expand(ProceduralChildren& out, int level, ChildBodyMaker& maker, Log& log, bool own,
                            bool count) const {
    ExpandContext ctx;
    ctx.detail = detailOfLevel(level);
    ctx.sceneToWorld = maker.sceneToWorld(desc_.life, desc_.objectToWorld.times().front());
    ctx.read.pixelsPerUnit = pixelsPerUnit(desc_, ctx.detail, ctx.sceneToWorld);
    ctx.objectToWorld = desc_.objectToWorld;
    ctx.attributes = desc_.attributes;
    ctx.loc = desc_.loc;
    ctx.windowStart = maker.windowStart();
    ctx.windowEnd = maker.windowEnd();
    ctx.depth = depth_;
    ctx.log = &log;
    ProceduralOutput output;
    generator_->expand(ctx, output);
    if (!desc_.life.always()) {  // one frame's procedural (a frame sequence): its children live as long
        setLifetime(output.scene, desc_.life);
        for (GeneratedProcedural& g : output.procedurals) g.desc.life = desc_.life;
    }
    maker.addChildren(output, primitiveId(), depth_ + 1, out.bodies, own ? &out.keep : nullptr, count);
    for (const BodyPtr& c : out.bodies)
        if (c->expands()) static_cast<const ProceduralBody&>(*c).parent_ = this;

    // Children reaching outside the declared bound are not lost: the renderer renders again
    // with the grown bound (see Renderer::render).
    Bounds3f grown = bound_;
    for (const BodyPtr& c : out.bodies) grown.extend(c->bound().swept());
    const float slack = 1e-4f * std::max({1.0f, std::fabs(bound_.lo.x), std::fabs(bound_.hi.x), std::fabs(bound_.lo.y),
                                          std::fabs(bound_.hi.y), std::fabs(bound_.lo.z), std::fabs(bound_.hi.z)});
    const bool outgrew = grown.lo.x < bound_.lo.x - slack || grown.lo.y < bound_.lo.y - slack ||
                         grown.lo.z < bound_.lo.z - slack || grown.hi.x > bound_.hi.x + slack ||
                         grown.hi.y > bound_.hi.y + slack || grown.hi.z > bound_.hi.z + slack;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (grown_.empty()) grown_ = bound_;
        grown_.extend(grown);
    }
    if (outgrew && !outgrew_.exchange(true)) {
        log.warnOnce("procedural-bound:" + desc_.loc.str(), desc_.loc,
                     generator_->describe() +
                         ": its children reach outside the declared bound; the frames are rendered again with "
                         "the bound they need (declare a larger bound to avoid the extra work)");
        maker.reportOutgrown(const_cast<ProceduralBody*>(this));
    }
}

}  // namespace streyes
