#include "trace/shader_rays.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "bodies/material.h"
#include "shade/shading.h"

namespace streyes {

namespace {

constexpr float kPi = 3.14159265358979323846f;

uint64_t mix64(uint64_t h) {
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return h;
}

// A point's own offset of the sample pattern: a hash of its position's bits, the grid's seed
// and the call site (a pure function of what the point is, never of the block). Not of the
// time: a point that stays still casts the same rays in every frame, so what stays still does
// not flicker.
uint64_t pointHash(Vec3f p, unsigned seed, uint32_t site) {
    uint32_t bits[3];
    std::memcpy(bits, &p, sizeof bits);
    uint64_t h = 0x9e3779b97f4a7c15ull ^ (uint64_t(seed) << 32 | site);
    for (uint32_t b : bits) h = mix64(h ^ b);
    return h;
}

float radicalInverse2(uint32_t i) {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
    i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
    i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
    i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
    return float(i) * 2.3283064365386963e-10f;
}

// Sample j of s: a Hammersley point shifted by the point's offset (Cranley-Patterson), so that
// each point's s directions are stratified and neighbours' patterns do not line up.
void sample2(uint32_t j, uint32_t s, uint64_t h, float* a, float* b) {
    const float ra = float(h >> 40) * (1.0f / 16777216.0f), rb = float((h >> 16) & 0xffffff) * (1.0f / 16777216.0f);
    *a = (float(j) + 0.5f) / float(s) + ra;
    *b = radicalInverse2(j) + rb;
    if (*a >= 1) *a -= 1;
    if (*b >= 1) *b -= 1;
}

// An orthonormal frame about unit n (Duff et al. 2017).
void frameOf(Vec3f n, Vec3f* t, Vec3f* b) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    *t = {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
    *b = {c, sign + n.y * n.y * a, -n.y};
}

// A direction in the cone of half-angle `cone` about n (its frame t, b): cosine-weighted
// (sin^2 of the angle uniform in [0, sin^2 cone]) when `cosine`, else uniform in solid angle.
Vec3f coneDirection(Vec3f n, Vec3f t, Vec3f b, float cone, bool cosine, float ua, float ub) {
    float sinT, cosT;
    if (cosine) {
        const float s = std::sin(std::min(cone, 0.5f * kPi));
        sinT = std::sqrt(ua) * s;
        cosT = std::sqrt(std::max(0.0f, 1 - sinT * sinT));
    } else {
        cosT = 1 - ua * (1 - std::cos(cone));
        sinT = std::sqrt(std::max(0.0f, 1 - cosT * cosT));
    }
    const float phi = 2 * kPi * ub;
    return t * (sinT * std::cos(phi)) + b * (sinT * std::sin(phi)) + n * cosT;
}

Vec3f at3(const float* const* a, int i) { return {a[0][i], a[1][i], a[2][i]}; }

}  // namespace

ShaderRays::ShaderRays(const TraceScene& trace, const SceneShaders* shaders, int depth, int maxDepth)
    : trace_(trace), shaders_(shaders), depth_(depth), maxDepth_(maxDepth) {}

ShaderRays::~ShaderRays() = default;

void ShaderRays::takeCounters(RenderCounters& out) {
    out.shaderRays += rays_;
    out.rayBodyTests += ctx_.bodyTests - bodyTests_;
    out.rayBoxTests += ctx_.boxTests - boxTests_;
    rays_ = 0;
    bodyTests_ = ctx_.bodyTests;
    boxTests_ = ctx_.boxTests;
    if (hitShader_) hitShader_->takeCounters(out);
    if (next_) next_->takeCounters(out);
}

// The hierarchy of the frame whose exposure holds `time` (one for all under spacetime tracing).
const SpacetimeBVH& ShaderRays::hierarchyAt(double time) const {
    const int frame = int(std::floor(time - trace_.scene().shutter.open + 1e-9));
    return trace_.hierarchy(frame);
}

// One pixel's footprint at the point unless the call gives its own: the shadow rays' bias.
float ShaderRays::biasAt(const sl::RayOptions& o, Vec3f p, double time) const {
    return o.bias >= 0 ? o.bias : trace_.shadowBias(p.z, time);
}

const std::vector<CameraLight>& ShaderRays::lightsAt(double t) {
    const LightSet& lights = trace_.scene().lights;
    if (!lightsValid_ || (!lights.isStatic() && t != lightsTime_)) {
        lights.at(t, lights_);
        lightsTime_ = t;
        lightsValid_ = true;
    }
    return lights_;
}

// As SampleTracer::addVisibleLights does for the rasterizer's samples: each light that casts
// shadows adds its part where a shadow ray reaches it (an area light: the point a hash picks).
Color ShaderRays::addReachedLights(Color c, Vec3f p, double time, const SpacetimeBVH& bvh) {
    const LightSet& lights = trace_.scene().lights;
    const float bias = trace_.shadowBias(p.z, time);
    for (int k = 0; k < lights.shadowSlots(); ++k) {
        const Color part = shadowed_[size_t(k)];
        if (part.x == 0 && part.y == 0 && part.z == 0) continue;
        const int li = lights.shadowLight(k);
        const CameraLight& l = lightsAt(time)[size_t(li)];
        Ray ray{p, l.direction};
        float tMax = std::numeric_limits<float>::infinity();
        if (const int n = coneShadowSamples(l); n > 1)  // a cone: one of its directions, as for area lights
            ray.d = coneShadowDirection(l, int(pointHash(p, 0, uint32_t(k)) % uint64_t(n)));
        if (shadowsTowardsPoint(l)) {
            Vec3f target = l.position;
            if (const int n = lights.areaSamples(li); n > 0)
                target = lights.areaPoint(li, int(pointHash(p, 0, uint32_t(k)) % uint64_t(n)), time);
            const Vec3f d = target - p;
            const float dist = length(d);
            if (!(dist > 2 * bias)) {
                c += part;
                continue;
            }
            ray.d = d / dist;
            tMax = dist - bias;
        }
        ++rays_;
        if (!bvh.occluded(ray, time, bias, tMax, ctx_)) c += part;
    }
    return c;
}

// A hit shaded as the eye rays' hits are (SampleTracer::traceSamples): its own surface shader on
// a grid of one point, at the next ray depth, or the built-in shading.
Color ShaderRays::shadeHit(const TrilinearBody& body, const TraceHit& h, const Ray& ray, double time, Color* opacity) {
    const Vec3f p = ray.o + ray.d * h.t;
    const Vec3f n = bilinearNormal(body.cornersAt(time), h.u, h.v);
    const Color cs = bilerp(body.colors(), h.u, h.v);
    const Material& m = *body.material();
    const RenderScene& scene = trace_.scene();
    const int K = scene.lights.shadowSlots();
    shadowed_.resize(size_t(K));
    *opacity = m.Os;
    Color c;
    if (m.surface && shaders_) {
        hitShader().setRayContext(depth_, rayType_);
        c = hitShader_->shadeHit(m, cs, p, n, time, body.uv[0] + h.u * (body.uv[1] - body.uv[0]),
                                 body.uv[2] + h.v * (body.uv[3] - body.uv[2]), body.primitiveId(),
                                 K ? shadowed_.data() : nullptr, K, opacity, body.primvarCorners);
    } else {
        c = shadePoint(m, cs, p, n, !scene.camera.perspective(), lightsAt(time), K ? shadowed_.data() : nullptr, K);
    }
    if (K) c = addReachedLights(c, p, time, hierarchyAt(time));
    *opacity = {std::clamp(opacity->x, 0.0f, 1.0f), std::clamp(opacity->y, 0.0f, 1.0f), std::clamp(opacity->z, 0.0f, 1.0f)};
    return c;
}

GridShader& ShaderRays::hitShader() {
    if (!hitShader_) {
        const RenderScene& scene = trace_.scene();
        hitShader_ = std::make_unique<GridShader>(shaders_, scene.camera, scene.lights);
        if (depth_ < maxDepth_) next_ = std::make_unique<ShaderRays>(trace_, shaders_, depth_ + 1, maxDepth_);
        hitShader_->setRaySource(next_.get());  // null past the depth: no-hit values
    }
    return *hitShader_;
}

ShaderRays::Volume ShaderRays::volumeAt(const TrilinearBody& body, const TraceHit& h, const Ray& ray, double time,
                                        bool after) const {
    const Material* m = body.material();
    if (!m || !shaders_ || (!m->interior && !m->exterior)) return {};
    Vec3f n = bilinearNormal(body.cornersAt(time), h.u, h.v);
    if (m->flipNormals) n = -n;  // the side Orientation calls outside
    const bool leaves = dot(ray.d, n) > 0;
    const bool inside = after ? !leaves : leaves;
    const Attributes* a = m->attributes;
    if (inside) return {m, m->interior.get(), a ? &a->interior.shaderToWorld : nullptr};
    return {m, m->exterior.get(), a ? &a->exterior.shaderToWorld : nullptr};
}

Color ShaderRays::runVolume(const Volume& v, Vec3f from, Vec3f to, double time, Color c, Color* o) {
    GridShader& g = hitShader();
    g.setRayContext(depth_, rayType_);
    return g.runVolume(*v.material, *v.shader, v.space, from, to, time, c, o);
}

// The mean colour the shaded hits of s rays in the cone of half-angle `cone` around `axis` give
// (cosine-weighted or uniform): indirectdiffuse() and blurred trace(). A ray that hits nothing
// brings the environment map's colour in its direction (looked up for the point's s rays at once,
// each over its share of the cone), or black.
Color ShaderRays::coneMean(Vec3f p, Vec3f axis, float cone, bool cosine, uint32_t s, uint64_t h, double time,
                           float bias, float maxdist, const sl::RayOptions* env, float* hitShare) {
    Vec3f t, b;
    frameOf(axis, &t, &b);
    directions_.resize(s);
    background_.assign(s, Color{0, 0, 0});
    for (uint32_t j = 0; j < s; ++j) {
        float ua, ub;
        sample2(j, s, h, &ua, &ub);
        directions_[j] = coneDirection(axis, t, b, cone, cosine, ua, ub);
    }
    if (env && !env->environmentmap.empty()) {
        const float solidAngle = 2 * kPi * (1 - std::cos(std::min(cone, kPi)));
        environmentColors(*env, directions_.data(), s, std::sqrt(solidAngle / float(s)), time, background_.data());
    }
    Color sum{0, 0, 0};
    uint32_t hits = 0;
    for (uint32_t j = 0; j < s; ++j) {
        Color c;
        hits += shadeAlong({p, directions_[j]}, time, bias, maxdist, background_[j], &c) ? 1 : 0;
        sum += c;
    }
    if (hitShare) *hitShare = float(hits) / float(s);
    return sum * (1.0f / float(s));
}

void ShaderRays::environmentColors(const sl::RayOptions& o, const Vec3f* d, uint32_t n, float width, double time,
                                   Color* out) {
    if (n == 0) return;
    envDirections_.resize(size_t(n) * 6);
    float* dirs = envDirections_.data();
    float* rgb = dirs + size_t(n) * 3;
    for (uint32_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) dirs[size_t(i) * 3 + size_t(c)] = d[i][c];
    if (!sl::lookupEnvironment(shaders_ ? shaders_->textures() : nullptr, o, dirs, int(n), nullptr, width, float(time),
                               envScratch_, rgb))
        return;
    for (uint32_t i = 0; i < n; ++i) out[i] = {rgb[size_t(i) * 3], rgb[size_t(i) * 3 + 1], rgb[size_t(i) * 3 + 2]};
}

// Hits are shaded front to back until one is opaque; where a part of the ray between them lies in
// an Interior or Exterior volume, they are composited back to front, each part's volume run on
// what the ray brings from its far end (as RenderMan runs a volume over a ray's segment).
bool ShaderRays::shadeAlong(const Ray& ray, double time, float tMin, float tMax, Color background, Color* c) {
    const SpacetimeBVH& bvh = hierarchyAt(time);
    ++rays_;
    Color sum{0, 0, 0}, through{1, 1, 1};
    bool any = false, volumes = false;
    std::vector<Layer> layers;  // this call's own: shading a hit may trace (at the next depth) but not here
    layers.swap(layers_);
    layers.clear();
    TraceHit h;
    // Past the first hit, the walk through solids goes on from where the last call left it.
    while (tMin < tMax && bvh.intersectResult(ray, time, tMin, tMax, &h, ctx_, any)) {
        any = true;
        Color o;
        const TrilinearBody& body = *bvh.bodies()[h.body];
        const Color ci = shadeHit(body, h, ray, time, &o);
        const Volume v = volumeAt(body, h, ray, time, false);
        volumes = volumes || v.shader;
        layers.push_back({ci, o, h.t, v});
        // Ci is premultiplied by Oi, as RenderMan's shaders leave it.
        sum += through * ci;
        through = through * (Color{1, 1, 1} - o);
        if (through.x <= 0 && through.y <= 0 && through.z <= 0) break;
        tMin = std::nextafter(h.t, std::numeric_limits<float>::infinity());
    }
    sum += through * background;
    if (volumes) {
        Color back = background, backO{0, 0, 0};
        for (size_t i = layers.size(); i-- > 0;) {
            const Layer& l = layers[i];
            back = l.ci + (Color{1, 1, 1} - l.oi) * back;
            backO = l.oi + (Color{1, 1, 1} - l.oi) * backO;
            if (!l.volume.shader) continue;
            const Vec3f from = i ? ray.o + ray.d * layers[i - 1].t : ray.o;
            back = runVolume(l.volume, from, ray.o + ray.d * l.t, time, back, &backO);
        }
        sum = back;
    }
    layers.swap(layers_);
    *c = sum;
    return any;
}

// With "environmentcolor" wanted (out[1]), the directions of the rays that hit nothing are kept
// and the map looked up in them at once, each over its share of the cone (as coneMean does): the
// sum of what they see over all s rays, so that a constant map c gives c (1 - occlusion) with the
// occlusion of the same rays.
void ShaderRays::occlusion(const sl::RayOptions& o, const sl::RayQuery& q, float* const* out) {
    if (depth_ > maxDepth_) return;  // the op filled 0
    const SpacetimeBVH& bvh = hierarchyAt(q.time);
    const uint32_t s = uint32_t(std::clamp(o.samples > 0 ? o.samples : 16.0f, 1.0f, 65536.0f));
    const float cone = o.coneangle >= 0 ? o.coneangle : 0.5f * kPi;
    const bool seen = out[1] && !o.environmentmap.empty();
    const float width = std::sqrt(2 * kPi * (1 - std::cos(std::min(cone, kPi))) / float(s));
    if (seen) directions_.resize(s);
    for (int i = 0; i < q.n; ++i) {
        if (q.active && !q.active[i]) continue;
        const Vec3f p = at3(q.P, i);
        const Vec3f n = normalize(at3(q.D, i));
        if (!(dot(n, n) > 0.5f)) {
            out[0][i] = 0;
            continue;
        }
        Vec3f t, b;
        frameOf(n, &t, &b);
        const uint64_t h = pointHash(p, q.seed, q.site);
        const float bias = biasAt(o, p, q.time);
        uint32_t hits = 0, misses = 0;
        for (uint32_t j = 0; j < s; ++j) {
            float ua, ub;
            sample2(j, s, h, &ua, &ub);
            const Ray ray{p, coneDirection(n, t, b, cone, true, ua, ub)};
            if (bvh.occluded(ray, q.time, bias, o.maxdist, ctx_)) ++hits;
            else if (seen) directions_[misses++] = ray.d;
        }
        rays_ += s;
        out[0][i] = float(hits) / float(s);
        if (!seen || misses == 0) continue;
        background_.assign(misses, Color{0, 0, 0});
        environmentColors(o, directions_.data(), misses, width, q.time, background_.data());
        // Summed in double: a constant map's sum is exact, so the mean is c (1 - occlusion) rounded once.
        double sum[3] = {0, 0, 0};
        for (uint32_t j = 0; j < misses; ++j)
            for (int c = 0; c < 3; ++c) sum[c] += double(background_[j][c]);
        for (int c = 0; c < 3; ++c) out[1 + c][i] = float(sum[c] / double(s));
    }
}

void ShaderRays::indirectdiffuse(const sl::RayOptions& o, const sl::RayQuery& q, float* const* out) {
    rayType_ = "diffuse";
    if (depth_ > maxDepth_) return;
    const uint32_t s = uint32_t(std::clamp(o.samples > 0 ? o.samples : 16.0f, 1.0f, 65536.0f));
    const float cone = o.coneangle >= 0 ? o.coneangle : 0.5f * kPi;
    for (int i = 0; i < q.n; ++i) {
        if (q.active && !q.active[i]) continue;
        const Vec3f p = at3(q.P, i);
        const Vec3f n = normalize(at3(q.D, i));
        Color sum{0, 0, 0};
        float hitShare = 0;
        if (dot(n, n) > 0.5f)
            sum = coneMean(p, n, cone, true, s, pointHash(p, q.seed, q.site), q.time, biasAt(o, p, q.time), o.maxdist, &o,
                           &hitShare);
        for (int c = 0; c < 3; ++c) out[c][i] = sum[c];
        if (out[3]) out[3][i] = hitShare;
    }
}

void ShaderRays::trace(const sl::RayOptions& o, const sl::RayQuery& q, float* const* out) {
    rayType_ = "specular";
    if (depth_ > maxDepth_) return;
    const float cone = o.coneangle > 0 ? o.coneangle : 0;
    const uint32_t s = cone > 0 ? uint32_t(std::clamp(o.samples > 0 ? o.samples : 1.0f, 1.0f, 65536.0f)) : 1u;
    for (int i = 0; i < q.n; ++i) {
        if (q.active && !q.active[i]) continue;
        const Vec3f p = at3(q.P, i);
        const Vec3f d = normalize(at3(q.D, i));
        Color sum{0, 0, 0};
        if (dot(d, d) > 0.5f) {
            const float bias = biasAt(o, p, q.time);
            if (s == 1) {
                Color c;
                if (shadeAlong({p, d}, q.time, bias, o.maxdist, Color{0, 0, 0}, &c)) sum = c;
            } else {  // a blurred reflection: uniform in the cone
                sum = coneMean(p, d, cone, false, s, pointHash(p, q.seed, q.site), q.time, bias, o.maxdist);
            }
        }
        for (int c = 0; c < 3; ++c) out[c][i] = sum[c];
    }
}

// Each surface crossed between the two points lets (1 - its opacity) through: the Opacity it was
// given (PRMan's default "transmissionhitmode" "primitive": no shader runs).
void ShaderRays::transmission(const sl::RayOptions& o, const sl::RayQuery& q, float* const* out) {
    if (depth_ > maxDepth_) return;
    const SpacetimeBVH& bvh = hierarchyAt(q.time);
    for (int i = 0; i < q.n; ++i) {
        if (q.active && !q.active[i]) continue;
        const Vec3f p = at3(q.P, i);
        const Vec3f d = at3(q.D, i) - p;
        const float dist = length(d);
        Color through{1, 1, 1};
        const float bias = biasAt(o, p, q.time);
        if (dist > 2 * bias) {
            const Ray ray{p, d / dist};
            float tMin = bias;
            const float tMax = std::min(dist - bias, o.maxdist);
            TraceHit h;
            ++rays_;
            // Each part of the segment in an Interior or Exterior volume lets through what its
            // shader leaves of white (Ci 1, Oi 0 in): the part before each hit, and past the last.
            Vec3f from = p;
            Volume last;
            bool resume = false;  // past the first hit (shadeAlong)
            while (tMin < tMax && bvh.intersectResult(ray, q.time, tMin, tMax, &h, ctx_, resume)) {
                resume = true;
                const TrilinearBody& body = *bvh.bodies()[h.body];
                const Vec3f at = ray.o + ray.d * h.t;
                if (const Volume v = volumeAt(body, h, ray, q.time, false); v.shader) {
                    Color o{0, 0, 0};
                    through = through * runVolume(v, from, at, q.time, Color{1, 1, 1}, &o);
                }
                const Color os = body.material()->Os;
                through = through * Color{1 - std::clamp(os.x, 0.0f, 1.0f), 1 - std::clamp(os.y, 0.0f, 1.0f),
                                          1 - std::clamp(os.z, 0.0f, 1.0f)};
                from = at;
                last = volumeAt(body, h, ray, q.time, true);
                if (through.x <= 0 && through.y <= 0 && through.z <= 0) break;
                tMin = std::nextafter(h.t, std::numeric_limits<float>::infinity());
            }
            if (last.shader && (through.x > 0 || through.y > 0 || through.z > 0)) {
                Color o{0, 0, 0};
                through = through * runVolume(last, from, at3(q.D, i), q.time, Color{1, 1, 1}, &o);
            }
        }
        for (int c = 0; c < 3; ++c) out[c][i] = through[c];
    }
}

// One gather() sample a point: sample j of the loop's s, from the same stratified pattern as
// occlusion()'s (so the loop's rays together cover the cone as occlusion's do), its nearest hit
// shaded alone (not composited with what is behind it).
void ShaderRays::gather(const sl::RayOptions& o, const sl::RayQuery& q, int sample, const sl::GatherHits& out) {
    rayType_ = "diffuse";
    const SpacetimeBVH& bvh = hierarchyAt(q.time);
    const uint32_t s = uint32_t(std::clamp(o.samples, 1.0f, 65536.0f));
    const uint32_t j = uint32_t(std::max(sample, 0)) % s;
    const float cone = std::clamp(o.coneangle, 0.0f, kPi);
    for (int i = 0; i < q.n; ++i) {
        if (q.active && !q.active[i]) continue;
        out.hit[i] = 0;
        const Vec3f p = at3(q.P, i);
        const Vec3f n = normalize(at3(q.D, i));
        Vec3f d = n;
        if (dot(n, n) > 0.5f) {
            Vec3f t, b;
            frameOf(n, &t, &b);
            float ua, ub;
            sample2(j, s, pointHash(p, q.seed, q.site), &ua, &ub);
            d = coneDirection(n, t, b, cone, !o.uniform && cone <= 0.5f * kPi, ua, ub);
        }
        for (int c = 0; c < 3; ++c) out.dir[c][i] = d[c];
        if (depth_ > maxDepth_ || !(dot(n, n) > 0.5f)) continue;
        const Ray ray{p, d};
        TraceHit h;
        ++rays_;
        if (!bvh.intersectResult(ray, q.time, biasAt(o, p, q.time), o.maxdist, &h, ctx_)) continue;
        out.hit[i] = 1;
        const TrilinearBody& body = *bvh.bodies()[h.body];
        Color opacity;
        const Color ci = shadeHit(body, h, ray, q.time, &opacity);
        const Vec3f hp = ray.o + ray.d * h.t;
        const Vec3f hn = bilinearNormal(body.cornersAt(q.time), h.u, h.v);
        for (int c = 0; c < 3; ++c) {
            out.Ci[c][i] = ci[c];
            out.Oi[c][i] = opacity[c];
            out.P[c][i] = hp[c];
            out.N[c][i] = hn[c];
        }
        out.length[i] = h.t;
    }
}

}  // namespace streyes
