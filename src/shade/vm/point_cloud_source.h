// Where bake3d(), texture3d() and bake() write and read their files: an interface the renderer
// implements (shade/point_clouds.h: files written when the render ends, read once a render) and
// tests replace with a double. One call per call site and grid, never per point.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace streyes::sl {

// A channel a shader names in bake3d() or texture3d(): its name and float count (1 float,
// 3 color/point/vector/normal, 16 matrix).
struct CloudChannel {
    std::string name;
    int comps = 1;
};

// bake3d(): `count` records of 7 + the channels' floats each: world-space P, N, the radius the
// point stands for, then each channel's values in `channels` order.
struct BakeRecords {
    const std::vector<CloudChannel>* channels = nullptr;
    const float* records = nullptr;
    int count = 0;
};

// texture3d(): n points (world-space P and N, structure of arrays) and the channels wanted;
// out[k] is channel k's first component, n floats a component, one after the other.
struct CloudQuery {
    int n = 0;
    const uint8_t* active = nullptr;  // nullptr: every point
    const float* P[3] = {};
    const float* N[3] = {};
    const std::vector<CloudChannel>* channels = nullptr;
    float* const* out = nullptr;
};

// Point-based occlusion() / indirectdiffuse() (shade/point_based_buffer.h): n points (world-space
// P and unit N, structure of arrays) seen against the discs of a baked cloud; out[0] the
// occlusion, out[1..3] (indirect, or environmentColour) the colour, n floats each.
struct PointBasedQuery {
    int n = 0;
    const uint8_t* active = nullptr;  // nullptr: every point
    const float* P[3] = {};
    const float* N[3] = {};
    bool indirect = false;
    int microbufres = 10;
    float maxsolidangle = 0.03f;
    float coneangle = 1.57079632679f;
    // What each microbuffer pixel sees where no disc covers it (RGB, CubeMicrobuffer's 6
    // microbufres^2 pixels in its order: the "environmentmap" looked up once a grid); null: black.
    const float* environment = nullptr;
    // occlusion()'s "environmentcolor": out[1..3] the environment the discs let through.
    bool environmentColour = false;
    float* const* out = nullptr;
};

class PointCloudSource {
  public:
    virtual ~PointCloudSource() = default;
    virtual void bake3d(const std::string& file, const BakeRecords& records) = 0;
    // False with `error` when the file cannot be read (missing, not a cloud, truncated); then
    // nothing is written. A channel the cloud lacks (or has with another float count) is left
    // as it was and named in `missing`.
    virtual bool texture3d(const std::string& file, const CloudQuery& q, std::string* error,
                           std::vector<std::string>* missing) = 0;
    // False with `error` when the cloud cannot be read, or (indirect) has no "_radiosity" color;
    // then nothing is written. The default has no clouds.
    virtual bool pointBased(const std::string& file, const PointBasedQuery& q, std::string* error) {
        (void)q;
        *error = "no point clouds in this render (\"" + file + "\")";
        return false;
    }
    // bake(): `count` records of (s, t, comps values).
    virtual void bake(const std::string& file, int comps, const float* records, int count) = 0;
};

}  // namespace streyes::sl
