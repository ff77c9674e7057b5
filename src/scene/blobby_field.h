// Blobby (RI Spec 3.2, 5.6): the field its code describes, and that field's level surface cut into
// triangles in object space.
//
// A leaf blob has the field (1 - r^2)^3 for r < 1 and 0 beyond, r the distance in the blob's own
// space (ellipsoid: from the origin of the unit sphere its matrix places; segment blob: from the
// segment, over its radius). The surface is where the last instruction's value is 27/64 = (3/4)^3:
// a lone blob's surface is the sphere r = 1/2 of its own space, half its field's reach: the radius
// of Wyvill et al.'s soft objects (whose field is 1/2 at half its reach), the style PRMan's
// application note on Blobby names, and the level and radius Aqsis draws (its geometry/blobby.cpp).
//
// The polygonizer samples the field on a grid of cubic cells over the leaves' bound, splits every
// cell into six tetrahedra around its main diagonal (neighbouring cells split their shared faces
// the same way) and puts a vertex on each edge that crosses the level, placed by bisection on the
// field. Cells share their edge vertices, so the mesh has no cracks; triangles are wound so that
// dPdu x dPdv points out of the blob (toward lower field).
//
// Kept in the scene stage because the scene keeps a Blobby as the polygons it makes
// (PolygonMeshDesc), like any other polygon request.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "scene/blobby_plugin.h"
#include "streyes/rib.h"
#include "streyes/transform.h"

namespace streyes {

constexpr double kBlobbyLevel = 27.0 / 64.0;

// The field of one leaf blob at squared distance r2 in its own space.
double blobFalloff(double r2);

// A repelling plane's field (opcode 1003, as PRMan and Aqsis define it) at height z above its
// ground: 0 from z = A up; below, (D bump(z / C) - B / z) (1 - ease(z / A)), z taken as at least
// 1e-6 (at and under the ground the field is about -B 10^6: nothing is there). bump rises from 0 at
// 0 to 1 at 1 and back to 0 at 2 (flat to the second derivative at both ends), ease from 0 to 1
// over [0, 1] (flat at both): D pulls the surface toward height C, B pushes it off the ground.
double blobbyRepulsion(double z, double A, double B, double C, double D);

// A repelling plane's ground: the depth map it names, read from the blobby's object space.
struct BlobbyGround {
    BlobbyDepthImage map;
    Matrix4 objectToCamera;  // object -> the map's camera
    Matrix4 objectToScreen;  // object -> the map's screen (homogeneous)
    // The height of p above the ground along the map camera's view: the map's depth where p
    // projects (bilinear between the four nearest pixels when they all saw something, else the
    // nearest) minus p's depth. Infinite (no repulsion) off the map, behind its camera or where
    // it saw nothing.
    double height(Vec3d p) const;
};

struct BlobbyOp {
    // The RI Spec opcodes: leaves 1000-1003, operators 0-7; field plug-ins (1004, 9000).
    enum class Kind {
        Constant, Ellipsoid, Segment, Plane, Plugin,  // leaves
        Add, Multiply, Max, Min, Subtract, Divide, Negate, Identity
    };
    Kind kind = Kind::Constant;
    std::vector<int> operands;  // operators: earlier instructions, by number
    double value = 0;           // Constant
    Matrix4 toObject;           // Ellipsoid, Segment: blob space to object space, as given
    Matrix4 toBlob;             // its inverse
    Vec3d a, b;                 // Segment: its ends and radius, in blob space
    double radius = 1;
    double repel[4] = {0, 0, 0, 0};       // Plane: A, B, C, D
    std::shared_ptr<const BlobbyGround> ground;  // Plane: null: the plane z = 0 of object space (Aqsis)
    std::shared_ptr<const BlobbyPluginLeaf> plugin;  // Plugin: null: not found, its field is 0
    bool leaf() const {
        return kind == Kind::Constant || kind == Kind::Ellipsoid || kind == Kind::Segment || kind == Kind::Plane ||
               kind == Kind::Plugin;
    }
};

struct BlobbyField {
    std::vector<BlobbyOp> ops;  // in code order; the last one's value is the field

    // The field at an object-space point; scratch holds one value per instruction.
    double value(Vec3d p, std::vector<double>& scratch) const;
    // The field of leaf instruction i alone (0 for a constant or a repelling plane: the weights
    // of per-leaf variables are the blobs' and plug-ins' alone).
    double leafValue(size_t i, Vec3d p) const;
    // Where the ellipsoids, segment blobs and plug-ins are not 0, in object space; false when there
    // are none.
    bool bound(Vec3d* lo, Vec3d* hi) const;
};

// Evaluates a field at many points, as BlobbyField::value does and to the same bits, in time that
// follows the leaves near each point rather than all of them (Aqsis's bigblobby.rib has 4,816):
// the leaves are sorted into a grid of bins over their bound, and at a point only the leaves of
// its bin whose support holds it are evaluated; the instructions above them are updated from
// every other instruction's value with no leaf present, an Add summing its non-zero operands in
// their order (adding a 0 changes no sum), any other instruction recomputed from its operands.
// Not thread-safe (it keeps scratch).
class BlobbyEvaluator {
  public:
    explicit BlobbyEvaluator(const BlobbyField& field);
    double value(Vec3d p);
    // The leaf instructions whose field may not be 0 at p, in code order.
    const std::vector<size_t>& leavesNear(Vec3d p);

  private:
    const BlobbyField& field_;
    std::vector<double> base_;                 // each instruction's value with no leaf present
    // The instructions that take each one as an operand, with where among their operands.
    std::vector<std::vector<std::pair<size_t, size_t>>> users_;
    std::vector<std::vector<size_t>> fixed_;   // per Add: the positions of operands with a base other than 0
    std::vector<Vec3d> leafLo_, leafHi_;       // per instruction: its support's box (leaves)
    Vec3d lo_, size_;                          // the bins' box
    int bins_ = 0;                             // along each axis
    std::vector<std::vector<size_t>> binLeaves_;
    std::vector<size_t> planes_;               // repelling planes: their field reaches everywhere
    // Scratch: values (base_ but where a point changed them), the instructions changed, the
    // leaves near the point.
    std::vector<double> v_;
    std::vector<uint8_t> pending_;
    std::vector<size_t> heap_, changed_, near_;
    std::vector<std::vector<size_t>> positions_;  // per Add: its operands changed to a value other than 0
};

struct BlobbyMesh {
    std::vector<Vec3d> P;
    std::vector<std::array<int, 3>> triangles;
    bool openAtBound = false;  // the field is above the level on the grid's edge (constants): cut open there
};

// The surface on a grid of `cells` cells along the bound's longest side (the bound padded by one
// cell on every side).
BlobbyMesh polygonizeBlobby(const BlobbyField& field, int cells);

}  // namespace streyes
