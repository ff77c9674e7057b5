#include "scene/blobby_field.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <functional>
#include <unordered_map>

namespace streyes {

double blobFalloff(double r2) {
    if (!(r2 < 1)) return 0;
    const double s = 1 - r2;
    return s * s * s;
}

namespace {

// Aqsis's (libs/core/geometry/blobby.cpp): the lowest-degree polynomials with these ends.
double repulsionBump(double r) {
    if (r <= 0 || r >= 2) return 0;
    return (((6 - r) * r - 12) * r + 8) * r * r * r;
}
double repulsionEase(double r) {
    if (r <= 0) return 0;
    if (r >= 1) return 1;
    return r * r * (3 - 2 * r);
}

}  // namespace

double blobbyRepulsion(double z, double A, double B, double C, double D) {
    if (!(A > 0) || !(z < A)) return 0;  // A = 0: no repulsion; z infinite: no ground
    z = std::max(z, 1e-6);
    return (D * repulsionBump(z / C) - B / z) * (1 - repulsionEase(z / A));
}

double BlobbyGround::height(Vec3d p) const {
    const double inf = std::numeric_limits<double>::infinity();
    const double depth = objectToCamera.point(p).z;
    if (!(depth > 0) || map.width < 1 || map.height < 1) return inf;
    const Vec3d s = objectToScreen.point(p);
    // Pixel coordinates, pixel centres at half-integers; y down from the top row.
    const double x = (s.x + 1) * 0.5 * map.width, y = (1 - s.y) * 0.5 * map.height;
    if (!(x >= 0 && x <= map.width && y >= 0 && y <= map.height)) return inf;
    auto at = [&](int i, int j) {
        i = std::clamp(i, 0, map.width - 1);
        j = std::clamp(j, 0, map.height - 1);
        return double(map.z[size_t(j) * size_t(map.width) + size_t(i)]);
    };
    const double fx = x - 0.5, fy = y - 0.5;
    const int i0 = int(std::floor(fx)), j0 = int(std::floor(fy));
    const double tx = fx - i0, ty = fy - j0;
    const double z00 = at(i0, j0), z10 = at(i0 + 1, j0), z01 = at(i0, j0 + 1), z11 = at(i0 + 1, j0 + 1);
    const double none = double(std::numeric_limits<float>::max());
    double ground;
    if (z00 < none && z10 < none && z01 < none && z11 < none) {
        ground = (z00 * (1 - tx) + z10 * tx) * (1 - ty) + (z01 * (1 - tx) + z11 * tx) * ty;
    } else {
        ground = at(int(std::floor(x)), int(std::floor(y)));
        if (!(ground < none)) return inf;
    }
    return ground - depth;
}

namespace {

// A repelling plane's field at p.
double planeValue(const BlobbyOp& op, Vec3d p) {
    const double z = op.ground ? op.ground->height(p) : -p.z;
    return blobbyRepulsion(z, op.repel[0], op.repel[1], op.repel[2], op.repel[3]);
}

// Squared distance from q to the segment a-b.
double segmentDistance2(Vec3d q, Vec3d a, Vec3d b) {
    const Vec3d ab = b - a;
    const double len2 = dot(ab, ab);
    double t = len2 > 0 ? dot(q - a, ab) / len2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    const Vec3d d = q - (a + ab * t);
    return dot(d, d);
}

void grow(Vec3d p, Vec3d* lo, Vec3d* hi) {
    *lo = {std::min(lo->x, p.x), std::min(lo->y, p.y), std::min(lo->z, p.z)};
    *hi = {std::max(hi->x, p.x), std::max(hi->y, p.y), std::max(hi->z, p.z)};
}

}  // namespace

double BlobbyField::leafValue(size_t i, Vec3d p) const {
    const BlobbyOp& op = ops[i];
    switch (op.kind) {
    case BlobbyOp::Kind::Ellipsoid: {
        const Vec3d q = op.toBlob.point(p);
        return blobFalloff(dot(q, q));
    }
    case BlobbyOp::Kind::Segment: {
        const Vec3d q = op.toBlob.point(p);
        return blobFalloff(segmentDistance2(q, op.a, op.b) / (op.radius * op.radius));
    }
    case BlobbyOp::Kind::Plugin: return op.plugin ? op.plugin->value(p) : 0;
    default: return 0;
    }
}

double BlobbyField::value(Vec3d p, std::vector<double>& v) const {
    v.resize(ops.size());
    for (size_t i = 0; i < ops.size(); ++i) {
        const BlobbyOp& op = ops[i];
        const std::vector<int>& o = op.operands;
        double r = 0;
        switch (op.kind) {
        case BlobbyOp::Kind::Constant: r = op.value; break;
        case BlobbyOp::Kind::Ellipsoid:
        case BlobbyOp::Kind::Segment:
        case BlobbyOp::Kind::Plugin: r = leafValue(i, p); break;
        case BlobbyOp::Kind::Plane: r = planeValue(op, p); break;
        case BlobbyOp::Kind::Add:
            for (int k : o) r += v[size_t(k)];
            break;
        case BlobbyOp::Kind::Multiply:
            r = 1;
            for (int k : o) r *= v[size_t(k)];
            break;
        case BlobbyOp::Kind::Max:
            r = -std::numeric_limits<double>::infinity();
            for (int k : o) r = std::max(r, v[size_t(k)]);
            break;
        case BlobbyOp::Kind::Min:
            r = std::numeric_limits<double>::infinity();
            for (int k : o) r = std::min(r, v[size_t(k)]);
            break;
        case BlobbyOp::Kind::Subtract: r = v[size_t(o[0])] - v[size_t(o[1])]; break;
        case BlobbyOp::Kind::Divide: {
            // x / 0 is taken as 0: outside, and never a NaN that would poison the bisection.
            const double d = v[size_t(o[1])];
            r = d != 0 ? v[size_t(o[0])] / d : 0;
            break;
        }
        case BlobbyOp::Kind::Negate: r = -v[size_t(o[0])]; break;
        case BlobbyOp::Kind::Identity: r = v[size_t(o[0])]; break;
        }
        v[i] = r;
    }
    return v.empty() ? 0 : v.back();
}

bool BlobbyField::bound(Vec3d* lo, Vec3d* hi) const {
    const double inf = std::numeric_limits<double>::infinity();
    *lo = {inf, inf, inf};
    *hi = {-inf, -inf, -inf};
    bool any = false;
    for (const BlobbyOp& op : ops) {
        Vec3d blo, bhi;
        if (op.kind == BlobbyOp::Kind::Ellipsoid) {
            blo = {-1, -1, -1};
            bhi = {1, 1, 1};
        } else if (op.kind == BlobbyOp::Kind::Segment) {
            const Vec3d r{op.radius, op.radius, op.radius};
            blo = {std::min(op.a.x, op.b.x), std::min(op.a.y, op.b.y), std::min(op.a.z, op.b.z)};
            bhi = {std::max(op.a.x, op.b.x), std::max(op.a.y, op.b.y), std::max(op.a.z, op.b.z)};
            blo = blo - r;
            bhi = bhi + r;
        } else if (op.kind == BlobbyOp::Kind::Plugin && op.plugin) {
            grow(op.plugin->lo(), lo, hi);  // already in object space
            grow(op.plugin->hi(), lo, hi);
            any = true;
            continue;
        } else {
            continue;
        }
        // The blob-space box's corners in object space (an affine matrix keeps the box inside).
        for (int c = 0; c < 8; ++c)
            grow(op.toObject.point({c & 1 ? bhi.x : blo.x, c & 2 ? bhi.y : blo.y, c & 4 ? bhi.z : blo.z}), lo, hi);
        any = true;
    }
    return any;
}

// ---- BlobbyEvaluator ----------------------------------------------------------------------------
namespace {

// A leaf's support (where its field is not 0) in object space: the box of its blob-space box.
bool leafBox(const BlobbyOp& op, Vec3d* lo, Vec3d* hi) {
    Vec3d blo, bhi;
    if (op.kind == BlobbyOp::Kind::Ellipsoid) {
        blo = {-1, -1, -1};
        bhi = {1, 1, 1};
    } else if (op.kind == BlobbyOp::Kind::Segment) {
        const Vec3d r{op.radius, op.radius, op.radius};
        blo = Vec3d{std::min(op.a.x, op.b.x), std::min(op.a.y, op.b.y), std::min(op.a.z, op.b.z)} - r;
        bhi = Vec3d{std::max(op.a.x, op.b.x), std::max(op.a.y, op.b.y), std::max(op.a.z, op.b.z)} + r;
    } else if (op.kind == BlobbyOp::Kind::Plugin && op.plugin) {
        *lo = op.plugin->lo();
        *hi = op.plugin->hi();
        return true;
    } else {
        return false;
    }
    const double inf = std::numeric_limits<double>::infinity();
    *lo = {inf, inf, inf};
    *hi = {-inf, -inf, -inf};
    for (int c = 0; c < 8; ++c)
        grow(op.toObject.point({c & 1 ? bhi.x : blo.x, c & 2 ? bhi.y : blo.y, c & 4 ? bhi.z : blo.z}), lo, hi);
    return true;
}

// Instruction i's value from its operands' values in v (BlobbyField::value's arithmetic).
double evaluateOp(const BlobbyField& field, size_t i, const std::vector<double>& v, Vec3d p) {
    const BlobbyOp& op = field.ops[i];
    const std::vector<int>& o = op.operands;
    double r = 0;
    switch (op.kind) {
    case BlobbyOp::Kind::Constant: r = op.value; break;
    case BlobbyOp::Kind::Ellipsoid:
    case BlobbyOp::Kind::Segment:
    case BlobbyOp::Kind::Plugin: r = field.leafValue(i, p); break;
    case BlobbyOp::Kind::Plane: r = planeValue(op, p); break;
    case BlobbyOp::Kind::Add:
        for (int k : o) r += v[size_t(k)];
        break;
    case BlobbyOp::Kind::Multiply:
        r = 1;
        for (int k : o) r *= v[size_t(k)];
        break;
    case BlobbyOp::Kind::Max:
        r = -std::numeric_limits<double>::infinity();
        for (int k : o) r = std::max(r, v[size_t(k)]);
        break;
    case BlobbyOp::Kind::Min:
        r = std::numeric_limits<double>::infinity();
        for (int k : o) r = std::min(r, v[size_t(k)]);
        break;
    case BlobbyOp::Kind::Subtract: r = v[size_t(o[0])] - v[size_t(o[1])]; break;
    case BlobbyOp::Kind::Divide: {
        // x / 0 is taken as 0: outside, and never a NaN that would poison the bisection.
        const double d = v[size_t(o[1])];
        r = d != 0 ? v[size_t(o[0])] / d : 0;
        break;
    }
    case BlobbyOp::Kind::Negate: r = -v[size_t(o[0])]; break;
    case BlobbyOp::Kind::Identity: r = v[size_t(o[0])]; break;
    }
    return r;
}

}  // namespace

BlobbyEvaluator::BlobbyEvaluator(const BlobbyField& field) : field_(field) {
    const size_t n = field.ops.size();
    users_.resize(n);
    fixed_.resize(n);
    leafLo_.resize(n);
    leafHi_.resize(n);
    base_.assign(n, 0);
    for (size_t i = 0; i < n; ++i) {
        const BlobbyOp& op = field.ops[i];
        for (size_t at = 0; at < op.operands.size(); ++at) users_[size_t(op.operands[at])].push_back({i, at});
        // With no leaf present (every leaf's field 0), at a point where no support reaches.
        if (op.kind == BlobbyOp::Kind::Plane) planes_.push_back(i);
        base_[i] = op.kind == BlobbyOp::Kind::Ellipsoid || op.kind == BlobbyOp::Kind::Segment ||
                           op.kind == BlobbyOp::Kind::Plane || op.kind == BlobbyOp::Kind::Plugin
                       ? 0
                       : evaluateOp(field, i, base_, {0, 0, 0});
        if (op.kind == BlobbyOp::Kind::Add)
            for (size_t at = 0; at < op.operands.size(); ++at)
                if (base_[size_t(op.operands[at])] != 0) fixed_[i].push_back(at);
    }
    v_ = base_;
    positions_.resize(n);
    pending_.assign(n, 0);
    // Bins: about two leaves a bin along each axis, at most 64 a side.
    std::vector<size_t> leaves;
    Vec3d lo, hi;
    const bool any = field.bound(&lo, &hi);
    for (size_t i = 0; i < n; ++i)
        if (leafBox(field.ops[i], &leafLo_[i], &leafHi_[i])) leaves.push_back(i);
    if (!any || leaves.empty()) return;
    bins_ = std::clamp(int(std::cbrt(double(leaves.size()))), 1, 64);
    lo_ = lo;
    size_ = hi - lo;
    binLeaves_.resize(size_t(bins_) * size_t(bins_) * size_t(bins_));
    auto binOf = [&](double x, double l, double s) {
        return s > 0 ? std::clamp(int(std::floor((x - l) / s * bins_)), 0, bins_ - 1) : 0;
    };
    for (size_t i : leaves) {
        const int x0 = binOf(leafLo_[i].x, lo_.x, size_.x), x1 = binOf(leafHi_[i].x, lo_.x, size_.x);
        const int y0 = binOf(leafLo_[i].y, lo_.y, size_.y), y1 = binOf(leafHi_[i].y, lo_.y, size_.y);
        const int z0 = binOf(leafLo_[i].z, lo_.z, size_.z), z1 = binOf(leafHi_[i].z, lo_.z, size_.z);
        for (int z = z0; z <= z1; ++z)
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x)
                    binLeaves_[size_t(x) + size_t(bins_) * (size_t(y) + size_t(bins_) * size_t(z))].push_back(i);
    }
}

const std::vector<size_t>& BlobbyEvaluator::leavesNear(Vec3d p) {
    near_.clear();
    if (bins_ == 0) return near_;
    auto binOf = [&](double x, double l, double s, int* b) {
        if (!(x >= l && x <= l + s)) return false;
        *b = s > 0 ? std::clamp(int(std::floor((x - l) / s * bins_)), 0, bins_ - 1) : 0;
        return true;
    };
    int bx, by, bz;
    if (!binOf(p.x, lo_.x, size_.x, &bx) || !binOf(p.y, lo_.y, size_.y, &by) || !binOf(p.z, lo_.z, size_.z, &bz))
        return near_;
    for (size_t i : binLeaves_[size_t(bx) + size_t(bins_) * (size_t(by) + size_t(bins_) * size_t(bz))]) {
        const Vec3d &l = leafLo_[i], &h = leafHi_[i];
        if (p.x >= l.x && p.x <= h.x && p.y >= l.y && p.y <= h.y && p.z >= l.z && p.z <= h.z) near_.push_back(i);
    }
    return near_;
}

double BlobbyEvaluator::value(Vec3d p) {
    const size_t n = field_.ops.size();
    if (n == 0) return 0;
    leavesNear(p);
    if (near_.empty() && planes_.empty()) return base_.back();
    // Instructions changed from their base, in code order (operands come before their users): a
    // min-heap of indices.
    auto push = [&](size_t i) {
        if (pending_[i]) return;
        pending_[i] = 1;
        heap_.push_back(i);
        std::push_heap(heap_.begin(), heap_.end(), std::greater<size_t>());
    };
    for (size_t i : near_) push(i);
    for (size_t i : planes_) push(i);
    while (!heap_.empty()) {
        std::pop_heap(heap_.begin(), heap_.end(), std::greater<size_t>());
        const size_t i = heap_.back();
        heap_.pop_back();
        changed_.push_back(i);
        const BlobbyOp& op = field_.ops[i];
        double r;
        if (op.kind == BlobbyOp::Kind::Add) {
            // Its operands in order, but those that are 0 (adding 0 changes no sum).
            std::vector<size_t>& at = positions_[i];
            at.insert(at.end(), fixed_[i].begin(), fixed_[i].end());
            std::sort(at.begin(), at.end());
            at.erase(std::unique(at.begin(), at.end()), at.end());
            r = 0;
            for (size_t k : at) r += v_[size_t(op.operands[k])];
            at.clear();
        } else {
            r = evaluateOp(field_, i, v_, p);
        }
        v_[i] = r;
        for (const auto& [u, k] : users_[i]) {
            if (field_.ops[u].kind == BlobbyOp::Kind::Add && r != 0) positions_[u].push_back(k);
            push(u);
        }
    }
    const double result = v_.back();
    for (size_t i : changed_) v_[i] = base_[i], pending_[i] = 0;
    changed_.clear();
    return result;
}

namespace {

// The six tetrahedra of a cell around its diagonal from corner 0 to corner 7 (corner c is at
// x = c & 1, y = c & 2, z = c & 4): every cell cuts a shared face along the same diagonal.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

std::array<int, 3> cornerOffset(int c) { return {c & 1, (c >> 1) & 1, (c >> 2) & 1}; }

// The sign of the volume of tetrahedron (a, b, c, d) of cell corners: exact, in whole numbers.
int orientation(int a, int b, int c, int d) {
    const std::array<int, 3> p = cornerOffset(a), q = cornerOffset(b), r = cornerOffset(c), s = cornerOffset(d);
    const int u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const int v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    const int w[3] = {s[0] - p[0], s[1] - p[1], s[2] - p[2]};
    const int det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                    u[2] * (v[0] * w[1] - v[1] * w[0]);
    return det > 0 ? 1 : -1;
}

class Polygonizer {
  public:
    Polygonizer(const BlobbyField& field, Vec3d origin, double h, int nx, int ny, int nz)
        : eval_(field), origin_(origin), h_(h), n_{nx, ny, nz} {}

    BlobbyMesh run() {
        const size_t px = size_t(n_[0]) + 1, py = size_t(n_[1]) + 1, pz = size_t(n_[2]) + 1;
        values_.resize(px * py * pz);
        for (size_t k = 0; k < pz; ++k)
            for (size_t j = 0; j < py; ++j)
                for (size_t i = 0; i < px; ++i) {
                    const size_t idx = i + px * (j + py * k);
                    values_[idx] = eval_.value(position(idx));
                    const bool edge = i == 0 || j == 0 || k == 0 || i + 1 == px || j + 1 == py || k + 1 == pz;
                    if (edge && values_[idx] > kBlobbyLevel) mesh_.openAtBound = true;
                }
        for (int k = 0; k < n_[2]; ++k)
            for (int j = 0; j < n_[1]; ++j)
                for (int i = 0; i < n_[0]; ++i) cell(size_t(i), size_t(j), size_t(k));
        return std::move(mesh_);
    }

  private:
    Vec3d position(size_t idx) const {
        const size_t px = size_t(n_[0]) + 1, py = size_t(n_[1]) + 1;
        const size_t i = idx % px, j = (idx / px) % py, k = idx / (px * py);
        return origin_ + Vec3d{double(i), double(j), double(k)} * h_;
    }

    // The vertex where the level crosses the edge from grid point `in` (above it) to `out`. A
    // crossing at a grid point (exactly: 27/64 is a binary fraction and a blob's level sphere passes
    // through grid points; or within a millionth of a cell, where the surface grazes the grid) is
    // one vertex for every edge that meets the level there, keyed by the point: the triangles
    // around it share it, those it collapses have two equal corners and are left out, and the mesh
    // stays closed. Elsewhere each edge has its own vertex, found by bisection on the field.
    int vertex(size_t in, size_t out) {
        const uint64_t n = values_.size();
        const uint64_t key = uint64_t(std::min(in, out)) * n + uint64_t(std::max(in, out));
        auto found = vertices_.find(key);
        if (found != vertices_.end()) return found->second;
        const Vec3d inP = position(in), outP = position(out);
        size_t at = values_[out] == kBlobbyLevel ? out : SIZE_MAX;
        Vec3d p = outP;
        if (at == SIZE_MAX) {
            Vec3d a = inP, b = outP;
            for (int it = 0; it < 30; ++it) {
                const Vec3d m = (a + b) * 0.5;
                (eval_.value(m) > kBlobbyLevel ? a : b) = m;
            }
            p = (a + b) * 0.5;
            constexpr double kGraze = 1e-6;  // of a cell
            if (length(p - outP) < kGraze * h_) at = out;
            else if (length(p - inP) < kGraze * h_) at = in;
        }
        int v;
        if (at == SIZE_MAX) {
            v = int(mesh_.P.size());
            mesh_.P.push_back(p);
        } else {
            const uint64_t pointKey = uint64_t(at) * n + uint64_t(at);  // no edge has min == max
            auto shared = vertices_.find(pointKey);
            if (shared != vertices_.end()) {
                v = shared->second;
            } else {
                v = int(mesh_.P.size());
                mesh_.P.push_back(position(at));
                vertices_.emplace(pointKey, v);
            }
        }
        vertices_.emplace(key, v);
        return v;
    }

    void triangle(int a, int b, int c) {
        if (a == b || b == c || a == c) return;
        const Vec3d n = cross(mesh_.P[size_t(b)] - mesh_.P[size_t(a)], mesh_.P[size_t(c)] - mesh_.P[size_t(a)]);
        // No area (rounding only: a vertex within a millionth of a cell of a grid point is that point):
        // nothing to draw, no crack left.
        if (dot(n, n) <= 1e-32 * h_ * h_ * h_ * h_) return;
        mesh_.triangles.push_back({a, b, c});
    }

    void cell(size_t i, size_t j, size_t k) {
        const size_t px = size_t(n_[0]) + 1, py = size_t(n_[1]) + 1;
        size_t corner[8];
        for (int c = 0; c < 8; ++c) {
            const std::array<int, 3> o = cornerOffset(c);
            corner[c] = (i + size_t(o[0])) + px * ((j + size_t(o[1])) + py * (k + size_t(o[2])));
        }
        for (const auto& tet : kTets) {
            int in[4], out[4], nin = 0, nout = 0;
            for (int c : tet) (values_[corner[c]] > kBlobbyLevel ? in[nin++] : out[nout++]) = c;
            if (nin == 0 || nout == 0) continue;
            auto v = [&](int a, int b) { return vertex(corner[a], corner[b]); };
            if (nin == 1) {
                // Wound (o0, o1, o2) seen from `in`: dPdu x dPdv points away from it when
                // (in, o0, o1, o2) has positive volume.
                const bool pos = orientation(in[0], out[0], out[1], out[2]) > 0;
                if (pos)
                    triangle(v(in[0], out[0]), v(in[0], out[1]), v(in[0], out[2]));
                else
                    triangle(v(in[0], out[0]), v(in[0], out[2]), v(in[0], out[1]));
            } else if (nin == 3) {
                // Facing the outside corner: the reverse of the winding that faces away from it.
                const bool pos = orientation(out[0], in[0], in[1], in[2]) > 0;
                if (pos)
                    triangle(v(in[0], out[0]), v(in[2], out[0]), v(in[1], out[0]));
                else
                    triangle(v(in[0], out[0]), v(in[1], out[0]), v(in[2], out[0]));
            } else {
                // Two in (a, b), two out (c, d): the quad a-c, a-d, b-d, b-c faces c and d when
                // (a, b, c, d) has positive volume.
                int q[4] = {v(in[0], out[0]), v(in[0], out[1]), v(in[1], out[1]), v(in[1], out[0])};
                if (orientation(in[0], in[1], out[0], out[1]) < 0) std::swap(q[1], q[3]);
                triangle(q[0], q[1], q[2]);
                triangle(q[0], q[2], q[3]);
            }
        }
    }

    BlobbyEvaluator eval_;
    Vec3d origin_;
    double h_;
    int n_[3];
    std::vector<double> values_;
    std::unordered_map<uint64_t, int> vertices_;
    BlobbyMesh mesh_;
};

}  // namespace

BlobbyMesh polygonizeBlobby(const BlobbyField& field, int cells) {
    Vec3d lo, hi;
    if (!field.bound(&lo, &hi)) return {};
    const Vec3d extent = hi - lo;
    const double longest = std::max({extent.x, extent.y, extent.z});
    if (!(longest > 0) || cells < 1) return {};
    const double h = longest / cells;
    auto count = [h](double e) { return int(std::ceil(e / h - 1e-9)) + 2; };  // one cell of padding each side
    return Polygonizer(field, lo - Vec3d{h, h, h}, h, count(extent.x), count(extent.y), count(extent.z)).run();
}

}  // namespace streyes
