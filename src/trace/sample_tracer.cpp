// SampleTracer (trace/trace.h): per-sample shadow rays over an image block, and the per-vertex
// shadows of still grids, through TraceScene's hierarchies.
#include "trace/trace.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "film/film.h"
#include "shade/shading.h"

namespace streyes {

namespace {
// Calls fn(sample index, time) for every sample of the block, frame by frame, then pixel by
// pixel: consecutive rays share their frame's part of the hierarchy, which stays in cache (the
// block's own order, pixel then frame, jumps through time from one ray to the next).
// fn(hit, shadowed parts, position, lens point, frame, time, where) for every sample of every
// record (of a dense block: every frame's every pixel; of a sparse one, the still layer's
// samples are folded still grids', which need no shadow ray).
struct SampleAt {
    int fi;        // the frame's index in the block
    size_t pixel;  // the block's pixel index
    int sample;    // of the pixel
};
template <typename Fn>
void forEachSampleByFrame(ImageBlock& block, const Shutter& shutter, Fn fn) {
    const int S = block.samplesPerPixel();
    const int K = block.shadowSlots();
    const double exposure = shutter.close - shutter.open;
    for (int fi = 0; fi < block.frameCount(); ++fi) {
        const double start = block.firstFrame() + fi + shutter.open;
        for (size_t i = 0; i < size_t(block.pixelCount()); ++i) {
            SampleHit* hits = block.record(fi, i);
            if (!hits) continue;  // a sparse block's pixel that frame sees in the still layer
            Color* shadowed = K ? block.shadowed(fi, i) : nullptr;
            for (int j = 0; j < S; ++j) {
                const SamplePosition s = block.position(fi, i, j);
                const size_t si = i * size_t(S) + size_t(j);
                const Vec2f lens = block.hasLens() ? Vec2f{block.lus()[si], block.lvs()[si]} : Vec2f{0, 0};
                fn(hits[j], K ? shadowed + size_t(j) * size_t(K) : nullptr, s, lens, block.firstFrame() + fi,
                   start + double(s.tf) * exposure, SampleAt{fi, i, j});
            }
        }
    }
}
}  // namespace


namespace {
// Which of an area light's n points a shadow ray from p at `time` goes to: a hash of their bits.
int areaPointOf(Vec3f p, double time, int n) {
    uint32_t bits[3];
    std::memcpy(bits, &p, sizeof bits);
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (uint32_t b : bits) h = (h ^ b) * 0xff51afd7ed558ccdull, h ^= h >> 33;
    uint64_t tb;
    std::memcpy(&tb, &time, sizeof tb);
    h = (h ^ tb) * 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return int(h % uint64_t(n));
}
}  // namespace

namespace {
// Whether the ray from the origin along d (s >= 0) meets box c (slabs).
bool rayMeetsBox(Vec3f d, const Bounds3f& c) {
    float s0 = 0, s1 = std::numeric_limits<float>::infinity();
    const float o[3] = {0, 0, 0}, dd[3] = {d.x, d.y, d.z}, lo[3] = {c.lo.x, c.lo.y, c.lo.z}, hi[3] = {c.hi.x, c.hi.y, c.hi.z};
    for (int a = 0; a < 3; ++a) {
        if (dd[a] == 0) {
            if (o[a] < lo[a] || o[a] > hi[a]) return false;
            continue;
        }
        float ta = (lo[a] - o[a]) / dd[a], tb = (hi[a] - o[a]) / dd[a];
        if (ta > tb) std::swap(ta, tb);
        s0 = std::max(s0, ta);
        s1 = std::min(s1, tb);
        if (s0 > s1) return false;
    }
    return true;
}
}  // namespace

// The light slots (bit k: slot k, the first seven) that no moving occluder can shadow at any
// point a sample of the grid may stand on. Those points lie in the box of the grid's vertices
// (orthographic) or, under perspective, where the rasterizer rebuilds them from a raster
// position inside the projected vertices and a depth between theirs: x / z and y / z within the
// vertices' range, z within theirs. Depth of field moves them along lens rays: no cull then.
namespace {

// Whether a segment from somewhere in box g to the point L can meet box b. Segments from g to L
// lie in the box of both; and where g and b lie on one side of L along an axis (distance d > 0
// along it), seen from L (x / d, y / d across it) a segment is a point of g's outline, so b can
// meet one only if their outlines overlap and b begins before g ends.
bool segmentsMeetBox(const Bounds3f& g, const Bounds3f& b, Vec3f L) {
    Bounds3f hull = g;
    hull.extend(L);
    if (!hull.overlaps(b)) return false;
    for (int a = 0; a < 3; ++a) {
        const int u = (a + 1) % 3, v = (a + 2) % 3;
        for (float sign : {1.0f, -1.0f}) {
            // Each box's outline seen from L along sign * axis a, and its range of distances.
            auto outline = [&](const Bounds3f& box, float r[6]) {
                r[0] = r[2] = r[4] = std::numeric_limits<float>::infinity();
                r[1] = r[3] = r[5] = -r[0];
                for (int c = 0; c < 8; ++c) {
                    const Vec3f p{(c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y, (c & 4) ? box.hi.z : box.lo.z};
                    const float d = sign * (p[a] - L[a]);
                    if (!(d > 0)) return false;
                    const float x = (p[u] - L[u]) / d, y = (p[v] - L[v]) / d;
                    r[0] = std::min(r[0], x), r[1] = std::max(r[1], x);
                    r[2] = std::min(r[2], y), r[3] = std::max(r[3], y);
                    r[4] = std::min(r[4], d), r[5] = std::max(r[5], d);
                }
                return true;
            };
            float rg[6], rb[6];
            if (!outline(g, rg) || !outline(b, rb)) continue;
            // A margin for the divisions' rounding.
            const float eps = 1e-5f * (1.0f + std::max({std::fabs(rg[0]), std::fabs(rg[1]), std::fabs(rg[2]), std::fabs(rg[3])}));
            if (rb[0] > rg[1] + eps || rb[1] < rg[0] - eps || rb[2] > rg[3] + eps || rb[3] < rg[2] - eps) return false;
            if (rb[4] > rg[5] * (1.0f + 1e-5f)) return false;  // all of b beyond all of g
        }
    }
    return true;
}

// Whether a ray from somewhere in box g to light l (slot k's light li) can meet box b.
bool lightMeetsBox(const Bounds3f& g, const Bounds3f& b, const CameraLight& l, const LightSet& lights, int li,
                   double lightTime) {
    if (!shadowsTowardsPoint(l)) {
        // Rays g + s d, s >= 0, from any g in the grid's box meet b only if s d meets b - g
        // (each of a cone's directions).
        for (int j = 0; j < coneShadowSamples(l); ++j)
            if (rayMeetsBox(coneShadowDirection(l, j), Bounds3f{b.lo - g.hi, b.hi - g.lo})) return true;
        return false;
    }
    if (const int n = lights.areaSamples(li); n > 0) {
        for (int j = 0; j < n; ++j)
            if (segmentsMeetBox(g, b, lights.areaPoint(li, j, lightTime))) return true;
        return false;
    }
    return segmentsMeetBox(g, b, l.position);
}

// Rounding in points rebuilt from samples: a generous margin (it only makes the cull test more).
Bounds3f paddedForRounding(Bounds3f g) {
    const float pad = 1e-3f * (std::max({std::fabs(g.lo.x), std::fabs(g.hi.x), std::fabs(g.lo.y), std::fabs(g.hi.y),
                                         std::fabs(g.lo.z), std::fabs(g.hi.z)}) + 1.0f);
    g.lo = g.lo - Vec3f{pad, pad, pad};
    g.hi = g.hi + Vec3f{pad, pad, pad};
    return g;
}

}  // namespace

unsigned SampleTracer::unblockedByMoving(Grid& grid, const TraceScene& trace, const std::vector<CameraLight>& ls,
                                         double lightTime, int firstFrame, int frameCount) {
    const RenderScene& scene = trace.scene();
    grid.frameShadows.clear();
    if (!trace.anyMovingOccluder()) return kUnblockedBits;
    const Camera& cam = scene.camera;
    if (cam.depthOfField()) return 0;
    Bounds3f g;
    if (cam.perspective()) {
        float rx0 = std::numeric_limits<float>::infinity(), rx1 = -rx0, ry0 = rx0, ry1 = -rx0, z0 = rx0, z1 = -rx0;
        for (const Vec3f& p : grid.P[0]) {
            if (!(p.z > 0)) return 0;
            rx0 = std::min(rx0, p.x / p.z), rx1 = std::max(rx1, p.x / p.z);
            ry0 = std::min(ry0, p.y / p.z), ry1 = std::max(ry1, p.y / p.z);
            z0 = std::min(z0, p.z), z1 = std::max(z1, p.z);
        }
        for (float rx : {rx0, rx1})
            for (float ry : {ry0, ry1})
                for (float z : {z0, z1}) g.extend(Vec3f{rx * z, ry * z, z});
    } else {
        for (const Vec3f& p : grid.P[0]) g.extend(p);
    }
    g = paddedForRounding(g);
    const Bounds3f& b = trace.movingBound();
    const LightSet& lights = scene.lights;
    const int K = std::min(grid.shadowSlots, kUnblockedSlots);
    unsigned bits = 0;
    for (int k = 0; k < K; ++k) {
        const int li = lights.shadowLight(k);
        if (!lightMeetsBox(g, b, ls[size_t(li)], lights, li, lightTime)) bits |= 1u << k;
    }
    // Frame by frame, against the moving roots' boxes of that frame, where the block-wide box
    // leaves some light.
    const unsigned all = (1u << K) - 1u;
    grid.frameShadows.clear();
    if (bits == all || frameCount <= 0 || trace.shotMoverGroups() == 0) return bits;
    grid.frameShadowsFirst = firstFrame;
    grid.frameShadows.resize(size_t(frameCount));
    const std::vector<Bounds3f>& boxes = trace.shotMoverBoxes();
    const size_t roots = trace.shotMoverRoots(), groups = trace.shotMoverGroups();
    for (int fi = 0; fi < frameCount; ++fi) {
        unsigned fb = bits;
        const long gi = trace.shotMoverGroupOf(firstFrame + fi);
        if (gi >= 0) {
            for (int k = 0; k < K; ++k) {
                if (fb & (1u << k)) continue;
                const int li = lights.shadowLight(k);
                bool clear = true;
                for (size_t r = 0; r < roots && clear; ++r) {
                    const Bounds3f& box = boxes[r * groups + size_t(gi)];
                    clear = box.empty() || !lightMeetsBox(g, box, ls[size_t(li)], lights, li, lightTime);
                }
                if (clear) fb |= 1u << k;
            }
        }
        grid.frameShadows[size_t(fi)] = uint8_t(1u | (fb << 1));
    }
    return bits;
}

bool SampleTracer::frameClear(const Grid& grid, const TraceScene& trace, const std::vector<CameraLight>& ls,
                              double lightTime, int frame) {
    if (trace.shotMoverRoots() == 0) return true;
    const long gi = trace.shotMoverGroupOf(frame);
    if (gi < 0) return false;
    // A sample's hit lies on a micropolygon: in the box of the grid's vertices.
    Bounds3f g;
    for (const Vec3f& p : grid.P[0]) {
        if (!isFinite(p)) return false;
        g.extend(p);
    }
    g = paddedForRounding(g);
    const LightSet& lights = trace.scene().lights;
    const std::vector<Bounds3f>& boxes = trace.shotMoverBoxes();
    for (size_t r = 0; r < trace.shotMoverRoots(); ++r) {
        const Bounds3f& b = boxes[r * trace.shotMoverGroups() + size_t(gi)];
        if (b.empty()) continue;
        for (int k = 0; k < grid.shadowSlots; ++k) {
            const int li = lights.shadowLight(k);
            if (lightMeetsBox(g, b, ls[size_t(li)], lights, li, lightTime)) return false;
        }
    }
    return true;
}

const std::vector<CameraLight>& SampleTracer::lightsAt(const LightSet& lights, double t) {
    if (!lightsValid_ || (!lights.isStatic() && t != lightsTime_)) {
        lights.at(t, lights_);
        lightsTime_ = t;
        lightsValid_ = true;
    }
    return lights_;
}

Color SampleTracer::addVisibleLights(Color c, Vec3f p, double time, const Color* shadowed, const TraceScene& trace,
                                     const SpacetimeBVH& bvh, RenderCounters& counters, const SpacetimeBVH* also,
                                     unsigned unblocked) {
    const LightSet& lights = trace.scene().lights;
    const float bias = trace.shadowBias(p.z, time);
    for (int k = 0; k < lights.shadowSlots(); ++k) {
        const Color part = shadowed[k];
        if (part.x == 0 && part.y == 0 && part.z == 0) continue;  // the light does not reach p anyway
        if (k < 31 && (unblocked >> k) & 1u) {
            c += part;
            continue;
        }
        const int li = lights.shadowLight(k);
        const CameraLight& l = lightsAt(lights, time)[size_t(li)];
        Ray ray{p, l.direction};
        float tMax = std::numeric_limits<float>::infinity();
        // A cone (the sun's disc): one of its directions, picked by the hash that picks an area
        // light's point, so that a pixel's samples spread over it (soft shadows) alike in any block.
        if (const int n = coneShadowSamples(l); n > 1) ray.d = coneShadowDirection(l, areaPointOf(p, time, n));
        if (shadowsTowardsPoint(l)) {
            // An area light: towards one of its points, picked by a hash of the shaded point, so
            // that a pixel's samples spread over the light (soft shadows) the same in any block.
            Vec3f target = l.position;
            if (const int n = lights.areaSamples(li); n > 0) target = lights.areaPoint(li, areaPointOf(p, time, n), time);
            const Vec3f d = target - p;
            const float dist = length(d);
            if (!(dist > 2 * bias)) {  // the light sits on the surface: nothing between
                c += part;
                continue;
            }
            ray.d = d / dist;
            tMax = dist - bias;
        }
        ++counters.shadowRays;
        if (!bvh.occluded(ray, time, bias, tMax, ctx_) && !(also && also->occluded(ray, time, bias, tMax, ctx_)))
            c += part;
    }
    return c;
}

// The eye ray of a sample: from the eye through its raster position (perspective) or parallel to
// +z (orthographic); with depth of field from its lens point R (lu, lv) through the point of the
// focal plane z = d the pinhole sees there (geom/camera.h). Every way the direction has z = 1, so
// the ray parameter is camera-space z and the near and far planes clip it directly.
namespace {
Ray eyeRay(const Camera& cam, float x, float y, Vec2f lens) {
    if (!cam.perspective()) return {cam.fromRaster(x, y, 0), {0, 0, 1}};
    if (!cam.depthOfField()) return {{0, 0, 0}, cam.fromRaster(x, y, 1)};
    const float d = cam.focalDistance();
    const Vec3f o{cam.lensRadius() * lens.x, cam.lensRadius() * lens.y, 0};
    return {o, (cam.fromRaster(x, y, d) - o) * (1.0f / d)};
}
}  // namespace

void SampleTracer::traceSamples(ImageBlock& block, const TraceScene& trace, RenderCounters& counters) {
    const RenderScene& scene = trace.scene();
    const Camera& cam = scene.camera;
    const bool ortho = !cam.perspective();
    const int K = scene.lights.shadowSlots();
    shadowed_.resize(size_t(K));
    const uint64_t testsBefore = ctx_.bodyTests, boxesBefore = ctx_.boxTests;
    forEachSampleByFrame(block, scene.shutter, [&](SampleHit& hit, Color*, const SamplePosition& s, Vec2f lens, int frame,
                                                   double time, const SampleAt& at) {
        const Ray ray = eyeRay(scene.cameras.ofFrame(frame), s.x, s.y, lens);  // a zoom's frame's
        const SpacetimeBVH& bvh = trace.hierarchy(frame);
        ++counters.eyeRays;
        // Nearest first: a see-through hit (Oi < 1) adds its colour through what is in front and
        // the ray goes on past it, as the rasterizer's fragments are composited (film.h).
        OverComposite over;
        float nearestZ = 0;  // of the see-through layers
        uint64_t nearestId = kNoPrimitive;
        float tNear = cam.nearClip();
        TraceHit h;
        ctx_.dissolve = {&block, at.fi, at.pixel, at.sample};  // a level of detail's share (TraceContext)
        struct Reset {
            TraceContext& ctx;
            ~Reset() { ctx.dissolve.block = nullptr; }
        } reset{ctx_};
        bool walking = false;  // through solids' boundaries, from outside every solid at the eye
        while (bvh.intersect(ray, time, tNear, cam.farClip(), &h, ctx_)) {
            const TrilinearBody& body = *bvh.bodies()[h.body];
            const Vec3f p = ray.o + ray.d * h.t;
            const Vec3f n = bilinearNormal(body.cornersAt(time), h.u, h.v);
            if (const Material* sm = body.material(); sm && sm->solid >= 0 && !scene.solids.empty()) {
                // A crossing of a solid's boundary is a surface only where the solid's result
                // begins or ends (the rasterizer's fragments are resolved alike, film.cpp).
                if (!walking) solidWalk_.reset(scene.solids), walking = true;
                const bool entering = dot(sm->flipNormals ? -n : n, ray.d) < 0;
                if (!solidWalk_.cross(sm->solid, entering)) {
                    tNear = std::nextafter(h.t, std::numeric_limits<float>::infinity());
                    continue;
                }
            }
            const Material& m = *body.material();
            if (m.matte) {
                // A holdout (Matte 1): opaque, and nothing of its own. What is in front of it is
                // kept as one fragment over its hit, which resolves to colour 0 and alpha 0.
                hit = {p.z, {0, 0, 0}, hitId(body.primitiveId(), true)};
                if (over.t == Color{1, 1, 1}) return;
                block.startFragments();
                block.addFragment(block.recordFragments(at.fi, at.pixel) + at.sample,
                                  SampleFragment{nearestZ, over.c, over.t, nearestId, -1});
                return;
            }
            const Color cs = bilerp(body.colors(), h.u, h.v);
            const std::vector<CameraLight>& lights =
                lightsAt(scene.lights, time);  // refreshed per sample only when lights or camera move
            Color o = m.Os;
            Color c = m.surface && shader_
                          ? shader_->shadeHit(m, cs, p, n, time, body.uv[0] + h.u * (body.uv[1] - body.uv[0]),
                                              body.uv[2] + h.v * (body.uv[3] - body.uv[2]), body.primitiveId(),
                                              K ? shadowed_.data() : nullptr, K, &o, body.primvarCorners)
                          : shadePoint(m, cs, p, n, ortho, lights, K ? shadowed_.data() : nullptr, K);
            if (K) c = addVisibleLights(c, p, time, shadowed_.data(), trace, bvh, counters);
            o = {std::clamp(o.x, 0.0f, 1.0f), std::clamp(o.y, 0.0f, 1.0f), std::clamp(o.z, 0.0f, 1.0f)};
            const bool opaque = o.x >= 1 && o.y >= 1 && o.z >= 1;
            if (opaque && over.t == Color{1, 1, 1}) {
                hit = {p.z, c, hitId(body.primitiveId(), false)};  // nothing in front: its colour as it is
                return;
            }
            if (over.t == Color{1, 1, 1}) nearestZ = p.z, nearestId = hitId(body.primitiveId(), false);
            over.add(c, Color{1, 1, 1} - o);
            if (opaque) {  // the opaque hit behind see-through ones
                hit = {p.z, over.c, hitId(body.primitiveId(), false)};
                return;
            }
            tNear = std::nextafter(h.t, std::numeric_limits<float>::infinity());
        }
        if (over.t == Color{1, 1, 1}) return;  // nothing seen
        // See-through layers alone: one fragment of what they make together, over no opaque hit,
        // composited when the block is resolved as the rasterizer's fragments are (film.h).
        block.startFragments();
        const SampleFragment layers{nearestZ, over.c, over.t, nearestId, -1};
        block.addFragment(block.recordFragments(at.fi, at.pixel) + at.sample, layers);
    });
    counters.rayBodyTests += ctx_.bodyTests - testsBefore;
    counters.rayBoxTests += ctx_.boxTests - boxesBefore;
}

// The rasterizer's hit point is rebuilt from the sample's eye ray (through its lens point, with
// depth of field) and depth.
void SampleTracer::shadeShadows(ImageBlock& block, const TraceScene& trace, RenderCounters& counters) {
    const RenderScene& scene = trace.scene();
    const uint64_t testsBefore = ctx_.bodyTests, boxesBefore = ctx_.boxTests;
    // The point a sample's eye ray (through its lens point, with depth of field) meets at depth z.
    auto pointAt = [&](const SamplePosition& s, Vec2f lens, float z, int frame) {
        const Camera& cam = scene.cameras.ofFrame(frame);
        if (!cam.depthOfField()) return cam.fromRaster(s.x, s.y, z);
        const Ray ray = eyeRay(cam, s.x, s.y, lens);
        return ray.o + ray.d * z;
    };
    const bool split = trace.hasShadowHierarchies();
    const bool anyMoving = split && trace.anyMovingOccluder();
    const int K = scene.lights.shadowSlots();
    // c plus the parts whose lights the sample at depth z sees (`tested`: the still occluders'
    // shadow is in the parts already, from its grid's vertices).
    // `tested`: Grid::stillShadows' bits.
    auto lit = [&](Color c, const Color* parts, uint8_t tested, const SamplePosition& s, Vec2f lens, float z, int frame,
                   double time) {
        if (tested == kFoldedShadows) return c;  // the parts are in c already
        if (!split) return addVisibleLights(c, pointAt(s, lens, z, frame), time, parts, trace, trace.hierarchy(frame), counters);
        if (!(tested & 1))
            return addVisibleLights(c, pointAt(s, lens, z, frame), time, parts, trace, trace.stillOccluders(), counters,
                                    anyMoving ? &trace.movingOccluders() : nullptr);
        const unsigned unblocked = unsigned(tested) >> 1;
        if (anyMoving && unblocked != (1u << std::min(K, kUnblockedSlots)) - 1u)
            return addVisibleLights(c, pointAt(s, lens, z, frame), time, parts, trace, trace.movingOccluders(), counters,
                                    nullptr, unblocked);
        for (int k = 0; k < K; ++k) {  // no moving occluder in the way: no ray at all (zero parts skipped as there)
            const Color part = parts[k];
            if (part.x == 0 && part.y == 0 && part.z == 0) continue;
            c += part;
        }
        return c;
    };
    forEachSampleByFrame(block, scene.shutter,
                         [&](SampleHit& hit, Color* shadowed, const SamplePosition& s, Vec2f lens, int frame,
                             double time, const SampleAt& at) {
        const int32_t fragments = block.hasFragments() ? block.recordFragments(at.fi, at.pixel)[at.sample] : -1;
        if (!hit.empty())
            hit.c = lit(hit.c, shadowed, block.stillTested(at.fi, at.pixel)[at.sample], s, lens, hit.z, frame, time);
        // See-through fragments likewise, each from its own depth.
        for (int32_t k = fragments; k >= 0; k = block.fragment(k).next) {
            SampleFragment& f = block.fragment(k);
            f.c = lit(f.c, block.fragmentShadowed(k), *block.fragmentStillTested(k), s, lens, f.z, frame, time);
        }
    });
    counters.rayBodyTests += ctx_.bodyTests - testsBefore;
    counters.rayBoxTests += ctx_.boxTests - boxesBefore;
}

void SampleTracer::occludeStillVertices(Grid& grid, const TraceScene& trace, RenderCounters& counters, int firstFrame,
                                        int frameCount) {
    grid.frameShadows.clear();
    grid.CiFolded.clear();
    const LightSet& lights = trace.scene().lights;
    const SpacetimeBVH& bvh = trace.stillOccluders();
    const double time = trace.stillTime();  // still occluders and camera: any time answers alike
    // The lights at the grid's own time: in a frame sequence, a frame's area light is in that
    // frame's camera space (the grid lives within its frame).
    const double lightTime = std::clamp(grid.t0, trace.scene().renderedStart, trace.scene().renderedEnd);
    const std::vector<CameraLight>& ls = lightsAt(lights, lightTime);
    const int K = grid.shadowSlots;
    const uint64_t testsBefore = ctx_.bodyTests, boxesBefore = ctx_.boxTests;
    Color* cl = grid.Cl[0].data();
    for (int v = 0; v < grid.vertexCount(); ++v) {
        const Vec3f p = grid.P[0][size_t(v)];
        const float bias = trace.shadowBias(p.z, time);
        for (int k = 0; k < K; ++k) {
            Color& part = cl[size_t(v) * size_t(K) + size_t(k)];
            if (part.x == 0 && part.y == 0 && part.z == 0) continue;  // the light does not reach p anyway
            const int li = lights.shadowLight(k);
            const CameraLight& l = ls[size_t(li)];
            // Whether a ray from p to `target` (a point light's) or along the light's direction
            // reaches it past the still occluders.
            auto reaches = [&](const Vec3f* target, const Vec3f* direction = nullptr) {
                Ray ray{p, direction ? *direction : l.direction};
                float tMax = std::numeric_limits<float>::infinity();
                if (target) {
                    const Vec3f d = *target - p;
                    const float dist = length(d);
                    if (!(dist > 2 * bias)) return true;  // the light sits on the surface: nothing between
                    ray.d = d / dist;
                    tMax = dist - bias;
                }
                ++counters.shadowVertexRays;
                return !bvh.occluded(ray, time, bias, tMax, ctx_);
            };
            if (!shadowsTowardsPoint(l)) {
                // A directional light: along its direction, or the share of its cone's directions
                // that get through (the per-sample path picks one a sample).
                const int n = coneShadowSamples(l);
                if (n == 1) {
                    if (!reaches(nullptr)) part = {0, 0, 0};
                } else {
                    int seen = 0;
                    for (int j = 0; j < n; ++j) {
                        const Vec3f d = coneShadowDirection(l, j);
                        seen += reaches(nullptr, &d);
                    }
                    if (seen < n) part = part * (float(seen) / float(n));
                }
            } else if (const int n = lights.areaSamples(li); n > 0) {
                // Every point of the area light (the per-sample path picks one a sample, and a
                // pixel's samples spread over them): the share it sees, smooth over the grid.
                int seen = 0;
                for (int j = 0; j < n; ++j) {
                    const Vec3f target = lights.areaPoint(li, j, lightTime);
                    seen += reaches(&target);
                }
                if (seen < n) part = part * (float(seen) / float(n));
            } else {
                const Vec3f target = l.position;
                if (!reaches(&target)) part = {0, 0, 0};
            }
        }
    }
    // Frame by frame: whether no moving root's box of that frame (made over the shot: the same
    // whatever frames are rendered) meets the rays from this grid to its lights. In such a frame
    // its shadows are all decided here, and its samples take the colour with them added
    // (CiFolded); in every frame of the block, the grid's own colour is that (folded: it samples
    // into the still layer as an unshadowed still grid does). Either way a frame's samples get
    // the same colours whatever its block.
    bool all = frameCount > 0;
    foldFrames_.assign(size_t(std::max(frameCount, 0)), 0);
    for (int fi = 0; fi < frameCount; ++fi) {
        foldFrames_[size_t(fi)] = frameClear(grid, trace, ls, lightTime, firstFrame + fi);
        all = all && foldFrames_[size_t(fi)];
    }
    bool any = false;
    for (uint8_t f : foldFrames_) any = any || f;
    if (all) {
        Color* ci = grid.Ci[0].data();
        for (int v = 0; v < grid.vertexCount(); ++v) {
            Color* parts = &cl[size_t(v) * size_t(K)];
            for (int k = 0; k < K; ++k) ci[v] += parts[k], parts[k] = {0, 0, 0};
        }
        grid.stillShadows = kFoldedShadows;
        ++counters.shadowFoldedGrids;
    } else {
        grid.stillShadows = uint8_t(1u | (unblockedByMoving(grid, trace, ls, lightTime, firstFrame, frameCount) << 1));
        if (any) {
            grid.CiFolded.assign(grid.Ci[0].begin(), grid.Ci[0].end());
            for (int v = 0; v < grid.vertexCount(); ++v)
                for (int k = 0; k < K; ++k) grid.CiFolded[size_t(v)] += cl[size_t(v) * size_t(K) + size_t(k)];
            if (grid.frameShadows.empty()) {
                grid.frameShadowsFirst = firstFrame;
                grid.frameShadows.assign(size_t(frameCount), grid.stillShadows);
            }
            for (int fi = 0; fi < frameCount; ++fi)
                if (foldFrames_[size_t(fi)]) grid.frameShadows[size_t(fi)] = kFoldedShadows;
        }
    }
    counters.rayBodyTests += ctx_.bodyTests - testsBefore;
    counters.rayBoxTests += ctx_.boxTests - boxesBefore;
}

}  // namespace streyes
