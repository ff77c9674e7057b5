// Patches: Patch "bilinear" (a bilinear patch), Patch "bicubic" and PatchMesh (patch meshes, in the
// Basis in force).
#include "scene/rib_geometry.h"

namespace streyes {

namespace {

bool wrapMode(RibArgs& args, const char* what) {
    const RibValue* v = args.peek();
    std::string mode = args.string(what);
    if (mode != "periodic" && mode != "nonperiodic")
        args.fail(*v, std::string(what) + " must be \"periodic\" or \"nonperiodic\", got \"" + mode + "\"");
    return mode == "periodic";
}

// One key of PatchMesh, or of Patch "bicubic" (a 4 x 4 mesh), in the Basis in force.
bool readPatchMeshKey(RibParser& reader, RibArgs& args, PatchMeshDesc* d) {
    const RibValue* typeValue = args.peek();
    const std::string type = args.string("type");
    if (args.name() == "Patch") {
        d->nu = d->nv = 4;
    } else {
        if (type != "bicubic" && type != "bilinear")
            args.fail(*typeValue, "the patch type must be \"bilinear\" or \"bicubic\", got \"" + type + "\"");
        const RibValue* nuValue = args.peek();
        d->nu = args.integer("nu");
        d->uPeriodic = wrapMode(args, "uwrap");
        const RibValue* nvValue = args.peek();
        d->nv = args.integer("nv");
        d->vPeriodic = wrapMode(args, "vwrap");
        d->bicubic = type == "bicubic";
        d->uBasis = reader.state().attributes->uBasis;
        d->vBasis = reader.state().attributes->vBasis;
        // The control points must make whole patches (RenderMan's rule).
        auto check = [&](const RibValue* at, int n, bool periodic, int step, const char* axis) {
            const std::string name(axis);
            if (!d->bicubic) {
                if (n < 2) args.fail(*at, "a bilinear patch mesh needs at least 2 points along " + name);
                return;
            }
            if (periodic ? n < 1 || n % step != 0 : n < 4 || (n - 4) % step != 0)
                args.fail(*at, std::to_string(n) + " points along " + name + " do not make whole " +
                                   (periodic ? "periodic" : "nonperiodic") + " patches with a basis step of " +
                                   std::to_string(step) +
                                   (periodic ? " (the count must be a multiple of the step)"
                                             : " (the count must be 4 plus a multiple of the step)"));
        };
        check(nuValue, d->nu, d->uPeriodic, d->uBasis.step, "u");
        check(nvValue, d->nv, d->vPeriodic, d->vBasis.step, "v");
    }
    if (args.name() == "Patch") {
        d->bicubic = true;
        d->uBasis = reader.state().attributes->uBasis;
        d->vBasis = reader.state().attributes->vBasis;
    }
    ParamList params = reader.readParams(args);
    const Param& pos = positionParam(args, params);
    checkCount(args, pos, size_t(d->nu) * size_t(d->nv));
    ClassCounts counts;
    counts.uniform = size_t(d->uPatches()) * size_t(d->vPatches());
    counts.varying = counts.faceVarying = size_t(d->uVarying()) * size_t(d->vVarying());
    counts.vertex = size_t(d->nu) * size_t(d->nv);
    d->P = {pointsOf(args, pos)};
    d->Cs = readColors(args, params, counts);
    // Each patch's corners (as "Cs" is read), or a bicubic one's vertex values in Bezier form.
    d->primvars = otherParams(args, params, counts, reader.log(), false, true);
    return true;
}

// A patch mesh (PatchMesh, Patch "bicubic"): every key the same type, size and wrap.
void patchMeshKeys(RibParser& reader, const RibKeys& keys) {
    auto sameShape = [](const PatchMeshDesc& k, const PatchMeshDesc& f) {
        return k.bicubic == f.bicubic && k.nu == f.nu && k.nv == f.nv && k.uPeriodic == f.uPeriodic &&
               k.vPeriodic == f.vPeriodic;
    };
    auto positions = [](PatchMeshDesc& d) -> auto& { return d.P; };
    if (auto d = mergeKeys<PatchMeshDesc>(reader, keys, readPatchMeshKey, sameShape, "type, size and wrap", positions))
        reader.scene().patchMeshes.push_back(std::move(*d));
}

// Patch "bilinear" into one key; false for Patch "bicubic", which is a patch mesh.
bool readBilinearKey(RibParser& reader, RibArgs& args, FaceKey* key) {
    const RibValue* typeValue = args.peek();
    std::string type = args.string("type");
    if (type == "bicubic") return false;
    if (type != "bilinear")
        args.fail(*typeValue, "the patch type must be \"bilinear\" or \"bicubic\", got \"" + type + "\"");
    return readFaceKey(reader, args, false, key);
}

// A bilinear patch of its keys: one static patch when they are all equal.
void addBilinearPatch(RibParser& reader, const std::vector<double>& times, const std::vector<FaceKey>& keys,
                      const SourceLoc& loc) {
    BilinearPatchDesc patch;
    const bool moves = faceKeysMove(reader.log(), keys, loc);
    patch.times = moves ? times : std::vector<double>{times.front()};
    for (size_t i = 0; i < (moves ? keys.size() : 1); ++i)
        std::copy(keys[i].P.begin(), keys[i].P.end(), patch.P.emplace_back().begin());
    const FaceKey& first = keys.front();
    patch.hasCs = first.Cs.given();
    if (patch.hasCs) std::copy(first.vertexCs.begin(), first.vertexCs.end(), patch.Cs.begin());
    patch.primvars = first.primvars;  // per vertex in corner order already
    patch.objectToWorld = reader.state().ctm;
    patch.attributes = reader.state().attributes;
    patch.loc = loc;
    shapeAreaLight(reader, {patch.P.front()}, loc);
    reader.scene().patches.push_back(std::move(patch));
}

constexpr char kBicubicPatchUsage[] = "Patch \"bicubic\" \"P\" [48 numbers]";

void patch(RibParser& reader, RibArgs& args) {
    FaceKey key;
    if (readBilinearKey(reader, args, &key))
        addBilinearPatch(reader, {0.0}, {key}, args.loc());
    else
        patchMeshKeys(reader, {{0.0}, {args.request()}, kBicubicPatchUsage});
}

void patchKeys(RibParser& reader, const RibKeys& keys) {
    std::vector<FaceKey> faces(keys.requests.size());
    for (size_t i = 0; i < faces.size(); ++i) {
        RibArgs args(keys.requests[i], keys.usage);
        if (!readBilinearKey(reader, args, &faces[i])) {
            patchMeshKeys(reader, keys);  // a bicubic patch
            return;
        }
    }
    addBilinearPatch(reader, keys.times, faces, keys.requests.front().loc);
}

}  // namespace

void addPatchRequests(RibRequestTable& table) {
    const RibPhase world = RibPhase::World;
    table.add("Patch", {patch, "Patch \"bilinear\" \"P\" [12 numbers]", world, patchKeys});
    table.add("PatchMesh", {oneKey<patchMeshKeys>,
                            "PatchMesh \"bicubic\"|\"bilinear\" nu \"nonperiodic\"|\"periodic\" nv "
                            "\"nonperiodic\"|\"periodic\" \"P\" [...]",
                            world, patchMeshKeys});
}

}  // namespace streyes
