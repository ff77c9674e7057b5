// Reading scenes from RIB (RenderMan Interface Bytestream, ASCII), the subset in
// docs/SCENE-FORMAT.md. Malformed input throws InputError naming file:line; requests outside
// the subset warn once through the Log and are skipped.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "streyes/scene.h"
#include "streyes/scene_access.h"  // what a scene may reach: programs, files, where it writes

namespace streyes {

// How large on screen what is read will be, for detail chosen while reading (a Blobby's cells, a
// cell every 2 pixels). By default the scene's own camera and Format say.
// A depth map as a Blobby's repelling plane (opcode 1003) reads it: each pixel the depth, in the
// map camera's space, of what it saw (from the top-left pixel, row by row; FLT_MAX: nothing), the
// camera (world -> its camera space) and its projection (world -> screen, [-1, 1] across the image).
struct BlobbyDepthImage {
    int width = 0, height = 0;
    std::vector<float> z;
    Matrix4 worldToCamera, worldToScreen;
};
// Reads the depth map a Blobby names: true with *out; false with *error empty when there is no such
// file, with *error saying why when the file is there but is not a depth map.
using BlobbyDepthReader = std::function<bool(const std::string& name, BlobbyDepthImage* out, std::string* error)>;

struct ReadDetail {
    int xres = 0, yres = 0;    // the image size rendered (--res) in place of the Format's; 0: the Format's
    double formatScale = 1;    // the Format scaled, where no size is given (--preview renders at half)
    double pixelsPerUnit = 0;  // a procedural's output, which has no camera of its own: pixels on
                               // screen per world unit, from the procedural's detail (0: none)
    // Where a Blobby's repelling planes find their depth maps (the image library lives above the
    // reader); none: every map is taken as missing.
    BlobbyDepthReader readDepthMap;
    // A Blobby whose repelling planes read depth maps is kept uncut (PolygonMeshDesc::deferred) and
    // cut when its pass renders (cutDeferredBlobbies, scene/blobby_cut.h), by what renders passes
    // (streyes render): a map a depth pass of the same input writes is read after it is written.
    bool deferRepellingMaps = false;
};

Scene parseRibFile(const std::string& path, Log& log);
Scene parseRibString(const std::string& text, const std::string& sourceName, Log& log);
// RIB requests read before a scene file, as defaults the file may override: `streyes render
// --option 'Option "searchpath" "shader" ["dir"]'` (Aqsis's -option). Each is one or more requests
// of the kind a file gives before WorldBegin (options, Format, PixelSamples ...); messages name them
// "--option N" (the Nth given).
using RibDefaults = std::vector<std::string>;
// Reads them alone, strictly: InputError at "--option N:line" for a request the reader would warn
// about in a file (an unknown one, a misplaced one), or one that opens the world or leaves a block
// open. The commands call it once before reading the scene.
void checkRibDefaults(const RibDefaults& defaults);

// A file of FrameBegin n ... FrameEnd blocks: each frame, as it ends, is handed to `frame` as a
// complete scene (Scene::frameNumber, Scene::frameLoc). A file without frame blocks is handed over
// whole, as one scene with no frame location. Memory holds one frame at a time. `after`, when
// given, gets what follows the last frame of a file of frames (the state outside the frames: its
// make requests, RenderSettings::makeTextures and makeShadows, are those not yet handed over with
// a frame). `defaults` are read first (InputError when one leaves a block open or begins the world).
void parseRibFrames(const std::string& path, Log& log, const std::function<void(Scene&&)>& frame,
                    const ReadDetail& detail = {}, const std::function<void(Scene&&)>& after = {},
                    const RibDefaults& defaults = {});

// A procedural's RIB output (DelayedReadArchive, RunProgram): requests inside a world block,
// read under the procedural's transform and attributes into a scene of their own. Every block
// the text opens must be closed.
Scene parseRibFragment(const std::string& text, const std::string& sourceName, const MotionTransform& ctm,
                       const AttributesPtr& attributes, Log& log, const ReadDetail& detail = {});

}  // namespace streyes
