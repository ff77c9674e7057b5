// Scenes the pass planner (streyes/passes.h) reads or makes: the strings a frame names (the maps
// and textures it may read) and the depth frame an "autoshadows" light renders.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "streyes/passes.h"
#include "streyes/scene.h"
#include "streyes/sequence.h"

namespace streyes {

// Every display that writes a file writes a depth map (and one does).
bool depthFrame(const Scene& s);

// The frame numbers of the files a pattern matches, in order.
std::vector<int> framesOnDisk(const std::string& pattern);

// One frame's file: a scene, or FrameBegin blocks (the passes of that frame: each takes the file's
// number), and what follows its last block.
struct FrameFile {
    std::vector<Scene> scenes;
    Scene after;
};
FrameFile readFrameFile(const std::string& file, int f, Log& log, const ReadDetail& detail, const RibDefaults& defaults);

// Each pass's still runs over the input (by passKey; streyes/sequence.h, RunTable), the input read
// once more, quietly, before its blocks are built: a frame pattern over the epochs of the frames
// wanted and the frame after them (whether runs go on past them), a file of frames whole. Empty
// when the input does not read (the reading proper says why) or has no frames.
std::map<std::string, std::shared_ptr<const RunTable>> scanRuns(const std::string& path, const PassRequest& req,
                                                                 const ReadDetail& detail);

// Every string a shader parameter of the scene gives (lights, surfaces, displacements,
// atmospheres, the imager, in objects too), with where it is first given: the names a frame may
// read maps and textures by.
void stringsOf(const Scene& s, std::map<std::string, SourceLoc>& out);

// Attribute "autoshadows" on a light (Aqsis): the depth frame rendered from it before the frame.
Scene autoShadowFrame(const Scene& picture, const LightDesc& light);

}  // namespace streyes
