// A Blobby request as read (its field, per-leaf variables and repelling planes' map names) and its
// cutting into the triangles of a PolygonMeshDesc (scene/blobby_field.h's polygonizer), at read
// time or, for one whose repelling planes read depth maps, when its pass renders
// (PolygonMeshDesc::deferred): a map an earlier pass of the same input writes is then read after
// that pass has written it.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scene/blobby_field.h"
#include "streyes/error.h"
#include "streyes/rib.h"
#include "streyes/scene.h"

namespace streyes {

struct BlobbyKey {
    int nleaf = 0;
    BlobbyField field;
    std::vector<size_t> leaves;  // the leaf instructions, in order: "Cs" is given per leaf
    ColorPrimvar Cs;
    ParamList primvars;           // constant ones (otherParams)
    std::vector<Param> leafVars;  // a value per leaf: float, color, point, vector, normal, mpoint
    std::vector<std::pair<size_t, std::string>> planeMaps;  // repelling planes: instruction, depth map name
};

// A repelling plane's map by name: null with *error empty when there is none, with *error saying
// why when the file is there but is no depth map.
using BlobbyMapLookup = std::function<std::shared_ptr<const BlobbyDepthImage>(const std::string& name, std::string* error)>;

// Each repelling plane's ground (A > 0) from `lookup` (null: maps are not read, in a procedural's
// output), seen from object space through objectToWorld. A map that is not there leaves the plane
// z = 0 of object space, as Aqsis takes it, with a warning; one that is not a depth map is an
// InputError at loc.
void readBlobbyGrounds(BlobbyKey& key, const Matrix4& objectToWorld, const SourceLoc& loc, Log& log,
                       const BlobbyMapLookup& lookup);

// The key's surface on `cells` cells into d (polygons, P, Cs and per-leaf variables blended by the
// leaves' fields); false when there is none.
bool cutBlobby(const BlobbyKey& key, int cells, const SourceLoc& loc, Log& log, PolygonMeshDesc& d);

// A Blobby cut when its pass renders.
struct BlobbyDeferredCut {
    BlobbyKey key;          // grounds not read
    int cells = 0;
    Matrix4 objectToWorld;  // places the grounds
    SourceLoc loc;
    std::string signature;  // the request's arguments: equal requests of two frames are one primitive
    bool operator==(const BlobbyDeferredCut& o) const { return signature == o.signature && cells == o.cells; }
};

// The map frame `frame` reads under a name (as BlobbyMapLookup).
using BlobbyFrameMaps =
    std::function<std::shared_ptr<const BlobbyDepthImage>(int frame, const std::string& name, std::string* error)>;

// Cuts the scene's deferred Blobbies: each, over those of `frames` (ascending) its lifetime holds
// (frame f lives over [f + open, f + close]), once per run of frames whose maps are the same
// objects, into meshes living over their runs. Maps come from `maps`. In frames not listed (a pass
// renders other passes' frames between its own, and keeps nothing of them) it is not drawn.
void cutDeferredBlobbies(Scene& scene, const std::vector<int>& frames, const BlobbyFrameMaps& maps, Log& log);

}  // namespace streyes
