// The disc hierarchy of a baked cloud (point_based_tree.h): a top-down octree over cubic cells.
#include "shade/point_based_tree.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace streyes {

namespace {

constexpr float kPi = 3.14159265358979f;

}  // namespace

DiscHierarchy::DiscHierarchy(const BakedPointCloud& cloud) {
    int areaAt = -1, areaComps = 0, radAt = -1, radComps = 0;
    if (!cloud.channel("_area", &areaAt, &areaComps) || areaComps != 1) areaAt = -1;
    hasRadiosity_ = cloud.channel("_radiosity", &radAt, &radComps) && radComps == 3;
    input_.reserve(cloud.size());
    for (size_t i = 0; i < cloud.size(); ++i) {
        const float* p = cloud.point(i);
        CloudDisc d;
        const float nl = std::sqrt(p[3] * p[3] + p[4] * p[4] + p[5] * p[5]);
        // A point without a direction or a size hides nothing (bake3d never writes NaN).
        if (!(nl > 0) || !(p[6] > 0) || !std::isfinite(nl)) continue;
        for (int c = 0; c < 3; ++c) d.P[c] = p[c], d.N[c] = p[3 + c] / nl;
        d.radius = p[6];
        d.area = areaAt >= 0 && p[areaAt] > 0 ? p[areaAt] : kPi * d.radius * d.radius;
        for (int c = 0; c < 3; ++c) d.radiosity[c] = hasRadiosity_ ? p[radAt + c] : 0.0f;
        input_.push_back(d);
    }
    if (input_.empty()) return;
    // A cubic root cell: clusters of an elongated cell would bunch their discs in the middle and
    // leave gaps between neighbouring clusters' discs.
    float lo[3], hi[3];
    for (int c = 0; c < 3; ++c) lo[c] = hi[c] = input_[0].P[c];
    for (const CloudDisc& d : input_)
        for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], d.P[c]), hi[c] = std::max(hi[c], d.P[c]);
    const float size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-30f});
    float cubeLo[3];
    for (int c = 0; c < 3; ++c) cubeLo[c] = 0.5f * (lo[c] + hi[c]) - 0.5f * size;
    std::vector<uint32_t> idx(input_.size());
    std::iota(idx.begin(), idx.end(), 0u);
    discs_.reserve(input_.size());
    clusters_.emplace_back();
    build(0, idx.data(), idx.size(), cubeLo, size, 0);
    input_.clear();
    input_.shrink_to_fit();
}

void DiscHierarchy::aggregate(DiscCluster& c, const CloudDisc* const* members, size_t n) const {
    double area = 0, P[3] = {}, N[3] = {}, rad[3] = {};
    for (size_t i = 0; i < n; ++i) {
        const CloudDisc& d = *members[i];
        area += d.area;
        for (int k = 0; k < 3; ++k) {
            P[k] += double(d.area) * d.P[k];
            N[k] += double(d.area) * d.N[k];
            rad[k] += double(d.area) * d.radiosity[k];
        }
    }
    const double nl = std::sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
    c.area = float(area);
    // Normals that (nearly) cancel, as a thin slab's two faces do, make no disc: such a cluster
    // is always opened.
    c.drawable = area > 0 && nl > 1e-3 * area;
    for (int k = 0; k < 3; ++k) {
        c.P[k] = float(area > 0 ? P[k] / area : 0);
        c.N[k] = float(c.drawable ? N[k] / nl : 0);
        c.radiosity[k] = float(area > 0 ? rad[k] / area : 0);
    }
    float bound = 0;
    for (size_t i = 0; i < n; ++i) {
        const CloudDisc& d = *members[i];
        const float dx = d.P[0] - c.centre[0], dy = d.P[1] - c.centre[1], dz = d.P[2] - c.centre[2];
        bound = std::max(bound, std::sqrt(dx * dx + dy * dy + dz * dz) + d.radius);
    }
    c.bound = bound;
}

// Node `node` over the discs idx[0, n) in the cell [lo, lo + size]^3. Children are made
// contiguous (clusters_ grows here, so nodes are addressed by index).
void DiscHierarchy::build(int32_t node, uint32_t* idx, size_t n, const float lo[3], float size, int depth) {
    const float half = 0.5f * size;
    {
        DiscCluster& c = clusters_[size_t(node)];
        for (int k = 0; k < 3; ++k) c.centre[k] = lo[k] + half;
        std::vector<const CloudDisc*> members(n);
        for (size_t i = 0; i < n; ++i) members[i] = &input_[idx[i]];
        aggregate(c, members.data(), n);
    }
    if (n <= size_t(kLeafDiscs) || depth >= kMaxDepth) {
        DiscCluster& c = clusters_[size_t(node)];
        c.leaf = true;
        c.first = int32_t(discs_.size());
        c.count = int32_t(n);
        for (size_t i = 0; i < n; ++i) discs_.push_back(input_[idx[i]]);
        return;
    }
    const float mid[3] = {lo[0] + half, lo[1] + half, lo[2] + half};
    auto octant = [&](uint32_t i) {
        const float* p = input_[i].P;
        return int(p[0] > mid[0]) + 2 * int(p[1] > mid[1]) + 4 * int(p[2] > mid[2]);
    };
    // Ascending indices within an octant (as a stable sort of the ascending input gives): the tree
    // is the same bytes whatever the sort's order of equal keys. (std::stable_sort's temporary
    // buffer trips the address sanitizer with clang and libstdc++ 12.)
    std::sort(idx, idx + n, [&](uint32_t a, uint32_t b) {
        const int oa = octant(a), ob = octant(b);
        return oa < ob || (oa == ob && a < b);
    });
    size_t begin[9] = {};
    for (size_t i = 0; i < n; ++i) ++begin[octant(idx[i]) + 1];
    for (int o = 0; o < 8; ++o) begin[o + 1] += begin[o];
    int children = 0;
    for (int o = 0; o < 8; ++o) children += begin[o + 1] > begin[o];
    const int32_t first = int32_t(clusters_.size());
    clusters_.resize(clusters_.size() + size_t(children));
    clusters_[size_t(node)].first = first;
    clusters_[size_t(node)].count = children;
    int32_t child = first;
    for (int o = 0; o < 8; ++o) {
        if (begin[o + 1] == begin[o]) continue;
        const float clo[3] = {o & 1 ? mid[0] : lo[0], o & 2 ? mid[1] : lo[1], o & 4 ? mid[2] : lo[2]};
        build(child++, idx + begin[o], begin[o + 1] - begin[o], clo, half, depth + 1);
    }
}

}  // namespace streyes
