// What the geometry requests share: positions, "Cs" and the other primitive variables, counted by
// storage class; the key of a single face (Patch "bilinear", a small Polygon); and one primitive
// made of the keys of a motion block.
#pragma once

#include <optional>
#include <type_traits>
#include <string>
#include <vector>

#include "scene/rib_requests.h"

namespace streyes {

// ---- Primitive variables ----------------------------------------------------------------------------
// How many items a parameter of each storage class has on one primitive.
struct ClassCounts {
    size_t uniform = 1, varying = 1, vertex = 1, faceVarying = 1;
    size_t of(ParamClass c) const;
    // A single face: one uniform item, one varying, vertex or facevarying item per vertex.
    static ClassCounts face(size_t vertices) { return {1, vertices, vertices, vertices}; }
};

// An error unless the parameter has `items` items of its type, naming both counts.
void checkCount(const RibArgs& args, const Param& p, size_t items);
// The positions: "P" (x y z) or "Pw" (x y z w) per vertex, declared as such.
const Param& positionParam(const RibArgs& args, const ParamList& params);
// Those positions as points ("Pw" divided by w, which must not be 0).
std::vector<Vec3d> pointsOf(const RibArgs& args, const Param& pos);
// "Cs", if given: a color with as many values as its class has items here.
ColorPrimvar readColors(const RibArgs& args, const ParamList& params, const ClassCounts& counts);
// Parameters other than positions and Cs, checked for size: the primitive variables a shader can
// bind (float, color or string, "st" as float[2]; one value for the primitive: constant, or uniform
// where it has one face), uniform ones made constant. With `perVertex` (a primitive of one face:
// Patch "bilinear" or "bicubic", a Polygon of 3 or 4 vertices, a quadric) varying, vertex and
// facevarying floats and colours too, a value per corner of the face (a bicubic patch's 16 vertex
// values are not). The rest are ignored with a warning.
// A polygon mesh (`mesh`) takes uniform ones (a value per polygon) and per-vertex ones too: each
// face it is cut into gets its corners' values.
ParamList otherParams(const RibArgs& args, const ParamList& params, const ClassCounts& counts, Log& log,
                      bool perVertex = false, bool mesh = false);

// A primitive with nothing in it (a procedural's PointsPolygons with no faces, Points with no
// points): true, with a warning once ("PointsPolygons has no faces: nothing is drawn"), when
// `items` is 0; the caller then skips the request.
bool emptyPrimitive(RibParser& reader, const RibArgs& args, size_t items, const char* what);

// Positional arrays: whole numbers each at least `min`; an array of strings or of numbers.
std::vector<int> intArray(RibArgs& args, const std::string& what, int min);
const RibValue& takeArray(RibArgs& args, const std::string& what, bool strings);
std::string indexCount(size_t n);  // "1 index", "2 indices"
size_t sum(const std::vector<int>& v);

// ---- A single face: Patch "bilinear", or a Polygon of 3 or 4 vertices ----------------------------
struct FaceKey {
    std::vector<Vec3d> P;         // a patch's corners in RenderMan order; a polygon's vertices around its edge
    ColorPrimvar Cs;
    ParamList primvars;           // otherParams', per vertex in the order of P
    std::vector<Color> vertexCs;  // Cs at each vertex (empty when none is given), to compare keys
};
// Reads the parameter list of Patch "bilinear" (polygon = false) or of a Polygon into one key.
// False for a Polygon of more than four vertices: that is read as polygons (rib_polygons.cpp).
bool readFaceKey(RibParser& reader, RibArgs& args, bool polygon, FaceKey* key);
// Checks that a face's keys agree (the same number of vertices; a Cs that differs warns, as colours
// do not move) and says whether its positions move.
bool faceKeysMove(Log& log, const std::vector<FaceKey>& keys, const SourceLoc& loc);

// ---- Area lights ----------------------------------------------------------------------------------
// When an AreaLightSource is in force, adds these object-space patches (corners in RenderMan order),
// under the current transform at its first key, to that light's shape. `what` names geometry that
// cannot shape one (empty patches): it warns once instead.
void shapeAreaLight(RibParser& reader, const std::vector<std::array<Vec3d, 4>>& patches, const SourceLoc& loc,
                    const std::string& what = "");

// ---- One primitive from the keys of a motion block -----------------------------------------------
// The current transform and attributes, the key times and where the primitive was declared.
void placePrimitive(const RibParser& reader, PrimitiveDesc& d, std::vector<double> times, const SourceLoc& loc);
// Colours do not move: a key whose Cs differs from the first key's warns (once).
void warnIfColorsDiffer(Log& log, const ColorPrimvar& key, const ColorPrimvar& first, const SourceLoc& loc);
// "the Sphere requests of a motion block must have the same <what>".
[[noreturn]] void keysDiffer(const RibKeys& keys, const std::string& what);

// Reads every key with read(reader, args, &desc) (false: the primitive is skipped, nullopt) and
// checks that each has the first key's shape (`sameShape`; `what` names what may not change). Then
// the first key's primitive with the positions of every key (`positions` picks the member that
// moves), or of the first alone when they are all equal, placed under the current state.
template <class Desc, class Read, class SameShape, class Positions>
std::optional<Desc> mergeKeys(RibParser& reader, const RibKeys& keys, Read read, SameShape sameShape, const char* what,
                              Positions positions) {
    const SourceLoc& loc = keys.requests.front().loc;
    std::vector<Desc> descs(keys.requests.size());
    for (size_t i = 0; i < descs.size(); ++i) {
        RibArgs args(keys.requests[i], keys.usage);
        if (!read(reader, args, &descs[i])) return std::nullopt;
        if (!sameShape(descs[i], descs[0])) keysDiffer(keys, what);
        warnIfColorsDiffer(reader.log(), descs[i].Cs, descs[0].Cs, loc);
    }
    Desc d = descs[0];
    bool moves = false;
    for (size_t i = 1; i < descs.size(); ++i) moves = moves || positions(descs[i]) != positions(descs[0]);
    placePrimitive(reader, d, moves ? keys.times : std::vector<double>{keys.times.front()}, loc);
    if constexpr (!std::is_same_v<Desc, QuadricDesc>)  // quadrics shape area lights themselves
        shapeAreaLight(reader, {}, loc, keys.requests.front().name);
    positions(d).clear();
    for (size_t i = 0; i < d.times.size(); ++i) positions(d).push_back(positions(descs[i])[0]);
    return d;
}

}  // namespace streyes
