// The request table: every RIB request the reader knows, with its handler and what dispatch needs.
//
// Requests come in groups, one file each (rib_options.cpp, rib_blocks.cpp, ...). A group's file
// defines its handlers and a function that adds them to the table, and ribRequests() calls each
// group's function once. Dispatch (RibParser::dispatch) looks a request up, checks that it may
// appear where it is, holds it while a motion block is open, and calls its handler.
//
// Adding a request: write its handler in its group's file and add an entry in that file's add
// function, for example (with the field it sets added to the Scene)
//
//     void exposure(RibParser& reader, RibArgs& args) { reader.scene().settings.gain = args.number("gain"); ... }
//     table.add("Exposure", {exposure, "Exposure gain gamma", RibPhase::Options});
//
// Geometry that can move also names a handler for the keys of a motion block, and reads one key
// outside it with oneKey: {oneKey<pointsKeys>, "Points \"P\" [...]", RibPhase::World, pointsKeys}.
// A new group is a new file with its add function declared below and called in ribRequests().
// A name may be added once: a request that becomes supported leaves the lists of requests
// outside the subset (addUnsupportedRequests, rib_requests.cpp).
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "scene/rib_parser.h"

namespace streyes {

// Where in the file a request is valid: anywhere, only before WorldBegin (options), or only
// between WorldBegin and WorldEnd.
enum class RibPhase { Anywhere, Options, World };

// Reads one request, outside a motion block.
using RibHandler = void (*)(RibParser& reader, RibArgs& args);

// The requests of a motion block at MotionEnd: one per time, all the same request.
struct RibKeys {
    std::vector<double> times;
    std::vector<RibRequest> requests;
    const char* usage = "";  // how the request is written, for messages
};
using RibKeysHandler = void (*)(RibParser& reader, const RibKeys& keys);

// A request that can move, read outside a motion block: one key at time 0.
template <RibKeysHandler keys>
void oneKey(RibParser& reader, RibArgs& args) {
    keys(reader, RibKeys{{0.0}, {args.request()}, args.usage()});
    args.skipRest();
}

struct RibRequestInfo {
    RibHandler handler;
    const char* usage = "";  // how it is written: shown with mistakes in its positional arguments
    RibPhase phase = RibPhase::Anywhere;
    RibKeysHandler motion = nullptr;  // reads a motion block's keys; none: it cannot move
};

class RibRequestTable {
  public:
    // A name added twice is a mistake in the table (std::logic_error when it is built).
    void add(const std::string& name, const RibRequestInfo& info);
    const RibRequestInfo* find(const std::string& name) const;
    // The known name that `name` spells in other case ("worldend"), or "".
    std::string sameButForCase(const std::string& name) const;

  private:
    std::unordered_map<std::string, RibRequestInfo> requests_;
};

// Every group's requests, built once.
const RibRequestTable& ribRequests();

// The groups, by file.
void addUnsupportedRequests(RibRequestTable& table);  // rib_requests.cpp: version, requests outside the subset
void addParamRequests(RibRequestTable& table);        // rib_params.cpp: Declare
void addOptionRequests(RibRequestTable& table);       // rib_options.cpp: camera, image and frame options
void addBlockRequests(RibRequestTable& table);        // rib_blocks.cpp: World, Attribute, Transform, Motion, ...
void addTransformRequests(RibRequestTable& table);    // rib_transforms.cpp: Translate, Rotate, CoordinateSystem, ...
// A named coordinate system for shaders (transform("name", P)): kept among the options as
// "CoordinateSystem:name", its object-to-world matrix at the first motion key (rib_transforms.cpp).
void keepCoordinateSystem(RenderSettings& settings, const std::string& name, const MotionTransform& objectToWorld);
void addAttributeRequests(RibRequestTable& table);    // rib_attributes.cpp: Color, Attribute, Basis, ...
void addShadingRequests(RibRequestTable& table);      // rib_shading.cpp: Surface, Displacement, Atmosphere, Imager, LightSource, Illuminate
void addObjectRequests(RibRequestTable& table);       // rib_objects.cpp: ObjectBegin, ObjectEnd, ObjectInstance
void addPatchRequests(RibRequestTable& table);        // rib_patches.cpp: Patch, PatchMesh
void addPolygonRequests(RibRequestTable& table);      // rib_polygons.cpp: Polygon, PointsPolygons, ...
void addSubdivisionRequests(RibRequestTable& table);  // rib_subdivision.cpp: SubdivisionMesh
void addQuadricRequests(RibRequestTable& table);      // rib_quadrics.cpp: Sphere, Cylinder, ...
void addArchiveRequests(RibRequestTable& table);      // rib_archives.cpp: ReadArchive, Procedural
void addCurveRequests(RibRequestTable& table);        // rib_curves.cpp: Curves, Points
void addNurbsRequests(RibRequestTable& table);        // rib_nurbs.cpp: NuPatch, TrimCurve
void addBlobbyRequests(RibRequestTable& table);       // rib_blobby.cpp: Blobby
void addTextureRequests(RibRequestTable& table);      // rib_textures.cpp: the Make* requests
void addGeometryRequests(RibRequestTable& table);     // rib_teapot.cpp: Geometry "teapot"
void addDetailRequests(RibRequestTable& table);       // rib_detail.cpp: Detail, DetailRange, RelativeDetail
void addSolidRequests(RibRequestTable& table);        // rib_solids.cpp: SolidBegin, SolidEnd

}  // namespace streyes
