// The cube microbuffer of point-based occlusion and colour bleeding (point_based_buffer.h).
#include "shade/point_based_buffer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace streyes {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kHalfPi = 1.57079632679f;

float dot(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The solid angle of [0, u] x [0, v] of the plane at distance 1 (signed by u and v).
double cornerSolidAngle(double u, double v) { return std::atan(u * v / std::sqrt(1 + u * u + v * v)); }

// Nearest first: insertion sort of a few (distance, index) pairs (a node's children, a leaf's
// discs), ties by index so the order is the same on every machine.
void sortNearestFirst(std::pair<float, int32_t>* a, int n) {
    for (int i = 1; i < n; ++i) {
        const std::pair<float, int32_t> v = a[i];
        int j = i - 1;
        while (j >= 0 && v < a[j]) {
            a[j + 1] = a[j];
            --j;
        }
        a[j + 1] = v;
    }
}

// True when a sphere (centre c relative to the point, radius r) lies wholly outside the cone of
// half-angle `cone` about unit n.
bool outsideCone(const float c[3], float r, const float n[3], float cone) {
    if (cone == kHalfPi) return dot(c, n) < -r;  // the hemisphere: wholly below the tangent plane
    const float len = std::sqrt(dot(c, c));
    if (len <= r) return false;
    const float half = std::asin(std::min(1.0f, r / len));
    if (cone + half >= kPi) return false;
    const float angle = std::acos(std::clamp(dot(c, n) / len, -1.0f, 1.0f));
    return angle > cone + half;
}

}  // namespace

void CubeMicrobuffer::setResolution(int res) {
    if (res == res_) return;
    res_ = res;
    const size_t n = size_t(6) * size_t(res) * size_t(res);
    dir_.assign(n * 3, 0.0f);
    omega_.assign(n, 0.0f);
    depth_.assign(n, 0.0f);
    cover_.assign(n, 0.0f);
    colour_.assign(n * 3, 0.0f);
    const double step = 2.0 / res;
    for (int f = 0; f < 6; ++f)
        for (int iv = 0; iv < res; ++iv)
            for (int iu = 0; iu < res; ++iu) {
                const double u0 = -1 + iu * step, u1 = u0 + step, v0 = -1 + iv * step, v1 = v0 + step;
                const double u = u0 + 0.5 * step, v = v0 + 0.5 * step, len = std::sqrt(1 + u * u + v * v);
                const int px = pixel(f, iu, iv), a = axis(f);
                float* d = &dir_[size_t(px) * 3];
                d[a] = float(side(f) / len);
                d[(a + 1) % 3] = float(u / len);
                d[(a + 2) % 3] = float(v / len);
                omega_[size_t(px)] = float(cornerSolidAngle(u1, v1) - cornerSolidAngle(u0, v1) -
                                           cornerSolidAngle(u1, v0) + cornerSolidAngle(u0, v0));
            }
}

void CubeMicrobuffer::clear() {
    std::fill(depth_.begin(), depth_.end(), std::numeric_limits<float>::infinity());
    std::fill(cover_.begin(), cover_.end(), 0.0f);
    std::fill(colour_.begin(), colour_.end(), 0.0f);
}

void CubeMicrobuffer::add(int px, float depth, float cover, const float* colour) {
    const size_t i = size_t(px);
    if (cover >= 1 && depth < depth_[i]) {
        // A whole disc nearer than whatever filled the pixel: it is what the pixel sees.
        depth_[i] = depth;
        cover_[i] = 1;
        if (colour)
            for (int c = 0; c < 3; ++c) colour_[i * 3 + size_t(c)] = colour[c];
        return;
    }
    const float room = 1 - cover_[i];
    if (room <= 0) return;
    const float take = std::min(cover, room);
    cover_[i] += take;
    depth_[i] = std::min(depth_[i], depth);
    if (colour)
        for (int c = 0; c < 3; ++c) colour_[i * 3 + size_t(c)] += take * colour[c];
}

// Every pixel whose centre's ray meets the disc (centre p relative to the point, unit normal n
// facing the point, radius r).
void CubeMicrobuffer::drawExact(const float p[3], const float n[3], float radius, const float* colour) {
    const float pn = dot(p, n);
    const float half = 0.5f * float(res_);
    for (int f = 0; f < 6; ++f) {
        const int a = axis(f), ua = (a + 1) % 3, va = (a + 2) % 3;
        const float pa = side(f) * p[a];
        if (pa + radius <= 0) continue;  // wholly behind the face
        int u0 = 0, u1 = res_, v0 = 0, v1 = res_;
        if (pa - radius > 0) {
            // The disc's bounding sphere, in front of the face: its face coordinates lie within
            // these (x / depth over the sphere's box).
            const float nearD = pa - radius, farD = pa + radius;
            const float ulo = std::min((p[ua] - radius) / nearD, (p[ua] - radius) / farD);
            const float uhi = std::max((p[ua] + radius) / nearD, (p[ua] + radius) / farD);
            const float vlo = std::min((p[va] - radius) / nearD, (p[va] - radius) / farD);
            const float vhi = std::max((p[va] + radius) / nearD, (p[va] + radius) / farD);
            if (ulo > 1 || uhi < -1 || vlo > 1 || vhi < -1) continue;
            u0 = std::max(0, int(std::floor((ulo + 1) * half)));
            u1 = std::min(res_, int(std::ceil((uhi + 1) * half)));
            v0 = std::max(0, int(std::floor((vlo + 1) * half)));
            v1 = std::min(res_, int(std::ceil((vhi + 1) * half)));
        }
        for (int iv = v0; iv < v1; ++iv)
            for (int iu = u0; iu < u1; ++iu) {
                const int px = pixel(f, iu, iv);
                const float* d = &dir_[size_t(px) * 3];
                const float dn = dot(d, n);
                if (dn >= 0) continue;
                const float t = pn / dn;
                if (!(t > 0)) continue;
                const float h[3] = {t * d[0] - p[0], t * d[1] - p[1], t * d[2] - p[2]};
                if (dot(h, h) < radius * radius) add(px, t, 1.0f, colour);
            }
    }
}

// A rectangle of the disc's projected area on the face its centre lies in front of (and on the
// neighbouring faces it spills onto), box-filtered: cheap, and far discs and clusters are not
// resolved beyond their area anyway. Its sides have the proportions of the projected ellipse's
// extents along the face's axes, so the thin slivers a plane makes towards its horizon tile as
// slivers (squares of their area would overlap row on row, and leave gaps between).
void CubeMicrobuffer::drawSquare(const float p[3], const float n[3], float area, float distance, const float* colour) {
    int a = 0;
    for (int k = 1; k < 3; ++k)
        if (std::fabs(p[k]) > std::fabs(p[a])) a = k;
    const float pa = std::fabs(p[a]);
    if (!(pa > 0)) return;
    const float inv = 1 / pa, sa = p[a] < 0 ? -1.0f : 1.0f;
    const int face = 2 * a + (p[a] < 0 ? 1 : 0);
    const int ua = (a + 1) % 3, va = (a + 2) % 3;
    const float u = p[ua] * inv, v = p[va] * inv;
    // The disc's area seen from the point, moved onto the face's plane at distance 1.
    const float projected = area * std::fabs(dot(p, n)) * inv * inv * inv;
    // The squared extents of the projected disc along u and v (times pa^2): the gradients of
    // u = x_u / x_a and of v at p, (e_u - sa u e_a) / pa, over the disc's plane.
    const float gun = n[ua] - sa * u * n[a], gvn = n[va] - sa * v * n[a];
    const float eu2 = 1 + u * u - gun * gun, ev2 = 1 + v * v - gvn * gvn;
    if (!(eu2 > 0) || !(ev2 > 0) || !(projected > 0)) return;
    const float scale = 0.5f * float(res_);
    const float hu = 0.5f * scale * std::sqrt(projected * std::sqrt(eu2 / ev2));
    const float hv = 0.25f * scale * scale * projected / hu;
    const float x = (u + 1) * scale, y = (v + 1) * scale;
    rectOnFace(face, x, y, hu, hv, distance, colour);
    // Spilling over an edge: the neighbour across it shares the axis along the edge; the other
    // axis swaps roles (its extent there is taken as the other one's).
    auto neighbour = [&](int f) {
        const int na = axis(f);
        const float q = side(f) * p[na];
        if (!(q > 0)) return;
        rectOnFace(f, (p[(na + 1) % 3] / q + 1) * scale, (p[(na + 2) % 3] / q + 1) * scale, hv, hu, distance, colour);
    };
    if (x - hu < 0) neighbour(2 * ua + 1);
    else if (x + hu > float(res_)) neighbour(2 * ua);
    if (y - hv < 0) neighbour(2 * va + 1);
    else if (y + hv > float(res_)) neighbour(2 * va);
}

void CubeMicrobuffer::rectOnFace(int face, float x, float y, float hu, float hv, float depth, const float* colour) {
    const float x0 = x - hu, x1 = x + hu, y0 = y - hv, y1 = y + hv;
    if (x1 <= 0 || y1 <= 0 || x0 >= float(res_) || y0 >= float(res_)) return;
    const int iu0 = std::max(0, int(std::floor(x0))), iu1 = std::min(res_, int(std::ceil(x1)));
    const int iv0 = std::max(0, int(std::floor(y0))), iv1 = std::min(res_, int(std::ceil(y1)));
    for (int iv = iv0; iv < iv1; ++iv) {
        const float cy = std::min(float(iv + 1), y1) - std::max(float(iv), y0);
        for (int iu = iu0; iu < iu1; ++iu) {
            const float cx = std::min(float(iu + 1), x1) - std::max(float(iu), x0);
            if (cx > 0 && cy > 0) add(pixel(face, iu, iv), depth, cx * cy, colour);
        }
    }
}

void CubeMicrobuffer::integrate(const DiscHierarchy& tree, const float P[3], const float N[3],
                                const PointBasedSettings& s, float* occlusion, float* colour, const float* environment,
                                float* environmentSeen) {
    setResolution(std::max(1, s.res));
    clear();
    const std::vector<DiscCluster>& clusters = tree.clusters();
    const std::vector<CloudDisc>& discs = tree.discs();
    const float cone = std::clamp(s.coneAngle, 0.0f, kPi);
    const float sliver = 4 * kPi / float(6 * res_ * res_) / 16;  // a sixteenth of a pixel
    if (!clusters.empty()) {
        // Depth first, nearest child first: at most 7 siblings wait a level.
        int32_t stack[8 * (DiscHierarchy::kMaxDepth + 2)];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const DiscCluster& node = clusters[size_t(stack[--top])];
            const float c[3] = {node.centre[0] - P[0], node.centre[1] - P[1], node.centre[2] - P[2]};
            if (outsideCone(c, node.bound, N, cone)) continue;
            if (!node.leaf) {
                const float p[3] = {node.P[0] - P[0], node.P[1] - P[1], node.P[2] - P[2]};
                const float d2 = dot(p, p);
                if (node.drawable && dot(c, c) > node.bound * node.bound && node.area < s.maxSolidAngle * d2) {
                    if (dot(p, node.N) < 0) drawSquare(p, node.N, node.area, std::sqrt(d2), colour ? node.radiosity : nullptr);
                    continue;
                }
                std::pair<float, int32_t> order[8];
                const int children = std::min(node.count, 8);
                for (int k = 0; k < children; ++k) {
                    const DiscCluster& ch = clusters[size_t(node.first + k)];
                    const float q[3] = {ch.centre[0] - P[0], ch.centre[1] - P[1], ch.centre[2] - P[2]};
                    order[k] = {dot(q, q), node.first + k};
                }
                sortNearestFirst(order, children);
                for (int k = children - 1; k >= 0; --k) stack[top++] = order[k].second;
                continue;
            }
            constexpr int kSorted = 64;  // a leaf holds 8 discs but at the depth limit
            std::pair<float, int32_t> order[kSorted];
            const int m = std::min(node.count, kSorted);
            for (int k = 0; k < m; ++k) {
                const CloudDisc& d = discs[size_t(node.first + k)];
                const float q[3] = {d.P[0] - P[0], d.P[1] - P[1], d.P[2] - P[2]};
                order[k] = {dot(q, q), node.first + k};
            }
            if (node.count <= kSorted) sortNearestFirst(order, m);
            for (int k = 0; k < node.count; ++k) {
                const CloudDisc& d = discs[size_t(node.count <= kSorted ? order[k].second : node.first + k)];
                const float p[3] = {d.P[0] - P[0], d.P[1] - P[1], d.P[2] - P[2]};
                if (dot(p, d.N) >= 0) continue;  // seen from behind, or edge on
                if (outsideCone(p, d.radius, N, cone)) continue;
                // Exactly when near (its bounding solid angle at least maxsolidangle) and not so
                // nearly edge on that it covers under a sixteenth of a pixel (the discs of the
                // shading point's own surface, seen along it): drawing those exactly costs whole
                // faces of ray tests and point-samples a sliver.
                const float d2 = dot(p, p);
                const float seen = d.area * -dot(p, d.N) / (d2 * std::sqrt(d2));  // solid angle
                if (kPi * d.radius * d.radius >= s.maxSolidAngle * d2 && seen >= sliver)
                    drawExact(p, d.N, d.radius, colour ? d.radiosity : nullptr);
                else drawSquare(p, d.N, d.area, std::sqrt(d2), colour ? d.radiosity : nullptr);
            }
        }
    }
    const float cosCone = std::cos(cone);
    double wsum = 0, occ = 0, col[3] = {}, env[3] = {};
    const size_t perFace = size_t(res_) * size_t(res_);
    for (int f = 0; f < 6; ++f) {
        // (side e_a + u e_u + v e_v) . N over the face is at most this: at most 0, all below.
        const int a = axis(f);
        if (side(f) * N[a] + std::fabs(N[(a + 1) % 3]) + std::fabs(N[(a + 2) % 3]) <= 0) continue;
        for (size_t i = size_t(f) * perFace; i < size_t(f + 1) * perFace; ++i) {
            const float w = dot(&dir_[i * 3], N);
            if (!(w > cosCone) || !(w > 0)) continue;
            const double wo = double(w) * omega_[i];
            wsum += wo;
            const float cover = std::min(1.0f, cover_[i]);
            occ += wo * cover;
            if (colour)
                for (int c = 0; c < 3; ++c) col[c] += wo * colour_[i * 3 + size_t(c)];
            if (environment && cover < 1)
                for (int c = 0; c < 3; ++c) env[c] += wo * (1 - cover) * environment[i * 3 + size_t(c)];
        }
    }
    *occlusion = wsum > 0 ? float(occ / wsum) : 0.0f;
    if (colour)
        for (int c = 0; c < 3; ++c) colour[c] = wsum > 0 ? float((col[c] + env[c]) / wsum) : 0.0f;
    if (environmentSeen)
        for (int c = 0; c < 3; ++c) environmentSeen[c] = wsum > 0 ? float(env[c] / wsum) : 0.0f;
}

}  // namespace streyes
