#include "geom/triangulate.h"

#include <algorithm>
#include <cmath>

namespace streyes {

namespace {

struct P2 {
    double x = 0, y = 0;
};

// Twice the signed area of the triangle o a b (positive when counter-clockwise).
double orient(P2 o, P2 a, P2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

bool samePoint(P2 a, P2 b) { return a.x == b.x && a.y == b.y; }

// Inside or on the boundary of the counter-clockwise triangle a b c.
bool inTriangle(P2 p, P2 a, P2 b, P2 c) { return orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0; }

double signedArea(const std::vector<int>& loop, const std::vector<P2>& q) {
    double a = 0;
    for (size_t i = 0; i < loop.size(); ++i) {
        P2 p = q[size_t(loop[i])], n = q[size_t(loop[(i + 1) % loop.size()])];
        a += p.x * n.y - n.x * p.y;
    }
    return 0.5 * a;
}

// Joins a hole (clockwise) to the outer loop (counter-clockwise) by a bridge from the hole's
// rightmost vertex to a vertex of the outer loop that it can see.
void bridgeHole(std::vector<int>& outer, const std::vector<int>& hole, const std::vector<P2>& q) {
    size_t mi = 0;
    for (size_t i = 1; i < hole.size(); ++i)
        if (q[size_t(hole[i])].x > q[size_t(hole[mi])].x) mi = i;
    const P2 M = q[size_t(hole[mi])];
    // The nearest edge of the outer loop that the ray from M towards +x meets.
    double bestX = INFINITY;
    size_t bestEdge = outer.size();
    for (size_t i = 0; i < outer.size(); ++i) {
        const P2 a = q[size_t(outer[i])], b = q[size_t(outer[(i + 1) % outer.size()])];
        if ((a.y > M.y) == (b.y > M.y) && !(a.y == M.y || b.y == M.y)) continue;
        if (a.y == b.y) continue;
        const double x = a.x + (M.y - a.y) * (b.x - a.x) / (b.y - a.y);
        if (x >= M.x && x < bestX) bestX = x, bestEdge = i;
    }
    size_t pi = 0;
    if (bestEdge == outer.size()) {
        // No edge to the right (should not happen for a hole inside): the nearest vertex.
        double best = INFINITY;
        for (size_t i = 0; i < outer.size(); ++i) {
            const P2 p = q[size_t(outer[i])];
            const double d = (p.x - M.x) * (p.x - M.x) + (p.y - M.y) * (p.y - M.y);
            if (d < best) best = d, pi = i;
        }
    } else {
        const size_t ia = bestEdge, ib = (bestEdge + 1) % outer.size();
        pi = q[size_t(outer[ia])].x > q[size_t(outer[ib])].x ? ia : ib;
        const P2 I{bestX, M.y}, P = q[size_t(outer[pi])];
        if (!samePoint(I, P)) {
            // A reflex vertex inside the triangle M I P would hide P: take the one at the smallest
            // angle from the ray instead.
            double bestCos = -2, bestDist = INFINITY;
            for (size_t i = 0; i < outer.size(); ++i) {
                const P2 r = q[size_t(outer[i])];
                const P2 prev = q[size_t(outer[(i + outer.size() - 1) % outer.size()])];
                const P2 next = q[size_t(outer[(i + 1) % outer.size()])];
                if (i == pi || orient(prev, r, next) > 0) continue;
                const bool inside = orient(M, I, P) > 0 ? inTriangle(r, M, I, P) : inTriangle(r, M, P, I);
                if (!inside) continue;
                const double dx = r.x - M.x, dy = r.y - M.y, d = std::hypot(dx, dy);
                const double c = d > 0 ? dx / d : -2;
                if (c > bestCos || (c == bestCos && d < bestDist)) bestCos = c, bestDist = d, pi = i;
            }
        }
    }
    std::vector<int> merged(outer.begin(), outer.begin() + long(pi) + 1);
    for (size_t k = 0; k <= hole.size(); ++k) merged.push_back(hole[(mi + k) % hole.size()]);
    merged.push_back(outer[pi]);
    merged.insert(merged.end(), outer.begin() + long(pi) + 1, outer.end());
    outer = std::move(merged);
}

// Ear clipping of a counter-clockwise loop (which may visit a point twice, along a bridge).
void clipEars(const std::vector<int>& loop, const std::vector<P2>& q, std::vector<std::array<int, 3>>& out) {
    std::vector<int> ring = loop;
    size_t guard = 0;
    while (ring.size() > 3 && guard++ < 4 * loop.size() * loop.size()) {
        const size_t n = ring.size();
        bool clipped = false;
        for (size_t i = 0; i < n && !clipped; ++i) {
            const int ia = ring[(i + n - 1) % n], ib = ring[i], ic = ring[(i + 1) % n];
            const P2 a = q[size_t(ia)], b = q[size_t(ib)], c = q[size_t(ic)];
            const double o = orient(a, b, c);
            if (o == 0) {
                // Collinear (or repeated) corner: it adds no area; drop it.
                ring.erase(ring.begin() + long(i));
                clipped = true;
                break;
            }
            if (o < 0) continue;  // reflex
            bool ear = true;
            for (size_t j = 0; j < n && ear; ++j) {
                const P2 p = q[size_t(ring[j])];
                if (samePoint(p, a) || samePoint(p, b) || samePoint(p, c)) continue;
                ear = !inTriangle(p, a, b, c);
            }
            if (!ear) continue;
            out.push_back({ia, ib, ic});
            ring.erase(ring.begin() + long(i));
            clipped = true;
        }
        if (!clipped) {
            // No clean ear (a self-intersecting loop): clip the first convex corner anyway.
            for (size_t i = 0; i < n && !clipped; ++i) {
                const int ia = ring[(i + n - 1) % n], ib = ring[i], ic = ring[(i + 1) % n];
                if (orient(q[size_t(ia)], q[size_t(ib)], q[size_t(ic)]) > 0) {
                    out.push_back({ia, ib, ic});
                    ring.erase(ring.begin() + long(i));
                    clipped = true;
                }
            }
            if (!clipped) return;
        }
    }
    if (ring.size() == 3 && orient(q[size_t(ring[0])], q[size_t(ring[1])], q[size_t(ring[2])]) > 0)
        out.push_back({ring[0], ring[1], ring[2]});
}

}  // namespace

bool cutPolygon(const std::vector<Vec3d>& points, const std::vector<std::vector<int>>& loops,
                std::vector<std::array<int, 4>>* faces) {
    if (loops.empty() || loops[0].size() < 3) return false;
    // Newell's normal of the outer loop: the plane to project onto.
    Vec3d n;
    const std::vector<int>& outer = loops[0];
    for (size_t i = 0; i < outer.size(); ++i) {
        const Vec3d a = points[size_t(outer[i])], b = points[size_t(outer[(i + 1) % outer.size()])];
        n += Vec3d{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
    }
    const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
    if (!(std::max({ax, ay, az}) > 0)) return false;
    const int drop = az >= ax && az >= ay ? 2 : (ay >= ax ? 1 : 0);
    // Only the loops' own points are projected, renumbered 0..k-1 (a polygon of a large mesh reads
    // a handful of its points; projecting them all made a mesh's cutting quadratic).
    std::vector<int> used;
    for (const std::vector<int>& l : loops) used.insert(used.end(), l.begin(), l.end());
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    std::vector<P2> q(used.size());
    for (size_t i = 0; i < used.size(); ++i) {
        const Vec3d& p = points[size_t(used[i])];
        q[i] = drop == 2 ? P2{p.x, p.y} : drop == 1 ? P2{p.z, p.x} : P2{p.y, p.z};
    }
    std::vector<std::vector<int>> local(loops);
    for (std::vector<int>& l : local)
        for (int& i : l) i = int(std::lower_bound(used.begin(), used.end(), i) - used.begin());
    // Counter-clockwise outer loop, clockwise holes; remember to turn the faces back.
    std::vector<int> ring = local[0];
    const bool flipped = signedArea(ring, q) < 0;
    if (flipped) std::reverse(ring.begin(), ring.end());
    if (!(std::fabs(signedArea(ring, q)) > 0)) return false;

    auto emit = [&](std::array<int, 3> t) {
        if (flipped) std::swap(t[1], t[2]);
        faces->push_back({used[size_t(t[0])], used[size_t(t[1])], used[size_t(t[2])], used[size_t(t[2])]});
    };
    if (loops.size() == 1 && ring.size() == 4) {
        // A convex quad stays one face (a bilinear patch, as RenderMan dices it).
        bool convex = true;
        for (size_t i = 0; i < 4; ++i)
            convex = convex && orient(q[size_t(ring[i])], q[size_t(ring[(i + 1) % 4])], q[size_t(ring[(i + 2) % 4])]) > 0;
        if (convex) {
            const std::vector<int>& v = outer;  // original winding
            faces->push_back({v[0], v[1], v[3], v[2]});
            return true;
        }
    }
    std::vector<std::vector<int>> holes(local.begin() + 1, local.end());
    for (std::vector<int>& h : holes) {
        if (h.size() < 3) continue;
        if (signedArea(h, q) > 0) std::reverse(h.begin(), h.end());
    }
    std::sort(holes.begin(), holes.end(), [&](const std::vector<int>& a, const std::vector<int>& b) {
        auto maxX = [&](const std::vector<int>& l) {
            double m = -INFINITY;
            for (int i : l) m = std::max(m, q[size_t(i)].x);
            return m;
        };
        return maxX(a) > maxX(b);
    });
    for (const std::vector<int>& h : holes)
        if (h.size() >= 3) bridgeHole(ring, h, q);
    std::vector<std::array<int, 3>> tris;
    clipEars(ring, q, tris);
    for (const auto& t : tris) emit(t);
    return !tris.empty();
}

}  // namespace streyes
