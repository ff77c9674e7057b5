#include "scene/blobby_plugin.h"

#include <dlfcn.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>

#include "ImplicitField.h"
#include "scene/search_path.h"

namespace streyes {

namespace {

// AIR's interface (its implicit.h), written from its documented signatures.
struct AirState {
    int blobbyId;
    int opId;
};
extern "C" {
typedef void (*AirBoundFn)(AirState*, float* bd, int niarg, int* iarg, int nfarg, float* farg, int nsarg,
                           char** sarg);
typedef void (*AirValueFn)(AirState*, float* result, float* p, int niarg, int* iarg, int nfarg, float* farg,
                           int nsarg, char** sarg);
typedef void (*AirFreeFn)(AirState*);
}

}  // namespace

// A loaded shared object; never unloaded (plug-ins may keep state between Blobbies).
struct BlobbyPluginLibrary {
    std::string path;
    void* handle = nullptr;
    ImplicitFieldNewFunction prmanNew = nullptr;
    AirBoundFn airBound = nullptr;
    AirValueFn airValue = nullptr;
    AirFreeFn airFree = nullptr;
};

std::shared_ptr<BlobbyPluginLibrary> loadBlobbyPlugin(const std::string& name, const std::string& searchPath,
                                                      const std::string& directory, const SourceLoc& loc,
                                                      std::string* where) {
    const std::string path = findPluginFile(name, searchPath, directory);
    if (path.empty()) {
        *where = pluginSearchDescription(name, searchPath, directory);
        return nullptr;
    }
    static std::mutex mutex;
    static std::map<std::string, std::shared_ptr<BlobbyPluginLibrary>> loaded;
    std::lock_guard<std::mutex> lock(mutex);
    std::shared_ptr<BlobbyPluginLibrary>& slot =
        loaded[std::filesystem::absolute(path).lexically_normal().string()];
    if (slot) return slot;
    dlerror();
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = dlerror();
        throw InputError(loc, "Blobby: cannot load the field plug-in '" + path + "': " +
                                  (why ? why : "unknown error") + " (build it as a shared object for this machine)");
    }
    auto lib = std::make_shared<BlobbyPluginLibrary>();
    lib->path = path;
    lib->handle = handle;
    lib->prmanNew = reinterpret_cast<ImplicitFieldNewFunction>(dlsym(handle, "ImplicitFieldNew"));
    lib->airBound = reinterpret_cast<AirBoundFn>(dlsym(handle, "ImplicitBound"));
    lib->airValue = reinterpret_cast<AirValueFn>(dlsym(handle, "ImplicitValue"));
    lib->airFree = reinterpret_cast<AirFreeFn>(dlsym(handle, "ImplicitFree"));
    slot = lib;
    return lib;
}

namespace {

bool finiteBox(const float* b) {
    for (int i = 0; i < 6; ++i)
        if (!std::isfinite(b[i])) return false;
    return b[0] <= b[1] && b[2] <= b[3] && b[4] <= b[5];
}

std::string boxText(const float* b) {
    std::string s;
    for (int i = 0; i < 6; ++i) s += (i ? " " : "") + std::to_string(b[i]);
    return s;
}

}  // namespace

BlobbyPluginLeaf::~BlobbyPluginLeaf() {
    if (field_) {
        delete static_cast<ImplicitField*>(field_);
    } else if (library_ && library_->airFree) {
        AirState state{blobby_, op_};
        library_->airFree(&state);
    }
}

std::shared_ptr<const BlobbyPluginLeaf> BlobbyPluginLeaf::makePrman(std::shared_ptr<BlobbyPluginLibrary> library,
                                                                    const std::vector<float>& floats,
                                                                    const std::vector<std::string>& strings,
                                                                    const SourceLoc& loc) {
    if (!library->prmanNew)
        throw InputError(loc, "Blobby: the field plug-in '" + library->path +
                                  "' does not export ImplicitFieldNew (opcode 1004 is PRMan's implicit field "
                                  "plug-in: extern \"C\" ImplicitField *ImplicitFieldNew(int nfloat, const RtFloat "
                                  "*float0, const RtFloat *float1, int nstring, const RtString *string); see "
                                  "include/ImplicitField.h)");
    std::shared_ptr<BlobbyPluginLeaf> leaf(new BlobbyPluginLeaf);
    leaf->library_ = std::move(library);
    std::vector<const char*> names;
    for (const std::string& s : strings) names.push_back(s.c_str());
    const float* f = floats.empty() ? nullptr : floats.data();
    ImplicitField* field = leaf->library_->prmanNew(int(floats.size()), f, f, int(names.size()),
                                                    names.empty() ? nullptr : names.data());
    if (!field)
        throw InputError(loc, "Blobby: the field plug-in '" + leaf->library_->path +
                                  "': ImplicitFieldNew returned no field (its arguments are wrong?)");
    leaf->field_ = field;  // deleted with the leaf from here on
    if (!finiteBox(field->bbox))
        throw InputError(loc, "Blobby: the field plug-in '" + leaf->library_->path + "' gives the bbox " +
                                  boxText(field->bbox) +
                                  ": it must be xmin xmax ymin ymax zmin zmax, finite, each min <= max");
    leaf->lo_ = {field->bbox[0], field->bbox[2], field->bbox[4]};
    leaf->hi_ = {field->bbox[1], field->bbox[3], field->bbox[5]};
    return leaf;
}

std::shared_ptr<const BlobbyPluginLeaf> BlobbyPluginLeaf::makeAir(std::shared_ptr<BlobbyPluginLibrary> library,
                                                                  const Matrix4& toObject, const Matrix4& toBlob,
                                                                  std::vector<float> floats,
                                                                  std::vector<std::string> strings,
                                                                  std::vector<int> ints, int blobby, int op,
                                                                  const SourceLoc& loc) {
    if (!library->airValue || !library->airBound)
        throw InputError(loc, "Blobby: the field plug-in '" + library->path + "' does not export" +
                                  (library->airValue ? "" : " ImplicitValue") +
                                  (library->airBound ? "" : " ImplicitBound") +
                                  " (opcode 9000 is AIR's dynamic blob op: C functions ImplicitBound, ImplicitValue "
                                  "and optionally ImplicitFree; docs/SCENE-FORMAT.md, Blobby)");
    std::shared_ptr<BlobbyPluginLeaf> leaf(new BlobbyPluginLeaf);
    leaf->library_ = std::move(library);
    leaf->toBlob_ = toBlob;
    leaf->floats_ = std::move(floats);
    leaf->strings_ = std::move(strings);
    for (std::string& s : leaf->strings_) leaf->stringPointers_.push_back(s.data());
    leaf->ints_ = std::move(ints);
    leaf->blobby_ = blobby;
    leaf->op_ = op;
    float bd[6] = {0, 0, 0, 0, 0, 0};
    AirState state{blobby, op};
    leaf->library_->airBound(&state, bd, int(leaf->ints_.size()), leaf->ints_.empty() ? nullptr : leaf->ints_.data(),
                             int(leaf->floats_.size()), leaf->floats_.empty() ? nullptr : leaf->floats_.data(),
                             int(leaf->stringPointers_.size()),
                             leaf->stringPointers_.empty() ? nullptr : leaf->stringPointers_.data());
    if (!finiteBox(bd))
        throw InputError(loc, "Blobby: the field plug-in '" + leaf->library_->path + "': ImplicitBound gives " +
                                  boxText(bd) + ": it must be xmin xmax ymin ymax zmin zmax, finite, each min <= max");
    leaf->blobLo_ = {bd[0], bd[2], bd[4]};
    leaf->blobHi_ = {bd[1], bd[3], bd[5]};
    const Bounds3d box = toObject.box(Bounds3d(leaf->blobLo_, leaf->blobHi_));
    leaf->lo_ = box.lo;
    leaf->hi_ = box.hi;
    return leaf;
}

double BlobbyPluginLeaf::value(Vec3d p) const {
    if (!(p.x >= lo_.x && p.x <= hi_.x && p.y >= lo_.y && p.y <= hi_.y && p.z >= lo_.z && p.z <= hi_.z)) return 0;
    if (field_) {
        const RtPoint q = {float(p.x), float(p.y), float(p.z)};
        const double v = static_cast<ImplicitField*>(field_)->Eval(q);
        return std::isfinite(v) ? v : 0;  // never a NaN that would poison the bisection
    }
    const Vec3d b = toBlob_.point(p);
    if (!(b.x >= blobLo_.x && b.x <= blobHi_.x && b.y >= blobLo_.y && b.y <= blobHi_.y && b.z >= blobLo_.z &&
          b.z <= blobHi_.z))
        return 0;
    float q[3] = {float(b.x), float(b.y), float(b.z)};
    float d = 1;
    AirState state{blobby_, op_};
    // The plug-in's arguments are not const in AIR's interface; it must not change them.
    auto* self = const_cast<BlobbyPluginLeaf*>(this);
    library_->airValue(&state, &d, q, int(ints_.size()), ints_.empty() ? nullptr : self->ints_.data(),
                       int(floats_.size()), floats_.empty() ? nullptr : self->floats_.data(),
                       int(stringPointers_.size()), stringPointers_.empty() ? nullptr : self->stringPointers_.data());
    return d < 1 ? 1.0 - double(d) : 0.0;  // a NaN distance fails d < 1: no field
}

}  // namespace streyes
