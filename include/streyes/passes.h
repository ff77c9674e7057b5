// Passes: the renders one input asks for, in an order that makes every file before it is read.
//
// A RIB file (FrameBegin blocks), a frame sequence (shot.####.rib) or one scene may hold frames
// that differ in camera, projection, resolution, display type or options: depth-map frames from
// each light (Display "zfile" | "shadow" "z"), then the picture; several shots; a camera that
// zooms. Frames with the same settings (passKey: resolution, projection and screen window,
// sampling, filter, shutter, options, depth or picture) form a *pass*, and a pass's frames are
// rendered together as one spacetime scene (a *job*: their FrameBegin numbers increasing, not
// necessarily consecutive; the numbers between that the pass does not have are rendered and not
// written). Exporters interleave a depth frame and a picture frame per frame of a shot: the depth
// frames form one job, the pictures another, each frame's pictures reading its own frame's maps.
//
// Requests between frames (MakeShadow, MakeTexture, MakeLatLongEnvironment,
// MakeCubeFaceEnvironment) become jobs of their own, run when what they read is made. Names are
// *versioned*: every frame or request writing a name makes a new version of it, and a reader reads
// the latest version written before it in the input (what rendering the input frame by frame in
// order would give). Depth maps (a depth display's output, a MakeShadow's) are kept per version in
// memory, so that the picture of each frame reads the map its own frame made however many frames a
// job renders and however often the input writes one name; other files are read from disk, and a
// job never holds two frames that read different versions of one.
//
// With FrameRequest given, only the frames numbered there are wanted (and with `done`, those it
// does not call done), plus every frame and request a wanted frame reads from (a picture's depth
// frames; the frames whose pictures a MakeTexture, MakeLatLongEnvironment or
// MakeCubeFaceEnvironment turns into a texture a wanted frame names, said by a Log::info line). Memory holds at most about two blocks of frames (merged per job), and the few frames
// kept until it is known whether a later wanted frame reads them.
#pragma once

#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "streyes/rib.h"
#include "streyes/scene.h"
#include "streyes/sequence.h"

namespace streyes {

// A version of a named file (numbered in the order the input writes them from 1); 0: the file on
// disk, which nothing in the input writes before it is read.
using FileVersion = int;

// Displays that write depth maps: Display "zfile" and "shadow".
bool isDepthDisplay(const DisplayDesc& d);

// The settings a pass's frames share (text, compared whole): a frame with another key renders
// in another pass.
std::string passKey(const Scene& frame);

// A frame a render job makes.
struct PassFrame {
    int number = 0;
    SourceLoc loc;
    CameraDesc camera;  // the frame's own camera (a depth map's light camera)
    // Depth maps it writes: each depth display (the name as written) and the version it makes.
    std::vector<std::pair<DisplayDesc, FileVersion>> maps;
    // Depth maps it reads: the name (as a shader parameter gives it) and the version it sees.
    std::map<std::string, FileVersion> reads;
    // Not wanted itself (--frames): rendered because a texture a wanted frame reads is made from its
    // pictures. Its displays write under their own names, never -o's.
    bool madeFrom = false;
    // A version it writes with Display "append" -> the version of that file it adds its map to
    // (the latest written before it in the input; none: the file starts with this map).
    std::map<FileVersion, FileVersion> appends;
};

struct PassJob {
    enum class Kind { Render, MakeShadow, MakeTexture };
    Kind kind = Kind::Render;
    // Render: the frames merged into one scene (Sequence::isSequence), or an ordinary scene (one
    // job for the file; its frames are the render's). Frames of the merged range not in `frames`
    // belong to other passes: rendered, not written.
    Sequence sequence;
    bool depth = false;  // every display of its frames writes a depth map
    int pass = 0;        // jobs of one pass share passKey
    std::map<int, PassFrame> frames;
    // Where the scene names each string it gives a shader (maps among them), for messages.
    std::map<std::string, SourceLoc> namedAt;
    // MakeShadow / MakeTexture (and MakeLatLongEnvironment, MakeCubeFaceEnvironment): the request, the version of its
    // input it reads (0: the file on disk) and the version it makes.
    MakeShadowDesc makeShadow;
    MakeTextureDesc makeTexture;
    FileVersion input = 0, output = 0;
    // Depth-map versions no later job reads: let go once this job is done.
    std::vector<FileVersion> release;
};

struct PassRequest {
    FrameRequest frames;  // the frames wanted (by FrameBegin or file number); all when not given
    int blockFrames = 64;  // the most frames a job merges
    // Frames that need no render (--resume: written already), or null. A frame it calls done is
    // rendered only when a wanted frame reads from it.
    std::function<bool(const Scene& frame)> done;
    // RIB requests read before each file (streyes render --option; streyes/rib.h).
    RibDefaults defaults;
};

// Reads the input at `path` (a frame pattern, a file of frames, or a scene) and hands `job` each
// job in an order that makes every version before a job reads it. InputError when the input does
// not parse, a frame file is missing, or a frame --frames asks for is not there.
void readPasses(const std::string& path, const PassRequest& request, Log& log,
                const std::function<void(PassJob&&)>& job, const ReadDetail& detail = {});

}  // namespace streyes
