// The render's point clouds and bake files (sl::PointCloudSource): what bake3d() and bake()
// give is gathered from every thread and written when the render ends (write()); what texture3d()
// reads is loaded once a render and shared.
//
// Files are the same bytes whatever the thread count, the frame block or the order grids were
// shaded in: the records are sorted (bake3d's by position, normal, radius and values; bake's by
// s, t and values) and exact duplicates dropped (a still grid shaded once for a block of frames
// and once in each frame bakes the same points). A cloud's channels are every name baked into it,
// in name order; a point baked without one of them has 0 there.
//
// A file is read as it is on disk when texture3d() first asks for it in a render: a cloud baked
// by an earlier frame of the input is there when the later frame renders in a job of its own
// (another pass: the bake frame and the beauty frame differ in their settings, as they do in
// every scene that bakes). A render that both bakes and reads one file reads the earlier file.
// Point-based occlusion() and indirectdiffuse() read clouds the same way, through a disc
// hierarchy built once a cloud and shared by every thread (point_based_tree.h).
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "shade/point_based_tree.h"
#include "shade/point_cloud.h"
#include "shade/vm/point_cloud_source.h"
#include "streyes/error.h"

namespace streyes {

class PointClouds final : public sl::PointCloudSource {
  public:
    explicit PointClouds(Log& log) : log_(log) {}

    void bake3d(const std::string& file, const sl::BakeRecords& records) override;
    bool texture3d(const std::string& file, const sl::CloudQuery& q, std::string* error,
                   std::vector<std::string>* missing) override;
    void bake(const std::string& file, int comps, const float* records, int count) override;
    bool pointBased(const std::string& file, const sl::PointBasedQuery& q, std::string* error) override;

    // Writes every file baked into in this render (and forgets them). InputError when a file
    // cannot be written.
    void write();
    // The cloud bake3d() gathered for `file` so far, as write() would write it (tests).
    BakedPointCloud gathered(const std::string& file) const;

  private:
    struct Baked {
        std::map<std::vector<std::pair<std::string, int>>, std::vector<float>> bySignature;
    };
    struct Baked2D {
        std::map<int, std::vector<float>> byComps;
    };
    BakedPointCloud merge(const std::string& file, const Baked& b) const;
    // The cloud on disk at `file`, read once a render (null with `error` when it cannot be).
    std::shared_ptr<const BakedPointCloud> load(const std::string& file, std::string* error);

    Log& log_;
    mutable std::mutex mutex_;
    std::map<std::string, Baked> baked_;
    std::map<std::string, Baked2D> baked2D_;
    std::map<std::string, std::shared_ptr<const BakedPointCloud>> read_;
    std::map<std::string, std::string> readErrors_;
    std::map<std::string, std::shared_ptr<const DiscHierarchy>> hierarchies_;
};

// Aqsis's bake file (the text bake() writes): "Aqsis bake file", the value count, then a line of
// "s t values..." a record.
void writeBakeFile(const std::string& path, int comps, const std::vector<float>& records);

}  // namespace streyes
