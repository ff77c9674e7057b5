#include "geom/nurbs_trim.h"

#include <algorithm>
#include <limits>

#include "geom/nurbs.h"

namespace streyes {

NurbsTrim::NurbsTrim(const TrimLoops& loops, int stepsPerSpan) {
    ulo_ = vlo_ = std::numeric_limits<double>::infinity();
    uhi_ = vhi_ = -ulo_;
    std::vector<Vec2<double>> line;
    for (const std::vector<TrimCurveDesc>& loop : loops.loops) {
        line.clear();
        for (const TrimCurveDesc& c : loop)
            nurbsCurvePolyline(int(c.u.size()), c.order, c.knot.data(), c.tmin, c.tmax, c.u.data(), c.v.data(),
                               c.w.data(), stepsPerSpan * std::max(1, c.order - 1), &line);
        if (line.size() < 2) continue;
        line.push_back(line.front());  // loops "must be explicitly closed"; this closes rounding gaps
        for (size_t i = 0; i + 1 < line.size(); ++i) {
            edges_.push_back({line[i], line[i + 1]});
            ulo_ = std::min(ulo_, line[i].x), uhi_ = std::max(uhi_, line[i].x);
            vlo_ = std::min(vlo_, line[i].y), vhi_ = std::max(vhi_, line[i].y);
        }
    }
}

namespace {
// Whether edge (a, b) crosses the line v = y (half-open in v, so a vertex on the line counts once),
// and where.
bool crosses(Vec2<double> a, Vec2<double> b, double y, double* x) {
    if ((a.y <= y) == (b.y <= y)) return false;
    *x = a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
    return true;
}
}  // namespace

bool NurbsTrim::cut(double u, double v) const {
    bool inside = false;
    double x;
    for (const Edge& e : edges_)
        if (crosses(e.a, e.b, v, &x) && x > u) inside = !inside;
    return inside;
}

bool NurbsTrim::covers(double u0, double u1, double v0, double v1) const {
    if (edges_.empty() || u1 < ulo_ || u0 > uhi_ || v1 < vlo_ || v0 > vhi_) return false;
    for (const Edge& e : edges_)
        if (std::max(e.a.x, e.b.x) >= u0 && std::min(e.a.x, e.b.x) <= u1 && std::max(e.a.y, e.b.y) >= v0 &&
            std::min(e.a.y, e.b.y) <= v1)
            return false;
    return cut(0.5 * (u0 + u1), 0.5 * (v0 + v1));
}

bool NurbsTrim::mark(double u0, double u1, double v0, double v1, int nu, int nv, std::vector<uint8_t>& hole) const {
    if (edges_.empty() || u1 < ulo_ || u0 > uhi_ || v1 < vlo_ || v0 > vhi_) return false;
    thread_local std::vector<const Edge*> near;  // the edges reaching into the rows' range
    thread_local std::vector<double> xs;
    near.clear();
    for (const Edge& e : edges_)
        if (std::max(e.a.y, e.b.y) >= v0 && std::min(e.a.y, e.b.y) <= v1) near.push_back(&e);
    hole.assign(size_t(nu) * size_t(nv), 0);
    for (int j = 0; j < nv; ++j) {
        const double v = v0 + (v1 - v0) * (j + 0.5) / nv;
        // Crossings of the row's centre line, in order: a centre is cut where an odd number lie
        // beyond it.
        xs.clear();
        double x;
        for (const Edge* e : near)
            if (crosses(e->a, e->b, v, &x)) xs.push_back(x);
        if (xs.empty()) continue;
        std::sort(xs.begin(), xs.end());
        size_t k = 0;  // crossings at or before the centre
        for (int i = 0; i < nu; ++i) {
            const double u = u0 + (u1 - u0) * (i + 0.5) / nu;
            while (k < xs.size() && xs[k] <= u) ++k;
            hole[size_t(j) * size_t(nu) + size_t(i)] = uint8_t((xs.size() - k) & 1);
        }
    }
    return true;
}

}  // namespace streyes
