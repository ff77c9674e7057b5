#include "geom/curved_body.h"

#include <algorithm>
#include <cmath>

#include "geom/grid.h"

namespace streyes {

// ---- Line lattices ---------------------------------------------------------------------------------
// A line's lattice is a binary tree over its parameter [0, 1]. A node is measured by its raster
// length at the mesh's keys (three points); it is refined while that length asks for more than
// kLeafRate steps, and otherwise is a leaf of 2^k equal steps (rateFor). Everything here
// depends only on the line, the camera, the shading rate and the mesh's keys: the pieces on both
// sides of a line find the same lattice.
namespace {

constexpr int kLeafRate = 8;
constexpr int kMaxLineDepth = 24;

struct LineContext {
    const SurfaceMesh& mesh;
    const Camera& camera;
    float side;  // micropolygon edge length in pixels: sqrt(shading rate)
    int keys;    // keys to measure at
};

LineContext contextOf(const SurfaceMesh& mesh) {
    return {mesh, mesh.camera(), std::sqrt(std::max(mesh.shadingRate(), 1e-4f)), mesh.moving() ? 2 : 1};
}

// Points on a line are evaluated as points of a face, canonically (through the owner of the
// edge or vertex they lie on).
void evalLine(const SurfaceMesh& mesh, const SurfaceLine& line, double s, int k, Vec3f* P, Vec3f* N) {
    switch (line.kind) {
    case SurfaceLine::Edge: {
        const SurfaceTopology::Owner& o = mesh.topology().edgeOwner[size_t(line.id)];
        double u, v;
        sideParam(o.index, s, &u, &v);
        mesh.evaluatePoint(o.face, u, v, k, P, N);
        break;
    }
    case SurfaceLine::IsoU: mesh.evaluatePoint(line.id, line.c, s, k, P, N); break;
    case SurfaceLine::IsoV: mesh.evaluatePoint(line.id, s, line.c, k, P, N); break;
    }
}

// Raster position; points nearer than the eye plane are measured as if on it (lengths only
// need to be the same for everyone, and finite).
Vec3f projectClamped(const Camera& camera, Vec3f p) {
    if (camera.perspective() && !(p.z >= camera.eyePlane())) p.z = camera.eyePlane();
    return camera.toRaster(p);
}


// Steps for a raster length of `edges` micropolygon edges: the smallest power of two whose steps
// are at most two edges long (so between one and two). A grid has at least as many columns as
// its sides have steps (dice()), so a lattice finer than the piece's own rate costs micropolygons
// over the whole grid: with steps between 0.7 and 1.4 edges (the nearest power of two) the
// lattices added a quarter to every curved surface's micropolygons (1.24x on a subdivision cube,
// 1.23x on a sphere); rounded down they never exceed what the split loop asks for. The price is
// sparser vertices along the pieces' sides only, where the surface is still sampled exactly.
int rateFor(float edges) {
    int r = 1;
    while (r < (1 << 20) && float(r) * 2.0f < edges) r *= 2;
    return r;
}

int nodeRate(const LineContext& ctx, const SurfaceLine& line, double a, double b) {
    const double s[3] = {a, 0.5 * (a + b), b};
    float length = 0;
    for (int k = 0; k < ctx.keys; ++k) {
        Vec3f r[3];
        for (int i = 0; i < 3; ++i) {
            Vec3f P;
            evalLine(ctx.mesh, line, s[i], k, &P, nullptr);
            r[i] = projectClamped(ctx.camera, P);
        }
        length = std::max(length, rasterDistance(r[0], r[1]) + rasterDistance(r[1], r[2]));
    }
    return rateFor(length / ctx.side);
}

int depthOf(double length) { return -std::ilogb(length); }  // segments are 2^-depth long

bool isLeaf(int rate, int depth) { return rate <= kLeafRate || depth >= kMaxLineDepth; }

// Finds where side.[a, b] sits in its line's tree: inside a leaf, or a refined node itself.
void resolveState(const LineContext& ctx, PieceSide& side) {
    if (side.state == PieceSide::InLeaf || side.state == PieceSide::Refined) return;
    double na = 0, nb = 1;
    int depth = 0;
    if (side.state == PieceSide::BelowRefined) {
        na = side.a, nb = side.b;
        depth = depthOf(side.b - side.a);
    }
    while (true) {
        const int rate = nodeRate(ctx, side.line, na, nb);
        if (isLeaf(rate, depth)) {
            side.state = PieceSide::InLeaf;
            side.la = na, side.lb = nb, side.rate = rate;
            return;
        }
        if (na == side.a && nb == side.b) {
            side.state = PieceSide::Refined;
            return;
        }
        const double m = 0.5 * (na + nb);
        if (side.b <= m) nb = m;
        else na = m;
        ++depth;
    }
}

// Lattice points of the leaf [la, lb] (rate steps) strictly inside (a, b), in increasing order.
// Dyadic numbers throughout: the arithmetic is exact.
void leafPoints(double la, double lb, int rate, double a, double b, std::vector<double>& out) {
    const double h = (lb - la) / rate;
    const double first = std::floor((a - la) / h) + 1, last = std::ceil((b - la) / h) - 1;
    for (double m = first; m <= last; ++m) out.push_back(la + m * h);
}

// Lattice points strictly inside the refined node [a, b].
void refinedPoints(const LineContext& ctx, const SurfaceLine& line, double a, double b, int depth,
                   std::vector<double>& out) {
    const double m = 0.5 * (a + b);
    const double child[2][2] = {{a, m}, {m, b}};
    for (int c = 0; c < 2; ++c) {
        const double ca = child[c][0], cb = child[c][1];
        const int rate = nodeRate(ctx, line, ca, cb);
        if (isLeaf(rate, depth + 1)) leafPoints(ca, cb, rate, ca, cb, out);
        else refinedPoints(ctx, line, ca, cb, depth + 1, out);
        if (c == 0) out.push_back(m);
    }
}

void latticePoints(const LineContext& ctx, const PieceSide& side, std::vector<double>& out) {
    if (side.state == PieceSide::InLeaf) leafPoints(side.la, side.lb, side.rate, side.a, side.b, out);
    else refinedPoints(ctx, side.line, side.a, side.b, depthOf(side.b - side.a), out);
}

// The corner made by splitting `side` at its midpoint. On the line's lattice it is the point of
// the surface, evaluated exactly. Otherwise no lattice point lies inside the side, and a coarser
// neighbour across the line has no vertex inside it either: its edge runs straight through the
// side's two corners (which, by the same rule, lie on it), so the new corner goes halfway
// between them. Either way the position depends only on the line and the segment, so every
// piece that makes this corner makes the same bits.
PieceCorner cornerOnSide(const LineContext& ctx, PieceSide& side, const PieceCorner& end0, const PieceCorner& end1,
                         int face, double u, double v) {
    resolveState(ctx, side);
    const double s = 0.5 * (side.a + side.b);
    PieceCorner c;
    bool onLattice = side.state == PieceSide::Refined;
    if (side.state == PieceSide::InLeaf) {
        const double q = (s - side.la) / ((side.lb - side.la) / side.rate);
        onLattice = q == std::floor(q);
    }
    if (!onLattice) {
        for (int k = 0; k < 2; ++k) {
            c.P[k] = (end0.P[k] + end1.P[k]) * 0.5f;
            c.N[k] = (end0.N[k] + end1.N[k]) * 0.5f;
        }
        return c;
    }
    for (int k = 0; k < ctx.keys; ++k) {
        evalLine(ctx.mesh, side.line, s, k, &c.P[k], &c.N[k]);
        // The position is the owner's; the normal is this face's own (faces meet at an angle
        // along a crease).
        if (side.line.kind == SurfaceLine::Edge) {
            Vec3f unused;
            ctx.mesh.evaluate(face, u, v, k, &unused, &c.N[k]);
        }
    }
    if (ctx.keys == 1) c.P[1] = c.P[0], c.N[1] = c.N[0];
    return c;
}

// The half of a side towards the piece's low (first) or high end.
PieceSide halfSide(const PieceSide& s, bool low) {
    PieceSide h = s;
    const double m = 0.5 * (s.a + s.b);
    if (low != s.reversed) h.b = m;
    else h.a = m;
    if (s.state == PieceSide::Refined) h.state = PieceSide::BelowRefined;
    else if (s.state != PieceSide::InLeaf) h.state = PieceSide::Unknown;
    return h;
}

// The vertices along one side of a grid, from its first corner to its last.
struct SideVertices {
    std::vector<Vec3f> P[2], N[2];
    std::vector<double> u, v;   // face parameters, for Cs
    std::vector<float> along;   // position along the side in [0, 1]
    std::vector<double> params; // scratch: line parameters
    std::vector<int> map;       // grid column -> vertex
    size_t count() const { return along.size(); }
    // Columns that fit the side's smallest step (a power-of-two fraction of the side) exactly.
    int columnsNeeded() const {
        float step = 1;
        for (size_t m = 1; m < along.size(); ++m) step = std::min(step, along[m] - along[m - 1]);
        return int(std::ceil(1.0f / step - 1e-3f));
    }
    void clear() {
        for (int k = 0; k < 2; ++k) P[k].clear(), N[k].clear();
        u.clear(), v.clear(), along.clear(), params.clear(), map.clear();
    }
    void add(const Vec3f* p, const Vec3f* n, double pu, double pv, float t) {
        for (int k = 0; k < 2; ++k) P[k].push_back(p[k]), N[k].push_back(n[k]);
        u.push_back(pu), v.push_back(pv), along.push_back(t);
    }
};

// Grid column i (of n) -> vertex of the side: every vertex gets at least one column, in order,
// at the column nearest to it; columns in between repeat a vertex (degenerate micropolygons).
void columnMap(SideVertices& s, int n) {
    const int M = int(s.count()) - 1;
    thread_local std::vector<int> col;
    col.assign(size_t(M + 1), 0);
    for (int m = 1; m <= M; ++m) col[size_t(m)] = std::max(col[size_t(m - 1)] + 1, int(std::lround(s.along[size_t(m)] * n)));
    col[size_t(M)] = n;
    for (int m = M - 1; m >= 1; --m) col[size_t(m)] = std::min(col[size_t(m)], col[size_t(m + 1)] - 1);
    s.map.assign(size_t(n + 1), 0);
    for (int m = 0; m < M; ++m)
        for (int i = col[size_t(m)]; i < col[size_t(m + 1)]; ++i) s.map[size_t(i)] = m;
    s.map[size_t(n)] = M;
}

Bounds3f lerpBox(const Bounds3f& a, const Bounds3f& b, float s) { return {lerp(a.lo, b.lo, s), lerp(a.hi, b.hi, s)}; }

}  // namespace

// ---- Construction -----------------------------------------------------------------------------------
CurvedBody::CurvedBody(const SurfaceMesh* mesh, int face) : mesh_(mesh), face_(face) {
    time_ = mesh->keys();
    material_ = mesh->material();
    source_ = mesh->source();
    moving_ = mesh->moving() && mesh->faceMoving(face);
    const SurfaceTopology::Face& f = mesh->topology().faces[size_t(face)];
    for (int c = 0; c < 4; ++c) {
        double u, v;
        cornerParam(c, &u, &v);
        PieceCorner& pc = corner_[c];
        for (int k = 0; k < 2; ++k) {
            Vec3f unused;
            mesh->evaluatePoint(face, u, v, mesh->moving() ? k : 0, &pc.P[k], nullptr);
            mesh->evaluate(face, u, v, mesh->moving() ? k : 0, &unused, &pc.N[k]);
        }
    }
    for (int k = 0; k < 4; ++k) {
        side_[k].line = {SurfaceLine::Edge, f.side[size_t(k)], 0};
        side_[k].reversed = f.reversed[size_t(k)];
    }
    setPayload();
    cachedBound_ = bound();
    cachedMeasure_ = measure(mesh->camera());
    cached_ = true;
}

float CurvedBody::keyFraction(double t) const {
    const TimeSpan& K = mesh_->keys();
    if (!(K.t1 > K.t0) || t <= K.t0) return 0;
    if (t >= K.t1) return 1;
    return float((t - K.t0) / (K.t1 - K.t0));
}

void CurvedBody::setPayload() {
    const int keys = mesh_->moving() ? 2 : 1;
    BezierPatch kcp[2];
    hasBezier_ = true;
    for (int k = 0; k < keys && hasBezier_; ++k) hasBezier_ = mesh_->bezier(face_, rect_, k, &kcp[k]);
    const float s[2] = {keyFraction(time_.t0), keyFraction(time_.t1)};
    if (hasBezier_) {
        if (keys == 1) kcp[1] = kcp[0];
        for (int t = 0; t < 2; ++t)
            for (size_t i = 0; i < 16; ++i) cp_[t][i] = lerp(kcp[0][i], kcp[1][i], s[t]);
        return;
    }
    Bounds3f kb[2];
    for (int k = 0; k < keys; ++k) kb[k] = mesh_->bound(face_, rect_, k);
    if (keys == 1) kb[1] = kb[0];
    for (int t = 0; t < 2; ++t) box_[t] = lerpBox(kb[0], kb[1], s[t]);
}

std::unique_ptr<CurvedBody> CurvedBody::child() const {
    std::unique_ptr<CurvedBody> c(new CurvedBody());
    c->inheritFrom(*this);
    c->mesh_ = mesh_;
    c->face_ = face_;
    c->time_ = time_;
    c->moving_ = moving_;
    c->rect_ = rect_;
    std::copy(corner_, corner_ + 4, c->corner_);
    std::copy(side_, side_ + 4, c->side_);
    c->hasBezier_ = hasBezier_;
    return c;
}

// ---- Bound and measures -----------------------------------------------------------------------------
LBBox3f CurvedBody::bound() const {
    if (cached_) return cachedBound_;
    LBBox3f b;
    const float s[2] = {keyFraction(time_.t0), keyFraction(time_.t1)};
    for (int t = 0; t < 2; ++t) {
        Bounds3f& bt = t == 0 ? b.b0 : b.b1;
        bt = hasBezier_ ? paddedBound(cp_[t].data(), 16) : box_[t];
        // Corners placed on a neighbour's chord may lie a hair outside the hull.
        for (const PieceCorner& c : corner_) bt.extend(atTime(c.P, s[t]));
    }
    return b;
}

void CurvedBody::sampleGrid(int n, Vec3f* out, int k) const {
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double u = rect_.u0 + (rect_.u1 - rect_.u0) * i / (n - 1);
            const double v = rect_.v0 + (rect_.v1 - rect_.v0) * j / (n - 1);
            mesh_->evaluate(face_, u, v, k, &out[j * n + i], nullptr);
        }
}

RasterMeasure CurvedBody::measure(const Camera& camera) const {
    if (cached_ && &camera == &mesh_->camera()) return cachedMeasure_;
    RasterMeasure m;
    const int times = moving_ ? 2 : 1;
    const float s[2] = {keyFraction(time_.t0), keyFraction(time_.t1)};
    float eu = 0, ev = 0, mo = 0;
    // Points whose projections bound the piece (control points, or the box's corners) and a
    // 4x4 or 3x3 net over it for the lengths of its rows and columns.
    Vec3f net[2][16];
    int n = 4;
    if (hasBezier_) {
        for (int t = 0; t < times; ++t)
            for (int i = 0; i < 16; ++i) net[t][i] = camera.toRaster(cp_[t][size_t(i)]);
    } else {
        n = 3;
        Vec3f key[2][9];
        for (int k = 0; k < (mesh_->moving() ? 2 : 1); ++k) sampleGrid(3, key[k], k);
        for (int t = 0; t < times; ++t)
            for (int i = 0; i < 9; ++i)
                net[t][i] = camera.toRaster(mesh_->moving() ? lerp(key[0][i], key[1][i], s[t]) : key[0][i]);
    }
    for (int t = 0; t < times; ++t) {
        Bounds3f& rb = t == 0 ? m.bound.b0 : m.bound.b1;
        if (hasBezier_) {
            for (int i = 0; i < 16; ++i) rb.extend(net[t][i]);
        } else {
            const Bounds3f& b = box_[t];
            for (int c = 0; c < 8; ++c)
                rb.extend(camera.toRaster({(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z}));
        }
        for (const PieceCorner& c : corner_) rb.extend(camera.toRaster(atTime(c.P, s[t])));
        for (int j = 0; j < n; ++j) {
            float lu = 0, lv = 0;
            for (int i = 0; i + 1 < n; ++i) {
                lu += rasterDistance(net[t][j * n + i], net[t][j * n + i + 1]);
                lv += rasterDistance(net[t][i * n + j], net[t][(i + 1) * n + j]);
            }
            eu = std::max(eu, lu);
            ev = std::max(ev, lv);
        }
    }
    if (!moving_) m.bound.b1 = m.bound.b0;
    else
        for (int i = 0; i < n * n; ++i) mo = std::max(mo, rasterDistance(net[0][i], net[1][i]));
    m.extentU = eu;
    m.extentV = ev;
    m.motion = mo;
    return m;
}

CameraExtents CurvedBody::cameraExtents() const {
    CameraExtents e;
    Vec3f net[2][16];
    int n = 4;
    if (hasBezier_) {
        for (int t = 0; t < 2; ++t) std::copy(cp_[t].begin(), cp_[t].end(), net[t]);
    } else {
        n = 3;
        Vec3f key[2][9];
        const int keys = mesh_->moving() ? 2 : 1;
        for (int k = 0; k < keys; ++k) sampleGrid(3, key[k], k);
        const float s[2] = {keyFraction(time_.t0), keyFraction(time_.t1)};
        for (int t = 0; t < 2; ++t)
            for (int i = 0; i < 9; ++i) net[t][i] = keys == 2 ? lerp(key[0][i], key[1][i], s[t]) : key[0][i];
    }
    for (int t = 0; t < 2; ++t)
        for (int j = 0; j < n; ++j) {
            float lu = 0, lv = 0;
            for (int i = 0; i + 1 < n; ++i) {
                lu += length(net[t][j * n + i + 1] - net[t][j * n + i]);
                lv += length(net[t][(i + 1) * n + j] - net[t][i * n + j]);
            }
            e.u = std::max(e.u, lu);
            e.v = std::max(e.v, lv);
        }
    if (moving_)
        for (int i = 0; i < n * n; ++i) e.t = std::max(e.t, length(net[1][i] - net[0][i]));
    return e;
}

// ---- Splits -----------------------------------------------------------------------------------------
void CurvedBody::split(SplitAxis axis, std::unique_ptr<Body> out[2]) const {
    std::unique_ptr<CurvedBody> lo = child(), hi = child();
    if (axis == SplitAxis::T) {
        const double tm = 0.5 * (time_.t0 + time_.t1);
        lo->time_.t1 = hi->time_.t0 = tm;
        lo->time_.openEnd = true;  // a sample exactly at tm belongs to the second half (TimeSpan)
        for (int t = 0; t < 2; ++t) {
            for (size_t i = 0; i < 16; ++i) {
                const Vec3f m = (cp_[0][i] + cp_[1][i]) * 0.5f;
                lo->cp_[t][i] = t == 0 ? cp_[0][i] : m;
                hi->cp_[t][i] = t == 0 ? m : cp_[1][i];
            }
            const Bounds3f mb = lerpBox(box_[0], box_[1], 0.5f);
            lo->box_[t] = t == 0 ? box_[0] : mb;
            hi->box_[t] = t == 0 ? mb : box_[1];
        }
        out[0] = std::move(lo);
        out[1] = std::move(hi);
        return;
    }

    const LineContext ctx = contextOf(*mesh_);
    const bool alongU = axis == SplitAxis::U;
    // The split crosses two sides (v = v0 and v = v1 for a u split) and makes a new line.
    const int sa = alongU ? 0 : 3, sb = alongU ? 2 : 1;
    // Their corners: side 0 runs from corner 0 to 1, side 2 from 2 to 3, side 3 from 0 to 2 and
    // side 1 from 1 to 3.
    PieceSide crossA = side_[sa], crossB = side_[sb];
    const double um = 0.5 * (rect_.u0 + rect_.u1), vm = 0.5 * (rect_.v0 + rect_.v1);
    const PieceCorner ca = alongU ? cornerOnSide(ctx, crossA, corner_[0], corner_[1], face_, um, rect_.v0)
                                  : cornerOnSide(ctx, crossA, corner_[0], corner_[2], face_, rect_.u0, vm);
    const PieceCorner cb = alongU ? cornerOnSide(ctx, crossB, corner_[2], corner_[3], face_, um, rect_.v1)
                                  : cornerOnSide(ctx, crossB, corner_[1], corner_[3], face_, rect_.u1, vm);
    PieceSide mid;
    if (alongU) {
        mid.line = {SurfaceLine::IsoU, face_, um};
        mid.a = rect_.v0, mid.b = rect_.v1;
        lo->rect_.u1 = hi->rect_.u0 = um;
    } else {
        mid.line = {SurfaceLine::IsoV, face_, vm};
        mid.a = rect_.u0, mid.b = rect_.u1;
        lo->rect_.v1 = hi->rect_.v0 = vm;
    }
    resolveState(ctx, mid);

    lo->side_[sa] = halfSide(crossA, true);
    hi->side_[sa] = halfSide(crossA, false);
    lo->side_[sb] = halfSide(crossB, true);
    hi->side_[sb] = halfSide(crossB, false);
    if (alongU) {
        // Corners: 0 (u0,v0) 1 (u1,v0) 2 (u0,v1) 3 (u1,v1). Sides 1 (u = u1) and 3 (u = u0).
        lo->corner_[1] = ca, lo->corner_[3] = cb;
        hi->corner_[0] = ca, hi->corner_[2] = cb;
        lo->side_[1] = mid;
        hi->side_[3] = mid;
    } else {
        lo->corner_[2] = ca, lo->corner_[3] = cb;
        hi->corner_[0] = ca, hi->corner_[1] = cb;
        lo->side_[2] = mid;
        hi->side_[0] = mid;
    }
    if (hasBezier_) {
        for (int t = 0; t < 2; ++t) splitBezier(cp_[t], alongU ? 0 : 1, lo->cp_[t], hi->cp_[t]);
    } else {
        lo->setPayload();
        hi->setPayload();
    }
    out[0] = std::move(lo);
    out[1] = std::move(hi);
}

std::unique_ptr<Body> CurvedBody::restrictedTo(double a, double b) const {
    std::unique_ptr<CurvedBody> r = child();
    r->time_ = {a, b, b == time_.t1 && time_.openEnd};  // cut short of t1: closed at b
    if (moving_) {
        const double len = time_.t1 - time_.t0;
        const float sa = a == time_.t0 ? 0.0f : float((a - time_.t0) / len);
        const float sb = b == time_.t1 ? 1.0f : float((b - time_.t0) / len);
        for (size_t i = 0; i < 16; ++i) {
            r->cp_[0][i] = lerp(cp_[0][i], cp_[1][i], sa);
            r->cp_[1][i] = lerp(cp_[0][i], cp_[1][i], sb);
        }
        r->box_[0] = lerpBox(box_[0], box_[1], sa);
        r->box_[1] = lerpBox(box_[0], box_[1], sb);
    } else {
        std::copy(cp_, cp_ + 2, r->cp_);
        std::copy(box_, box_ + 2, r->box_);
    }
    return r;
}

// ---- Dicing -----------------------------------------------------------------------------------------
void CurvedBody::dice(int nu, int nv, Grid& grid) const {
    if (mesh_->trimmedAway(face_, rect_)) {
        // Wholly inside a trim hole: every micropolygon of any grid would be cut, so one cut
        // micropolygon over the corners stands for them (nothing to evaluate, shade or sample).
        startGrid(1, 1, grid);
        const float s[2] = {keyFraction(time_.t0), keyFraction(time_.t1)};
        for (int c = 0; c < 4; ++c) {
            const size_t idx = size_t(grid.index(c & 1, c >> 1));
            for (int t = 0; t < (moving_ ? 2 : 1); ++t) {
                grid.P[t][idx] = atTime(corner_[c].P, s[t]);
                grid.N[t][idx] = atTime(corner_[c].N, s[t]);
            }
            grid.Cs[idx] = mesh_->colorAt(face_, (c & 1) ? rect_.u1 : rect_.u0, (c & 2) ? rect_.v1 : rect_.v0);
        }
        grid.hole.assign(1, 1);
        return;
    }
    const LineContext ctx = contextOf(*mesh_);
    const int keys = ctx.keys;
    // Sides in grid order: 0 (row 0), 1 (column NU), 2 (row NV), 3 (column 0), and their corners.
    static constexpr int kEnds[4][2] = {{0, 1}, {1, 3}, {2, 3}, {0, 2}};
    thread_local SideVertices sides[4];
    for (int k = 0; k < 4; ++k) {
        SideVertices& sv = sides[k];
        sv.clear();
        PieceSide s = side_[k];
        resolveState(ctx, s);
        latticePoints(ctx, s, sv.params);
        if (s.reversed) std::reverse(sv.params.begin(), sv.params.end());
        const PieceCorner& first = corner_[kEnds[k][0]];
        const PieceCorner& last = corner_[kEnds[k][1]];
        auto faceParam = [&](float t, double* u, double* v) {
            const bool horizontal = k == 0 || k == 2;
            const double along = horizontal ? rect_.u0 + (rect_.u1 - rect_.u0) * t : rect_.v0 + (rect_.v1 - rect_.v0) * t;
            const double across = k == 0 ? rect_.v0 : k == 2 ? rect_.v1 : k == 3 ? rect_.u0 : rect_.u1;
            *u = horizontal ? along : across;
            *v = horizontal ? across : along;
        };
        double pu, pv;
        faceParam(0, &pu, &pv);
        sv.add(first.P, first.N, pu, pv, 0);
        for (double p : sv.params) {
            const float t = float(s.reversed ? (s.b - p) / (s.b - s.a) : (p - s.a) / (s.b - s.a));
            faceParam(t, &pu, &pv);
            Vec3f P[2], N[2];
            for (int key = 0; key < keys; ++key) {
                evalLine(*mesh_, s.line, p, key, &P[key], &N[key]);
                if (s.line.kind == SurfaceLine::Edge) {  // the owner's position, this face's normal
                    Vec3f unused;
                    mesh_->evaluate(face_, pu, pv, key, &unused, &N[key]);
                }
            }
            if (keys == 1) P[1] = P[0], N[1] = N[0];
            sv.add(P, N, pu, pv, t);
        }
        faceParam(1, &pu, &pv);
        sv.add(last.P, last.N, pu, pv, 1);
    }
    // Enough columns (rows) for each side's finest step, so that every side vertex sits at the
    // column of its own parameter (within half a column) and the first row of micropolygons does
    // not fold over.
    const int NU = std::max({nu, sides[0].columnsNeeded(), sides[2].columnsNeeded()});
    const int NV = std::max({nv, sides[1].columnsNeeded(), sides[3].columnsNeeded()});
    columnMap(sides[0], NU);
    columnMap(sides[2], NU);
    columnMap(sides[1], NV);
    columnMap(sides[3], NV);

    startGrid(NU, NV, grid);
    grid.paramU.resize(size_t(grid.vertexCount()));
    grid.paramV.resize(size_t(grid.vertexCount()));
    const double du = rect_.u1 - rect_.u0, dv = rect_.v1 - rect_.v0;
    const float s[2] = {keyFraction(time_.t0), keyFraction(time_.t1)};
    for (int j = 0; j <= NV; ++j) {
        for (int i = 0; i <= NU; ++i) {
            Vec3f P[2], N[2];
            double u, v;
            const SideVertices* sv = nullptr;
            size_t m = 0;
            if (j == 0) sv = &sides[0], m = size_t(sides[0].map[size_t(i)]);
            else if (j == NV) sv = &sides[2], m = size_t(sides[2].map[size_t(i)]);
            else if (i == 0) sv = &sides[3], m = size_t(sides[3].map[size_t(j)]);
            else if (i == NU) sv = &sides[1], m = size_t(sides[1].map[size_t(j)]);
            if (sv) {
                for (int k = 0; k < 2; ++k) P[k] = sv->P[k][m], N[k] = sv->N[k][m];
                u = sv->u[m], v = sv->v[m];
            } else {
                u = rect_.u0 + (rect_.u1 - rect_.u0) * i / NU;
                v = rect_.v0 + (rect_.v1 - rect_.v0) * j / NV;
                for (int k = 0; k < keys; ++k) mesh_->evaluate(face_, u, v, k, &P[k], &N[k]);
                if (keys == 1) P[1] = P[0], N[1] = N[0];
            }
            const size_t idx = size_t(grid.index(i, j));
            for (int t = 0; t < (moving_ ? 2 : 1); ++t) {
                grid.P[t][idx] = atTime(P, s[t]);
                grid.N[t][idx] = atTime(N, s[t]);
            }
            grid.Cs[idx] = mesh_->colorAt(face_, u, v);
            grid.paramU[idx] = i == 0 ? 0.0f : i == NU ? 1.0f : du > 0 ? float((u - rect_.u0) / du) : 0.0f;
            grid.paramV[idx] = j == 0 ? 0.0f : j == NV ? 1.0f : dv > 0 ? float((v - rect_.v0) / dv) : 0.0f;
        }
    }
    // Micropolygons whose centre a trim curve cuts away (a NuPatch's TrimCurve); none elsewhere.
    mesh_->trimQuads(face_, rect_, NU, NV, grid.hole);
}

}  // namespace streyes
