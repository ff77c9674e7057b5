// The built-in "grass" procedural (Procedural "DynamicLoad" ["grass" "key=value ..."]): a ground
// rectangle on y = 0 filled with grass blades as Curves, for the ground near the camera.
//
// The rectangle is cut into square tiles, each a procedural of its own (expanded only when seen,
// at the level of detail of its projected size). Each blade is one cubic Bezier segment from its
// root on the ground: three legs of a third of its length each, leaning by `lean` and bending
// further by `bend` towards its tip, its width tapering from root to tip. Blade counts are
// stratified over the tiles: tile k holds floor(density A_k) - floor(density A_(k-1)) blades
// (A_k: the area of tiles 0..k), so the whole rectangle holds floor(density x area) and each tile
// within one blade of density x its area; roots are uniform in their tile. Everything is drawn
// from the seed, by tile and blade, so the same seed gives the same grass in any order.
//
// Wind: each blade turns about the horizontal axis across the wind through its root, its legs by
// 1/3, 2/3 and all of the angle wind x 0.35 rad x (1 + sin(2 pi (t / period - d / wavelength) +
// phase)) / 2 (d: the root's distance along the wind; phase: the blade's own, within +-0.5 rad),
// keyed at the multiples of keystep that cover the shot's window, so that a frame does not
// depend on the block it is rendered in.
#pragma once

#include <memory>
#include <string>

#include "procedural/procedural.h"

namespace streyes {

struct GrassParams {
    uint64_t seed = 1;
    double x0 = -5, z0 = -5, x1 = 5, z1 = 5;  // the rectangle on y = 0 (object space)
    double density = 400;                      // blades per square unit
    double heightMin = 0.15, heightMax = 0.4;  // a blade's length along its control polygon
    double width = 0.008;                      // at the root (+-30% a blade); the tip is a tenth
    double lean = 20;                          // degrees from vertical, at most (uniform a blade)
    double bend = 30;                          // degrees more at the tip, at most (uniform a blade)
    double wind = 0;                           // 0: still, no motion keys
    double windX = 1, windZ = 0;               // wind direction on the ground (unit)
    double period = 48;                        // frames per sway cycle
    double wavelength = 4;                     // units between gusts along the wind
    double keyStep = 4;                        // frames between motion keys
    double detail = 1;                         // scales the level-of-detail thresholds
    double tile = 1;                           // tile side, units
    Color color{0.22f, 0.42f, 0.08f};          // the blades' tips (roots darker)
};

// Parses "key=value ..." (seed rect=X0,Z0,X1,Z1 density height=MIN,MAX width lean bend wind
// winddir=X,Z period wavelength keystep detail tile color=R,G,B); unknown keys or bad values
// throw InputError at `loc`.
GrassParams parseGrassParams(const std::string& datablock, const SourceLoc& loc);

std::shared_ptr<const ProceduralGenerator> makeGrassGenerator(const std::string& datablock, const SourceLoc& loc);

// Blades in tiles 0..k-1 (tiles numbered row by row, x fastest), as the stratification counts them.
int64_t grassBladesBefore(const GrassParams& g, int64_t tiles);

}  // namespace streyes
