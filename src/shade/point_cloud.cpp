// Point clouds (point_cloud.h): the file format, and nearest points by nanoflann's k-d tree.
#include "shade/point_cloud.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include <nanoflann.hpp>

namespace streyes {

namespace {

constexpr char kMagic[8] = {'S', 'T', 'R', 'Y', 'P', 'T', 'C', '\n'};
constexpr int kMaxComps = 16;

// The file is little-endian; so is every machine streyes builds for (x86-64, arm64), which
// the static_assert below keeps honest for the float layout.
static_assert(sizeof(float) == 4, "float32");

template <class T>
void put(std::string& out, T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.append(b, sizeof(T));
}

class Reader {
  public:
    Reader(const std::string& bytes) : s_(bytes) {}
    template <class T>
    bool get(T* v) {
        if (s_.size() - pos_ < sizeof(T)) return false;
        std::memcpy(v, s_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return true;
    }
    bool bytes(size_t n, std::string* v) {
        if (s_.size() - pos_ < n) return false;
        v->assign(s_.data() + pos_, n);
        pos_ += n;
        return true;
    }
    size_t left() const { return s_.size() - pos_; }
    const char* here() const { return s_.data() + pos_; }

  private:
    const std::string& s_;
    size_t pos_ = 0;
};

}  // namespace

// nanoflann reads the points through this adaptor (positions are the first three floats).
struct BakedPointCloud::Tree {
    struct Adaptor {
        const BakedPointCloud* cloud;
        size_t kdtree_get_point_count() const { return cloud->size(); }
        float kdtree_get_pt(size_t i, size_t dim) const { return cloud->point(i)[dim]; }
        template <class Box>
        bool kdtree_get_bbox(Box&) const {
            return false;
        }
    };
    using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>, Adaptor, 3, size_t>;
    Adaptor adaptor;
    Index index;
    explicit Tree(const BakedPointCloud* c)
        : adaptor{c}, index(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
        index.buildIndex();
    }
};

BakedPointCloud::BakedPointCloud(std::vector<PointChannel> channels, std::vector<float> data)
    : channels_(std::move(channels)), data_(std::move(data)) {
    stride_ = kHeaderFloats;
    for (const PointChannel& c : channels_) stride_ += size_t(c.comps);
}

BakedPointCloud::BakedPointCloud() = default;
BakedPointCloud::~BakedPointCloud() = default;
BakedPointCloud::BakedPointCloud(BakedPointCloud&&) noexcept = default;
BakedPointCloud& BakedPointCloud::operator=(BakedPointCloud&&) noexcept = default;

bool BakedPointCloud::channel(const std::string& name, int* offset, int* comps) const {
    int at = kHeaderFloats;
    for (const PointChannel& c : channels_) {
        if (c.name == name) {
            *offset = at;
            *comps = c.comps;
            return true;
        }
        at += c.comps;
    }
    return false;
}

bool BakedPointCloud::write(const std::string& path, std::string* error) const {
    std::string out(kMagic, sizeof kMagic);
    put<uint32_t>(out, kVersion);
    put<uint32_t>(out, uint32_t(channels_.size()));
    for (const PointChannel& c : channels_) {
        put<uint32_t>(out, uint32_t(c.name.size()));
        out += c.name;
        put<uint32_t>(out, uint32_t(c.comps));
    }
    put<uint64_t>(out, uint64_t(size()));
    out.append(reinterpret_cast<const char*>(data_.data()), data_.size() * sizeof(float));
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    if (f) f.write(out.data(), std::streamsize(out.size()));
    if (!f) {
        *error = "cannot write point cloud \"" + path + "\"";
        return false;
    }
    return true;
}

bool BakedPointCloud::read(const std::string& path, std::string* error) {
    std::ifstream f(path, std::ios::binary);
    if (!f) {
        *error = "cannot open point cloud \"" + path + "\" (no such file, or not readable)";
        return false;
    }
    const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    Reader r(bytes);
    auto bad = [&](const std::string& what) {
        *error = "\"" + path + "\" is not a streyes point cloud: " + what;
        return false;
    };
    std::string magic;
    if (!r.bytes(sizeof kMagic, &magic) || std::memcmp(magic.data(), kMagic, sizeof kMagic) != 0)
        return bad("it does not begin with STRYPTC (bake3d() of streyes writes them)");
    uint32_t version = 0, count = 0;
    if (!r.get(&version)) return bad("truncated in its header");
    if (version != kVersion)
        return bad("version " + std::to_string(version) + ", this streyes reads version " + std::to_string(kVersion));
    if (!r.get(&count)) return bad("truncated in its header");
    if (count > 4096) return bad(std::to_string(count) + " channels (corrupt header)");
    std::vector<PointChannel> channels;
    for (uint32_t k = 0; k < count; ++k) {
        uint32_t len = 0, comps = 0;
        PointChannel c;
        if (!r.get(&len) || len > 4096 || !r.bytes(len, &c.name) || !r.get(&comps)) return bad("truncated in its channel list");
        if (comps < 1 || comps > uint32_t(kMaxComps))
            return bad("channel \"" + c.name + "\" has " + std::to_string(comps) + " components (1 to 16)");
        c.comps = int(comps);
        channels.push_back(std::move(c));
    }
    uint64_t points = 0;
    if (!r.get(&points)) return bad("truncated in its header");
    BakedPointCloud cloud(std::move(channels), {});
    const uint64_t floats = uint64_t(cloud.stride_);
    if (points > r.left() / (floats * sizeof(float)) || r.left() != points * floats * sizeof(float))
        return bad("holds " + std::to_string(r.left()) + " bytes of points where its header says " +
                   std::to_string(points) + " points of " + std::to_string(floats * sizeof(float)) +
                   " bytes (truncated or corrupt)");
    cloud.data_.resize(size_t(points * floats));
    if (!cloud.data_.empty())  // an empty cloud's data() may be null: memcpy must not see it
        std::memcpy(cloud.data_.data(), r.here(), cloud.data_.size() * sizeof(float));
    for (float v : cloud.data_)
        if (!std::isfinite(v)) return bad("a value is not finite (NaN or infinity)");
    *this = std::move(cloud);
    return true;
}

void BakedPointCloud::prepare() {
    if (!tree_ && size() > 0) tree_ = std::make_unique<Tree>(this);
}

int BakedPointCloud::nearest(const float p[3], int k, size_t* index, float* dist2) const {
    if (!tree_ || k <= 0) return 0;
    return int(tree_->index.knnSearch(p, size_t(k), index, dist2));
}

void filterPointCloud(const BakedPointCloud& cloud, const float p[3], const float n[3], int offset, int comps, float* out) {
    constexpr int kNear = 4;
    size_t index[kNear];
    float dist2[kNear];
    const int found = cloud.nearest(p, kNear, index, dist2);
    std::fill(out, out + comps, 0.0f);
    if (found == 0) return;
    if (dist2[0] == 0.0f) {  // a baked point itself: its own value
        const float* v = cloud.point(index[0]) + offset;
        std::copy(v, v + comps, out);
        return;
    }
    float w[kNear], total = 0;
    for (int i = 0; i < found; ++i) {
        const float* q = cloud.point(index[i]);
        const float facing = std::max(0.0f, n[0] * q[3] + n[1] * q[4] + n[2] * q[5]);
        const float r2 = q[6] * q[6];
        w[i] = r2 > 0 ? facing * std::exp(-1.3f * dist2[i] / r2) : 0.0f;
        total += w[i];
    }
    if (!(total > 0)) return;
    for (int i = 0; i < found; ++i) {
        const float* v = cloud.point(index[i]) + offset;
        const float wi = w[i] / total;
        for (int c = 0; c < comps; ++c) out[c] += wi * v[c];
    }
}

}  // namespace streyes
