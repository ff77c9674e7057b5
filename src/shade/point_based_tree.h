// The hierarchy point-based occlusion() and indirectdiffuse() read a baked point cloud through
// (Christensen 2008, "Point-based approximate color bleeding"): the cloud's discs in an octree,
// each cluster of the tree standing for the discs below it as one area-weighted disc, so a
// shading point can draw far clusters as one disc and near discs one by one
// (point_based_buffer.h).
//
// A disc is the cloud point's position, unit normal and radius; the area it stands for is its
// "_area" channel when the cloud has one (what bake3d's "_area", area(P) gives: the micropolygon's
// area) and pi r^2 otherwise; its colour is "_radiosity" (a color) when the cloud has it, else 0.
// The radius (bake3d's: half the micropolygon's longer diagonal, or its corners' distance from
// the centre with "interpolate") covers the micropolygon, so near discs drawn with it leave no
// gaps; far ones are drawn with their area, so a cluster's coverage is its surface's.
//
// Built once per cloud (by the render's PointClouds) and then read only: any number of threads
// may traverse it at once.
#pragma once

#include <cstdint>
#include <vector>

#include "shade/point_cloud.h"

namespace streyes {

struct CloudDisc {
    float P[3], N[3];
    float radius;        // drawn exactly out to this when near
    float area;          // drawn with this when far
    float radiosity[3];  // "_radiosity", else 0
};

// A node of the octree. Interior: `count` children at clusters()[first...]; leaf: `count` discs
// at discs()[first...]. The bounding sphere holds every disc below whole (centre and rim).
struct DiscCluster {
    float centre[3];
    float bound;
    float P[3], N[3];    // the discs' area-weighted mean position and normal (N unit)
    float area;          // their summed area
    float radiosity[3];  // area-weighted mean
    int32_t first = 0;
    int32_t count = 0;
    bool leaf = false;
    bool drawable = false;  // N is defined (the discs' normals do not cancel): may be drawn as one disc
};

class DiscHierarchy {
  public:
    static constexpr int kLeafDiscs = 8;
    static constexpr int kMaxDepth = 24;  // floats have 24 bits: splitting further separates nothing

    explicit DiscHierarchy(const BakedPointCloud& cloud);

    bool empty() const { return clusters_.empty(); }
    bool hasRadiosity() const { return hasRadiosity_; }
    // The root is clusters()[0] (when not empty).
    const std::vector<DiscCluster>& clusters() const { return clusters_; }
    const std::vector<CloudDisc>& discs() const { return discs_; }

  private:
    void build(int32_t node, uint32_t* idx, size_t n, const float lo[3], float size, int depth);
    void aggregate(DiscCluster& c, const CloudDisc* const* members, size_t n) const;

    std::vector<CloudDisc> input_;
    std::vector<CloudDisc> discs_;  // in leaf order
    std::vector<DiscCluster> clusters_;
    bool hasRadiosity_ = false;
};

}  // namespace streyes
