// Blobby field plug-ins: leaves whose field a shared object computes, in PRMan's form (opcode 1004,
// include/ImplicitField.h) and in AIR's (opcode 9000, Aqsis's "dynamic blob ops").
//
// PRMan's: ImplicitFieldNew(nfloat, float0, float1, nstring, strings) makes an object whose Eval
// is the field at an object-space point and whose bbox bounds it. AIR's: C functions
// ImplicitBound (the box, in the blob's own space, where the field may not be 0), ImplicitValue
// (a distance d at a blob-space point: the field is 1 - d for d < 1, 0 beyond, as Aqsis takes it,
// so the surface of a lone plug-in is at d = 37/64, where 1 - d is the level 27/64) and, if exported, ImplicitFree; the blob's own
// space is placed by a matrix (as an ellipsoid's is). Either field is 0 outside its box.
//
// A shared object is loaded once (per path) and stays loaded while the program runs. Lookup is
// Procedural "DynamicLoad"'s: Option "searchpath" "procedural", then STREYES_PROCEDURALPATH.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "streyes/error.h"
#include "streyes/transform.h"

namespace streyes {

struct BlobbyPluginLibrary;

// One plug-in leaf: the field one 1004 or 9000 instruction describes.
class BlobbyPluginLeaf {
  public:
    ~BlobbyPluginLeaf();
    BlobbyPluginLeaf(const BlobbyPluginLeaf&) = delete;
    BlobbyPluginLeaf& operator=(const BlobbyPluginLeaf&) = delete;

    // The field at an object-space point (0 outside the box).
    double value(Vec3d p) const;
    // The object-space box outside which the field is 0.
    Vec3d lo() const { return lo_; }
    Vec3d hi() const { return hi_; }

    // PRMan's form: ImplicitFieldNew with these arguments. Throws InputError naming loc when the
    // library lacks ImplicitFieldNew or it returns no field or a bad bbox.
    static std::shared_ptr<const BlobbyPluginLeaf> makePrman(std::shared_ptr<BlobbyPluginLibrary> library,
                                                             const std::vector<float>& floats,
                                                             const std::vector<std::string>& strings,
                                                             const SourceLoc& loc);
    // AIR's form: the blob space placed by toObject (blob -> object), its inverse toBlob; blobby and
    // op identify the instruction to the plug-in (its State). Throws InputError naming loc when the
    // library lacks ImplicitValue or ImplicitBound, or the bound is not a box.
    static std::shared_ptr<const BlobbyPluginLeaf> makeAir(std::shared_ptr<BlobbyPluginLibrary> library,
                                                           const Matrix4& toObject, const Matrix4& toBlob,
                                                           std::vector<float> floats, std::vector<std::string> strings,
                                                           std::vector<int> ints, int blobby, int op,
                                                           const SourceLoc& loc);

  private:
    BlobbyPluginLeaf() = default;
    std::shared_ptr<BlobbyPluginLibrary> library_;
    void* field_ = nullptr;  // PRMan's: the ImplicitField
    // AIR's: its arguments (kept for every call), its blob space and box there.
    Matrix4 toBlob_;
    std::vector<float> floats_;
    std::vector<std::string> strings_;
    std::vector<char*> stringPointers_;
    std::vector<int> ints_;
    int blobby_ = 0, op_ = 0;
    Vec3d blobLo_, blobHi_;
    Vec3d lo_, hi_;
};

// The shared object a plug-in name resolves to (searchPath: Option "searchpath" "procedural";
// directory: the naming file's folder), loaded; null when there is no such file. Throws
// InputError naming loc when the file is there but cannot be loaded. `where` gets the folders
// looked in when it is null.
std::shared_ptr<BlobbyPluginLibrary> loadBlobbyPlugin(const std::string& name, const std::string& searchPath,
                                                      const std::string& directory, const SourceLoc& loc,
                                                      std::string* where);

}  // namespace streyes
