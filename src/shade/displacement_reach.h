// How far displacement shaders moved points, against their Attribute "displacementbound": the
// renderer finds the pieces a grid may cover by its bound grown by the displacement bound, so a
// point moved farther may fall where its bucket never looks and be missing from the picture
// (PRMan warns about this too). Grids note their largest move as they are displaced (any thread);
// the render warns once per Displacement request (its file:line) when it ends, naming the bound,
// the largest move seen there and the bound that would hold it.
#pragma once

#include <map>
#include <mutex>
#include <string>

#include "bodies/material.h"
#include "streyes/error.h"

namespace streyes {

class DisplacementReach {
  public:
    // A grid of material `m` had a point moved by `largest` (camera space) by its displacement,
    // its points at most `far` from the eye. Only a move past the bound by more than float
    // rounding of the points (1e-5 of `far`, about 100 units in the last place) is kept: a cheap
    // check first, the lock only then.
    void note(const Material& m, float largest, float far) {
        if (!(largest > m.displacementBound * 1.001f + 1e-5f * far)) return;
        noteOver(m, largest);
    }
    // One warning per Displacement request whose moves went past its bound (Log::warnOnce).
    void report(Log& log) const;

  private:
    void noteOver(const Material& m, float largest);
    struct Over {
        SourceLoc loc;
        std::string shader, space;
        double bound = 0;        // as given (Attribute "displacementbound" "sphere")
        double cameraBound = 0;  // in camera space (Material::displacementBound)
        double largest = 0;      // camera space
    };
    mutable std::mutex mutex_;
    std::map<std::string, Over> over_;  // by the Displacement request's file:line (sorted: a fixed order)
};

}  // namespace streyes
