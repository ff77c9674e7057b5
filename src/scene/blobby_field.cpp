#include "scene/blobby_field.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace streyes {

double blobFalloff(double r2) {
    if (!(r2 < 1)) return 0;
    const double s = 1 - r2;
    return s * s * s;
}

namespace {

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
        case BlobbyOp::Kind::Segment: r = leafValue(i, p); break;
        case BlobbyOp::Kind::Plane: r = 0; break;  // skipped with a warning when read
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
        : field_(field), origin_(origin), h_(h), n_{nx, ny, nz} {}

    BlobbyMesh run() {
        const size_t px = size_t(n_[0]) + 1, py = size_t(n_[1]) + 1, pz = size_t(n_[2]) + 1;
        values_.resize(px * py * pz);
        for (size_t k = 0; k < pz; ++k)
            for (size_t j = 0; j < py; ++j)
                for (size_t i = 0; i < px; ++i) {
                    const size_t idx = i + px * (j + py * k);
                    values_[idx] = field_.value(position(idx), scratch_);
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

    // The vertex where the level crosses the edge from grid point `in` (above it) to `out`.
    int vertex(size_t in, size_t out) {
        const uint64_t key = uint64_t(std::min(in, out)) * values_.size() + uint64_t(std::max(in, out));
        auto found = vertices_.find(key);
        if (found != vertices_.end()) return found->second;
        Vec3d a = position(in), b = position(out);
        if (values_[out] == kBlobbyLevel) {
            a = b;  // on the level exactly
        } else {
            // Bisection keeps the vertex on the true surface to well below a cell's size.
            for (int it = 0; it < 30; ++it) {
                const Vec3d m = (a + b) * 0.5;
                (field_.value(m, scratch_) > kBlobbyLevel ? a : b) = m;
            }
        }
        const int v = int(mesh_.P.size());
        mesh_.P.push_back((a + b) * 0.5);
        vertices_.emplace(key, v);
        return v;
    }

    void triangle(int a, int b, int c) {
        if (a == b || b == c || a == c) return;
        const Vec3d n = cross(mesh_.P[size_t(b)] - mesh_.P[size_t(a)], mesh_.P[size_t(c)] - mesh_.P[size_t(a)]);
        if (dot(n, n) <= 1e-24 * h_ * h_ * h_ * h_) return;  // no area: nothing to draw, no crack left
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

    const BlobbyField& field_;
    Vec3d origin_;
    double h_;
    int n_[3];
    std::vector<double> values_, scratch_;
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
