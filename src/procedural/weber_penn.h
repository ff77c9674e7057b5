// Weber–Penn trees (J. Weber and J. Penn, "Creation and Rendering of Realistic Trees", SIGGRAPH
// 1995): the built-in "tree" procedural with model=weberpenn.
//
// A tree is a recursion of stems (level 0 the trunk, up to Levels - 1), each a chain of nCurveRes
// segments that curve, split into clones and carry child stems, the stems of the last level
// carrying leaves. Every number follows the paper's formulas for its parameters (named as the paper
// names them: Shape, BaseSize, 1DownAngle, ...; docs/SCENE-FORMAT.md). Each stem draws its random
// numbers from its own generator, keyed by its parent's key and its place, so that a stem does not
// depend on the order stems are grown in: the tree expands lazily (the trunk with its first-level
// branches' procedurals; each of those grows its own subtree when seen) and a test grows the same
// tree at once (growWeberPenn).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "procedural/procedural.h"

namespace streyes {

// The paper's per-level parameters (column n of its table: nDownAngle, ...). Angles in degrees.
struct WeberPennLevel {
    double downAngle = 0, downAngleV = 0;   // nDownAngle, nDownAngleV (< 0: varies along the parent)
    double rotate = 0, rotateV = 0;         // nRotate (< 0: alternating sides), nRotateV
    double length = 1, lengthV = 0;         // nLength, nLengthV
    double taper = 1;                       // nTaper: 0..1 cone, 1..2 to spherical end, 2..3 periodic
    double segSplits = 0;                   // nSegSplits (0BaseSplits is apart)
    double splitAngle = 0, splitAngleV = 0; // nSplitAngle, nSplitAngleV
    int curveRes = 3;                       // nCurveRes: segments of a stem
    double curve = 0, curveBack = 0, curveV = 0;  // nCurve, nCurveBack, nCurveV
    double branches = 0;                    // nBranches: most child stems of a stem of level n - 1
};

struct WeberPennParams {
    std::string name = "custom";
    int shape = 0;                 // Shape 0-7 (ShapeRatio)
    double baseSize = 0.25;        // BaseSize: share of the trunk without branches
    double scale = 10, scaleV = 0; // Scale, ScaleV: the tree's size (metres)
    double zScale = 1, zScaleV = 0;// ZScale, ZScaleV: scale along the trunk's axis
    int levels = 3;                // Levels: stem levels (trunk = 0); leaves on the last
    double ratio = 0.015, ratioPower = 1.2;  // Ratio, RatioPower
    int lobes = 0;                 // Lobes, LobeDepth: the trunk's cross-section
    double lobeDepth = 0;
    double flare = 0;              // Flare: the trunk's widening at its foot
    double scale0 = 1, scale0V = 0;// 0Scale, 0ScaleV: the trunk's radius
    int baseSplits = 0;            // 0BaseSplits: clones of the trunk at its first segment's end
    std::array<WeberPennLevel, 4> level{};  // columns 0..3; leaves use column Levels (or the last)
    double leaves = 0;             // Leaves: most leaves of a stem of the last level
    int leafShape = 0;             // LeafShape: 0 ellipse, 1 ovate (pointed), 2 lanceolate
    double leafScale = 0.2, leafScaleX = 1;  // LeafScale, LeafScaleX
    double leafBend = 0;           // LeafBend: leaves turn to face out from the trunk and up, 0..1 of the way
    double attractionUp = 0;       // AttractionUp: stems of level >= 2 bend up (down when < 0)
    // Pruning: stems of level >= 1 leaving the envelope are shortened, blended by PruneRatio.
    double pruneRatio = 0;         // PruneRatio: 0 no pruning, 1 stems wholly inside
    double pruneWidth = 0.5;       // PruneWidth: the envelope's largest radius / scale_tree
    double pruneWidthPeak = 0.5;   // PruneWidthPeak: height of the widest point, share of the crown
    double prunePowerLow = 0.5, prunePowerHigh = 0.5;  // PrunePowerLow/High: the profile's curvature below/above it
    // Wind sway (weber_penn_wind.h): each stem's segments turn about its x and y axes.
    double windSpeed = 0, windGust = 0;  // WindSpeed, WindGust
    double windTime = 50;          // (streyes) the paper's time units a frame
    double keyStep = 4;            // (streyes) frames between motion keys
    // Not the paper's: looks, and the level of detail's reach.
    Color barkColor{0.33f, 0.27f, 0.21f}, leafColor{0.25f, 0.45f, 0.12f};
    double detail = 1;             // scales the level-of-detail thresholds (2: more detail)
    uint64_t seed = 1;
};

// The species of the paper's table: quaking_aspen, black_tupelo, weeping_willow, ca_black_oak.
// Null for another name.
const WeberPennParams* weberPennPreset(const std::string& name);
std::vector<std::string> weberPennPresetNames();

// The paper's ShapeRatio(shape, ratio), shapes 0-7.
double weberPennShapeRatio(int shape, double ratio);

// The paper's pruning envelope, ShapeRatio 8: its relative width at ratio = (scale_tree - y) /
// (scale_tree (1 - BaseSize)), 0 outside [0, 1]: (ratio / (1 - PruneWidthPeak))^PrunePowerHigh above
// the peak, ((1 - ratio) / PruneWidthPeak)^PrunePowerLow below it (the paper prints 1 - PruneWidthPeak
// in the second denominator too, which leaves the profile discontinuous at the peak but for 0.5).
double weberPennEnvelope(const WeberPennParams& p, double ratio);
// Whether the point q (tree space, y up, before ZScale) lies inside the envelope: its distance from
// the trunk's axis over scale_tree below PruneWidth times the envelope at its height.
bool weberPennInsideEnvelope(const WeberPennParams& p, double scaleTree, Vec3d q);
// scale_tree = Scale ± ScaleV, as the trunk draws it.
double weberPennScaleTree(const WeberPennParams& p);

// A grown tree, y up, the trunk's foot at the origin.
struct WeberPennStem {
    int level = 0;
    int parent = -1;             // index into stems; -1 for the trunk
    uint64_t key = 0;
    double offset = 0;           // along the parent (path length from its base) where it starts
    double parentLength = 0;     // length_parent (0 for the trunk)
    double length = 0;           // length_stem
    double lengthChildMax = 0;   // nLength ± nLengthV drawn for it (its length's factor)
    double radius = 0;           // radius_stem (at its base, before flare)
    double baseLength = 0;       // the trunk's length_base (BaseSize * scale_tree); 0 for others
    int parentPath = 0, parentSegment = 0;  // where on its parent it grows (the segment moves it in the wind)
    int children = 0;            // child stems it carries (the paper's count); leaves on the last level
    int leaves = 0;
    // The axis: segments of length length / nCurveRes; a segment's start is a point of a path.
    // Path 0 is the stem; each clone a path of its own that starts where it split (at segment
    // firstSegment). Each path's points: firstSegment's start, then one a segment.
    struct Path {
        int firstSegment = 0;
        Vec3d before;              // the point before its first (a clone: its parent path's), for the tangent
        std::vector<Vec3d> points;
        std::vector<Vec3d> xAxis;  // the stem's frame at each point (x across, for rotations)
        int from = 0;              // a clone: the path it split from
    };
    std::vector<Path> paths;
    Vec3d direction{0, 1, 0};    // at its base
};

struct WeberPennLeaf {
    Vec3d position, direction, normal;  // base of the leaf, along its blade, its face
    int stem = 0;
    int path = 0, segment = 0;  // where on its stem it grows
    // Degraded at range (WeberPennReduction): its size's factor, the inverse square root of the
    // share of leaves kept where it grows (of its stem's, times that of its stem among its
    // siblings), so that the leaves kept have the area of the leaves of the full tree there.
    double grow = 1;
};

struct WeberPennTree {
    WeberPennParams params;
    double scaleTree = 0;        // Scale ± ScaleV
    std::vector<WeberPennStem> stems;
    std::vector<WeberPennLeaf> leaves;
};

// The paper's leaf orientation, by LeafBend of the way: the leaf turns about the vertical so that its
// face's horizontal direction nears its position's about the trunk (theta_bend = theta_position -
// theta_normal, the short way round), then about its own x axis (across the blade) towards facing
// up (phi_bend = the face's angle from the vertical). Both about the leaf's base.
void weberPennBendLeaf(double leafBend, WeberPennLeaf* leaf);

// The radius of a stem at fraction z (0..1) of its length: the paper's taper, and the trunk's
// flare (with trunk = true).
double weberPennRadiusAt(const WeberPennParams& p, const WeberPennStem& s, double z);

// The paper's degradation at range: at quality q in (0, 1] (how large the tree is on screen) a
// subtree keeps about q of its leaves, each larger by the inverse square root of the share kept
// (WeberPennLeaf::grow) so that the crown keeps its leaf area, and about sqrt(q) of its last stem
// level's stems (those that carry the leaves; a level of 2 or deeper: the first-level branches are
// the tree's procedurals). What is kept is a subset of the full tree, each where the full tree has
// it: child j of a stem when j % stemStep == 0 (ceil(n / stemStep) of n), leaf j of a stem when
// j % leafStep == 0.
struct WeberPennReduction {
    int stemStep = 1;  // of the last stem level (when >= 2), every stemStep-th stem of each parent
    int leafStep = 1;  // of each kept stem's leaves, every leafStep-th
};
// stemStep = floor(1 / sqrt(q)) (1 when the last stem level is the first or the trunk), leafStep =
// max(1, round(1 / (q stemStep))): the share kept, 1 / (stemStep leafStep), is about q. q is taken
// at least kWeberPennLeastQuality, so that a leaf grows at most sqrt(20) times (bounds count on it).
constexpr double kWeberPennLeastQuality = 0.05;
WeberPennReduction weberPennReduction(const WeberPennParams& p, double quality);

// Grows a whole tree (for tests and tools): the same stems the procedural makes.
WeberPennTree growWeberPenn(const WeberPennParams& p, const WeberPennReduction& reduce = {});
// The steps the procedural takes lazily: the trunk (and scale_tree), then the stems below
// stems[index] down to level lastLevel (appended to `stems`, depth first) with the leaves of those
// of the last level; `reduce` leaves out stems and leaves (what it keeps is as in the full tree).
WeberPennStem weberPennTrunk(const WeberPennParams& p, double* scaleTree);
void weberPennGrowBelow(const WeberPennParams& p, std::vector<WeberPennStem>& stems, size_t index, int lastLevel,
                        std::vector<WeberPennLeaf>* leaves, const WeberPennReduction& reduce = {});

// Parses "model=weberpenn preset=NAME seed=N Shape=... 1DownAngle=... barkcolor=r,g,b ...";
// unknown keys or bad values throw InputError at `loc`.
WeberPennParams parseWeberPennParams(const std::string& datablock, const SourceLoc& loc);
// Whether a tree datablock asks for this model (model=weberpenn).
bool isWeberPennDatablock(const std::string& datablock);
// A bound of the tree the procedural makes (object space, before wind): for Procedural's bound.
Bounds3d weberPennBound(const WeberPennParams& p);
std::shared_ptr<const ProceduralGenerator> makeWeberPennGenerator(const std::string& datablock, const SourceLoc& loc);
std::shared_ptr<const ProceduralGenerator> makeWeberPennGenerator(WeberPennParams p);
// A bound about the trunk's foot of every tree these parameters make, whatever the seed and the
// wind (no stem is longer than its lengths' largest draw, and turning stems about their joints
// keeps their path lengths from the foot): for a forest's cells, without growing their trees.
Bounds3d weberPennFootBound(const WeberPennParams& p);

}  // namespace streyes
