// A point cloud as bake3d() writes and texture3d() reads it: for each point its position, normal
// and radius (world space) and the named channels the shader baked, in streyes's own binary
// file (.ptc by habit; Partio, which Aqsis uses, is not packaged for Debian 12).
//
// The file, version 1 (all numbers little-endian):
//   8 bytes   "STRYPTC\n"
//   uint32    version (1)
//   uint32    channel count C
//   C times:  uint32 name length, the name's bytes, uint32 component count (1 to 16)
//   uint64    point count N
//   N times:  float32 P[3], N[3], radius, then each channel's components in channel order
// Nothing follows. Reading checks every count against the file's length, so a truncated or
// padded file is an error, not a cloud with garbage in it.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace streyes {

struct PointChannel {
    std::string name;
    int comps = 1;
};

class BakedPointCloud {
  public:
    static constexpr int kHeaderFloats = 7;  // P, N, radius
    static constexpr uint32_t kVersion = 1;

    BakedPointCloud();
    BakedPointCloud(std::vector<PointChannel> channels, std::vector<float> data);
    ~BakedPointCloud();
    BakedPointCloud(BakedPointCloud&&) noexcept;
    BakedPointCloud& operator=(BakedPointCloud&&) noexcept;

    // Reads `path`; false with `error` saying what is wrong (missing, not a point cloud, another
    // version, truncated).
    bool read(const std::string& path, std::string* error);
    // Writes the cloud to `path`; false with `error` when the file cannot be written.
    bool write(const std::string& path, std::string* error) const;

    const std::vector<PointChannel>& channels() const { return channels_; }
    // The channel named `name` (its first float's offset within a point's record, its component
    // count), or false.
    bool channel(const std::string& name, int* offset, int* comps) const;
    size_t size() const { return stride_ ? data_.size() / stride_ : 0; }
    int stride() const { return int(stride_); }
    const float* point(size_t i) const { return data_.data() + i * stride_; }

    // The k points nearest to p (fewer when the cloud has fewer), nearest first; their squared
    // distances in dist2. Builds the search tree on first use (not thread-safe until then:
    // call prepare() once before sharing the cloud).
    int nearest(const float p[3], int k, size_t* index, float* dist2) const;
    void prepare();

  private:
    struct Tree;
    std::vector<PointChannel> channels_;
    size_t stride_ = kHeaderFloats;
    std::vector<float> data_;
    std::unique_ptr<Tree> tree_;
};

// texture3d()'s filter at world position p with normal n over `cloud` (prepared): the values of
// channel (offset, comps) into out. A point of the cloud at p itself gives its own values exactly;
// elsewhere the four nearest points are blended as Aqsis does, each weighted by
// max(0, n . N_i) exp(-1.3 d_i^2 / r_i^2) (normalised; all weights 0: 0).
void filterPointCloud(const BakedPointCloud& cloud, const float p[3], const float n[3], int offset, int comps, float* out);

}  // namespace streyes
