// The built-in "forest" and "tree" procedurals (Procedural "DynamicLoad").
//
// Expansion is nested and lazy, each level with a conservative bound over the whole animation
// (wind sway included): forest -> cells (a few dozen trees each) -> trees -> branches (each with
// its leaves). Trunks stand still; branches and leaves sway in the wind with motion keys every
// `keystep` frames, linear between. A tree's level of detail follows the projected size of its
// bound (like RenderMan's DetailRange):
//   far   (under ~4 px):          two crossed quads the colour of the crown;
//   middle (under 40 px * detail): trunk and a still crown proxy (cone or ellipsoid of patches);
//   near:                          trunk, swaying branches and leaves.
#pragma once

#include <memory>
#include <string>

#include <string>
#include <vector>

#include "procedural/procedural.h"

namespace streyes {

struct ForestParams {
    int count = 1000;              // trees
    uint64_t seed = 1;
    double areaX = 100, areaZ = 100;  // the forest covers [-areaX/2, areaX/2] x [-areaZ/2, areaZ/2] on y = 0
    double mix[3] = {0.5, 0.3, 0.2};  // share of conifers, broadleaf trees, birches
    double leafSize = 0.3;         // metres
    double wind = 0.5;             // sway strength, 0 = still
    double windX = 1, windZ = 0;   // wind direction on the ground
    double period = 48;            // frames per sway cycle
    double keyStep = 4;            // frames between motion keys
    double detail = 1;             // scales the level-of-detail thresholds (2: more detail)
    int treesPerCell = 64;
    // shaders=BARK,LEAF: the surfaces near trees' trunks and branches (BARK) and leaves (LEAF, cut
    // out by its opacity) are shaded with, given white base colours so that the tree's own colour
    // (Cs) tints them. Empty (the default): everything takes the procedural's own surface.
    std::string barkShader, leafShader;
    // The attribute states made for those (one per parent state, shared by every tree).
    std::shared_ptr<struct ForestLooks> looks;
    // model=weberpenn (presets=a,b,...): each tree a Weber-Penn tree of one of these presets, drawn
    // evenly; empty: the forest's own trees (model=simple).
    std::vector<std::string> weberPennPresets;
};

// Parses "key=value ..." (count seed area=X,Z species=a,b,c leafsize wind winddir=X,Z period
// keystep detail cell shaders=BARK,LEAF model=simple|weberpenn presets=NAME,...); unknown keys or bad values throw InputError at `loc`.
ForestParams parseForestParams(const std::string& datablock, const SourceLoc& loc);

std::shared_ptr<const ProceduralGenerator> makeForestGenerator(const std::string& datablock, const SourceLoc& loc);
// One tree at the origin: the forest's keys plus kind=conifer|broadleaf|birch, height=H.
std::shared_ptr<const ProceduralGenerator> makeTreeGenerator(const std::string& datablock, const SourceLoc& loc);

}  // namespace streyes
