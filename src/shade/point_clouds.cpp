// The render's point clouds and bake files (point_clouds.h).
#include "shade/point_clouds.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <set>

#include "shade/point_based_buffer.h"
#include "streyes/scene_access.h"

namespace streyes {

namespace {

// Sorted, exact duplicates dropped: `stride` floats a record.
std::vector<float> sortedUnique(const std::vector<float>& in, size_t stride) {
    const size_t n = stride ? in.size() / stride : 0;
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t(0));
    auto rec = [&](size_t i) { return in.data() + i * stride; };
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return std::lexicographical_compare(rec(a), rec(a) + stride, rec(b), rec(b) + stride);
    });
    std::vector<float> out;
    out.reserve(in.size());
    const float* last = nullptr;
    for (size_t i : order) {
        if (last && std::equal(last, last + stride, rec(i))) continue;
        out.insert(out.end(), rec(i), rec(i) + stride);
        last = rec(i);
    }
    return out;
}

// -0 as +0: two records equal as numbers are equal as bytes (and sort the same).
void appendPositiveZeros(std::vector<float>& to, const float* from, size_t count) {
    for (size_t i = 0; i < count; ++i) to.push_back(from[i] + 0.0f);
}

}  // namespace

void PointClouds::bake3d(const std::string& file, const sl::BakeRecords& r) {
    std::vector<std::pair<std::string, int>> signature;
    size_t stride = BakedPointCloud::kHeaderFloats;
    for (const sl::CloudChannel& c : *r.channels) {
        signature.emplace_back(c.name, c.comps);
        stride += size_t(c.comps);
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (!baked_.count(file)) checkSceneWrite("bake3d", file, SourceLoc{});  // --safe: inside its folder
    appendPositiveZeros(baked_[file].bySignature[signature], r.records, stride * size_t(r.count));
}

void PointClouds::bake(const std::string& file, int comps, const float* records, int count) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!baked2D_.count(file)) checkSceneWrite("bake", file, SourceLoc{});  // --safe: inside its folder
    appendPositiveZeros(baked2D_[file].byComps[comps], records, size_t(2 + comps) * size_t(count));
}

// Every call's records into one cloud: the channels of all, in name order (a name baked with two
// float counts keeps the smaller, warned), 0 where a call did not bake a channel.
BakedPointCloud PointClouds::merge(const std::string& file, const Baked& b) const {
    std::map<std::string, int> comps;
    for (const auto& entry : b.bySignature)
        for (const auto& c : entry.first) {
            auto it = comps.find(c.first);
            if (it == comps.end()) comps[c.first] = c.second;
            else if (it->second != c.second) {
                log_.warnOnce("bake3d-channel-type:" + file + ":" + c.first, SourceLoc{},
                              "bake3d: channel \"" + c.first + "\" of \"" + file + "\" is baked as " +
                                  std::to_string(it->second) + " and as " + std::to_string(c.second) +
                                  " floats: the points baked with the other count have 0 there");
                it->second = std::min(it->second, c.second);
            }
        }
    std::vector<PointChannel> channels;
    std::map<std::string, int> offset;
    int stride = BakedPointCloud::kHeaderFloats;
    for (const auto& [name, k] : comps) {
        channels.push_back({name, k});
        offset[name] = stride;
        stride += k;
    }
    std::vector<float> data;
    for (const auto& entry : b.bySignature) {
        const auto& signature = entry.first;
        size_t inStride = BakedPointCloud::kHeaderFloats;
        for (const auto& c : signature) inStride += size_t(c.second);
        const std::vector<float>& in = entry.second;
        for (size_t at = 0; at + inStride <= in.size(); at += inStride) {
            const float* src = in.data() + at;
            const size_t base = data.size();
            data.resize(base + size_t(stride), 0.0f);
            std::copy(src, src + BakedPointCloud::kHeaderFloats, data.begin() + std::ptrdiff_t(base));
            size_t from = BakedPointCloud::kHeaderFloats;
            for (const auto& c : signature) {
                if (comps[c.first] == c.second)
                    std::copy(src + from, src + from + size_t(c.second), data.begin() + std::ptrdiff_t(base) + offset[c.first]);
                from += size_t(c.second);
            }
        }
    }
    return BakedPointCloud(std::move(channels), sortedUnique(data, size_t(stride)));
}

BakedPointCloud PointClouds::gathered(const std::string& file) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = baked_.find(file);
    return it == baked_.end() ? BakedPointCloud() : merge(file, it->second);
}

void PointClouds::write() {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [file, b] : baked_) {
        std::string error;
        if (!merge(file, b).write(file, &error)) throw InputError(error + " (bake3d): check the folder exists and is writable");
    }
    baked_.clear();
    for (const auto& [file, b] : baked2D_) {
        const auto& first = *b.byComps.begin();
        if (b.byComps.size() > 1)
            log_.warnOnce("bake-comps:" + file, SourceLoc{},
                          "bake: \"" + file + "\" is baked with values of different sizes: only the " +
                              std::to_string(first.first) + "-float records are written");
        writeBakeFile(file, first.first, sortedUnique(first.second, size_t(2 + first.first)));
    }
    baked2D_.clear();
}

void writeBakeFile(const std::string& path, int comps, const std::vector<float>& records) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) throw InputError("cannot write bake file \"" + path + "\" (bake): check the folder exists and is writable");
    std::fprintf(f, "Aqsis bake file\n%d\n", comps);
    const size_t stride = size_t(2 + comps);
    for (size_t at = 0; at + stride <= records.size(); at += stride) {
        for (size_t k = 0; k < stride; ++k) std::fprintf(f, k ? " %.9g" : "%.9g", double(records[at + k]));
        std::fputc('\n', f);
    }
    const bool ok = std::fflush(f) == 0 && !std::ferror(f);
    std::fclose(f);
    if (!ok) throw InputError("cannot write bake file \"" + path + "\" (bake): disk full or not writable");
}

std::shared_ptr<const BakedPointCloud> PointClouds::load(const std::string& file, std::string* error) {
    // (mutex_ held)
    auto it = read_.find(file);
    if (it != read_.end()) return it->second;
    auto bad = readErrors_.find(file);
    if (bad != readErrors_.end()) {
        *error = bad->second;
        return nullptr;
    }
    auto c = std::make_shared<BakedPointCloud>();
    std::string why;
    if (!c->read(file, &why)) {
        readErrors_[file] = why;
        *error = why;
        return nullptr;
    }
    c->prepare();
    read_[file] = c;
    return c;
}

bool PointClouds::texture3d(const std::string& file, const sl::CloudQuery& q, std::string* error,
                            std::vector<std::string>* missing) {
    std::shared_ptr<const BakedPointCloud> cloud;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        cloud = load(file, error);
        if (!cloud) return false;
    }
    for (size_t k = 0; k < q.channels->size(); ++k) {
        const sl::CloudChannel& want = (*q.channels)[k];
        int offset = 0, comps = 0;
        if (!cloud->channel(want.name, &offset, &comps) || comps != want.comps) {
            missing->push_back(want.name);
            continue;
        }
        float* out = q.out[k];
        for (int i = 0; i < q.n; ++i) {
            if (q.active && !q.active[i]) continue;
            const float p[3] = {q.P[0][i], q.P[1][i], q.P[2][i]};
            const float n[3] = {q.N[0][i], q.N[1][i], q.N[2][i]};
            float v[16];
            filterPointCloud(*cloud, p, n, offset, comps, v);
            for (int c = 0; c < comps; ++c) out[size_t(c) * size_t(q.n) + size_t(i)] = v[c];
        }
    }
    return true;
}

bool PointClouds::pointBased(const std::string& file, const sl::PointBasedQuery& q, std::string* error) {
    std::shared_ptr<const DiscHierarchy> tree;
    {
        // Built once a cloud, under the lock: the first grid to ask waits, the rest share it.
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = hierarchies_.find(file);
        if (it != hierarchies_.end()) tree = it->second;
        else {
            std::shared_ptr<const BakedPointCloud> cloud = load(file, error);
            if (!cloud) return false;
            tree = std::make_shared<const DiscHierarchy>(*cloud);
            hierarchies_[file] = tree;
        }
    }
    if (q.indirect && !tree->hasRadiosity() && !tree->empty()) {
        *error = "point cloud \"" + file + "\" has no \"_radiosity\" color channel (bake3d it with that name)";
        return false;
    }
    // One buffer a worker thread, reused from point to point and grid to grid.
    thread_local CubeMicrobuffer buffer;
    PointBasedSettings s;
    s.res = std::clamp(q.microbufres, 1, 256);
    s.maxSolidAngle = q.maxsolidangle;
    s.coneAngle = q.coneangle;
    for (int i = 0; i < q.n; ++i) {
        if (q.active && !q.active[i]) continue;
        const float p[3] = {q.P[0][i], q.P[1][i], q.P[2][i]};
        const float n[3] = {q.N[0][i], q.N[1][i], q.N[2][i]};
        float occlusion = 0, colour[3] = {};
        buffer.integrate(*tree, p, n, s, &occlusion, q.indirect ? colour : nullptr, q.environment,
                         !q.indirect && q.environmentColour ? colour : nullptr);
        q.out[0][i] = occlusion;
        if (q.indirect || q.environmentColour)
            for (int c = 0; c < 3; ++c) q.out[1 + c][i] = colour[c];
    }
    return true;
}

}  // namespace streyes
