// The request table, dispatch, and the requests outside the subset.
#include "scene/rib_requests.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace streyes {

void RibRequestTable::add(const std::string& name, const RibRequestInfo& info) {
    if (!requests_.emplace(name, info).second)
        throw std::logic_error("the RIB request table has '" + name + "' twice");
}

const RibRequestInfo* RibRequestTable::find(const std::string& name) const {
    auto found = requests_.find(name);
    return found == requests_.end() ? nullptr : &found->second;
}

std::string RibRequestTable::sameButForCase(const std::string& name) const {
    for (const auto& entry : requests_) {
        const std::string& known = entry.first;
        if (known.size() == name.size() &&
            std::equal(known.begin(), known.end(), name.begin(),
                       [](char a, char b) { return std::tolower(a) == std::tolower(b); }))
            return known;
    }
    return "";
}

const RibRequestTable& ribRequests() {
    static const RibRequestTable table = [] {
        RibRequestTable t;
        for (auto add : {addUnsupportedRequests, addParamRequests, addOptionRequests, addBlockRequests,
                         addTransformRequests, addAttributeRequests, addShadingRequests, addPatchRequests,
                         addPolygonRequests, addSubdivisionRequests, addQuadricRequests, addArchiveRequests, addObjectRequests,
                         addCurveRequests, addNurbsRequests, addTextureRequests, addBlobbyRequests,
                         addGeometryRequests, addDetailRequests, addSolidRequests})
            add(t);
        return t;
    }();
    return table;
}

// ---- Dispatch -----------------------------------------------------------------------------------
void RibParser::dispatch(const RibRequest& request) {
    const std::string& name = request.name;

    // Inside ArchiveBegin/ArchiveEnd: skip to the matching end.
    if (std::optional<RibState::SkippedBlock>& skipping = state_.skipping) {
        if (name == skipping->beginName) ++skipping->depth;
        if (name == skipping->endName && --skipping->depth == 0) skipping.reset();
        return;
    }

    // An unknown request is skipped with its arguments (the next request name ends them), as
    // PRMan and Aqsis do; --strict makes it an error.
    const RibRequestInfo* info = ribRequests().find(name);
    if (!info) {
        const std::string known = ribRequests().sameButForCase(name);
        const std::string hint = known.empty() ? " (see docs/SCENE-FORMAT.md for the requests streyes reads)"
                                               : ": did you mean '" + known + "'? (request names are case-sensitive)";
        log_.lenient("unknown-request:" + name, request.loc, "unknown request '" + name + "' ignored" + hint);
        return;
    }

    // A request that is valid only in part of the file is skipped elsewhere, with a warning (as
    // the peers do: an Imager inside the world, geometry before it).
    auto rightPhase = [&] {
        if (info->phase == RibPhase::Options && state_.world != RibState::World::Before) {
            log_.lenient("phase:" + name, request.loc,
                         name + " is an option: it belongs before WorldBegin (line " +
                             std::to_string(state_.worldBegin.line) + "); ignored here");
            return false;
        }
        if (info->phase == RibPhase::World && state_.world != RibState::World::Inside) {
            std::string where = state_.world == RibState::World::Before ? "before WorldBegin" : "after WorldEnd";
            log_.lenient("phase:" + name, request.loc,
                         name + " belongs between WorldBegin and WorldEnd: ignored " + where);
            return false;
        }
        return true;
    };

    // Inside MotionBegin/MotionEnd: keep the requests until MotionEnd, checking what we can now.
    if (std::optional<RibState::MotionBlock>& motion = state_.motion; motion && name != "MotionEnd") {
        std::string block = "MotionBegin at line " + std::to_string(motion->begin.line);
        if (name == "MotionBegin") throw InputError(request.loc, "nested MotionBegin: the " + block + " is still open");
        if (!info->motion)
            throw InputError(request.loc, name + " cannot appear inside a motion block (" + block +
                                              " has no MotionEnd yet): only transforms (Translate, Rotate, Scale, "
                                              "ConcatTransform, Transform, Identity) or geometry (Patch, PatchMesh, "
                                              "Polygon, SubdivisionMesh, a quadric, ...) can move");
        if (!rightPhase()) return;
        const std::vector<RibRequest>& held = motion->requests;
        if (!held.empty() && name != held.front().name)
            throw InputError(request.loc, "every request in a motion block must be the same: " + name + " after " +
                                              held.front().name + " (" + block + ")");
        if (held.size() == motion->times.size())
            throw InputError(request.loc, "the " + block + " gives " + plural(motion->times.size(), "time") +
                                              ", but this is request " + std::to_string(held.size() + 1) +
                                              " in the block: give one request per time");
        motion->requests.push_back(request);
        motion->usage = info->usage;
        return;
    }

    if (!rightPhase()) return;
    if (state_.openSolid >= 0 && info->phase == RibPhase::World &&
        (info->motion || name == "Blobby" || name == "Geometry" || name == "ObjectInstance" || name == "Procedural"))
        checkSolidGeometry(request);
    RibArgs args(request, info->usage);
    if (!state_.defining) {
        info->handler(*this, args);
        return;
    }
    // Inside an object's definition: a request that gives the attributes a new state is kept with
    // that state (the ones before it too), for each instance to replay (rib_objects.cpp).
    // AttributeEnd and ObjectEnd go back to an earlier state, kept already.
    const AttributesPtr before = state_.attributes;
    info->handler(*this, args);
    if (!state_.defining || state_.attributes == before || name == "AttributeEnd") return;
    RibState::AttributeEdits& edits = state_.defining->edits;
    std::vector<RibRequest> made;
    for (const auto& e : edits)
        if (e.first == before) made = e.second;
    made.push_back(request);
    edits.emplace_back(state_.attributes, std::move(made));
}

void RibParser::replay(const RibRequest& request) {
    RibArgs args(request, "");
    ribRequests().find(request.name)->handler(*this, args);
}

// ---- Requests outside the subset ------------------------------------------------------------------
namespace {

void silent(RibParser&, RibArgs& args) { args.skipRest(); }

void unsupported(RibParser& reader, RibArgs& args) {
    reader.log().lenient("request:" + args.name(), args.loc(), "unsupported request '" + args.name() + "' ignored");
    args.skipRest();
}

void unsupportedGeometry(RibParser& reader, RibArgs& args) {
    reader.log().lenient("request:" + args.name(), args.loc(),
                          "unsupported request '" + args.name() + "' ignored (not supported yet)");
    args.skipRest();
}

void unsupportedGeometryKeys(RibParser& reader, const RibKeys& keys) {
    RibArgs first(keys.requests.front(), keys.usage);
    unsupportedGeometry(reader, first);
}

}  // namespace

void addUnsupportedRequests(RibRequestTable& table) {
    // Requests that only tune another renderer or annotate the file: accepted silently.
    for (const char* name : {"version", "ArchiveRecord", "ErrorHandler", "PixelVariance", "Bound"})
        table.add(name, {silent, ""});
    // clang-format off
    // RIB requests outside the subset: warned about once and skipped.
    for (const char* name :
         {"ColorSamples", "Deformation",
          "TextureCoordinates", "Perspective", "Skew", "ArchiveEnd", "MakeBump",
          "MakeBrickMap",
          "Resource", "ResourceBegin", "ResourceEnd", "Camera", "IfBegin", "IfEnd", "Else", "ElseIf",
          "System", "Shader", "Bxdf", "Pattern", "Integrator", "DisplayFilter", "SampleFilter",
          "PixelSampleImager", "EditBegin", "EditEnd", "EditAttributeBegin",
          "EditAttributeEnd", "EditWorldBegin", "EditWorldEnd"})
        table.add(name, {unsupported});
    // Geometry outside the subset: skipped with a warning, also as the keys of a motion block.
    for (const char* name :
         {"HierarchicalSubdivisionMesh", "Procedural2", "Volume"})
        table.add(name, {unsupportedGeometry, "", RibPhase::World, unsupportedGeometryKeys});
    // clang-format on
}

}  // namespace streyes
