// Frame sequences: an animation as RenderMan pipelines write it, one complete scene per frame
// (a file per frame, shot.####.rib, or FrameBegin n ... FrameEnd blocks in one file), read into
// one spacetime scene.
//
// Each frame's primitives are matched with the previous frame's: same kind, same identifier
// (Attribute "identifier" "name", and the order among primitives of that name; stream order when
// unnamed). A primitive whose data (points, topology, transform to camera space, attributes, the
// lights it reads) do not change over a run of frames, and that does not move within them, is ONE
// primitive of the merged scene, living over the run's exposures: a still body, split, diced and
// shaded once. Anything else is that frame's own primitive, living over its exposure only, its
// motion keys as the frame gives them (in frame time). So every frame renders exactly what its
// RIB describes, whatever other frames are read with it. Transforms are taken to camera space per
// frame (the merged scene's camera is the identity), so a camera that moves makes every primitive
// a per-frame one and a camera that stops makes them still again; lights are taken to camera space
// and shared between frames where they are equal.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "streyes/rib.h"
#include "streyes/scene.h"

namespace streyes {

// Frames wanted (--frames); all the input has when not given.
struct FrameRequest {
    bool given = false;
    int first = 0, last = 0;
};

// A run: one primitive of the merged scene, over consecutive frames.
struct SequenceRun {
    std::string name;  // identifier, "" when unnamed
    int firstFrame = 0, lastFrame = 0;
};

struct SequenceStats {
    int frames = 0;
    uint64_t primitivesRead = 0;  // over every frame
    uint64_t runs = 0;            // primitives of the merged scene
    uint64_t stillRuns = 0;       // runs over more than one frame
    uint64_t bytesRead = 0;       // RIB read
};

struct Sequence {
    bool isSequence = false;  // false: one ordinary scene (no frame blocks, no pattern)
    Scene scene;              // merged: settings.firstFrame .. lastFrame are the frames read
    std::map<int, std::vector<DisplayDesc>> displays;  // each frame's own Display requests
    std::vector<SequenceRun> runs;                     // one per primitive of `scene`, made in order
    SequenceStats stats;
};

// A pass's still runs over the whole input, found by reading it once before its blocks are built
// (readPasses). A block's runs then live over their frames in the input, not the block's alone, cut
// only at epochs (kRunEpochFrames frames from frame 1, whatever the block): a frame's bodies (the
// ends of their motion segments, their pieces) and so its pixels are the same in every block.
struct RunTable {
    // By primitive (kind, place among its identifier's, identifier): its runs of more than one
    // frame, in order.
    std::unordered_map<std::string, std::vector<std::pair<int, int>>> runs;
    int lastFrame = 0;  // the pass's last frame in the input
};

constexpr int kRunEpochFrames = 64;
// The epoch of frame f: frames 1-64 are epoch 0, 65-128 epoch 1, 0 and -63..0 epoch -1.
inline int runEpoch(int frame) {
    const int f = frame - 1;
    return f >= 0 ? f / kRunEpochFrames : -((-f + kRunEpochFrames - 1) / kRunEpochFrames);
}
// The first and last frames of frame f's epoch.
inline std::pair<int, int> runEpochFrames(int frame) {
    const int first = runEpoch(frame) * kRunEpochFrames + 1;
    return {first, first + kRunEpochFrames - 1};
}

// Builds the merged scene from the frames of one pass (streyes/passes.h: the same settings) in
// increasing frame order. Frames may be missing between them (another pass's): a still run goes
// on over them, and they render what the runs hold (the passes do not write them).
class SequenceBuilder {
  public:
    // scan: only finds the still runs (runTable), keeping no more than the last frame's primitives.
    explicit SequenceBuilder(Log& log, bool scan = false) : log_(log), scan_(scan) {}
    // The pass's runs over the whole input (made by a scanning builder): runs live over their frames
    // there, within their epochs; the merged scene's settings carry the shot they span.
    void setRuns(std::shared_ptr<const RunTable> runs) { table_ = std::move(runs); }
    // One frame (Scene::frameNumber, Scene::frameLoc). InputError when it cannot join the others:
    // out of order, another shutter, or exposures that overlap (close - open > 1).
    void add(Scene&& frame);
    int frames() const { return out_.stats.frames; }  // in the block being built
    // The frames added since the last finish, merged; the next frame starts a new block.
    Sequence finish();
    // A scanning builder's runs, once every frame of its pass is added.
    RunTable runTable();

  private:
    struct Track {
        size_t run = 0;  // index into the merged vector of its kind, and into runs_
        int firstFrame = 0, lastFrame = 0;
        size_t runIndex = 0;
    };
    template <typename Desc>
    void addPrimitive(char kind, Desc&& p, std::vector<Desc>& merged, std::map<std::string, int>& seen, int frame,
                      int previous);
    AttributesPtr remap(const AttributesPtr& a);
    const std::pair<int, int>* tableRun(const std::string& key, int frame) const;
    Lifetime lifeOf(const std::string& key, int frame);
    void closeRun(const std::string& key, const Track& t);
    void dropEnded(int frame);
    template <typename Desc>
    static void keepAlive(std::vector<Desc>& v, std::vector<std::pair<size_t, Track*>>& alive);

    Log& log_;
    const bool scan_;
    std::shared_ptr<const RunTable> table_;  // setRuns
    RunTable found_;                         // a scan's
    int shotFirst_ = 0, shotLast_ = 0;       // the frames the block's runs live over
    Sequence out_;
    int lastFrame_ = 0, blockFirst_ = 0;
    std::unordered_map<std::string, Track> tracks_;
    // This frame's: lights' merged indices, attribute states with them.
    std::vector<int> lightIndex_;
    std::map<const Attributes*, AttributesPtr> remapped_;
    std::map<std::string, SourceLoc> declared_;  // where each identifier was given in this frame
    MotionTransform worldToCamera_;
    double open_ = 0, close_ = 0;
    CameraDesc previousCamera_;  // the last frame's, for zooms
    bool zoomed_ = false;        // this frame projects otherwise than the last: no run goes on
};

// True when `path` holds a frame field (a run of '#').
bool isFramePattern(const std::string& path);
// The pattern with its '#' run replaced by the frame number, zero-padded to the run's length.
std::string frameFileName(const std::string& pattern, int frame);

// Reads an input of one pass (streyes/passes.h): a frame pattern (every frame of `frames`, or every
// file there is, which must be consecutive), a file of FrameBegin blocks (the frames of `frames`
// among them), or an ordinary scene file (isSequence false; `frames` is left to the renderer),
// merged whole. An input of several passes (depth maps and a picture, or frames with other
// settings) is an InputError: readPasses reads it. A frame file missing or a frame the request
// names that the file lacks is an InputError. `detail`: the size the frames will be rendered at,
// for detail chosen while reading (streyes/rib.h); `defaults` (streyes render --option) are read
// before each file: before each frame of a pattern.
Sequence readScene(const std::string& path, const FrameRequest& frames, Log& log, const ReadDetail& detail = {},
                   const RibDefaults& defaults = {});

}  // namespace streyes
