// Cutting a Blobby into triangles (scene/blobby_cut.h): at read time, or when its pass renders.
#include "scene/blobby_cut.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "scene/object_st.h"

namespace streyes {

namespace {

// One leaf's value of a per-leaf variable at object-space point p: as given, or for an "mpoint"
// p carried from the leaf's blob space into its reference frame (a point that moves with the blob).
void leafValueAt(const BlobbyKey& key, const Param& v, size_t leaf, Vec3d p, double* out) {
    const size_t w = size_t(v.componentsPerItem());
    const double* given = &v.nums[leaf * w];
    if (v.type != ParamType::Matrix) {
        std::copy(given, given + w, out);
        return;
    }
    const Vec3d q = Matrix4::fromRowMajor(given).point(key.field.ops[key.leaves[leaf]].toBlob.point(p));
    out[0] = q.x, out[1] = q.y, out[2] = q.z;
}

// The per-leaf "Cs" and variables at the mesh's vertices: the sum of the leaves' values weighted by
// each leaf's field there, over the sum of those fields. Where no leaf's field reaches (a surface
// made by constants alone), the mean of the leaves' values.
void blendLeafValues(const BlobbyKey& key, const std::vector<Vec3d>& P, PolygonMeshDesc& d) {
    const bool blendCs = key.Cs.given() && key.Cs.cls != ParamClass::Constant && key.Cs.cls != ParamClass::Uniform;
    if (!blendCs && key.leafVars.empty()) return;
    std::vector<Param> out;
    for (const Param& v : key.leafVars) {
        Param q = v;
        q.cls = ParamClass::Vertex;
        if (v.type == ParamType::Matrix) q.type = ParamType::Point;
        q.nums.assign(P.size() * size_t(q.componentsPerItem()), 0.0);
        out.push_back(std::move(q));
    }
    const size_t leaves = key.leaves.size();
    Color meanCs{0, 0, 0};
    if (blendCs) {
        d.Cs.cls = ParamClass::Vertex;
        for (size_t l = 0; l < leaves; ++l) meanCs = meanCs + key.Cs.values[l] * (1.0f / float(leaves));
    }
    std::vector<int> leafOf(key.field.ops.size(), -1);
    for (size_t l = 0; l < leaves; ++l) leafOf[key.leaves[l]] = int(l);
    // Each vertex reads the leaves near it (the others' fields are 0 there and add nothing).
    BlobbyEvaluator near(key.field);
    std::vector<std::pair<size_t, double>> weights;  // leaf, its field at the vertex
    double value[3];
    for (size_t i = 0; i < P.size(); ++i) {
        weights.clear();
        double total = 0;
        for (size_t at : near.leavesNear(P[i])) {
            if (leafOf[at] < 0) continue;
            const double w = key.field.leafValue(at, P[i]);
            if (w > 0) weights.push_back({size_t(leafOf[at]), w}), total += w;
        }
        if (blendCs) {
            Color sum{0, 0, 0};
            for (const auto& [l, w] : weights) sum = sum + key.Cs.values[l] * float(w);
            d.Cs.values.push_back(total > 0 ? sum * float(1 / total) : meanCs);
        }
        if (!(total > 0)) {
            weights.clear();
            for (size_t l = 0; l < leaves; ++l) weights.push_back({l, 1.0});
            total = double(leaves);
        }
        for (size_t k = 0; k < out.size(); ++k) {
            const size_t n = size_t(out[k].componentsPerItem());
            double* at = &out[k].nums[i * n];
            for (const auto& [l, w] : weights) {
                leafValueAt(key, key.leafVars[k], l, P[i], value);
                for (size_t c = 0; c < n; ++c) at[c] += value[c] * (w / total);
            }
        }
    }
    for (Param& q : out) d.primvars.params.push_back(std::move(q));
}

}  // namespace

void readBlobbyGrounds(BlobbyKey& key, const Matrix4& objectToWorld, const SourceLoc& loc, Log& log,
                       const BlobbyMapLookup& lookup) {
    for (const auto& [at, name] : key.planeMaps) {
        if (!(key.field.ops[at].repel[0] > 0)) continue;  // A = 0: no repulsion, no map needed
        std::string error;
        std::shared_ptr<const BlobbyDepthImage> map = lookup ? lookup(name, &error) : nullptr;
        if (map) {
            if (map->width < 1 || map->height < 1 || map->z.size() != size_t(map->width) * size_t(map->height))
                throw InputError(loc, "Blobby: the repelling plane's depth map \"" + name + "\" has no pixels");
            auto ground = std::make_shared<BlobbyGround>();
            ground->map = *map;
            ground->objectToCamera = objectToWorld * map->worldToCamera;
            ground->objectToScreen = objectToWorld * map->worldToScreen;
            key.field.ops[at].ground = std::move(ground);
        } else if (!error.empty()) {
            throw InputError(loc, "Blobby: the repelling plane's depth map \"" + name + "\": " + error +
                                      ": give a depth map (Display \"zfile\" | \"shadow\" \"z\", or MakeShadow)");
        } else {
            key.field.ops[at].ground = nullptr;
            log.warnOnce("blobby:planemap:" + name, loc,
                         "Blobby: the repelling plane's depth map \"" + name + "\" " +
                             (lookup ? "is not a file" : "is not read in a procedural's output") +
                             ": the ground is taken as the plane z = 0 of the blobby's space, as Aqsis does");
        }
    }
}

bool cutBlobby(const BlobbyKey& key, int cells, const SourceLoc& loc, Log& log, PolygonMeshDesc& d) {
    BlobbyMesh mesh = polygonizeBlobby(key.field, cells);
    if (mesh.openAtBound)
        log.warnOnce("blobby:open", loc,
                     "Blobby: the field is above the level (1/2) beyond its blobs (a constant?): the "
                     "surface is cut open at the blobs' bound");
    if (mesh.triangles.empty()) return false;
    d.polygons.clear();
    for (const std::array<int, 3>& t : mesh.triangles) d.polygons.push_back({{t[0], t[1], t[2]}});
    d.primvars = key.primvars;
    d.Cs = ColorPrimvar();
    if (key.Cs.given() && (key.Cs.cls == ParamClass::Constant || key.Cs.cls == ParamClass::Uniform)) {
        d.Cs.cls = ParamClass::Constant;
        d.Cs.values = {key.Cs.values[0]};
    }
    blendLeafValues(key, mesh.P, d);
    addObjectSt(mesh.P, d);  // a pattern in s runs across the blobby, not restarting on every triangle
    d.P = {std::move(mesh.P)};
    return true;
}


void cutDeferredBlobbies(Scene& scene, const std::vector<int>& wanted, const BlobbyFrameMaps& maps, Log& log) {
    if (std::none_of(scene.polygonMeshes.begin(), scene.polygonMeshes.end(),
                     [](const PolygonMeshDesc& d) { return d.deferred != nullptr; }))
        return;
    const double open = scene.settings.shutterOpen, close = scene.settings.shutterClose;
    using Found = std::pair<std::shared_ptr<const BlobbyDepthImage>, std::string>;  // the map, or why not
    std::vector<PolygonMeshDesc> out;
    for (PolygonMeshDesc& d : scene.polygonMeshes) {
        if (!d.deferred) {
            out.push_back(std::move(d));
            continue;
        }
        const BlobbyDeferredCut& cut = *d.deferred;
        // Each frame it lives in, with the maps that frame reads.
        std::vector<std::pair<int, std::map<std::string, Found>>> frames;
        for (int f : wanted) {
            if (!d.life.always() && !(f + open >= d.life.t0 - 1e-9 && f + close <= d.life.t1 + 1e-9)) continue;
            std::map<std::string, Found> read;
            for (const auto& [at, name] : cut.key.planeMaps) {
                if (!(cut.key.field.ops[at].repel[0] > 0) || read.count(name)) continue;
                Found& found = read[name];
                found.first = maps(f, name, &found.second);
            }
            frames.push_back({f, std::move(read)});
        }
        // A run of frames reading the same maps is cut once.
        for (size_t i = 0; i < frames.size();) {
            size_t j = i + 1;
            while (j < frames.size() && frames[j].second == frames[i].second) ++j;
            const std::map<std::string, Found>& read = frames[i].second;
            BlobbyKey key = cut.key;
            readBlobbyGrounds(key, cut.objectToWorld, cut.loc, log,
                              [&read](const std::string& name, std::string* error) {
                                  auto it = read.find(name);
                                  if (it == read.end()) return std::shared_ptr<const BlobbyDepthImage>();
                                  *error = it->second.second;
                                  return it->second.first;
                              });
            PolygonMeshDesc m = d;
            m.deferred = nullptr;
            if (i > 0 || j < frames.size())
                m.life = Lifetime{frames[i].first + open, frames[j - 1].first + close,
                                  j == frames.size() && d.life.openEnd};
            if (cutBlobby(key, cut.cells, cut.loc, log, m)) out.push_back(std::move(m));
            i = j;
        }
    }
    scene.polygonMeshes = std::move(out);
}

}  // namespace streyes
