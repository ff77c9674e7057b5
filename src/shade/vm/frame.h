// One program's registers and mask stack inside a ShadingVM (internal to shade/vm).
//
// The mask stack: level d has a mask M[d] (1 where a point runs); the top level is the
// current mask. if pushes M[d+1] = M[d] & cond; a loop pushes a copy whose points leave as
// the condition fails; break and continue clear the points that run from every level down to
// their loop's (so that popping an if does not bring them back), continue also remembering
// them in the loop's C[d] to rejoin at the end of the body; return clears them down to the
// function's level (level 0 for the shader: they stay off to the end).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shade/vm/exec.h"

namespace streyes::sl {

struct Frame {
    const ShaderProgram* prog = nullptr;
    ProgramPtr keep;                // holds the program while its registers may be read
    uint64_t programId = 0;         // which program (addresses of freed programs come back)
    uint64_t lastRun = 0;           // the VM's run counter when last used
    const ShaderInstance* instance = nullptr;  // whose values the parameters hold
    uint64_t peerGrid = 0;          // the VM's peer-grid counter then (message passing)
    bool constantsLoaded = false;
    int n = 0;
    std::vector<float> arena;       // the uniform area, then varyingArrays arrays of n floats
    std::vector<std::string> strs;  // string slots
    std::vector<ResizableArray> arrays;  // resizable arrays (exec.h), emptied at each prepare
    std::vector<uint8_t> masks;     // level d: [d n, (d+1) n)
    std::vector<uint8_t> conts;     // loops: points that continued; illuminance: points that broke
    std::vector<int> lightIndex;    // illuminance levels: the light being visited
    int depth = 0;

    uint8_t* mask(int d) { return masks.data() + std::size_t(d) * std::size_t(n); }
    uint8_t* cont(int d) { return conts.data() + std::size_t(d) * std::size_t(n); }

    // Sizes everything for `p` over n points (allocating only when growing).
    void prepare(const ProgramPtr& p, int points);
};

// Makes level d current and counts its points.
inline void setLevel(Exec& x, int d) {
    x.frame.depth = d;
    x.mask = x.frame.mask(d);
    int k = 0;
    for (int i = 0; i < x.n; ++i) k += x.mask[i];
    x.active = k;
}

inline void recount(Exec& x) { setLevel(x, x.frame.depth); }

}  // namespace streyes::sl
